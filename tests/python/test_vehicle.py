# SPDX-License-Identifier: BSD-3-Clause
"""geaware.Vehicle, geaware.Truth, the model functions and the flat map against closed forms."""
import math
import re

import numpy as np
import pytest

import geaware

G = 9.81


@pytest.fixture(scope="module")
def vehicle():
    return geaware.builtin_vehicle()


def test_vehicle_file_reads_as_the_builtin(source_dir, vehicle):
    path = source_dir / "config/vehicles/paper_quad.yaml"
    loaded = geaware.load_vehicle(str(path))
    mass = float(re.search(r"^mass_kg:\s*([0-9.eE+-]+)", path.read_text(), re.M).group(1))
    assert loaded.mass_kg == mass == vehicle.mass_kg
    np.testing.assert_array_equal(loaded.inertia_kgm2, vehicle.inertia_kgm2)
    np.testing.assert_array_equal(loaded.drag_heights_m, vehicle.drag_heights_m)
    assert loaded.inertia_kgm2.shape == (3,) and vehicle.k_T_N_per_rpm2 > 0


def test_bad_vehicle_file_names_file_and_key(tmp_path, source_dir):
    text = (source_dir / "config/vehicles/paper_quad.yaml").read_text()
    bad = tmp_path / "bad.yaml"
    bad.write_text(re.sub(r"^mass_kg:\s*\S+", "mass_kg: heavy", text, flags=re.M))
    with pytest.raises(geaware.ConfigError) as e:
        geaware.load_vehicle(str(bad))
    assert "bad.yaml" in str(e.value) and "mass_kg" in str(e.value)
    assert isinstance(e.value, ValueError)
    with pytest.raises(RuntimeError):
        geaware.load_vehicle(str(tmp_path / "missing.yaml"))


def test_ground_effect_closed_forms(vehicle):
    h_min = vehicle.min_rotor_plane_height_m
    h = np.linspace(h_min, 2.0, 50)
    f_g = vehicle.g2_m2 / (h**2 + vehicle.g1_m2)
    np.testing.assert_allclose(vehicle.thrust_ratio(h), f_g, rtol=1e-14)
    m_g = vehicle.leveling_scale_m4 * h / (h**2 + vehicle.g3_m * h + vehicle.g4_m2) ** 2
    np.testing.assert_allclose(vehicle.leveling_coefficient(h), m_g, rtol=1e-14)
    # Clamped up to the landing gear's height, with slope 0 there.
    assert vehicle.thrust_ratio(0.0) == vehicle.thrust_ratio(h_min)
    assert vehicle.thrust_ratio_slope(0.5 * h_min) == 0.0
    slope = -2 * 0.5 * vehicle.g2_m2 / (0.25 + vehicle.g1_m2) ** 2
    assert vehicle.thrust_ratio_slope(0.5) == pytest.approx(slope, rel=1e-12)
    n_hover = np.sqrt(vehicle.mass_kg * G / (4 * vehicle.k_T_N_per_rpm2 * (1 + f_g)))
    np.testing.assert_allclose(vehicle.hover_speed_rpm(h), n_hover, rtol=1e-12)


def test_shapes_follow_the_input(vehicle):
    assert isinstance(vehicle.thrust_ratio(0.3), float)
    assert vehicle.thrust_ratio(np.zeros((2, 3)) + 0.3).shape == (2, 3)
    assert vehicle.drag_coefficients(np.array([0.1, 5.0])).shape == (2, 2)
    # Above the table the last row (the high-altitude drag) holds.
    np.testing.assert_array_equal(
        vehicle.drag_coefficients(100.0),
        [vehicle.drag_d_x_N_per_mps[-1], vehicle.drag_d_y_N_per_mps[-1]])


def test_rotor_and_throttle_curve(vehicle):
    n = np.array([0.0, 5000.0, 12000.0])
    np.testing.assert_array_equal(vehicle.rotor_thrust_N(n), vehicle.k_T_N_per_rpm2 * n**2)
    c2, c1, c0 = vehicle.throttle_curve_rpm2
    t = np.linspace(0.0, 1.0, 11)
    np.testing.assert_allclose(vehicle.throttle_to_speed_rpm(t), np.sqrt(c2 * t**2 + c1 * t + c0),
                               rtol=1e-14)
    np.testing.assert_allclose(vehicle.speed_to_throttle(vehicle.throttle_to_speed_rpm(t)), t,
                               atol=1e-12)
    lo, hi = vehicle.speed_range_rpm
    assert lo == pytest.approx(math.sqrt(c0)) and hi == pytest.approx(math.sqrt(c2 + c1 + c0))


def test_truth_files(source_dir, vehicle):
    ideal = geaware.load_truth("ideal")
    assert ideal.mass_kg == vehicle.mass_kg and not ideal.varies_per_flight
    np.testing.assert_array_equal(ideal.cog_offset_m, [0, 0, 0])
    as_built = geaware.load_truth("as_built")
    assert as_built.vehicle.mass_kg == vehicle.mass_kg
    assert as_built.inertia_kgm2.shape == (3, 3)
    # Any vehicle file is a truth file: its ideal world.
    from_file = geaware.load_truth(str(source_dir / "config/vehicles/paper_quad.yaml"))
    assert from_file.mass_kg == vehicle.mass_kg
    assert set(geaware.builtin_truth_names()) >= {"ideal", "as_built"}
    with pytest.raises(RuntimeError):
        geaware.load_truth("no_such_world.yaml")


def test_flat_map_hover(vehicle):
    fm = geaware.FlatMap(vehicle)
    h = np.array([0.08, 0.2, 1.0, 3.0])
    z = np.zeros((4, 3))
    p = np.column_stack([np.zeros(4), np.zeros(4), h])
    r = fm.evaluate(p, z, z, z, z, 0.0, 0.0, 0.0, h)
    assert (r["status"] == 0).all() and r["feasible"].all()
    f_g = vehicle.thrust_ratio(h)
    np.testing.assert_allclose(r["thrust_N"], vehicle.mass_kg * G / (1 + f_g), rtol=1e-12)
    np.testing.assert_allclose(r["q_wxyz"], np.tile([1.0, 0, 0, 0], (4, 1)), atol=1e-12)
    np.testing.assert_allclose(r["w_radps"], 0.0, atol=1e-12)
    n_hover = vehicle.hover_speed_rpm(h)
    np.testing.assert_allclose(r["rotor_speeds_rpm"], np.column_stack([n_hover] * 4), rtol=1e-9)
    # Without the additional thrust the map asks for the whole weight.
    plain = geaware.FlatMap(vehicle, additional_thrust=False).evaluate(
        p, z, z, z, z, 0.0, 0.0, 0.0, h)
    np.testing.assert_allclose(plain["thrust_N"], vehicle.mass_kg * G, rtol=1e-12)


def test_flat_map_rows_equal_single_calls(vehicle):
    fm = geaware.FlatMap(vehicle)
    rng = np.random.default_rng(3)
    n = 20
    a = rng.normal(0, 2, (n, 3))
    v = rng.normal(0, 1, (n, 3))
    j = rng.normal(0, 5, (n, 3))
    yaw = rng.uniform(-3, 3, n)
    h = rng.uniform(0.05, 1.5, n)
    batch = fm.evaluate(np.zeros(3), v, a, j, np.zeros(3), yaw, 0.3, 0.0, h)
    for i in (0, 7, 19):
        one = fm.evaluate(np.zeros(3), v[i], a[i], j[i], np.zeros(3), yaw[i], 0.3, 0.0, h[i])
        for key, value in batch.items():
            np.testing.assert_array_equal(value[i], one[key][0])
    bad = fm.evaluate(np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3), np.zeros(3),
                      0.0, 0.0, 0.0, math.nan)
    assert bad["status"][0] == 1
    with pytest.raises(ValueError):
        fm.evaluate(np.zeros((3, 2)), v, a, j, np.zeros(3), yaw, 0.3, 0.0, h)
