# SPDX-License-Identifier: BSD-3-Clause
"""geaware.Controller: a level hover in closed form, bad inputs, bad configurations."""
import math

import numpy as np
import pytest

import geaware

G = 9.81


@pytest.fixture(scope="module")
def vehicle():
    return geaware.builtin_vehicle()


def hover_inputs(vehicle, h, ground_effect=True):
    n = (vehicle.hover_speed_rpm(h) if ground_effect
         else math.sqrt(vehicle.mass_kg * G / (4 * vehicle.k_T_N_per_rpm2)))
    return dict(position_m=[0.0, 0.0, h], velocity_mps=np.zeros(3), attitude_wxyz=[1, 0, 0, 0],
                gyro_radps=np.zeros(3), accel_mps2=[0.0, 0.0, G], height_m=h,
                rotor_speeds_rpm=np.full(4, n), ref_position_m=[0.0, 0.0, h])


@pytest.mark.parametrize("configuration", ["model:model_indi", "none:none", "recommended"])
def test_level_hover_gives_the_hover_throttle(vehicle, configuration):
    c = geaware.Controller(vehicle, configuration)
    assert c.rate_hz == 200.0 and c.configuration == configuration
    for h in (0.1, 1.0):
        c.reset()
        x = hover_inputs(vehicle, h, ground_effect=configuration != "none:none")
        for k in range(20):
            t = c.update(k / c.rate_hz, **x)
        assert t.shape == (4,) and t.dtype == np.float64
        out = c.output()
        np.testing.assert_array_equal(out["throttle"], t)
        # In ground effect the model asks for less thrust: m g/(1 + F_G(h)).
        thrust = vehicle.mass_kg * G / (1 + vehicle.thrust_ratio(h))
        if configuration != "none:none":
            assert out["thrust_N"] == pytest.approx(thrust, rel=1e-6)
        else:
            assert out["thrust_N"] == pytest.approx(vehicle.mass_kg * G, rel=1e-6)
        np.testing.assert_allclose(out["torque_Nm"], 0.0, atol=1e-9)
        n = math.sqrt(out["thrust_N"] / (4 * vehicle.k_T_N_per_rpm2))
        np.testing.assert_allclose(t, vehicle.speed_to_throttle(n), atol=2e-3)
        assert out["flags"] & 1 == 0


def test_non_finite_input_holds_a_hover_and_flags_it(vehicle):
    c = geaware.Controller(vehicle, "model:model_indi")
    x = hover_inputs(vehicle, 0.5)
    x["velocity_mps"] = [math.nan, 0.0, 0.0]
    t = c.update(0.0, **x)
    assert np.isfinite(t).all() and (t > 0).all()
    assert c.output()["flags"] & 1  # non-finite input


def test_bad_arguments(vehicle, tmp_path):
    with pytest.raises(ValueError, match="configuration 'fast'"):
        geaware.Controller(vehicle, "fast")
    with pytest.raises(ValueError, match="neural"):
        geaware.Controller(vehicle, "neural:model")
    with pytest.raises(ValueError, match="rate"):
        geaware.Controller(vehicle, "recommended", rate_hz=-5.0)
    bad = tmp_path / "params.yaml"
    bad.write_text("format_version: 1\n")
    with pytest.raises(geaware.ConfigError, match="params.yaml"):
        geaware.Controller(vehicle, "recommended", controller_params_file=str(bad))
    c = geaware.Controller(vehicle)
    x = hover_inputs(vehicle, 0.5)
    x["rotor_speeds_rpm"] = [1.0, 2.0, 3.0]
    with pytest.raises(ValueError, match="rotor_speeds_rpm"):
        c.update(0.0, **x)


def test_controller_params_file(vehicle, source_dir):
    f = source_dir / "config/controller-params/default.yaml"
    c = geaware.Controller(vehicle, "model:model_indi", controller_params_file=str(f), rate_hz=400)
    assert c.rate_hz == 400.0
