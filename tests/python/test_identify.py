# SPDX-License-Identifier: BSD-3-Clause
"""geaware.identify_hover and identify_flight on arrays and on the same log as a file."""
import numpy as np
import pytest

import geaware


@pytest.fixture(scope="module")
def descent(tmp_path_factory):
    out = tmp_path_factory.mktemp("ident") / "descent.csv"
    log = geaware.fly(trajectory="hover-descent", from_height_m=0.6, height_m=0.1,
                      speed_mps=0.1, controller="recommended", truth="ideal", seed=2, out=str(out))
    rows = log["controller_active"] == 1
    arrays = {k: v[rows] for k, v in log.items() if isinstance(v, np.ndarray)}
    return arrays, out


def test_hover_on_arrays_finds_the_ideal_worlds_k_T(descent):
    arrays, _ = descent
    vehicle = geaware.builtin_vehicle()
    r = geaware.identify_hover(arrays, vehicle)
    assert r["kind"] == "hover"
    k_T = next(p for name, p in r["parameters"].items() if name.endswith("k_T_N_per_rpm2"))
    # The ideal world flies the vehicle file's k_T out of ground effect.
    assert k_T["value"] == pytest.approx(vehicle.k_T_N_per_rpm2, rel=0.05)
    assert 0 < k_T["std_error"] < 0.05 * k_T["value"]


def test_arrays_and_file_agree(descent):
    arrays, csv_file = descent
    vehicle = geaware.builtin_vehicle()
    from_arrays = geaware.identify_hover(arrays, vehicle)
    from_file = geaware.identify_hover(str(csv_file), vehicle)
    assert from_arrays["parameters"].keys() == from_file["parameters"].keys()
    for name, p in from_arrays["parameters"].items():
        # The file holds float32 values and the ticks before the controller started.
        assert from_file["parameters"][name]["value"] == pytest.approx(p["value"], rel=0.02), name


def test_missing_column_is_named(descent):
    arrays = dict(descent[0])
    del arrays["az_ext_mps2"]
    with pytest.raises(ValueError, match="az_ext_mps2"):
        geaware.identify_hover(arrays, geaware.builtin_vehicle())
    with pytest.raises(ValueError, match="loss|robust|huber"):
        geaware.identify_flight(arrays, geaware.builtin_vehicle(), robust="square")
