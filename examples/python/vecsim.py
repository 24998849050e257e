# SPDX-License-Identifier: BSD-3-Clause
"""Eight vehicles at once: geaware.VecSim steps a batch of simulated vehicles (the as-built
world, each with its own seed) with throttles from Python. Here each is flown by the C++
controller (`recommended`) behind a state estimate made in Python from the observations alone —
motion-capture position differenced and low-passed for velocity, the median of the ranger's
four centre zones for height — where `geaware fly` uses its error-state Kalman filter.
Vehicle i gives what a lone geaware.Sim with its seed gives, whatever the number of threads."""
import numpy as np

import geaware

n = 8
sims = geaware.VecSim(n, trajectory="lemniscate", height_m=0.3, speed_mps=1.0, first_seed=1)
obs = sims.reset()
controllers = [geaware.Controller(geaware.builtin_vehicle(), "recommended") for _ in range(n)]
centre = [7 * 16 + 7, 7 * 16 + 8, 8 * 16 + 7, 8 * 16 + 8]  # zones (i, j) at i * 16 + j
position = obs["true_p_W_m"].copy()  # where the vehicle was put down: known at the start
velocity = np.zeros((n, 3))
pose_t = np.full(n, np.nan)
height = position[:, 2].copy()
steps = 0
while not obs["done"].all():
    throttles = np.empty((n, 4))
    for i in range(n):
        if np.isfinite(obs["mocap_t_s"][i]) and obs["mocap_t_s"][i] != pose_t[i]:  # a new pose
            if np.isfinite(pose_t[i]):
                v = (obs["mocap_p_W_m"][i] - position[i]) / (obs["mocap_t_s"][i] - pose_t[i])
                velocity[i] += 0.3 * (v - velocity[i])
            position[i] = obs["mocap_p_W_m"][i]
            pose_t[i] = obs["mocap_t_s"][i]
        zones = obs["ranger_range_m"][i][centre]
        if np.isfinite(zones).any():
            height[i] = np.nanmedian(zones)
        have_pose = np.isfinite(pose_t[i])
        throttles[i] = controllers[i].update(
            obs["t_s"][i], position[i], velocity[i],
            obs["mocap_q_WB"][i] if have_pose else [1.0, 0.0, 0.0, 0.0],
            obs["imu_gyro_B_radps"][i], obs["imu_accel_B_mps2"][i], height[i],
            obs["rotor_n_rpm"][i],
            obs["ref_p_W_m"][i], ref_velocity_mps=obs["ref_v_W_mps"][i],
            ref_accel_mps2=obs["ref_a_W_mps2"][i], ref_yaw_rad=obs["ref_yaw_rad"][i],
            battery_voltage_V=obs["battery_V"][i])
    obs = sims.step(throttles)
    steps += 1
results = [sims.result(i) for i in range(n)]
print(f"{n} vehicles, {steps} steps of {sims.control_period_s * 1e3:.0f} ms, "
      f"struck: {int(obs['crashed'].sum())}")
print("position RMSE [cm]:", " ".join(f"{r['rmse_all_m'] * 100:.2f}" for r in results))
