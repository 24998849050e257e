#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Identification from Python (docs/python.md): a simulated hover descent into ground effect on
the as-built world, then k_T and F_G(h) = g2/(h^2 + g1) identified from its log (paper
eq. 10), as `geaware identify hover` does from a CSV file, next to the vehicle file's values.

Run: PYTHONPATH=build/python /usr/bin/python3 examples/python/identify.py
"""
import numpy as np

import geaware

vehicle = geaware.builtin_vehicle()
log = geaware.fly(trajectory="hover-descent", from_height_m=0.6, height_m=0.1, speed_mps=0.05,
                  controller="recommended", truth="as_built", seed=3)
# The ticks where the controller flew (rotor telemetry and the estimate exist).
rows = log["controller_active"] == 1
hover_log = {name: column[rows] for name, column in log.items() if isinstance(column, np.ndarray)}
result = geaware.identify_hover(hover_log, vehicle)
file_values = {"k_T_N_per_rpm2": vehicle.k_T_N_per_rpm2, "g1_m2": vehicle.g1_m2,
               "g2_m2": vehicle.g2_m2}
print(f"{rows.sum()} samples, {log['h_m'][rows].min():.3f} to {log['h_m'][rows].max():.3f} m")
for name, p in result["parameters"].items():
    known = file_values.get(name.split(".")[-1])
    note = f" (vehicle file {known:.4g})" if known is not None else ""
    print(f"{name:40s} {p['value']:.4g} ± {p['std_error']:.2g} {p['unit']}{note}")
for warning in result["warnings"]:
    print("warning:", warning)
