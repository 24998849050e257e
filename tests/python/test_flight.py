# SPDX-License-Identifier: BSD-3-Clause
"""geaware.fly against the command line's `geaware fly`, the controller replayed on a flight,
and the GIL released while a flight runs."""
import csv
import subprocess
import threading
import time

import numpy as np
import pytest

import geaware

# A short descent into ground effect: 1 s hover, 0.5 m -> 0.15 m at 0.35 m/s.
FLIGHT = dict(trajectory="hover-descent", height_m=0.15, from_height_m=0.5, speed_mps=0.35,
              controller="recommended")
CLI_ARGS = ["--trajectory", "hover-descent", "--height", "0.15", "--from-height", "0.5",
            "--speed", "0.35", "--controller", "recommended"]


def data_lines(path):
    return [line for line in path.read_bytes().splitlines(keepends=True)
            if not line.startswith(b"#")]


@pytest.fixture(scope="module")
def flight(tmp_path_factory):
    out = tmp_path_factory.mktemp("py") / "py.csv"
    return geaware.fly(seed=7, out=str(out), **FLIGHT), out


def test_python_and_cli_flights_give_identical_logs(flight, cli, tmp_path):
    arrays, py_csv = flight
    cli_csv = tmp_path / "cli.csv"
    subprocess.run([cli, "fly", *CLI_ARGS, "--seed", "7", "--out", str(cli_csv), "--quiet"],
                   check=True, capture_output=True)
    cli_lines = data_lines(cli_csv)
    assert len(cli_lines) > 300
    assert data_lines(py_csv) == cli_lines  # byte for byte after the provenance comments
    # The arrays are the log's values: times exact, every other column as the float32 the log
    # writes.
    rows = list(csv.reader(line.decode() for line in cli_lines))
    header, body = rows[0], np.array(rows[1:], dtype=np.float64)
    assert len(arrays["t_s"]) == len(body)
    for j, name in enumerate(header):
        column = arrays[name]
        if name in ("t_s", "t_traj_s"):
            np.testing.assert_array_equal(column, body[:, j], err_msg=name)
        else:
            np.testing.assert_array_equal(column.astype(np.float32), body[:, j].astype(np.float32),
                                          err_msg=name)
    assert arrays["completed"] and arrays["crash"] == ""


def test_same_seed_same_flight_other_seed_another(flight):
    arrays, _ = flight
    again = geaware.fly(seed=7, **FLIGHT)
    other = geaware.fly(seed=8, **FLIGHT)
    np.testing.assert_array_equal(again["true_z_m"], arrays["true_z_m"])
    assert not np.array_equal(other["true_z_m"], arrays["true_z_m"])


def test_columns_are_views_of_one_array(flight):
    arrays, _ = flight
    t = arrays["t_s"]
    assert t.base is not None and t.base is arrays["true_z_m"].base
    assert not t.flags.owndata


def test_controller_replayed_on_the_flight_gives_its_throttles(flight):
    """geaware.Controller fed what the flight's controller was given returns its throttles."""
    d, _ = flight
    c = geaware.Controller(geaware.builtin_vehicle(), "recommended")
    active = np.flatnonzero(d["controller_active"] == 1)
    assert len(active) > 300
    v3 = lambda prefix, suffix, i: [d[f"{prefix}{a}{suffix}"][i] for a in "xyz"]  # noqa: E731
    for i in active:
        t = c.update(
            d["t_s"][i], v3("est_", "_m", i), v3("est_v", "_mps", i),
            [d[f"est_q{a}"][i] for a in "wxyz"], v3("gyro_", "_radps", i),
            v3("accel_", "_mps2", i), d["h_meas_m"][i],
            [d[f"n_meas_{k}_rpm"][i] for k in range(1, 5)],
            v3("ref_", "_m", i), v3("ref_v", "_mps", i), v3("ref_a", "_mps2", i),
            v3("ref_j", "_mps3", i), v3("ref_s", "_mps4", i), d["ref_yaw_rad"][i],
            d["ref_yaw_rate_radps"][i], d["ref_yaw_accel_radps2"][i],
            height_valid=bool(d["h_meas_valid"][i]), battery_voltage_V=d["battery_V"][i])
        expected = [d[f"throttle_{k}"][i] for k in range(1, 5)]
        np.testing.assert_array_equal(t, expected, err_msg=f"tick {i}")


def test_gil_is_released_while_flying():
    """Another Python thread runs in the middle of a flight (with the GIL held it could run only
    just before the call or after it)."""
    stamps = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            stamps.append(time.perf_counter())
            time.sleep(0.001)

    thread = threading.Thread(target=tick)
    thread.start()
    try:
        t0 = time.perf_counter()
        # Ten laps: long enough (≈ 0.4 s here) on a fast, idle machine too.
        geaware.fly(trajectory="lemniscate", height_m=0.5, speed_mps=1.0, laps=10,
                    controller="recommended", seed=1)
        t1 = time.perf_counter()
    finally:
        stop.set()
        thread.join()
    quarter = (t1 - t0) / 4
    assert t1 - t0 > 0.05  # long against the interpreter's 5 ms switch interval
    assert any(t0 + quarter < t < t1 - quarter for t in stamps)


def test_bad_flights_are_refused_before_flying(tmp_path, source_dir):
    with pytest.raises(ValueError, match="trajectory"):
        geaware.fly(height_m=0.3, controller="recommended")
    with pytest.raises(ValueError, match="controller 'fast'"):
        geaware.fly(**{**FLIGHT, "controller": "fast"})
    # An input is never overwritten by the log.
    vehicle = tmp_path / "vehicle.yaml"
    vehicle.write_bytes((source_dir / "config/vehicles/paper_quad.yaml").read_bytes())
    before = vehicle.read_bytes()
    with pytest.raises(Exception, match="out"):
        geaware.fly(vehicle=str(vehicle), out=str(vehicle), **FLIGHT)
    assert vehicle.read_bytes() == before
