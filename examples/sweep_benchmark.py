#!/usr/bin/env python3
"""Wall time and rows per second of a 200-row sweep on 1 and on 2 local Dask workers.

    PYTHONPATH=build/python /usr/bin/python3 examples/sweep_benchmark.py [--workers 1 2]

A benchmark, not a test: it prints one JSON line per run (workers, rows, tasks, wall seconds,
rows per second, the load average before and after) and checks that every run's error columns
equal the first run's. Each run starts a fresh LocalCluster of worker processes (one thread
each), so every run renders its own references; the cluster's start-up is not timed.
docs/python.md quotes a run of this script.
"""

import argparse
import json
import os
import sys
import time

import shadowlab

# 5 techniques x 2 scenes x 4 map sides x 5 camera orbits = 200 rows, on 10 views.
SPEC = {
    "techniques": ["modern.hw", "modern.gems4", "modern.gems16", "modern.woo",
                   "modern.second-depth"],
    "scenes": ["fence", "brabec"],
    "sizes": ["128x96"],
    "shadow_maps": [256, 512, 1024, 2048],
    "orbits": [None, [30, 30, 7], [-30, 30, 7], [60, 40, 8], [-60, 40, 8]],
}


def error_columns(frame):
    return [c for c in frame.columns
            if c.endswith(("rmse", "max_abs", "share_above_half", "leak_share"))]


def main():
    from distributed import Client, LocalCluster

    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--workers", type=int, nargs="+", default=[1, 2],
                        help="worker processes of each run [1 2]")
    args = parser.parse_args()
    rows = len(shadowlab.sweep_rows(SPEC))
    first = None
    for workers in args.workers:
        with LocalCluster(n_workers=workers, processes=True, threads_per_worker=1,
                          host="127.0.0.1", dashboard_address=None) as cluster, \
                Client(cluster) as client:
            load_before = os.getloadavg()[0]
            start = time.perf_counter()
            frame = shadowlab.sweep(SPEC, client=client)
            seconds = time.perf_counter() - start
            load_after = os.getloadavg()[0]
        if first is None:
            first = frame
        same = frame[error_columns(frame)].equals(first[error_columns(first)])
        print(json.dumps({"workers": workers, "rows": rows, "wall_s": round(seconds, 1),
                          "rows_per_s": round(rows / seconds, 2),
                          "load_before": load_before, "load_after": load_after,
                          "cpus": os.cpu_count(), "errors_equal_first_run": same,
                          "commit": shadowlab.commit(),
                          "command": " ".join([sys.executable, *sys.argv])}), flush=True)
        if not same:
            return 1
    return 0


# The guard is required: each LocalCluster worker process starts by importing this script
# (Python's spawn/forkserver re-import the main module); unguarded, every worker would start a
# cluster of its own and the run would never end.
if __name__ == "__main__":
    sys.exit(main())
