# SPDX-License-Identifier: BSD-3-Clause
"""Throughput of geaware.VecSim (docs/python.md): 256 vehicles hovering open loop 1.5 m up
(no strike within the 0.5 s timed), 100 control periods, best of 3, on 1 and 2 threads.
Run: PYTHONPATH=build/python /usr/bin/python3 bench/vecsim_speed.py"""
import time

import numpy as np

import geaware

N, STEPS = 256, 100
for threads in (1, 2):
    sims = geaware.VecSim(N, trajectory="lemniscate", height_m=1.5, speed_mps=1.0, first_seed=1,
                          threads=threads)
    best_wall, cpu = float("inf"), 0.0
    for _ in range(3):
        obs = sims.reset()
        hold = np.array(obs["throttle"])
        t0, c0 = time.perf_counter(), time.process_time()
        for _ in range(STEPS):
            obs = sims.step(hold)
        wall = time.perf_counter() - t0
        if wall < best_wall:
            best_wall, cpu = wall, time.process_time() - c0
    simulated_s = N * STEPS * sims.control_period_s
    print(f"threads {threads}: {simulated_s:.0f} vehicle-seconds in {best_wall * 1e3:.0f} ms wall "
          f"({simulated_s / best_wall:.0f}x real time), {cpu * 1e3:.0f} ms CPU, "
          f"struck {int(obs['crashed'].sum())}")
