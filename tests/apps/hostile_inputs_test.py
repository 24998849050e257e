#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The kinds of issue 16's sweep of careless and hostile inputs, re-run on every command.

Usage: hostile_inputs_test.py GEAWARE_BINARY SOURCE_DIR

Every case must be refused (exit 1 or 2) within 10 s with a message on stderr, and no file in
the scratch directory may change, appear or disappear (the user's inputs, existing outputs, a
hard link, a symlink, a FIFO). Prints one line per failing case and a summary:
"N hostile cases: 0 files lost, 0 hangs, 0 accepted".
"""

import hashlib
import json
import os
import shutil
import subprocess
import sys
import tempfile

GEAWARE, SOURCE = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
FLY = ["fly", "--quiet", "--trajectory", "lemniscate", "--height", "1", "--speed", "1",
       "--controller", "model:model_indi"]


def snapshot(d):
    out = {}
    for name in sorted(os.listdir(d)):
        p = os.path.join(d, name)
        if os.path.islink(p):
            out[name] = "link->" + os.readlink(p)
        elif os.path.isfile(p) and os.path.getsize(p) > 10_000_000:  # the sparse 300 MB inputs
            st = os.stat(p)
            out[name] = f"size {st.st_size} mtime {st.st_mtime_ns} inode {st.st_ino}"
        elif os.path.isfile(p):
            with open(p, "rb") as f:
                out[name] = hashlib.sha256(f.read()).hexdigest()
        else:
            out[name] = "special"
    return out


def edited(path, old, new):
    with open(path) as f:
        text = f.read()
    assert old in text, (path, old)
    return text.replace(old, new, 1)


def cases():
    c = []
    # An output that is an input: every command, every output option, by name, other name,
    # hard link and symlink.
    for out in ["vehicle.yaml", "./vehicle.yaml", "hard.yaml", "link.yaml"]:
        c += [FLY + ["--vehicle", "vehicle.yaml", "--out", out],
              FLY + ["--vehicle", "vehicle.yaml", "--json", out],
              FLY + ["--truth", "vehicle.yaml", "--json", out],
              ["model", "--vehicle", "vehicle.yaml", "--json", out],
              ["identify", "rotor", "rotor.csv", "--vehicle", "vehicle.yaml", "--out", out],
              ["identify", "rotor", "rotor.csv", "--vehicle", "vehicle.yaml", "--json", out],
              ["rig", "rotor", "--truth", "vehicle.yaml", "--out", out],
              ["rig", "platform", "--truth", "vehicle.yaml", "--heights", "0.1", "--rpm", "8000", "--out", out],
              ["rig", "calibrate", "--truth", "vehicle.yaml", "--json", out],
              ["bench", "--quiet", "--vehicle", "vehicle.yaml", "--json", out]]
    for opt in ["--out", "--json"]:
        c += [["fly", "--quiet", "--scenario", "scenario.yaml", opt, "scenario.yaml"],
              ["fly", "--quiet", "--scenario", "scenario_v.yaml", opt, "vehicle.yaml"],
              ["identify", "rotor", "rotor.csv", opt, "rotor.csv"],
              ["identify", "platform", "rotor.csv", opt, "rotor.csv"],
              ["identify", "flight", "rotor.csv", opt, "rotor.csv"]]
    # Two outputs on one file; special files and directories as outputs.
    c += [FLY + ["--out", "x.csv", "--json", "x.csv"],
          ["identify", "rotor", "rotor.csv", "--out", "a.yaml", "--json", "a.yaml"]]
    for bad in ["/dev/full", "/dev/null", "fifo", "dir", "missing/x", "dangling"]:
        c += [FLY + ["--out", bad], FLY + ["--json", bad], ["model", "--json", bad],
              ["identify", "rotor", "rotor.csv", "--json", bad], ["rig", "rotor", "--out", bad],
              ["rig", "calibrate", "--json", bad], ["bench", "--quiet", "--json", bad]]
    for opt in ["--report"]:
        c += [FLY + [opt, "vehicle.yaml"], ["identify", "rotor", "rotor.csv", opt, "rotor.csv"],
              ["rig", "calibrate", opt, "vehicle.yaml"], ["bench", "--quiet", opt, "vehicle.yaml"]]
    c += [["bench", "--quiet", "--cache", "vehicle.yaml"]]
    # Refused runs over existing outputs.
    c += [["fly", "--quiet", "--trajectory", "lemniscate", "--height", "0.12", "--speed", "6",
           "--controller", "model:model_indi", "--out", "existing.csv", "--json", "existing.json"],
          ["rig", "rotor", "--throttle", "0:2:0.5", "--out", "existing.csv"],
          ["identify", "rotor", "vehicle.yaml", "--out", "existing.yaml", "--json", "existing.json"]]
    # Hangs: long flights, endless or huge inputs.
    c += [["fly", "--quiet", "--trajectory", "lemniscate", "--height", "1", "--speed", "1e-9",
           "--controller", "model:model_indi"],
          FLY + ["--start-hover", "1e9"],
          ["fly", "--quiet", "--scenario", "far.yaml"],
          ["identify", "rotor", "/dev/zero"], ["identify", "flight", "huge.csv", "--mass-kg", "1.0"],
          ["fly", "--quiet", "--scenario", "/dev/zero"], FLY + ["--vehicle", "/dev/zero"],
          FLY + ["--vehicle", "huge.yaml"]]
    # Numbers: NaN, infinities, negatives, overflow, junk — options and file values.
    for opt, values in [("--seed", ["-1", "18446744073709551616", "1.5", "nan"]),
                        ("--height", ["nan", "inf", "-1", "0", "1e999"]),
                        ("--speed", ["nan", "-inf", "-2"]),
                        ("--start-hover", ["-1", "nan"]), ("--max-sim-s", ["nan", "0", "-5"]),
                        ("--yaw-rate-gain", ["inf", "0"]), ("--laps", ["0", "1e3", "-1"]),
                        ("--extent-x", ["nan"]), ("--from-height", ["inf"])]:
        for v in values:
            args = list(FLY)
            if opt in args:
                args[args.index(opt) + 1] = v
            else:
                args += [opt, v]
            c.append(args)
    c += [["identify", "platform", "rotor.csv", "--tilt-limit", v] for v in ["nan", "inf", "-5", "95"]]
    c += [["identify", "platform", "rotor.csv", "--height-bands", "0"],
          ["identify", "platform", "rotor.csv", "--table-top", "nan"],
          ["bench", "--quiet", "--seeds", "0"], ["bench", "--quiet", "--first-seed", "-1"],
          ["bench", "--quiet", "--first-seed", "18446744073709551615", "--seeds", "2"],
          ["bench", "--quiet", "--jobs", "-1"],
          ["rig", "rotor", "--hold", "nan", "--out", "y.csv"],
          ["rig", "rotor", "--sample-period", "-1", "--out", "y.csv"],
          ["rig", "rotor", "--seed", "-1", "--out", "y.csv"],
          ["rig", "rotor", "--throttle", "0:nan:0.1", "--out", "y.csv"],
          ["rig", "platform", "--heights", "0.1:inf:0.1", "--rpm", "8000", "--out", "y.csv"],
          ["rig", "platform", "--heights", "0.1", "--rpm", "8000", "--samples", "0", "--out", "y.csv"],
          ["rig", "platform", "--heights", "0.1", "--rpm", "8000", "--force-noise", "nan", "--out", "y.csv"],
          ["model", "--heights", "nan:1:0.1"], ["model", "--heights", "0.1:1:0"]]
    c += [["fly", "--quiet", "--scenario", name] for name in
          ["nan_wind.yaml", "inf_gust.yaml", "inf_terrain.yaml", "nan_yaw.yaml", "neg_speed.yaml",
           "fast_waypoints.yaml"]]
    c += [FLY + ["--vehicle", name] for name in ["nan_vehicle.yaml", "inf_vehicle.yaml"]]
    c += [FLY + ["--truth", "nan_truth.yaml"]]
    # Sweeps: a directory holding someone's results.json (here the sweep file itself), a name
    # that is not UTF-8; the learned vehicle file over an input, into a missing directory, to stdout.
    c += [["sweep", "sweep.yaml", "--out", ".", "--quiet"], ["sweep", "results.json", "--out", ".", "--quiet"],
          ["sweep", "latin1.yaml", "--out", "new-sweep", "--quiet"],
          ["bench", "--quiet", "--suite", "faults", "--sweep", "latin1.yaml"]]
    learn = [a if a != "model:model_indi" else "model:model_indi+learn" for a in FLY]
    c += [learn + ["--vehicle", "vehicle.yaml", "--learned-vehicle", out] for out in ["vehicle.yaml", "link.yaml"]]
    c += [learn + ["--learned-vehicle", out] for out in ["-", "missing/x.yaml", "dir"]]
    return c


def setup(d):
    shutil.copy(os.path.join(SOURCE, "config/vehicles/paper_quad.yaml"), os.path.join(d, "vehicle.yaml"))
    scenario = os.path.join(SOURCE, "config/scenarios/lemniscate_low.yaml")
    shutil.copy(scenario, os.path.join(d, "scenario.yaml"))

    def w(name, text):
        with open(os.path.join(d, name), "w") as f:
            f.write(text)

    w("scenario_v.yaml", edited(scenario, "vehicle: builtin", "vehicle: vehicle.yaml"))
    w("nan_wind.yaml", edited(scenario, "wind_mps: [0.0, 0.0, 0.0]", "wind_mps: [.nan, 0.0, 0.0]"))
    w("inf_gust.yaml", edited(scenario, "gust_std_mps: [0.0, 0.0, 0.0]", "gust_std_mps: [0.0, .inf, 0.0]"))
    w("inf_terrain.yaml", edited(scenario, "  height_m: 0.0", "  height_m: .inf"))
    w("nan_yaw.yaml", edited(scenario, "yaw_deg: 0.0", "yaw_deg: .nan"))
    w("neg_speed.yaml", edited(scenario, "peak_speed_mps: 1.0", "peak_speed_mps: -1.0"))
    text = open(scenario).read()
    a, b = text.index("trajectory:"), text.index("controller:")
    w("far.yaml", text[:a] + "trajectory:\n  type: waypoints\n  points_m: [[0, 0, 1], [10000000, 0, 1]]\n"
      "  average_speed_mps: 1.0\n  yaw_deg: 0.0\n\n" + text[b:])
    w("fast_waypoints.yaml", text[:a] + "trajectory:\n  type: waypoints\n  points_m: [[0, 0, 1], [1, 0, 1]]\n"
      "  average_speed_mps: 3.0\n  yaw_deg: 0.0\n\n" + text[b:])
    vehicle = os.path.join(d, "vehicle.yaml")
    w("nan_vehicle.yaml", edited(vehicle, "mass_kg: 1.696", "mass_kg: .nan"))
    w("inf_vehicle.yaml", edited(vehicle, "k_T_N_per_rpm2: 4.0083e-8", "k_T_N_per_rpm2: .inf"))
    w("nan_truth.yaml", open(vehicle).read() + "truth:\n  motor:\n    time_constant_s: .nan\n")
    sweep = open(os.path.join(SOURCE, "tests/sweep/suites/faults_small.yaml")).read()
    w("sweep.yaml", sweep.replace("calibrate: true", "calibrate: false"))
    w("results.json", sweep.replace("calibrate: true", "calibrate: false"))
    with open(os.path.join(d, "latin1.yaml"), "wb") as f:
        f.write(sweep.replace("fault: motor 80%", "{fault: motor 80%, name: mot\xe9ur}").encode("latin-1"))
    w("existing.csv", "precious\n")
    w("existing.json", json.dumps({"precious": True}) + "\n")
    w("existing.yaml", "precious: true\n")
    subprocess.run([GEAWARE, "rig", "rotor", "--out", "rotor.csv"], cwd=d, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.link(vehicle, os.path.join(d, "hard.yaml"))
    os.symlink("vehicle.yaml", os.path.join(d, "link.yaml"))
    os.symlink("missing.yaml", os.path.join(d, "dangling"))
    os.mkfifo(os.path.join(d, "fifo"))
    os.mkdir(os.path.join(d, "dir"))
    for name, head in [("huge.csv", "t_s,h_m\n"), ("huge.yaml", "a: ")]:
        with open(os.path.join(d, name), "w") as f:
            f.write(head)
        os.truncate(os.path.join(d, name), 300_000_000)


def main():
    d = tempfile.mkdtemp(prefix="geaware_hostile_")
    try:
        setup(d)
        before = snapshot(d)
        all_cases = cases()
        lost = hangs = accepted = 0
        for args in all_cases:
            shown = "geaware " + " ".join(args)
            try:
                r = subprocess.run([GEAWARE] + args, cwd=d, capture_output=True, text=True,
                                   errors="replace", timeout=10)
            except subprocess.TimeoutExpired:
                hangs += 1
                print(f"HANG (> 10 s): {shown}")
                continue
            if r.returncode not in (1, 2) or not r.stderr.strip():
                accepted += 1
                print(f"NOT REFUSED (exit {r.returncode}): {shown}\n{r.stderr[-500:]}")
            if len(r.stderr) > 4000:
                accepted += 1
                print(f"MESSAGE OF {len(r.stderr)} BYTES: {shown}")
            after = snapshot(d)
            if after != before:
                lost += 1
                changed = sorted(k for k in set(before) | set(after) if before.get(k) != after.get(k))
                print(f"FILES CHANGED {changed}: {shown}")
                for k in changed:  # restore for the next cases
                    p = os.path.join(d, k)
                    if k not in before and os.path.lexists(p):
                        os.remove(p) if not os.path.isdir(p) or os.path.islink(p) else shutil.rmtree(p)
                before = snapshot(d)
        print(f"{len(all_cases)} hostile cases: {lost} files lost, {hangs} hangs, {accepted} accepted")
        return 0 if lost == hangs == accepted == 0 else 1
    finally:
        shutil.rmtree(d, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
