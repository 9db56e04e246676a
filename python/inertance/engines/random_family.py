"""The seeded random family: boxes and cylinders at random poses and twists, 1–4 contacts with
a floor (and a wall), for the statistics of the report.

:func:`generate` turns a seed into scene files' text, the same text for the same seed on every
platform (Python's ``random.Random(seed).random()`` stream, which Python keeps stable, and
numbers written as short decimals, which inertance reads exactly). :func:`scenes` writes them to
a directory and loads them as catalogue scenes, each with its exact answer. Every scene is
frictionless and asks the unilateral law — the law the LCP/PGS engines state — with one
restitution coefficient for all its contacts. The kinds, each equally likely:

* ``box-corner`` (1 contact): a box at a random orientation (a quaternion of four decimals)
  resting on its lowest corner;
* ``box-edge`` (2): a box tilted by 10°–80° about its y axis (a rational quaternion: the two
  corners of its lowest edge at exactly one height), then yawed;
* ``box-wall`` (3): the same box-edge on the floor with a wall touching its corner farthest
  along x;
* ``box-face`` (4): a box lying flat, yawed, on its four bottom corners;
* ``cylinder-rim`` (1): a cylinder tilted by 10°–80°, on the lowest point of its bottom rim;
* ``cylinder-side`` (2): a cylinder lying on its side, the two ends of its lowest line.

Sizes are 0.1–0.5 m (box edges; a cylinder's radius 0.03–0.2 m and height 0.05–0.5 m), masses
0.5–5 kg, e = 0 (one time in six) or in [0.1, 1] (two decimals), the velocity of the centre of mass (±0.5, ±0.5, −0.5…−2)
m/s and the angular velocity up to 2 rad/s about each axis; a draw where some contact does not
approach at 0.05 m/s or more, where another corner lies within 1 % of the body's size of an
obstacle (a near-tie the engines would see as a contact), or where after the exact impact
another point of the body reaches an obstacle within 0.2 s (:func:`second_impact`: the engines
would resolve that impact too) is drawn again; so the family needs inertance's solve to be
drawn, and is still a function of the seed alone.
"""

from __future__ import annotations

import math
import random
import tempfile
from pathlib import Path
from typing import Optional

import numpy as np

from .scene import _toml, rotation

KINDS = ("box-corner", "box-edge", "box-wall", "box-face", "cylinder-rim", "cylinder-side")

#: The least approach speed of every named contact before impact (m/s).
MIN_APPROACH = 0.05
#: The least clearance of every other corner from the obstacles, as a fraction of the body's size.
MIN_CLEARANCE = 0.01


def _d(x: float, digits: int = 3) -> str:
    """A short decimal (what the file says is what inertance reads, exactly)."""
    s = f"{x:.{digits}f}"
    return "0" if float(s) == 0 else s


def _u(rng: random.Random, lo: float, hi: float, digits: int = 3) -> str:
    return _d(lo + (hi - lo) * rng.random(), digits)


def _tilt(rng: random.Random) -> tuple:
    """A rational half-angle quaternion [a, 0, b, 0] (about y) of a tilt in 10°–80°."""
    t = math.radians(10 + 70 * rng.random()) / 2
    return _d(math.cos(t)), _d(math.sin(t))


def _yaw(rng: random.Random) -> tuple:
    t = 2 * math.pi * rng.random() / 2
    return _d(math.cos(t)), _d(math.sin(t))


def _vec(xs) -> str:
    return "[" + ", ".join(xs) + "]"


def _draw(rng: random.Random, kind: str) -> Optional[dict]:
    """One draw of ``kind``: the body's table, contacts and obstacles, or None to draw again."""
    box = kind.startswith("box")
    if box:
        size = [_u(rng, 0.1, 0.5, 2) for _ in range(3)]
        shape = f"{{ box = {_vec(size)} }}"
        dims = np.array([float(x) for x in size])
    else:
        r, h = _u(rng, 0.03, 0.2, 2), _u(rng, 0.05, 0.5, 2)
        shape = f"{{ cylinder = [{r}, {h}] }}"
        dims = np.array([float(r), float(h)])
    mass = _u(rng, 0.5, 5, 2)
    c, s = _yaw(rng)
    yaw = f"{{ quaternion = [{c}, 0, 0, {s}] }}"
    if kind == "box-corner":
        q = [_u(rng, -1, 1) for _ in range(4)]
        if sum(float(x) ** 2 for x in q) < 0.1:
            return None
        pose = f"{{ quaternion = {_vec(q)} }}"
    elif kind in ("box-edge", "box-wall", "cylinder-rim"):
        a, b = _tilt(rng)
        pose = f"[{{ quaternion = [{a}, 0, {b}, 0] }}, {yaw}]"
    elif kind == "box-face":
        pose = yaw
    else:  # cylinder-side: a quarter turn about x lays the axis (body z) horizontal
        pose = f"[{{ quaternion = [1, 1, 0, 0] }}, {yaw}]"
    rot = rotation(_toml.loads(f"p = {pose}")["p"], {})
    # the box's corners, body axes (a cylinder's lowest point is known in closed form: the tilt
    # in 10°–80° puts its bottom rim's point along +x lowest, the top rim higher by h cos 80° or
    # more; lying on its side, the line y = −r)
    half = dims / 2
    signs = [np.array([sx, sy, sz]) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    points = [(sgn, sgn * half) for sgn in signs] if box else []
    size = float(max(dims))
    heights = np.array([(rot @ p)[2] for _, p in points])
    low = heights.min() if box else 0.0
    contacts = []  # (key, value) of each contact's position
    if box:
        touching = [i for i, h in enumerate(heights) if h - low < 1e-9 * size]
        expected = {"box-corner": 1, "box-edge": 2, "box-wall": 2, "box-face": 4}[kind]
        if len(touching) != expected:
            return None
        others = [h for i, h in enumerate(heights) if i not in touching]
        if min(others) - low < MIN_CLEARANCE * size:
            return None
        for i in touching:
            contacts.append(("floor", f"corner = {_vec([str(int(x)) for x in points[i][0]])}"))
        floor_points = [rot @ points[i][1] for i in touching]
    elif kind == "cylinder-rim":
        contacts.append(("floor", f"body_point = [{_d(dims[0], 2)}, 0, {_d(-dims[1] / 2, 3)}]"))
        floor_points = [rot @ np.array([dims[0], 0, -dims[1] / 2])]
    else:
        for z in (-dims[1] / 2, dims[1] / 2):
            contacts.append(("floor", f"body_point = [0, {_d(-dims[0], 2)}, {_d(z, 3)}]"))
        floor_points = [rot @ np.array([0, -dims[0], z]) for z in (-dims[1] / 2, dims[1] / 2)]
    wall_points = []
    if kind == "box-wall":
        xs = np.array([(rot @ p)[0] for _, p in points])
        top = xs.max()
        far = [i for i, x in enumerate(xs) if top - x < 1e-9 * size]
        if len(far) != 1 or np.sort(xs)[-2] > top - MIN_CLEARANCE * size or far[0] in [
                i for i, h in enumerate(heights) if h - low < 1e-9 * size]:
            return None
        contacts.append(("wall", f"corner = {_vec([str(int(x)) for x in points[far[0]][0]])}"))
        wall_points = [rot @ points[far[0]][1]]
    # the twist: every named contact approaching at MIN_APPROACH or more
    v = np.array([float(_u(rng, -0.5, 0.5)), float(_u(rng, -0.5, 0.5)), float(_u(rng, -2, -0.5))])
    w = np.array([float(_u(rng, -2, 2)) for _ in range(3)])
    vtxt = _vec([_d(x) for x in v])
    wtxt = _vec([_d(x) for x in w])
    for p in floor_points:
        if -(v + np.cross(w, p))[2] < MIN_APPROACH:
            return None
    for p in wall_points:
        if (v + np.cross(w, p))[0] < MIN_APPROACH:
            return None
    # e = 0 one time in six, else 0.1–1: a single contact leaves at e times its approach, and
    # e below 0.1 would put it within reach of the separation test's 1 % cut (grading.py)
    e = "0" if rng.random() < 1 / 6 else _u(rng, 0.1, 1, 2)
    obstacles = ['[[obstacle]]\nname = "floor"\nnormal = [0, 0, 1]']
    if wall_points:
        obstacles.append('[[obstacle]]\nname = "wall"\nnormal = [-1, 0, 0]')
    body = (f"[body]\nshape = {shape}\nmass = {mass}\npose = {pose}\nvelocity = {vtxt}\n"
            f"angular_velocity = {wtxt}")
    cs = [f"[[contact]]\nobstacle = \"{o}\"\n{where}\nk = {e}" for o, where in contacts]
    return {"body": body, "obstacles": obstacles, "contacts": cs, "e": e}


def generate(seed: int, count: int) -> list:
    """``count`` scenes from ``seed``: ``[(name, toml_text)]``, the kinds in turn (scene i is
    ``KINDS[i % 6]``), names ``random-<seed>-<i>-<kind>``."""
    if count < 0:
        raise ValueError(f"a count of scenes is ≥ 0, not {count}")
    rng = random.Random(int(seed))
    out = []
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(count):
            kind = KINDS[i % len(KINDS)]
            name = f"random-{seed}-{i:03d}-{kind}"
            for _ in range(10000):
                d = _draw(rng, kind)
                if d is None:
                    continue
                text = "\n".join([f"# Random family (inertance.engines.random_family), seed {seed}, scene {i}: {kind}.",
                                  f'name = "{name}"', d["body"], *d["obstacles"], *d["contacts"],
                                  '[solve]\nmodels = ["newton"]\nlaw = "unilateral"', ""])
                path = Path(tmp) / f"{name}.toml"
                path.write_text(text)
                if second_impact(path) is None:
                    break
            else:  # pragma: no cover - every kind draws in a few tries
                raise RuntimeError(f"no {kind} scene drawn from seed {seed}")
            out.append((name, text))
    return out


#: How long after the exact impact no other point of the body may reach an obstacle (s).
SINGLE_IMPACT_HORIZON = 0.2


def second_impact(path) -> Optional[float]:
    """The time (s) at which, after the scene's exact impact, another point of the body reaches
    an obstacle in free flight (gravity off: the centre of mass moving at v⁺, the body turning
    at ω⁺), if within :data:`SINGLE_IMPACT_HORIZON`; else None. The points: a box's corners
    other than the contacts; a cylinder's two rims sampled every 5°, leaving out the arc within
    30° of a contact on its rim (where the rim touches as it rolls: a persisting contact, not a
    new one; a cylinder on its side has a contact on each rim).
    A scene with such a second impact is drawn again: an engine runs until its contacts are
    over, so it would resolve both impacts while the exact answer is the first one's. 0.2 s is
    longer than the contacts measured on the catalogue (benches/engines/README.md: MuJoCo's
    defaults at most 88 steps of 2 ms = 0.176 s, tuned 26 steps of 0.1 ms, PyBullet 4 steps of
    1/240 s); Drake's contact durations were not measured. One body only (the family's)."""
    from .catalogue import load

    s = load(path)
    b, t = s.engine.bodies[0], s.exact[0]
    contacts_local = [b.rotation.T @ (c.point - b.position) for c in s.engine.contacts]
    if b.shape == "box":
        half = np.array(b.size) / 2
        pts = [np.array([sx, sy, sz]) * half for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
        pts = [p for p in pts if min(np.linalg.norm(p - q) for q in contacts_local) > 1e-9 * max(b.size)]
    elif b.shape == "sphere":
        pts = []  # a sphere meets a plane at one point only
    else:
        r, h = b.size
        pts = []
        for z in (-h / 2, h / 2):
            for a in np.radians(np.arange(0, 360, 5)):
                p = np.array([r * math.cos(a), r * math.sin(a), z])
                near = any(abs(q[2] - z) < 1e-9 * h and
                           math.acos(max(-1.0, min(1.0, (p[:2] @ q[:2]) / (r * max(np.linalg.norm(q[:2]), 1e-300)))))
                           < math.radians(30) for q in contacts_local)
                if not near:
                    pts.append(p)
    w = t.angular_velocity
    speed = float(np.linalg.norm(w))
    axis = w / speed if speed > 0 else np.zeros(3)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    for time in np.linspace(0, SINGLE_IMPACT_HORIZON, 401)[1:]:
        a = speed * time
        rot = (np.eye(3) + math.sin(a) * k + (1 - math.cos(a)) * k @ k) @ b.rotation
        centre = b.position + t.velocity * time
        for p in pts:
            x = centre + rot @ p
            for o in s.engine.obstacles:
                if o.normal @ (x - o.point) < 0:
                    return float(time)
    return None


def scenes(seed: int, count: int, directory=None) -> list:
    """The family as catalogue scenes with their exact answers: the files written to
    ``directory`` (created; default a temporary one) and loaded."""
    from .catalogue import load

    d = Path(directory) if directory is not None else Path(tempfile.mkdtemp(prefix=f"inertance-random-{seed}-"))
    d.mkdir(parents=True, exist_ok=True)
    out = []
    for name, text in generate(seed, count):
        p = d / f"{name}.toml"
        p.write_text(text)
        out.append(load(p))
    return out
