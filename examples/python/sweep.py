# SPDX-License-Identifier: BSD-3-Clause
"""A sweep from Python (docs/sweeps.md): the 64 flights of tests/sweep/sweep64.yaml (4 truth
perturbations × 2 controllers × 2 lemniscates × 4 seeds) on two local processes, then the mean
all-RMSE per perturbation and controller from the merged results.json. The same call with
scheduler="tcp://HOST:8786" runs the flights on a Dask cluster; the results are the same bytes.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/sweep.py [OUT_DIR]
"""
import collections
import json
import pathlib
import sys
import tempfile

import geaware.sweep


def main():
    source = pathlib.Path(__file__).resolve().parents[2]
    spec = source / "tests/sweep/sweep64.yaml"
    out = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else pathlib.Path(tempfile.mkdtemp(prefix="sweep-"))
    flights, flown, results = geaware.sweep.run(str(spec), str(out), processes=2, quiet=True)
    print(f"{flights} flights, {flights - flown} already done, results in {results}")
    doc = json.loads(pathlib.Path(results).read_text())
    rmse = collections.defaultdict(list)
    strikes = collections.Counter()
    for r in doc["records"]:
        if r["struck"]:
            strikes[r["case"], r["controller"]] += 1
        else:
            rmse[r["case"], r["controller"]].append(r["rmse_all_cm"])
    controllers = doc["sweep"]["controllers"]
    print(f"{'all-RMSE [cm]':14}" + "".join(f"{c:>14}" for c in controllers))
    for case in (c["name"] for c in doc["sweep"]["cases"]):
        cells = []
        for c in controllers:
            v = rmse[case, c]
            cells.append(f"{sum(v) / len(v):14.2f}" if v else f"{'struck':>14}")
            if strikes[case, c]:
                cells[-1] = cells[-1].rstrip() + f" ({strikes[case, c]} struck)"
        print(f"{case:14}" + "".join(cells))


if __name__ == "__main__":  # the worker processes (spawned) import this file too
    main()
