"""A sweep in-process, on a process pool and on a Dask local cluster: wall time per call.

Run: python python/examples/scale_out.py [POINTS] [WORKERS]   (after `pip install
./python[dask]`; defaults 5000 points, 2 workers). The pool and the cluster are started, and
warmed by one call, before the timing; each row is the median of 5 calls of
`inertance.sweep(examples/planar-bar.toml, {"contact[1].k": (0, 1, POINTS)})`, in f64 and
with exact=True, and the result is checked equal to the in-process one. The ratio is
in-process time ÷ executor time (> 1: the executor is faster).
"""

import os
import pathlib
import statistics
import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

import inertance

ROOT = pathlib.Path(__file__).resolve().parents[2]
BAR = inertance.Scene.load(ROOT / "examples" / "planar-bar.toml")
POINTS = int(sys.argv[1]) if len(sys.argv) > 1 else 5000
WORKERS = int(sys.argv[2]) if len(sys.argv) > 2 else 2


def timed(call, repeats=5):
    """The median wall time of `call()` over `repeats` calls, and its last result."""
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        out = call()
        times.append(time.perf_counter() - t)
    return statistics.median(times), out


def same(a, b):
    return list(a) == list(b) and all(
        x.tobytes() == y.tobytes() if isinstance(x, np.ndarray) else x == y
        for x, y in zip(a.values(), b.values()))


def main():
    from dask.distributed import Client, LocalCluster

    print(f"{POINTS} points, {os.cpu_count()} cores, {WORKERS} workers; "
          f"inertance {inertance.__version__}")
    t = time.perf_counter()
    pool = ProcessPoolExecutor(WORKERS)
    pool.submit(int).result()
    pool_start = time.perf_counter() - t
    t = time.perf_counter()
    cluster = LocalCluster(n_workers=WORKERS, threads_per_worker=1, processes=True,
                           dashboard_address=None)
    client = Client(cluster)
    dask = client.get_executor()
    dask_start = time.perf_counter() - t
    print(f"start: process pool {pool_start:.2f} s, Dask local cluster {dask_start:.2f} s")
    for exact in (False, True):
        vary = {"contact[1].k": (0, 1, POINTS)}

        def run(executor=None):
            return inertance.sweep(BAR, vary, exact=exact, frame=False, executor=executor)

        here_s, here = timed(run)
        print(f"{'exact' if exact else 'f64'}: in-process {here_s * 1e3:.1f} ms")
        for name, executor in (("process pool", pool), ("Dask local cluster", dask)):
            run(executor)  # warm: workers import inertance
            there_s, there = timed(lambda: run(executor))
            assert same(here, there), name
            print(f"  {name:20s} {there_s * 1e3:8.1f} ms   in-process ÷ this = "
                  f"{here_s / there_s:.2f}")
    client.close()
    cluster.close()
    pool.shutdown()


if __name__ == "__main__":
    main()
