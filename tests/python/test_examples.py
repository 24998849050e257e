# SPDX-License-Identifier: BSD-3-Clause
"""The examples of examples/python/ run and print what docs/python.md shows."""
import re
import subprocess
import sys


def run(source_dir, name):
    done = subprocess.run([sys.executable, str(source_dir / "examples/python" / name)],
                          check=True, capture_output=True, text=True, timeout=300)
    return done.stdout.splitlines()


def test_fly_example(source_dir, cli):
    lines = run(source_dir, "fly.py")
    assert [line.split()[0] for line in lines] == ["none:none", "model:model_indi", "recommended"]
    for line in lines:
        controller = line.split()[0]
        # The command line says the same of the same flight.
        cli_out = subprocess.run(
            [cli, "fly", "--trajectory", "lemniscate", "--height", "0.15", "--speed", "1",
             "--controller", controller, "--seed", "1", "--quiet"],
            check=True, capture_output=True, text=True).stdout
        if "crashed:" in line:
            assert line.split("crashed: ")[1] in cli_out
            continue
        m = re.match(r"\S+\s+position RMSE\s+([0-9.]+) cm, max \|height error\| +[0-9.]+ cm, "
                     r"(\d+) ticks$", line)
        assert m, line
        assert f"all {m.group(1).strip()} cm" in cli_out and f"({m.group(2)} samples)" in cli_out, \
            cli_out


def test_identify_example(source_dir):
    lines = run(source_dir, "identify.py")
    assert re.match(r"\d+ samples, 0\.\d+ to 0\.\d+ m$", lines[0]), lines[0]
    assert any(re.search(r"k_T_N_per_rpm2\s+\S+ ± \S+ N/rpm", line) for line in lines), lines



def test_vecsim_example(source_dir):
    lines = run(source_dir, "vecsim.py")
    assert lines[0] == "8 vehicles, 3357 steps of 5 ms, struck: 0", lines
    rmse_cm = [float(v) for v in lines[1].split(":")[1].split()]
    assert len(rmse_cm) == 8
    # A Python estimate from the observations alone (no Kalman filter) still tracks to a few cm.
    assert all(1.0 < v < 6.0 for v in rmse_cm), rmse_cm
    assert len(set(rmse_cm)) > 1, "every vehicle has its own seed"
