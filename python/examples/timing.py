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

# Systems of bodies (guide/python.md, "Systems of bodies"): Newton's cradle, three free balls,
# and two bars pinned to the ground and to each other (two revolute joints) striking a floor.
ball = lambda name, x, v: {"name": name, "shape": {"sphere": 1}, "mass": 1,  # noqa: E731
                           "position": [x, 0, 0], "velocity": [v, 0, 0], "angular_velocity": [0, 0, 0]}
cradle = inertance.Scene.from_dict({
    "name": "Newton's cradle",
    "body": [ball("striker", 0, 1), ball("middle", 2, 0), ball("last", 4, 0)],
    "contact": [{"bodies": ["striker", "middle"], "point": [1, 0, 0], "normal": [1, 0, 0], "k": 1},
                {"bodies": ["middle", "last"], "point": [3, 0, 0], "normal": [1, 0, 0], "k": 1}],
})
bars = inertance.Scene.from_dict({
    "name": "two bars, pinned, striking the floor",
    "body": [
        {"name": "upper", "mass": 2, "inertia": [1, 2, 2], "position": [1, 0, 0],
         "velocity": [0, -1, 0], "angular_velocity": [0, 0, -1]},
        {"name": "lower", "mass": 1, "inertia": [1, 1, 2], "position": ["7/2", -2, 0],
         "velocity": [-2, "-7/2", 0], "angular_velocity": [0, 0, -1]},
    ],
    "obstacle": [{"name": "floor", "normal": [0, 1, 0], "point": [0, -4, 0]}],
    "contact": [{"body": "lower", "obstacle": "floor", "point": [5, -4, 0], "k": "1/2"}],
    "joint": [
        {"kind": "revolute", "bodies": ["upper"], "anchor": [0, 0, 0], "axis": [0, 0, 1]},
        {"kind": "revolute", "bodies": ["upper", "lower"], "anchor": [2, 0, 0], "axis": [0, 0, 1]},
    ],
})
show("system: solve(cradle) f64 (3 bodies, 2 contacts)", per_call(lambda: inertance.solve(cradle), 5_000))
show("system: ... + .newton.velocities (numpy)", per_call(lambda: inertance.solve(cradle).newton.velocities, 5_000))
show("system: solve(cradle, exact=True)", per_call(lambda: inertance.solve(cradle, exact=True), 500))
show("system: solve(bars) f64 (2 bodies, 2 joints, 1 contact)", per_call(lambda: inertance.solve(bars), 5_000))
show("system: solve(bars, exact=True)", per_call(lambda: inertance.solve(bars, exact=True), 500))
