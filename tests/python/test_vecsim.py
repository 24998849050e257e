# SPDX-License-Identifier: BSD-3-Clause
"""geaware.Sim and geaware.VecSim: the truth side of a flight stepped from Python.

Oracles: the in-process flight (geaware.fly, the C++ runner) — fed the throttles that flight
commanded, Sim gives its true state bit for bit; a lone Sim — vehicle i of a batch gives what
a Sim with its seed gives, whatever the thread count."""
import numpy as np
import pytest

import geaware

WORLD = dict(trajectory="lemniscate", height_m=0.3, speed_mps=1.0)


def fields_equal(a, b, which=None):
    for name in (which or a):
        np.testing.assert_array_equal(np.asarray(a[name]), np.asarray(b[name]), err_msg=name)


def test_fed_the_flights_throttles_sim_gives_the_flights_truth_bit_for_bit():
    f = geaware.fly(**WORLD, controller="recommended", seed=5)
    assert f["completed"], f["crash"]
    throttles = np.stack([f[f"throttle_{i}"] for i in range(1, 5)], axis=1)
    truth = np.stack([f["true_x_m"], f["true_y_m"], f["true_z_m"]], axis=1)
    attitude = np.stack([f["true_qw"], f["true_qx"], f["true_qy"], f["true_qz"]], axis=1)
    rotors = np.stack([f[f"n_true_{i}_rpm"] for i in range(1, 5)], axis=1)
    sim = geaware.Sim(**WORLD, controller="recommended", seed=5)
    o = sim.reset()
    ticks = len(throttles)
    assert ticks > 1000
    for k in range(ticks):
        assert o["t_s"] == f["t_s"][k]
        np.testing.assert_array_equal(o["true_p_W_m"], truth[k], err_msg=f"tick {k}")
        np.testing.assert_array_equal(o["true_q_WB"], attitude[k], err_msg=f"tick {k}")
        np.testing.assert_array_equal(o["true_n_rpm"], rotors[k], err_msg=f"tick {k}")
        assert o["true_height_m"] == f["h_true_m"][k]
        assert o["ref_p_W_m"][2] == f["ref_z_m"][k]
        assert not o["done"], k
        o = sim.step(throttles[k])
    # The flight ends between two ticks (its duration is not a whole number of ticks): the
    # last step stops there and says done.
    assert o["done"] and not o["crashed"]
    assert f["t_s"][-1] < o["t_s"] <= f["t_s"][-1] + sim.control_period_s
    r = sim.result()
    assert r["completed"] and r["crash"] == ""
    assert r["control_ticks"] == ticks


def random_throttles(rng, n, hover, steps):
    return [np.clip(hover + 0.02 * rng.standard_normal((n, 4)), 0.0, 1.0) for _ in range(steps)]


def test_vehicle_i_of_a_batch_is_a_lone_sim_with_its_seed():
    seeds = [3, 9, 27, 81]
    batch = geaware.VecSim(len(seeds), **WORLD, seeds=seeds, threads=2)
    ob = batch.reset()
    lone = [geaware.Sim(**WORLD, seed=s) for s in seeds]
    ol = [s.reset() for s in lone]
    actions = random_throttles(np.random.default_rng(1), len(seeds), ob["throttle"][0], 120)
    for a in actions:
        ob = batch.step(a)
        ol = [s.step(a[i]) for i, s in enumerate(lone)]
    for i in range(len(seeds)):
        row = {name: ob[name][i] for name in ob}
        fields_equal(row, ol[i])
    # Different seeds fly differently (the noise and turbulence streams are the vehicle's own).
    assert not np.array_equal(ob["imu_gyro_B_radps"][0], ob["imu_gyro_B_radps"][1])


def test_the_thread_count_changes_nothing():
    runs = []
    for threads in (1, 2, 5):
        v = geaware.VecSim(5, **WORLD, first_seed=7, threads=threads)
        assert v.threads == threads
        ob = v.reset()
        for a in random_throttles(np.random.default_rng(2), 5, ob["throttle"][0], 80):
            ob = v.step(a)
        runs.append(ob)
    fields_equal(runs[0], runs[1])
    fields_equal(runs[0], runs[2])


def test_reset_restarts_only_the_vehicles_named_with_their_new_seeds():
    v = geaware.VecSim(3, **WORLD, first_seed=1)
    ob = v.reset()
    hover = ob["throttle"][0]
    for _ in range(50):
        ob = v.step(np.tile(hover, (3, 1)))
    before = {name: np.array(ob[name]) for name in ob}
    ob = v.reset(seeds=[42], which=[1])
    assert v.seeds == [1, 42, 3]
    fresh = geaware.Sim(**WORLD, seed=42).reset()
    fields_equal({name: ob[name][1] for name in ob}, fresh)
    for i in (0, 2):
        fields_equal({name: ob[name][i] for name in ob}, {name: before[name][i] for name in before})


def test_a_struck_vehicle_is_done_and_keeps_its_last_observation():
    v = geaware.VecSim(2, **WORLD, first_seed=1)
    ob = v.reset()
    cut = np.array([[0.0] * 4, ob["throttle"][1]])
    for _ in range(400):
        ob = v.step(cut)
        if ob["done"][0]:
            break
    assert ob["done"][0] and ob["crashed"][0]
    assert not ob["done"][1]
    assert ob["true_height_m"][0] < 0.1  # the landing gear's feet are below the rotor plane
    frozen = np.array(ob["true_p_W_m"][0])
    t_other = ob["t_s"][1]
    ob = v.step(cut)
    np.testing.assert_array_equal(ob["true_p_W_m"][0], frozen)
    assert ob["t_s"][1] == pytest.approx(t_other + v.control_period_s)
    r = v.result(0)
    assert not r["completed"] and "struck" in r["crash"]


def test_the_observation_holds_what_the_sensors_saw():
    sim = geaware.Sim(**WORLD, seed=2)
    o = sim.reset()
    names = [f.name for f in sim.fields]
    assert names[:3] == ["t_s", "t_traj_s", "true_p_W_m"]
    assert set(names) <= set(o)
    hover = o["throttle"]
    for _ in range(40):  # 0.2 s: every sensor has delivered
        o = sim.step(hover)
    for name in ("imu_t_s", "mocap_t_s", "rotor_t_s", "ranger_t_s"):
        assert np.isfinite(o[name]) and o[name] <= o["t_s"], name
    # Motion capture: the true pose within millimetres, captured before now (latency).
    assert np.linalg.norm(o["mocap_p_W_m"] - o["true_p_W_m"]) < 0.01
    assert o["mocap_t_s"] < o["t_s"]
    # The lattice ranger looks down from ~0.3 m: the zones near the centre see the floor there.
    ranges = o["ranger_range_m"]
    assert ranges.shape == (256,)
    centre = ranges[[7 * 16 + 7, 7 * 16 + 8, 8 * 16 + 7, 8 * 16 + 8]]
    assert np.all(np.abs(centre - o["true_height_m"]) < 0.05), (centre, o["true_height_m"])


def test_bad_arguments_are_errors_naming_what_is_wrong():
    with pytest.raises(ValueError, match="n = 0"):
        geaware.VecSim(0, **WORLD)
    with pytest.raises(TypeError, match="unexpected argument 'hieght_m'"):
        geaware.Sim(trajectory="lemniscate", hieght_m=0.3, speed_mps=1.0)
    with pytest.raises(ValueError, match="3 seeds for 2 vehicles"):
        geaware.VecSim(2, **WORLD, seeds=[1, 2, 3])
    with pytest.raises(ValueError, match="-1 is not in"):
        geaware.VecSim(1, **WORLD, seeds=[-1])
    v = geaware.VecSim(2, **WORLD)
    with pytest.raises(ValueError, match="throttles"):
        v.step(np.zeros((3, 4)))
    bad = np.full((2, 4), 0.5)
    bad[1, 2] = np.nan
    with pytest.raises(ValueError, match="vehicle 1, motor 3 is not finite"):
        v.step(bad)
    with pytest.raises(IndexError):
        v.reset(which=[2])
    with pytest.raises(ValueError, match="trajectory"):
        geaware.Sim(height_m=0.3)
