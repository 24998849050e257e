# SPDX-License-Identifier: BSD-3-Clause
"""Sweeps three ways (docs/sweeps.md): `geaware sweep --jobs 1`, `python3 -m geaware.sweep
--processes 2` and a Dask LocalCluster of 2 workers give byte-identical DIR/results.json for the
64 flights of tests/sweep/sweep64.yaml; a sweep killed part-way, rerun, flies only the missing
keys. Labels python and sweep."""
import json
import os
import pathlib
import signal
import subprocess
import sys
import time

import pytest

import geaware


@pytest.fixture(scope="module")
def spec(source_dir):
    return str(source_dir / "tests/sweep/sweep64.yaml")


def python_sweep(spec, out, *where):
    env = dict(os.environ)
    return subprocess.run([sys.executable, "-m", "geaware.sweep", spec, "--out", str(out), "--quiet", *where],
                          capture_output=True, text=True, env=env, timeout=600)


@pytest.fixture(scope="module")
def serial(cli, spec, tmp_path_factory):
    out = tmp_path_factory.mktemp("serial")
    r = subprocess.run([cli, "sweep", spec, "--out", str(out), "--jobs", "1"], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stderr
    assert "64 flights, 0 already done, flown 64" in r.stdout
    return out


def test_keys_and_one_flight_match_the_command_line(serial, spec):
    keys = geaware.sweep_keys(spec)
    assert len(keys) == 64 and keys[0] == "case=none/ctl=recommended/scn=lem-0.3m-1mps/seed=1"
    key = keys[37]
    record = geaware.sweep_flight(spec, key)
    file = serial / "flights" / geaware.sweep_key_file(key)
    assert file.read_text() == record + "\n"
    assert json.loads(record)["key"] == key
    # The text of the file, as a remote worker gets it, gives the same bytes.
    assert geaware.sweep_flight(spec, key, pathlib.Path(spec).read_bytes()) == record


def test_processes_and_dask_give_the_same_bytes(serial, spec, tmp_path):
    expected = (serial / "results.json").read_bytes()
    doc = json.loads(expected)
    assert doc["flights"] == 64 and len(doc["records"]) == 64
    assert len({r["rmse_all_cm"] for r in doc["records"]}) > 60  # 64 flights, not one copied
    r = python_sweep(spec, tmp_path / "processes", "--processes", "2")
    assert r.returncode == 0, r.stderr
    assert "flown 64" in r.stdout
    assert (tmp_path / "processes" / "results.json").read_bytes() == expected
    r = python_sweep(spec, tmp_path / "dask", "--local", "2")
    assert r.returncode == 0, r.stderr
    assert "flown 64" in r.stdout
    assert (tmp_path / "dask" / "results.json").read_bytes() == expected


def test_a_killed_sweep_rerun_flies_only_the_missing_keys(cli, serial, spec, tmp_path):
    out = tmp_path / "killed"
    flights = out / "flights"
    p = subprocess.Popen([cli, "sweep", spec, "--out", str(out), "--jobs", "1", "--quiet"],
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and p.poll() is None:
        if flights.is_dir() and len(list(flights.glob("*.json"))) >= 8:
            break
        time.sleep(0.01)
    p.send_signal(signal.SIGTERM)
    p.communicate(timeout=60)
    done = sorted(flights.glob("*.json"))
    assert 8 <= len(done) < 64, "the sweep finished before it could be killed"
    assert not [f for f in flights.iterdir() if f.suffix != ".json"]  # no temporary file left
    before = {f.name: f.stat().st_mtime_ns for f in done}
    # Rerun on the processes: it flies the others only, and merges the same bytes.
    r = python_sweep(spec, out, "--processes", "2")
    assert r.returncode == 0, r.stderr
    assert f"{len(done)} already done, flown {64 - len(done)}" in r.stdout
    assert {f.name: f.stat().st_mtime_ns for f in done} == before
    assert (out / "results.json").read_bytes() == (serial / "results.json").read_bytes()
    # A rerun of a finished sweep flies nothing.
    r = subprocess.run([cli, "sweep", spec, "--out", str(out)], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0 and "64 already done, flown 0" in r.stdout


def test_bad_input_names_the_file_and_writes_nothing(cli, spec, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(pathlib.Path(spec).read_text().replace("  - indi:none\n", "  - indi:fast\n"))
    r = python_sweep(str(bad), tmp_path / "out", "--processes", "1")
    assert r.returncode == 1
    assert "bad.yaml:" in r.stderr and "controllers[1]" in r.stderr
    assert not (tmp_path / "out").exists()
    r = subprocess.run([cli, "sweep", str(bad), "--out", str(tmp_path / "out")], capture_output=True, text=True)
    assert r.returncode == 1 and "controllers[1]" in r.stderr
    assert not (tmp_path / "out").exists()
    # --out naming a file is refused before any work.
    r = subprocess.run([cli, "sweep", spec, "--out", spec], capture_output=True, text=True)
    assert r.returncode == 1 and "--out" in r.stderr


def test_the_sweep_example_prints_the_means_of_the_merged_records(serial, source_dir, tmp_path):
    done = subprocess.run([sys.executable, str(source_dir / "examples/python/sweep.py"), str(tmp_path / "ex")],
                          check=True, capture_output=True, text=True, timeout=300)
    lines = done.stdout.splitlines()
    assert lines[0] == f"64 flights, 0 already done, results in {tmp_path / 'ex' / 'results.json'}"
    assert lines[1].split()[-2:] == ["recommended", "indi:none"]
    records = json.loads((serial / "results.json").read_text())["records"]
    assert (tmp_path / "ex" / "results.json").read_bytes() == (serial / "results.json").read_bytes()
    rows = {line.split()[0]: line.split()[1:] for line in lines[2:]}
    assert list(rows) == ["none", "mass+10%", "cushion+0.5", "windy"]
    for case, cells in rows.items():
        for controller, cell in zip(["recommended", "indi:none"], cells):
            v = [r["rmse_all_cm"] for r in records
                 if r["case"] == case and r["controller"] == controller and not r["struck"]]
            assert cell == f"{sum(v) / len(v):.2f}", (case, controller)


def test_a_dask_scheduler_and_workers_started_as_on_other_machines(serial, spec, tmp_path):
    """`dask-scheduler` and `dask-worker` as docs/sweeps.md starts them on other machines (here on
    this one, over TCP), and `--scheduler ADDRESS`: the same bytes."""
    file = tmp_path / "scheduler.json"
    env = dict(os.environ)
    procs = [subprocess.Popen(["dask-scheduler", "--scheduler-file", str(file), "--host", "127.0.0.1",
                               "--no-dashboard"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        # The scheduler writes its file in place: it may exist and still be empty or partial.
        deadline = time.monotonic() + 60
        address = None
        while address is None and time.monotonic() < deadline:
            try:
                address = json.loads(file.read_text())["address"]
            except (OSError, ValueError, KeyError):
                time.sleep(0.1)
        assert address is not None, f"dask-scheduler wrote no address into {file} within 60 s"
        assert address.startswith("tcp://127.0.0.1:")
        procs.append(subprocess.Popen(["dask-worker", address, "--nthreads", "1", "--nworkers", "2",
                                       "--no-dashboard"], env=env, stdout=subprocess.DEVNULL,
                                      stderr=subprocess.DEVNULL))
        r = python_sweep(spec, tmp_path / "cluster", "--scheduler", address)
        assert r.returncode == 0, r.stderr
        assert "flown 64" in r.stdout
        assert (tmp_path / "cluster" / "results.json").read_bytes() == (serial / "results.json").read_bytes()
    finally:
        for p in reversed(procs):
            p.send_signal(signal.SIGTERM)
        for p in reversed(procs):
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
