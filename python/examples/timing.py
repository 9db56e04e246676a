"""Per-call cost of the bindings (no pytest-benchmark): median over repeats of the mean per call.

Run: python python/examples/timing.py   (from anywhere, after `pip install ./python`)
"""

import pathlib
import statistics
import time

import numpy as np

import inertance

ROOT = pathlib.Path(__file__).resolve().parents[2]
PATH = ROOT / "examples" / "planar-bar.toml"
bar = inertance.Scene.load(PATH)
text = PATH.read_text()


def per_call(f, n, repeats=5):
    times = []
    for _ in range(repeats):
        t = time.perf_counter()
        for _ in range(n):
            f()
        times.append((time.perf_counter() - t) / n)
    return statistics.median(times)


def show(label, seconds):
    unit = (1e6, "µs") if seconds < 1e-3 else (1e3, "ms")
    print(f"{label:58s} {seconds * unit[0]:9.2f} {unit[1]}")


show("solve(scene) f64, prebuilt Scene", per_call(lambda: inertance.solve(bar), 50_000))
show("solve(scene) f64 + .newton.impulses (numpy)", per_call(lambda: inertance.solve(bar).newton.impulses, 20_000))
show("solve(scene, model='newton') f64", per_call(lambda: inertance.solve(bar, "newton"), 50_000))
show("solve(TOML text) f64 (parse every call)", per_call(lambda: inertance.solve(text), 5_000))
show("solve(scene, exact=True)", per_call(lambda: inertance.solve(bar, exact=True), 500))
k = np.linspace(0, 1, 100_000)
t = time.perf_counter()
inertance.solve_batch(bar, {"contact[1].k": k})
show("solve_batch, per point (100 000 points, all cores)", (time.perf_counter() - t) / len(k))
t = time.perf_counter()
inertance.sweep(bar, {"contact[1].k": (0, 1, 100_001)}, frame=False)
show("sweep, per point (100 001 points, all cores)", (time.perf_counter() - t) / 100_001)
