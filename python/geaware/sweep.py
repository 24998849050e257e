# SPDX-License-Identifier: BSD-3-Clause
"""Run a sweep file's missing flights on local processes or a Dask cluster (docs/sweeps.md).

    /usr/bin/python3 -m geaware.sweep SPEC.yaml --out DIR --scheduler tcp://HOST:8786
    /usr/bin/python3 -m geaware.sweep SPEC.yaml --out DIR --local 4       # a Dask LocalCluster
    /usr/bin/python3 -m geaware.sweep SPEC.yaml --out DIR --processes 4   # no Dask

Each worker flies one key at a time (geaware.sweep_flight: a pure function of the sweep file's
text and the key) and returns its record to this process, which writes it to DIR/flights
atomically as it arrives: the workers need no shared file system, only geaware and the files the
sweep file names (vehicle, truth, scenario files) at the same paths. A rerun skips the keys whose
record exists; at the end the records are merged into DIR/results.json, the same bytes as
`geaware sweep SPEC.yaml --out DIR` writes.
"""
import argparse
import concurrent.futures
import multiprocessing
import os
import sys
import time

from . import _geaware


def _fly(spec, text, key):
    """One key's record (runs in a worker)."""
    return key, _geaware.sweep_flight(spec, key, text)


class _Progress:
    """'done of total' on stderr, at most once a second, and the last one."""

    def __init__(self, total, quiet):
        self.total, self.quiet, self.done, self.last = total, quiet, 0, 0.0

    def step(self):
        self.done += 1
        now = time.monotonic()
        if not self.quiet and (now - self.last >= 1.0 or self.done == self.total):
            self.last = now
            print(f"geaware.sweep: {self.done} of {self.total} flights", file=sys.stderr, flush=True)


def _run_processes(spec, text, keys, out, n, progress):
    ctx = multiprocessing.get_context("spawn")  # no fork of a process that may hold threads
    with concurrent.futures.ProcessPoolExecutor(max_workers=n, mp_context=ctx) as pool:
        futures = [pool.submit(_fly, spec, text, k) for k in keys]
        try:
            for f in concurrent.futures.as_completed(futures):
                key, record = f.result()
                _geaware.sweep_write_flight(out, key, record)
                progress.step()
        except BaseException:
            for f in futures:
                f.cancel()
            raise


def _run_dask(spec, text, keys, out, scheduler, local, progress):
    import distributed  # Debian: python3-distributed

    cluster = None
    if local:
        cluster = distributed.LocalCluster(n_workers=local, threads_per_worker=1, processes=True,
                                           dashboard_address=None)
        client = distributed.Client(cluster)
    else:
        client = distributed.Client(scheduler)
    try:
        futures = client.map(_fly, [spec] * len(keys), [text] * len(keys), keys, pure=False)
        for f in distributed.as_completed(futures):
            key, record = f.result()
            _geaware.sweep_write_flight(out, key, record)
            progress.step()
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


def run(spec, out, scheduler=None, local=None, processes=None, quiet=False):
    """Flies the keys of `spec` that `out` does not hold yet and merges DIR/results.json.

    Exactly one of `scheduler` (a Dask scheduler's address), `local` (workers of a Dask
    LocalCluster) or `processes` (a process pool without Dask) says where. Returns
    (flights, flown, path of results.json).
    """
    if sum(x is not None for x in (scheduler, local, processes)) != 1:
        raise ValueError("give exactly one of scheduler, local or processes")
    spec = os.path.abspath(spec)
    with open(spec, "rb") as f:
        text = f.read()  # bytes: the workers parse exactly what this file holds
    keys_all = _geaware.sweep_keys(spec)  # reads and checks the file before any work
    _geaware.sweep_prepare_dir(spec, out)
    keys = _geaware.sweep_missing(spec, out)
    where = (f"Dask scheduler {scheduler}" if scheduler else
             f"a Dask LocalCluster of {local} workers" if local else f"{processes} processes")
    if not quiet:
        print(f"geaware.sweep: {len(keys_all)} flights, {len(keys_all) - len(keys)} already done, "
              f"{len(keys)} to fly on {where}", file=sys.stderr, flush=True)
    progress = _Progress(len(keys), quiet)
    if keys:
        if processes:
            _run_processes(spec, text, keys, out, processes, progress)
        else:
            _run_dask(spec, text, keys, out, scheduler, local, progress)
    return len(keys_all), len(keys), _geaware.sweep_merge(spec, out)


def main(argv=None):
    p = argparse.ArgumentParser(prog="python3 -m geaware.sweep", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("spec", metavar="SPEC.yaml", help="the sweep file")
    p.add_argument("--out", required=True, metavar="DIR",
                   help="results directory: DIR/flights/<key>.json and DIR/results.json")
    where = p.add_mutually_exclusive_group(required=True)
    where.add_argument("--scheduler", metavar="ADDRESS", help="a Dask scheduler, e.g. tcp://host:8786")
    where.add_argument("--local", type=int, metavar="N", help="start a Dask LocalCluster of N worker processes")
    where.add_argument("--processes", type=int, metavar="N", help="N local processes, without Dask")
    p.add_argument("--quiet", action="store_true", help="no progress on stderr")
    a = p.parse_args(argv)
    for name in ("local", "processes"):
        n = getattr(a, name)
        if n is not None and not 1 <= n <= 256:
            p.error(f"--{name}: expected 1 … 256 workers, got {n}")
    if os.path.exists(a.out) and not os.path.isdir(a.out):
        p.error(f"--out '{a.out}': is not a directory")
    t0 = time.monotonic()
    try:
        flights, flown, results = run(a.spec, a.out, a.scheduler, a.local, a.processes, a.quiet)
    except (ValueError, RuntimeError, OSError) as e:
        print(f"geaware.sweep: error: {e}", file=sys.stderr)
        return 1
    print(f"sweep {a.spec}: {flights} flights, {flights - flown} already done, flown {flown} in "
          f"{time.monotonic() - t0:.1f} s\nresults: {results}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
