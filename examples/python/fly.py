#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""A simulated flight from Python (docs/python.md): the paper's lemniscate 0.15 m above the
ground in the as-built world, flown by the controller without ground-effect compensation, by
the paper's and by geaware's recommended one, seed 1. The same flights as

    geaware fly --trajectory lemniscate --height 0.15 --speed 1 --controller CONTROLLER

Run: PYTHONPATH=build/python /usr/bin/python3 examples/python/fly.py
"""
import numpy as np

import geaware

for controller in ("none:none", "model:model_indi", "recommended"):
    log = geaware.fly(trajectory="lemniscate", height_m=0.15, speed_mps=1.0,
                      controller=controller, seed=1)
    if not log["completed"]:  # a ground strike ends a flight; it is a result, not an error
        print(f"{controller:17s} crashed: {log['crash']}")
        continue
    on = log["in_trajectory"] == 1  # the control ticks of the trajectory
    rmse_cm = 100 * np.sqrt(np.mean(log["err_norm_m"][on] ** 2))
    max_z_cm = 100 * np.max(np.abs(log["err_z_m"][on]))
    print(f"{controller:17s} position RMSE {rmse_cm:5.2f} cm, max |height error| "
          f"{max_z_cm:5.2f} cm, {on.sum()} ticks")
