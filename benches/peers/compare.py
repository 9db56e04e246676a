#!/usr/bin/env python3
"""Peer comparison for `inertance`: the same two-contact free-body scenes solved by

  * Pinocchio's ``impulseDynamics`` (Newton restitution, one coefficient for every contact),
  * Pinocchio's rigid-body algebra (crba + frame Jacobians) with the impulse system solved in numpy,
  * a numpy closed form of the paper (eq. 57, 8, 20, 22-24, 28, 32),
  * SymPy in exact rationals,

checked against ``inertance solve SCENE --json`` (f64) and ``--json --exact``, and timed per solve as
a ratio to inertance's own in-process time per solve (``inertance bench --scene SCENE --json``) and to
inertance's time per solve **from Python** (the ``inertance`` package: ``inertance.solve`` on a
prebuilt ``Scene``, f64 and exact), all in one run.  It ends with the batch API seen from Rust
(``inertance bench --scene --batch``) and from Python (``inertance.solve_batch``) on the same points.

The Python package is the one ``pip install ./python`` put in this interpreter's environment or,
failing that, the one ``python/test.sh`` built into ``$CARGO_TARGET_DIR/python-test-venv``
(``--python-package DIR`` names another site-packages directory).

Run from anywhere:  python3 benches/peers/compare.py        (see benches/peers/README.md)

Not part of CI.  Exit status: 0 when every peer agrees with inertance, 1 otherwise.
"""

from __future__ import annotations

import argparse
import datetime
import gc
import json
import math
import os
import platform
import random
import statistics
import subprocess
import sys
import tempfile
import timeit
from dataclasses import dataclass, field
from fractions import Fraction as F
from pathlib import Path

import numpy as np
import pinocchio as pin
import sympy as sp

import pin_build  # benches/peers/pin_build.py: the C++ harnesses' build

REPO = Path(__file__).resolve().parents[2]

# Agreement tolerance of every f64 peer against inertance f64 (see README.md, "Agreement"):
# all scenes have cond(G) <= 50, so backward-stable solves differ by ~cond*eps ~ 1e-14; 1e-9 leaves
# four orders of margin for rounding and still catches any convention error (those are O(1)).
RTOL = 1e-9
# Pinocchio's RigidConstraintModel path needs a proximal regularisation (two 3-D point contacts on
# one body give a rank-5 Delassus matrix); its bias is ~mu * |lambda| / sigma_min.
PROX_MU = 1e-12


# ----------------------------------------------------------------------------------------------
# Scenes (exact rational data; f64 values are the correctly rounded floats of the same rationals)
# ----------------------------------------------------------------------------------------------


@dataclass
class Contact:
    point: tuple  # A_i from C, body axes (Fractions)
    normal: tuple  # outward normal, any length (Fractions)
    k_newton: F
    k_poisson: F


@dataclass
class Scene:
    name: str
    description: str
    mass: F
    inertia: tuple  # (Jx, Jy, Jz) central principal moments
    velocity: tuple  # v_C before impact
    angular_velocity: tuple  # omega before impact
    contacts: list = field(default_factory=list)

    @property
    def equal_k(self) -> bool:
        ks = {c.k_newton for c in self.contacts} | {c.k_poisson for c in self.contacts}
        return len(ks) == 1

    @property
    def k(self) -> F:
        return self.contacts[0].k_newton


def _num(x: F) -> str:
    """A number as the inertance schema reads it exactly: an integer, or a "p/q" string."""
    x = F(x)
    return str(x.numerator) if x.denominator == 1 else f'"{x.numerator}/{x.denominator}"'


def _vec(v) -> str:
    return "[" + ", ".join(_num(x) for x in v) + "]"


def scene_toml(s: Scene) -> str:
    out = [f'name = "{s.name}"', f'description = "{s.description}"', "[body]",
           f"mass = {_num(s.mass)}", f"inertia = {_vec(s.inertia)}",
           f"velocity = {_vec(s.velocity)}", f"angular_velocity = {_vec(s.angular_velocity)}"]
    for c in s.contacts:
        out += ["[[contact]]", f"point = {_vec(c.point)}", f"normal = {_vec(c.normal)}"]
        if c.k_newton == c.k_poisson:
            out.append(f"k = {_num(c.k_newton)}")
        else:
            out += [f"k_newton = {_num(c.k_newton)}", f"k_poisson = {_num(c.k_poisson)}"]
    out += ["[solve]", 'models = ["newton", "poisson"]', ""]
    return "\n".join(out)


def example3(name, desc, velocity, k1, k2) -> Scene:
    """Example 3 of the paper: the planar bar on two supports."""
    return Scene(name, desc, F(1), (F(12), F(8, 5), F(12)), velocity, (F(0), F(0), F(2, 5)), [
        Contact((F(0), F(-2), F(0)), (F(1), F(0), F(0)), k1, k1),
        Contact((F(0), F(4), F(0)), (F(1), F(0), F(0)), k2, k2),
    ])


# Rational unit vectors from Pythagorean quadruples a^2 + b^2 + c^2 = d^2.
_QUADRUPLES = [(1, 2, 2, 3), (2, 3, 6, 7), (1, 4, 8, 9), (4, 4, 7, 9), (2, 6, 9, 11),
               (6, 6, 7, 11), (3, 4, 12, 13), (2, 10, 11, 15), (1, 12, 12, 17), (8, 9, 12, 17)]


def _unit(rng: random.Random) -> tuple:
    a, b, c, d = rng.choice(_QUADRUPLES)
    comps = [a, b, c]
    rng.shuffle(comps)
    return tuple(F(x * rng.choice((-1, 1)), d) for x in comps)


def _rat(rng, lo, hi, den):
    return F(rng.randint(lo * den, hi * den), den)


def random_scene(rng: random.Random, idx: int) -> Scene:
    """A random well-conditioned 3-D two-contact scene with one restitution coefficient.

    Rejection sampling until: both contacts approach (v_ix^0 > 0, eq. 74), both Newton impulses are
    compressive (P_i > 0, eq. 73), and cond_2(G) <= 50.  Inertia is that of a solid box a x b x c,
    so the moments are physical (triangle inequalities)."""
    while True:
        m = _rat(rng, 1, 3, 4)
        a, b, c = (_rat(rng, 1, 3, 4) for _ in range(3))
        if min(a, b, c) <= 0:
            continue
        inertia = (m * (b * b + c * c) / 12, m * (a * a + c * c) / 12, m * (a * a + b * b) / 12)
        vel = tuple(_rat(rng, -3, 3, 4) for _ in range(3))
        omg = tuple(_rat(rng, -1, 1, 4) for _ in range(3))
        k = F(rng.randint(0, 10), 10)
        contacts = [Contact(tuple(_rat(rng, -2, 2, 4) for _ in range(3)), _unit(rng), k, k)
                    for _ in range(2)]
        s = Scene(f"random-{idx}", f"random 3-D scene {idx}, k = {k}", m, inertia, vel, omg, contacts)
        ex = sympy_solve(SympyInputs(s))
        v0 = ex["v0"]
        G = np.array(ex["G"].tolist(), dtype=float)
        if min(v0) <= 0 or min(ex["newton"]["impulses"]) <= 0 or np.linalg.cond(G) > 50:
            continue
        return s


# The exact corpus (benches/peers/corpus.txt): random scenes as one line each, the same rationals
# on both sides (the Rust criterion bench `exact` and `inertance bench --corpus` read this file).
CORPUS = REPO / "benches" / "peers" / "corpus.txt"
CORPUS_FIELDS = ("m Jx Jy Jz vCx vCy vCz wx wy wz "
                 "A1x A1y A1z n1x n1y n1z k1 A2x A2y A2z n2x n2y n2z k2")


def corpus_line(s: Scene) -> str:
    """A two-contact scene with one coefficient per contact as one line of 24 rationals."""
    nums = [s.mass, *s.inertia, *s.velocity, *s.angular_velocity]
    for c in s.contacts:
        assert c.k_newton == c.k_poisson
        nums += [*c.point, *c.normal, c.k_newton]
    return " ".join(str(F(x)) for x in nums)


def corpus_scene(line: str, idx: int) -> Scene:
    """The inverse of `corpus_line`."""
    x = [F(t) for t in line.split()]
    assert len(x) == 24, f"corpus line {idx}: {len(x)} numbers, expected 24"
    contacts = [Contact(tuple(x[o:o + 3]), tuple(x[o + 3:o + 6]), x[o + 6], x[o + 6]) for o in (10, 17)]
    return Scene(f"corpus-{idx}", f"corpus scene {idx}, k = {x[16]}, {x[23]}", x[0], tuple(x[1:4]),
                 tuple(x[4:7]), tuple(x[7:10]), contacts)


def read_corpus(path: Path, limit: int | None = None) -> list:
    lines = [ln for ln in path.read_text().splitlines() if ln.strip() and not ln.startswith("#")]
    return [corpus_scene(ln, i + 1) for i, ln in enumerate(lines[:limit])]


def write_corpus(path: Path, seed: int, n: int) -> None:
    rng = random.Random(seed)
    head = [f"# The exact peer corpus: {n} random two-contact scenes of `random_scene` (seed {seed}),",
            "# written by `python3 benches/peers/compare.py --write-corpus`; one scene a line:",
            f"# {CORPUS_FIELDS}"]
    body = [corpus_line(random_scene(rng, i + 1)) for i in range(n)]
    path.write_text("\n".join(head + body) + "\n")


def build_scenes(seed: int, n_random: int) -> list:
    scenes = [
        example3("example-3", "Example 3 of the paper, k1 = 0.3, k2 = 0.2 (no Pinocchio impulseDynamics)",
                 (F(3), F(2), F(0)), F(3, 10), F(1, 5)),
        example3("example-3-equal-k", "Example 3 with k1 = k2 = 0.3",
                 (F(3), F(2), F(0)), F(3, 10), F(3, 10)),
        example3("example-3-no-slip", "Example 3, k = 0.3, v_C0 = (3, 0, 0): no tangential velocity",
                 (F(3), F(0), F(0)), F(3, 10), F(3, 10)),
    ]
    rng = random.Random(seed)
    scenes += [random_scene(rng, i + 1) for i in range(n_random)]
    return scenes


# ----------------------------------------------------------------------------------------------
# Results in one shape: {"G", "det", "newton": {...}, "poisson": {...}}
# ----------------------------------------------------------------------------------------------

QUANTITIES = ("impulses", "velocity", "angular_velocity", "lost_velocity_energy", "kinetic_energy_loss")


def from_inertance(j: dict, conv) -> dict:
    out = {"G": [[conv(x) for x in row] for row in j["inertance"]], "det": conv(j["det"])}
    for model in ("newton", "poisson"):
        mj = j["models"][model]
        r = {q: (conv(mj[q]) if not isinstance(mj[q], list) else [conv(x) for x in mj[q]])
             for q in QUANTITIES}
        if model == "poisson":
            r["compression_impulses"] = [conv(x) for x in mj["compression_impulses"]]
        out[model] = r
    return out


# ----------------------------------------------------------------------------------------------
# Peer 1: numpy closed form (eq. 57 for G, eq. 8 for v_ix^0, eq. 20/22/23 by Cramer, eq. 24, 28, 32)
# ----------------------------------------------------------------------------------------------


class NumpyInputs:
    def __init__(self, s: Scene):
        self.m = float(s.mass)
        self.J = np.array([float(x) for x in s.inertia])
        self.vC = np.array([float(x) for x in s.velocity])
        self.w = np.array([float(x) for x in s.angular_velocity])
        self.R = np.array([[float(x) for x in c.point] for c in s.contacts])
        self.Nraw = np.array([[float(x) for x in c.normal] for c in s.contacts])
        self.kN = np.array([float(c.k_newton) for c in s.contacts])
        self.kP = np.array([float(c.k_poisson) for c in s.contacts])


_ROT1, _ROT2 = np.array([1, 2, 0]), np.array([2, 0, 1])


def numpy_solve(x: NumpyInputs) -> dict:
    m, J, vC, w = x.m, x.J, x.vC, x.w
    N = x.Nraw / np.sqrt((x.Nraw * x.Nraw).sum(axis=1))[:, None]  # x_i: (a, b, c), eq. 2
    R = x.R
    # (d, e, f) = S_i x_i = A_i x x_i (eq. 3-4), written out: np.cross costs ~20 us on 2x3 arrays
    D = R.take(_ROT1, 1) * N.take(_ROT2, 1) - R.take(_ROT2, 1) * N.take(_ROT1, 1)
    G = N @ N.T / m + (D / J) @ D.T  # eq. 57
    v0 = N @ vC + D @ w  # v_ix^0, eq. 8
    det = G[0, 0] * G[1, 1] - G[0, 1] * G[1, 0]

    def cramer(b):  # eq. 20 / 22
        return np.array([(b[0] * G[1, 1] - G[0, 1] * b[1]) / det,
                         (G[0, 0] * b[1] - b[0] * G[1, 0]) / det])

    T0 = 0.5 * (m * (vC @ vC) + J @ (w * w))

    def after(P):
        dv = -(P @ N) / m  # eq. 24, translational part of M^-1 E_ix
        dw = -(P @ D) / J  # eq. 24, rotational part
        v1, w1 = vC + dv, w + dw
        Ep = 0.5 * (m * (dv @ dv) + J @ (dw * dw))  # eq. 28
        dEc = T0 - 0.5 * (m * (v1 @ v1) + J @ (w1 * w1))  # eq. 32
        return {"impulses": P, "velocity": v1, "angular_velocity": w1,
                "lost_velocity_energy": Ep, "kinetic_energy_loss": dEc}

    PN = cramer((1.0 + x.kN) * v0)  # Newton, eq. 15, 20
    PC = cramer(v0)  # Poisson compression, eq. 21-22
    poisson = after((1.0 + x.kP) * PC)  # eq. 23
    poisson["compression_impulses"] = PC
    return {"G": G, "det": det, "newton": after(PN), "poisson": poisson}


# ----------------------------------------------------------------------------------------------
# Peer 2: SymPy, exact rationals (same equations, general LU solve instead of Cramer)
# ----------------------------------------------------------------------------------------------


class SympyInputs:
    def __init__(self, s: Scene):
        R = lambda x: sp.Rational(x.numerator, x.denominator)  # noqa: E731
        self.m = R(s.mass)
        self.J = [R(x) for x in s.inertia]
        self.vC = sp.Matrix([R(x) for x in s.velocity])
        self.w = sp.Matrix([R(x) for x in s.angular_velocity])
        self.pts = [sp.Matrix([R(x) for x in c.point]) for c in s.contacts]
        self.nrm = [sp.Matrix([R(x) for x in c.normal]) for c in s.contacts]
        self.kN = [R(c.k_newton) for c in s.contacts]
        self.kP = [R(c.k_poisson) for c in s.contacts]


def sympy_solve(x: SympyInputs) -> dict:
    m, J, vC, w = x.m, x.J, x.vC, x.w
    n = len(x.pts)
    X = [nr / sp.sqrt(nr.dot(nr)) for nr in x.nrm]  # exact; a rational unit normal stays rational
    D = [p.cross(a) for p, a in zip(x.pts, X)]
    Jinv = sp.diag(*[1 / j for j in J])
    Jd = sp.diag(*J)
    G = sp.Matrix(n, n, lambda i, j: X[i].dot(X[j]) / m + (D[i].T * Jinv * D[j])[0])  # eq. 57
    v0 = [X[i].dot(vC) + D[i].dot(w) for i in range(n)]  # eq. 8
    T0 = (m * vC.dot(vC) + (w.T * Jd * w)[0]) / 2

    def after(P):
        dv = -sum((P[i] * X[i] for i in range(n)), sp.zeros(3, 1)) / m
        dw = -Jinv * sum((P[i] * D[i] for i in range(n)), sp.zeros(3, 1))
        v1, w1 = vC + dv, w + dw
        Ep = (m * dv.dot(dv) + (dw.T * Jd * dw)[0]) / 2
        dEc = T0 - (m * v1.dot(v1) + (w1.T * Jd * w1)[0]) / 2
        return {"impulses": list(P), "velocity": list(v1), "angular_velocity": list(w1),
                "lost_velocity_energy": Ep, "kinetic_energy_loss": dEc}

    PN = G.LUsolve(sp.Matrix([(1 + x.kN[i]) * v0[i] for i in range(n)]))
    PC = G.LUsolve(sp.Matrix(v0))
    poisson = after([(1 + x.kP[i]) * PC[i] for i in range(n)])
    poisson["compression_impulses"] = list(PC)
    return {"G": G, "det": G.det(), "v0": v0, "X": X, "D": D,
            "newton": after(list(PN)), "poisson": poisson}


def sympy_closed_form(x: SympyInputs) -> dict:
    """The numpy closed form's equations (eq. 57, 8, 20, 22-24, 28, 32: Cramer's rule, every
    product written out) in SymPy `Rational` scalars, for two contacts: SymPy's exact arithmetic
    without its Matrix and LUsolve machinery -- the cheapest exact SymPy solve of these outputs."""
    m, J = x.m, x.J
    vC, w = list(x.vC), list(x.w)
    X = []
    for nr in x.nrm:
        s = sp.sqrt(nr[0] * nr[0] + nr[1] * nr[1] + nr[2] * nr[2])  # rational for these normals
        X.append([c / s for c in nr])
    P = [list(p) for p in x.pts]
    out = cramer_closed_form(m, J, vC, w, X, P, x.kN, x.kP, sp.Integer(1))
    out["G"] = sp.Matrix(out["G"])
    return out


def cramer_closed_form(m, J, vC, w, X, P, kN, kP, one) -> dict:
    """The numpy closed form's equations (eq. 57, 8, 20, 22-24, 28, 32: Cramer's rule on the 2x2,
    every product written out) in whatever exact scalar the inputs are (SymPy `Rational`, FLINT
    `fmpq`): X the unit normals, P the contact points, `one` the scalar's 1."""
    D = [[p[1] * a[2] - p[2] * a[1], p[2] * a[0] - p[0] * a[2], p[0] * a[1] - p[1] * a[0]]
         for p, a in zip(P, X)]

    def dot(a, b):
        return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]

    G = [[dot(X[i], X[j]) / m + D[i][0] * D[j][0] / J[0] + D[i][1] * D[j][1] / J[1]
          + D[i][2] * D[j][2] / J[2] for j in range(2)] for i in range(2)]
    v0 = [dot(X[i], vC) + dot(D[i], w) for i in range(2)]
    det = G[0][0] * G[1][1] - G[0][1] * G[1][0]

    def cramer(b):
        return [(b[0] * G[1][1] - G[0][1] * b[1]) / det, (G[0][0] * b[1] - b[0] * G[1][0]) / det]

    T0 = (m * dot(vC, vC) + J[0] * w[0] ** 2 + J[1] * w[1] ** 2 + J[2] * w[2] ** 2) / 2

    def after(Pi):
        dv = [-(Pi[0] * X[0][k] + Pi[1] * X[1][k]) / m for k in range(3)]
        dw = [-(Pi[0] * D[0][k] + Pi[1] * D[1][k]) / J[k] for k in range(3)]
        v1 = [vC[k] + dv[k] for k in range(3)]
        w1 = [w[k] + dw[k] for k in range(3)]
        Ep = (m * dot(dv, dv) + J[0] * dw[0] ** 2 + J[1] * dw[1] ** 2 + J[2] * dw[2] ** 2) / 2
        dEc = T0 - (m * dot(v1, v1) + J[0] * w1[0] ** 2 + J[1] * w1[1] ** 2 + J[2] * w1[2] ** 2) / 2
        return {"impulses": Pi, "velocity": v1, "angular_velocity": w1,
                "lost_velocity_energy": Ep, "kinetic_energy_loss": dEc}

    PN = cramer([(one + kN[i]) * v0[i] for i in range(2)])
    PC = cramer(v0)
    poisson = after([(one + kP[i]) * PC[i] for i in range(2)])
    poisson["compression_impulses"] = PC
    return {"G": G, "det": det, "newton": after(PN), "poisson": poisson}


# ----------------------------------------------------------------------------------------------
# Peer 2b: python-flint (FLINT's fmpq), exact rationals, the same closed form
# ----------------------------------------------------------------------------------------------

try:
    import flint
except ImportError:  # optional: benches/peers/requirements.txt installs it
    flint = None


class FlintInputs:
    """The scene in FLINT rationals; the unit normals n/|n| (rational for the corpus's normals)
    are divided out here, before timing, as the numbers a caller passes."""

    def __init__(self, s: Scene):
        Q = lambda x: flint.fmpq(x.numerator, x.denominator)  # noqa: E731
        self.m = Q(s.mass)
        self.J = [Q(x) for x in s.inertia]
        self.vC = [Q(x) for x in s.velocity]
        self.w = [Q(x) for x in s.angular_velocity]
        self.pts = [[Q(x) for x in c.point] for c in s.contacts]
        self.X = []
        for c in s.contacts:
            n2 = sum(x * x for x in c.normal)
            r = math.isqrt(n2.numerator), math.isqrt(n2.denominator)
            assert F(r[0] * r[0], r[1] * r[1]) == n2, "the corpus's normals have rational lengths"
            self.X.append([Q(x / F(*r)) for x in c.normal])
        self.kN = [Q(c.k_newton) for c in s.contacts]
        self.kP = [Q(c.k_poisson) for c in s.contacts]


def flint_closed_form(x: FlintInputs) -> dict:
    """`sympy_closed_form`'s equations (eq. 57, 8, 20, 22-24, 28, 32; Cramer's rule, two contacts)
    in FLINT's fmpq: the strongest exact peer (GMP integers, canonical fractions)."""
    return cramer_closed_form(x.m, x.J, x.vC, x.w, x.X, x.pts, x.kN, x.kP, flint.fmpq(1))


def flint_as_sympy(out: dict) -> dict:
    """A `flint_closed_form` result in SymPy Rationals, for `compare_exact`."""
    R = lambda q: sp.Rational(int(q.p), int(q.q))  # noqa: E731

    def conv(v):
        if isinstance(v, dict):
            return {k: conv(x) for k, x in v.items()}
        if isinstance(v, list):
            return [conv(x) for x in v]
        return R(v)

    res = conv(out)
    res["G"] = sp.Matrix(res["G"])
    return res


def as_doubles(s: Scene) -> Scene:
    """The scene with every input but the normals replaced by the exact value of its nearest
    double (what a measured decimal becomes: denominators up to 2^60 and more); the normals stay
    the corpus's, whose lengths are rational."""
    D = lambda x: F(float(x))  # noqa: E731
    cs = [Contact(tuple(D(x) for x in c.point), c.normal, D(c.k_newton), D(c.k_poisson)) for c in s.contacts]
    return Scene(s.name + "-doubles", s.description + " (inputs: exact values of doubles)", D(s.mass),
                 tuple(D(x) for x in s.inertia), tuple(D(x) for x in s.velocity),
                 tuple(D(x) for x in s.angular_velocity), cs)


def sympy_no_slip(s: Scene, ex: dict) -> bool:
    """True when Pinocchio's 3-D contacts reproduce the frictionless solution exactly: for the
    frictionless (normal-only) Newton solution, every contact point's whole velocity after impact
    is -k times its whole velocity before.  Then zero tangential impulses satisfy the 3-D contact
    law, and since impulse dynamics is the M-metric projection onto that law (a unique velocity),
    Pinocchio's CONTACT_3D answer is the frictionless one."""
    if not s.equal_k:
        return False
    x = SympyInputs(s)
    k = x.kN[0]
    v1 = sp.Matrix(ex["newton"]["velocity"])
    w1 = sp.Matrix(ex["newton"]["angular_velocity"])
    for p in x.pts:
        before = x.vC + x.w.cross(p)
        after_ = v1 + w1.cross(p)
        if after_ != -k * before:
            return False
    return True


# ----------------------------------------------------------------------------------------------
# Peer 3: Pinocchio.  Conventions (README.md, "Conventions"): the free-flyer velocity is
# v = [v_C; omega] in the body frame (= the paper's Cxyz: the CoM is at the joint origin and the
# principal axes are the joint axes); the paper's twist is eta v = [omega; v_C].  The row of the
# normal-only constraint Jacobian of contact i is n_i^T J_frame,lin = [n_i; A_i x n_i]^T, i.e.
# the paper's {E_ix} read in [force; moment] order, so G = J M^-1 J^T (Delassus matrix) and
# Pinocchio's impulse lambda = -P (M dv = J^T lambda vs. M dv = -sum P_i E_ix).
# ----------------------------------------------------------------------------------------------


class PinScene:
    def __init__(self, s: Scene):
        x = NumpyInputs(s)
        model = pin.Model()
        jid = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), "body")
        model.appendBodyToJoint(jid, pin.Inertia(x.m, np.zeros(3), np.diag(x.J)), pin.SE3.Identity())
        self.fids = [model.addFrame(pin.Frame(f"A{i + 1}", jid, pin.SE3(np.eye(3), x.R[i]),
                                              pin.FrameType.OP_FRAME)) for i in range(len(x.R))]
        self.model, self.data = model, model.createData()
        self.q = pin.neutral(model)  # identity pose: world axes = body axes
        self.v0 = np.concatenate([x.vC, x.w])  # Pinocchio order [v; omega]
        self.N = x.Nraw / np.sqrt((x.Nraw * x.Nraw).sum(axis=1))[:, None]
        self.kN, self.kP = x.kN, x.kP
        self.e = float(s.k) if s.equal_k else None
        M = pin.crba(model, self.data, self.q)
        assert np.array_equal(M, M.T), "crba returned a non-symmetric M"
        # RigidConstraintModel path (3-D point contacts), set up once
        self.cms = pin.StdVec_RigidConstraintModel()
        for r in x.R:
            self.cms.append(pin.RigidConstraintModel(pin.ContactType.CONTACT_3D, model, jid,
                                                     pin.SE3(np.eye(3), r), pin.ReferenceFrame.LOCAL))
        self.cds = pin.StdVec_RigidConstraintData()
        for cm in self.cms:
            self.cds.append(cm.createData())
        pin.initConstraintDynamics(model, self.data, self.cms, self.cds)
        self.prox = pin.ProximalSettings(1e-14, 1e-14, PROX_MU, 100)

    def normal_jacobian(self) -> np.ndarray:
        """Rows n_i^T J_lin(A_i): the normal velocity of each contact point, from Pinocchio's
        kinematics (computeJointJacobians + getFrameJacobian, LOCAL frame = body axes)."""
        pin.computeJointJacobians(self.model, self.data, self.q)
        return np.array([n @ pin.getFrameJacobian(self.model, self.data, f, pin.ReferenceFrame.LOCAL)[:3]
                         for f, n in zip(self.fids, self.N)])

    def _outputs(self, M, v_after, P) -> dict:
        dv = v_after - self.v0
        Ep = 0.5 * dv @ M @ dv  # eq. 28 (M is Pinocchio's [v; omega] mass matrix)
        dEc = 0.5 * (self.v0 @ M @ self.v0 - v_after @ M @ v_after)  # eq. 32
        return {"impulses": P, "velocity": v_after[:3], "angular_velocity": v_after[3:],
                "lost_velocity_energy": Ep, "kinetic_energy_loss": dEc}

    def impulse_dynamics(self) -> dict:
        """pin.impulseDynamics(model, data, q, v_before, J, r_coeff, damping=0): Newton's law
        J v+ = -e J v- with the normal-only Jacobian; internally crba + Cholesky of J M^-1 J^T."""
        Jn = self.normal_jacobian()
        v_after = pin.impulseDynamics(self.model, self.data, self.q, self.v0, Jn, self.e, 0.0)
        P = -self.data.impulse_c
        r = self._outputs(self.data.M, v_after, P)
        return {"newton": r, "poisson": r}  # equal coefficients: Poisson = Newton (eq. 50-55)

    def impulse_dynamics_call(self, Jn) -> np.ndarray:
        """The bare impulseDynamics call with a precomputed Jacobian (timing floor)."""
        return pin.impulseDynamics(self.model, self.data, self.q, self.v0, Jn, self.e, 0.0)

    def contact3d(self) -> dict:
        """impulseDynamics with RigidConstraintModel CONTACT_3D at each point (the whole point
        velocity obeys v+ = -e v-); valid only for scenes that pass sympy_no_slip."""
        v_after = pin.impulseDynamics(self.model, self.data, self.q, self.v0, self.cms, self.cds,
                                      self.e, self.prox)
        lam = self.data.impulse_c.reshape(-1, 3)  # per contact, body axes (LOCAL, identity rotation)
        P = -np.einsum("ij,ij->i", lam, self.N)
        tang = lam + P[:, None] * self.N  # tangential part of each contact impulse
        r = self._outputs(self.data.M, v_after, P)
        r["tangential_impulse"] = float(np.abs(tang).max())
        return {"newton": r, "poisson": r}

    def algebra(self) -> dict:
        """Pinocchio's algebra, our solve: M = crba, J = normal rows of the frame Jacobians,
        G = J M^-1 J^T, then Newton and Poisson with a coefficient per contact."""
        M = pin.crba(self.model, self.data, self.q)
        Jn = self.normal_jacobian()
        MinvJt = np.linalg.solve(M, Jn.T)
        G = Jn @ MinvJt
        v0n = Jn @ self.v0
        sol = np.linalg.solve(G, np.column_stack(((1.0 + self.kN) * v0n, v0n)))  # Newton | Poisson c.
        PN, PC = sol[:, 0], sol[:, 1]
        PP = (1.0 + self.kP) * PC
        out = {"G": G, "det": np.linalg.det(G)}
        for name, P in (("newton", PN), ("poisson", PP)):
            out[name] = self._outputs(M, self.v0 - MinvJt @ P, P)
        out["poisson"]["compression_impulses"] = PC
        return out


# ----------------------------------------------------------------------------------------------
# Peer 3b: Pinocchio's impulseDynamics called from C++ (pinocchio_call.cpp), so that no Python
# sits between the clock and the call.  Built with g++ against the headers and libraries the
# `pin` wheel installs (its cmeel prefix) and Eigen's headers (`cmeel-eigen`), with the compile
# definitions Pinocchio's CMake package exports (pin_build.py, shared with chains.py).
# ----------------------------------------------------------------------------------------------

def pinocchio_cpp_binary(cache: Path):
    """The compiled pinocchio_call, or (None, reason).  Rebuilt when the source is newer."""
    return pin_build.pinocchio_binary(Path(__file__).with_name("pinocchio_call.cpp"), cache)


def pinocchio_cpp(binary: Path, scenes: list) -> dict:
    """Run pinocchio_call on the scenes with one coefficient (impulseDynamics has Newton's law
    only): name -> {"ns": ns per call, "impulse": [...], "v_after": [...]}."""
    eligible = [s for s in scenes if s.equal_k]
    lines = [str(len(eligible))]
    for s in eligible:
        x = NumpyInputs(s)
        N = x.Nraw / np.sqrt((x.Nraw * x.Nraw).sum(axis=1))[:, None]
        vals = [x.m, *x.J, *x.vC, *x.w, float(s.k), len(x.R)]
        for r, n in zip(x.R, N):
            vals += [*r, *n]
        lines.append(" ".join(repr(float(v)) if not isinstance(v, int) else str(v) for v in vals))
    p = subprocess.run([str(binary)], input="\n".join(lines) + "\n", capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"pinocchio_call failed (exit {p.returncode}): {p.stderr[-300:]}")
    out = {}
    for s, line in zip(eligible, p.stdout.splitlines()):
        j = json.loads(line)
        out[s.name] = {"ns": j["ns_per_call"], "impulse": np.array(j["impulse"]),
                       "v_after": np.array(j["v_after"])}
    return out


def pinocchio_cpp_outputs(s: Scene, r: dict) -> dict:
    """The C++ call's results as compare_f64 reads them (M = diag(m, m, m, J) in Pinocchio's
    [v; omega] order: the CoM at the joint origin, principal axes)."""
    x = NumpyInputs(s)
    M = np.diag([x.m, x.m, x.m, *x.J])
    v0 = np.concatenate([x.vC, x.w])
    v = r["v_after"]
    dv = v - v0
    out = {"impulses": -r["impulse"], "velocity": v[:3], "angular_velocity": v[3:],
           "lost_velocity_energy": 0.5 * dv @ M @ dv,
           "kinetic_energy_loss": 0.5 * (v0 @ M @ v0 - v @ M @ v)}
    return {"newton": out, "poisson": out}


# ----------------------------------------------------------------------------------------------
# inertance from Python: the package built from python/ (PyO3), imported in this process
# ----------------------------------------------------------------------------------------------


def import_inertance_py(site: str | None):
    """The `inertance` Python package, or (None, reason).

    Looked up, in order: `site` (a site-packages directory, --python-package); this interpreter's
    environment (`pip install ./python`); the virtual environment python/test.sh builds,
    `$CARGO_TARGET_DIR/python-test-venv` (default target/).  A directory found that way is
    appended to sys.path, after this environment's own, so numpy & co. stay this environment's
    and only `inertance` (an abi3 extension: any CPython >= 3.9) comes from there."""
    import glob
    import importlib

    def try_import():
        try:
            mod = importlib.import_module("inertance")
            importlib.import_module("inertance._inertance")
            return mod
        except ImportError:
            sys.modules.pop("inertance", None)
            return None

    if site:
        sys.path.insert(0, site)
        mod = try_import()
        return (mod, None) if mod else (None, f"no importable `inertance` package in {site}")
    mod = try_import()
    if mod:
        return mod, None
    targets = [os.environ.get("CARGO_TARGET_DIR"), str(REPO / "target")]
    for t in [t for t in targets if t]:
        for d in sorted(glob.glob(os.path.join(t, "python-test-venv", "lib", "python3*", "site-packages"))):
            if os.path.isdir(os.path.join(d, "inertance")):
                sys.path.append(d)
                mod = try_import()
                if mod:
                    return mod, None
                sys.path.remove(d)
    return None, ("the `inertance` Python package is not installed: `pip install ./python`, or run "
                  "python/test.sh (its venv is found through CARGO_TARGET_DIR or target/)")


def from_python(sol, conv) -> dict:
    """A Solution of the Python package in the comparison's shape (`conv` per number)."""
    G = sol.inertance
    out = {"G": [[conv(x) for x in row] for row in G], "det": conv(sol.det)}
    for model in ("newton", "poisson"):
        ms = getattr(sol, model)
        r = {q: (conv(getattr(ms, q)) if not hasattr(getattr(ms, q), "__len__")
                 else [conv(x) for x in getattr(ms, q)]) for q in QUANTITIES}
        if model == "poisson":
            r["compression_impulses"] = [conv(x) for x in ms.compression_impulses]
        out[model] = r
    return out


def read_outputs(sol):
    """Read every output the peers return (G, Δ, per model P, v_C, ω, E_p, ΔE_c; Poisson's
    compression impulses), as a Python user of the result would."""
    out = [sol.inertance, sol.det]
    for ms in (sol.newton, sol.poisson):
        out += [ms.impulses, ms.velocity, ms.angular_velocity, ms.lost_velocity_energy,
                ms.kinetic_energy_loss]
    out.append(sol.poisson.compression_impulses)
    return out


# ----------------------------------------------------------------------------------------------
# Agreement
# ----------------------------------------------------------------------------------------------


def compare_f64(peer: dict, ref: dict, T0: float, models=("newton", "poisson"), with_G=True) -> float:
    """Largest relative difference: vectors normwise (inf-norm, relative to the reference's norm),
    E_p relative to itself, Delta E_c relative to T0 (it is a difference of kinetic energies)."""
    worst = 0.0

    def rel(a, b, scale=None):
        a, b = np.atleast_1d(np.asarray(a, float)), np.atleast_1d(np.asarray(b, float))
        s = scale if scale is not None else max(np.abs(b).max(), 1e-300)
        return float(np.abs(a - b).max() / s)

    if with_G and "G" in peer:
        worst = max(worst, rel(peer["G"], ref["G"]), rel(peer["det"], ref["det"]))
    for m in models:
        p, r = peer[m], ref[m]
        for q in ("impulses", "velocity", "angular_velocity", "lost_velocity_energy"):
            worst = max(worst, rel(p[q], r[q]))
        worst = max(worst, rel(p["kinetic_energy_loss"], r["kinetic_energy_loss"], T0))
        if "compression_impulses" in p:
            worst = max(worst, rel(p["compression_impulses"], r["compression_impulses"]))
    return worst


def compare_exact(peer: dict, ref: dict) -> list:
    """Exact equality of every value; returns the list of mismatching keys."""
    bad = []

    def eq(a, b):
        return sp.Rational(a) == b if isinstance(a, sp.Rational) and isinstance(b, sp.Rational) \
            else sp.simplify(a - b) == 0

    if not all(eq(a, b) for a, b in zip(list(peer["G"]), [x for row in ref["G"] for x in row])):
        bad.append("G")
    if not eq(peer["det"], ref["det"]):
        bad.append("det")
    for m in ("newton", "poisson"):
        for q, v in ref[m].items():
            pv = peer[m][q]
            ok = all(eq(a, b) for a, b in zip(pv, v)) if isinstance(v, list) else eq(pv, v)
            if not ok:
                bad.append(f"{m}.{q}")
    return bad


# ----------------------------------------------------------------------------------------------
# inertance: binary, solve, bench
# ----------------------------------------------------------------------------------------------


def inertance_bin(path: str | None, rebuild: bool) -> Path:
    target = Path(os.environ.get("CARGO_TARGET_DIR") or REPO / "target")
    b = Path(path) if path else target / "release" / "inertance"
    if rebuild or not b.exists():
        if path:
            sys.exit(f"error: {b} does not exist")
        print(f"building {b} (cargo build --release) ...", file=sys.stderr, flush=True)
        subprocess.run(["cargo", "build", "--release"], cwd=REPO, check=True)
    return b


def run_json(cmd: list) -> dict:
    p = subprocess.run([str(c) for c in cmd], capture_output=True, text=True)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} exited {p.returncode}: {p.stderr.strip()}")
    return json.loads(p.stdout)


def inertance_bench(binary: Path, scene_path: Path):
    """ns per solve from `inertance bench --scene SCENE --json`, or (None, reason)."""
    p = subprocess.run([str(binary), "bench", "--scene", str(scene_path), "--json"],
                       capture_output=True, text=True)
    if p.returncode != 0:
        first = (p.stderr.strip().splitlines() or ["no output"])[0]
        return None, f"`inertance bench` failed (exit {p.returncode}: {first})"
    try:
        ns = json.loads(p.stdout)["ns_per_solve"]
    except (ValueError, KeyError) as e:
        return None, f"`inertance bench` printed unexpected JSON ({e})"
    return ns, None


# ----------------------------------------------------------------------------------------------
# Timing
# ----------------------------------------------------------------------------------------------


def time_per_call(fn, repeat: int, min_time: float) -> float:
    """Median over `repeat` runs of the mean time per call; each run lasts >= min_time seconds
    (timeit, garbage collection off).  Everything the callable needs is built beforehand."""
    fn()  # warm-up
    t = timeit.Timer(fn)
    number = 1
    while True:
        if t.timeit(number) >= min_time:
            break
        number *= 2
    return statistics.median(t.repeat(repeat=repeat, number=number)) / number


def fmt_time(s: float | None) -> str:
    if s is None:
        return "—"
    ns = s * 1e9
    if ns < 1e3:
        return f"{ns:.0f} ns"
    if ns < 1e6:
        return f"{ns / 1e3:.3g} µs"
    if ns < 1e9:
        return f"{ns / 1e6:.3g} ms"
    return f"{ns / 1e9:.3g} s"


def fmt_ratio(r: float | None) -> str:
    if r is None:
        return "—"
    return f"{r:.3g}×" if r < 1000 else f"{r:,.0f}×"


# ----------------------------------------------------------------------------------------------
# Main
# ----------------------------------------------------------------------------------------------


def machine_info(binary: Path, py, py_why) -> list:
    cpu = platform.processor() or "unknown"
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        ver = subprocess.run([str(binary), "--version"], capture_output=True, text=True).stdout.strip()
    except OSError:
        ver = "?"
    pyline = (f"inertance (Python package) from {Path(py.__file__).parent}" if py
              else f"inertance (Python package) unavailable: {py_why}")
    return [
        f"date      {datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%d %H:%M UTC')}",
        f"machine   {platform.platform()}; {cpu}; {os.cpu_count()} logical CPUs",
        f"python    {platform.python_version()} ({platform.python_implementation()})",
        f"versions  pin {pin.__version__}, numpy {np.__version__}, sympy {sp.__version__}; {ver}",
        f"binary    {binary}",
        f"package   {pyline}",
        "load      1-min load average {:.2f} at start (other work on the machine disturbs timings)".format(
            os.getloadavg()[0]) if hasattr(os, "getloadavg") else "load      unknown",
    ]


METHODS = [
    # key, label
    ("numpy", "numpy closed form (eq. 57, 20, 24)"),
    ("pin_id", "pinocchio impulseDynamics, normal J"),
    ("pin_id_call", "  … the impulseDynamics call alone"),
    ("pin_cpp", "  … the same call from C++ (no Python)"),
    ("pin_alg", "pinocchio crba+Jacobians, numpy solve"),
    ("pin_3d", "pinocchio impulseDynamics, CONTACT_3D"),
    ("sympy", "sympy exact (Rational, LUsolve)"),
]
# inertance called from Python (the package), timed like the peers
PY_METHODS = [
    ("py_f64", "inertance.solve(Scene), f64 (Python)"),
    ("py_f64_read", "  … and reading every output"),
    ("py_exact", "inertance.solve(Scene, exact=True) (Py)"),
    ("py_exact_read", "  … and reading every output"),
]
# the four references a time is divided by: inertance f64 / exact in Rust (`inertance bench`,
# in-process) and from Python (`inertance.solve` on a prebuilt Scene)
REFS = [("f64/lean-newton", "÷ lean Newton"), ("f64/lean", "÷ Rust lean"), ("f64", "÷ Rust f64"), ("exact", "÷ Rust exact"), ("py_f64", "÷ Py f64"),
        ("py_exact", "÷ Py exact")]
REF_W = 13


def ratio_cols(t: float | None, ref: dict) -> str:
    return " ".join(f"{fmt_ratio(t / ref[k] if t and ref.get(k) else None):>{REF_W}}" for k, _ in REFS)


def batch_compare(py, binary: Path, points: int, rounds: int) -> None:
    """Issue 17, item 4: the batch API per point from Rust (`inertance bench --scene --batch`,
    tools::sweep::solve_batch in-process) and from Python (`inertance.solve_batch`), same scene
    and same points, rounds alternating between the two; medians over the rounds."""
    scene_path = REPO / "examples" / "planar-bar.toml"
    path = "contact[1].k"
    spec = f"{path}=0:1:{points}"
    # the grid inertance's Vary gives: i/(points-1) exactly, correctly rounded to f64
    values = np.array([float(F(i, points - 1)) for i in range(points)])
    scene = py.Scene.load(str(scene_path))
    runs = 3

    def python_run() -> float:
        py.solve_batch(scene, {path: values})  # warm-up
        ts = []
        for _ in range(runs):
            t = timeit.default_timer()
            py.solve_batch(scene, {path: values})
            ts.append((timeit.default_timer() - t) / points)
        return statistics.median(ts)

    print(f"── batch: solve_batch per point, examples/planar-bar.toml, {path} = 0 … 1 ({points:,} points), "
          f"{rounds} rounds Rust / Python alternating")
    rs, ps, threads = [], [], "?"
    for r in range(rounds):
        try:
            j = run_json([binary, "bench", "--quick", "--json", "--scene", scene_path, "--batch", spec])
            rs.append(j["batch"]["ns_per_point"] * 1e-9)
            threads = j["batch"]["threads"]
        except (RuntimeError, KeyError, ValueError) as e:
            print(f"   Rust batch timing unavailable ({e})")
            return
        gc_was = gc.isenabled()
        gc.disable()  # as timeit does for the per-solve timings
        try:
            ps.append(python_run())
        finally:
            if gc_was:
                gc.enable()
        print(f"   round {r + 1}: Rust {fmt_time(rs[-1])}, Python {fmt_time(ps[-1])} per point "
              f"(Python ÷ Rust {ps[-1] / rs[-1]:.2f}×)")
    rm, pm = statistics.median(rs), statistics.median(ps)
    print(f"   {'Rust tools::sweep::solve_batch (inertance bench --batch)':<58} {fmt_time(rm):>11} per point")
    print(f"   {'Python inertance.solve_batch (arrays in, numpy arrays out)':<58} {fmt_time(pm):>11} per point")
    print(f"   Python ÷ Rust: {pm / rm:.2f}× (medians over {rounds} rounds of the median of {runs} runs "
          f"each; {threads} rayon threads both)")
    print()


def corpus_compare(py, binary: Path, corpus: Path, n: int, rounds: int, outdir: Path,
                   doubles: bool = False) -> bool:
    """Issue 15, item 4: the exact solve on the peer corpus (the first `n` scenes of `corpus`),
    side by side with SymPy: rounds alternate between `inertance bench --corpus` (Rust in-process:
    Exact, plain BigRational, f64, each the median of 5 passes over the corpus) and one timed pass
    of `sympy_solve` over every scene (inputs built beforehand); medians over the rounds, per
    scene.  Every scene is first checked: `inertance solve --exact --json` equals SymPy exactly.
    Issue 29, item 4: python-flint's closed form beside them (agreement and time), and with
    `doubles` the same scenes with their inputs replaced by the exact values of doubles
    (`as_doubles`: what measured data become)."""
    scenes = read_corpus(corpus, n)
    if doubles:
        scenes = [as_doubles(s) for s in scenes]
    sub = outdir / ("corpus-doubles.txt" if doubles else "corpus.txt")
    sub.write_text("\n".join(corpus_line(s) for s in scenes) + "\n")
    print(f"── exact corpus: {len(scenes)} random two-contact scenes of {corpus.relative_to(REPO)}"
          + (", every input but the normals the exact value of its double" if doubles else "")
          + " (assemble + Newton + Poisson, every output; SymPy and python-flint: G, Δ, both models)")
    xs = [SympyInputs(s) for s in scenes]
    fx = [FlintInputs(s) for s in scenes] if flint else []
    if not flint:
        print("   python-flint not installed (pip install python-flint): its column is left out")
    bad = []
    for s, x in zip(scenes, xs):
        path = outdir / f"{s.name}.toml"
        path.write_text(scene_toml(s))
        refex = from_inertance(run_json([binary, "solve", path, "--json", "--exact"]), sp.sympify)
        if compare_exact(sympy_solve(x), refex) or compare_exact(sympy_closed_form(x), refex):
            bad.append(s.name)
        elif flint and compare_exact(flint_as_sympy(flint_closed_form(FlintInputs(s))), refex):
            bad.append(s.name + " (flint)")
    print(f"   agreement: inertance --exact == SymPy (both methods)" + (" == python-flint" if flint else "")
          + f" on {len(scenes) - len(bad)} of {len(scenes)} scenes"
          + (f"; DIFFERS on {', '.join(bad[:5])}" if bad else ""))
    py_scenes = [py.Scene.load(str(outdir / f"{s.name}.toml")) for s in scenes] if py else []
    rust, sym, closed, pyx, fl = [], [], [], [], []
    for r in range(rounds):
        try:
            j = run_json([binary, "bench", "--corpus", sub, "--json"])
            rust.append({k: v * 1e-9 for k, v in j["ns_per_solve"].items() if v is not None})
        except (RuntimeError, KeyError, ValueError) as e:
            print(f"   Rust corpus timing unavailable ({e})")
            return not bad
        gc_was = gc.isenabled()
        gc.disable()
        try:
            t = timeit.default_timer()
            for x in xs:
                sympy_solve(x)
            sym.append((timeit.default_timer() - t) / len(xs))
            t = timeit.default_timer()
            for x in xs:
                sympy_closed_form(x)
            closed.append((timeit.default_timer() - t) / len(xs))
            if flint:
                t = timeit.default_timer()
                for x in fx:
                    flint_closed_form(x)
                fl.append((timeit.default_timer() - t) / len(fx))
            if py:
                t = timeit.default_timer()
                for sc in py_scenes:
                    py.solve(sc, exact=True)
                pyx.append((timeit.default_timer() - t) / len(py_scenes))
        finally:
            if gc_was:
                gc.enable()
        print(f"   round {r + 1}: Rust exact {fmt_time(rust[-1].get('exact'))}, "
              f"BigRational {fmt_time(rust[-1].get('bigrational'))}, SymPy LU {fmt_time(sym[-1])}, "
              f"SymPy closed form {fmt_time(closed[-1])} per scene"
              + (f", python-flint closed form {fmt_time(fl[-1])}" if flint else "")
              + (f", Python exact {fmt_time(pyx[-1])}" if py else ""))
    med = {k: statistics.median(t[k] for t in rust) for k in ("exact", "bigrational", "f64") if all(k in t for t in rust)}
    s_med, c_med = statistics.median(sym), statistics.median(closed)
    rows = [("inertance exact, Rust in-process (Exact)", med.get("exact")),
            ("inertance exact on plain BigRational (before)", med.get("bigrational")),
            ("inertance f64, Rust in-process", med.get("f64"))]
    if py:
        rows.append(("inertance.solve(scene, exact=True), Python", statistics.median(pyx)))
    rows.append(("SymPy exact (Rational, LUsolve)", s_med))
    rows.append(("SymPy exact closed form (Rational, Cramer)", c_med))
    f_med = statistics.median(fl) if fl else None
    if f_med:
        rows.append(("python-flint closed form (fmpq, Cramer)", f_med))
    print(f"   {'method':<48} {'per scene':>11} {'LU ÷ it':>11} {'closed ÷ it':>11} {'it ÷ flint':>11}")
    for label, t in rows:
        print(f"   {label:<48} {fmt_time(t):>11} {fmt_ratio(s_med / t if t else None):>11} "
              f"{fmt_ratio(c_med / t if t else None):>11} {fmt_ratio(t / f_med if t and f_med else None):>11}")
    if f_med and med.get("exact"):
        print(f"   goal (issue 29, item 4): inertance exact within 2× of python-flint's closed form — "
              f"measured {med['exact'] / f_med:.1f}×")
    if med.get("exact") and med.get("bigrational"):
        print(f"   BigRational ÷ Exact: {med['bigrational'] / med['exact']:.1f}×; SymPy ÷ inertance exact: "
              f"{s_med / med['exact']:.1f}× (LU), {c_med / med['exact']:.1f}× (closed form); "
              f"medians over {rounds} rounds")
    print()
    return not bad


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--seed", type=int, default=1924, help="seed of the random scenes (default 1924)")
    ap.add_argument("--random", type=int, default=4, help="number of random scenes (default 4)")
    ap.add_argument("--repeat", type=int, default=7, help="timing runs per method (median; default 7)")
    ap.add_argument("--min-time", type=float, default=0.2, help="seconds per timing run (default 0.2)")
    ap.add_argument("--inertance", help="path to the inertance binary (default release/inertance in $CARGO_TARGET_DIR or target/)")
    ap.add_argument("--rebuild", action="store_true", help="run `cargo build --release` first")
    ap.add_argument("--python-package", metavar="DIR",
                    help="site-packages directory holding the inertance Python package (default: this "
                         "environment's, else python/test.sh's venv under CARGO_TARGET_DIR or target/)")
    ap.add_argument("--batch-points", type=int, default=100_000,
                    help="points of the batch comparison (default 100000; 0 skips it)")
    ap.add_argument("--batch-rounds", type=int, default=3,
                    help="alternating Rust / Python rounds of the batch comparison (default 3)")
    ap.add_argument("--keep", help="write the scene TOML files to this directory and keep them")
    ap.add_argument("--corpus-scenes", type=int, default=1000,
                    help="scenes of benches/peers/corpus.txt in the exact corpus comparison (default all "
                         "1000; 0 skips it)")
    ap.add_argument("--corpus-rounds", type=int, default=3,
                    help="alternating Rust / SymPy rounds of the exact corpus comparison (default 3)")
    ap.add_argument("--doubles-scenes", type=int, default=200,
                    help="scenes of the corpus run again with their inputs the exact values of doubles "
                         "(default 200; 0 skips it)")
    ap.add_argument("--corpus-only", action="store_true",
                    help="run only the exact corpus comparison (no Pinocchio or numpy, no batch)")
    ap.add_argument("--write-corpus", type=int, metavar="N",
                    help="write N random scenes (seed --seed) to benches/peers/corpus.txt and exit")
    args = ap.parse_args()

    if args.write_corpus:
        write_corpus(CORPUS, args.seed, args.write_corpus)
        print(f"wrote {args.write_corpus} scenes to {CORPUS}")
        return 0

    binary = inertance_bin(args.inertance, args.rebuild)
    py, py_why = import_inertance_py(args.python_package)
    print("inertance peer comparison (benches/peers/compare.py)")
    for line in machine_info(binary, py, py_why):
        print("  " + line)
    print(f"  timing    median of {args.repeat} runs of >= {args.min_time} s each (timeit, gc off); "
          f"agreement: f64 peers within {RTOL:g} relative of inertance f64, sympy == inertance --exact")
    print("  columns   time per solve ÷ inertance's: Rust = `inertance bench` in-process; "
          "Py = `inertance.solve` on a prebuilt Scene, from this Python")
    print()

    tmp = tempfile.TemporaryDirectory(prefix="inertance-peers-")
    outdir = Path(args.keep) if args.keep else Path(tmp.name)
    outdir.mkdir(parents=True, exist_ok=True)
    if args.corpus_only:
        ok = corpus_compare(py, binary, CORPUS, args.corpus_scenes, max(1, args.corpus_rounds), outdir)
        if args.doubles_scenes:
            ok &= corpus_compare(py, binary, CORPUS, args.doubles_scenes, max(1, args.corpus_rounds), outdir,
                                 doubles=True)
        tmp.cleanup()
        return 0 if ok else 1
    scenes = build_scenes(args.seed, args.random)

    all_ok = True
    bench_reason = None
    all_methods = PY_METHODS + METHODS
    ratios = {key: {k: [] for k, _ in REFS} for key, _ in all_methods}
    times = {key: [] for key, _ in all_methods}
    inert_times = {"f64/lean-newton": [], "f64/lean": [], "f64/impulses,twist": [], "f64": [], "exact": []}
    cpp_bin, cpp_why = pinocchio_cpp_binary(Path(os.environ.get("CARGO_TARGET_DIR", "target")) / "peers")
    cpp = pinocchio_cpp(cpp_bin, scenes) if cpp_bin else {}

    for s in scenes:
        path = outdir / f"{s.name}.toml"
        path.write_text(scene_toml(s))
        ref64 = from_inertance(run_json([binary, "solve", path, "--json"]), float)
        refex = from_inertance(run_json([binary, "solve", path, "--json", "--exact"]), sp.sympify)
        ns, why = inertance_bench(binary, path)
        if ns is None:
            bench_reason = why

        xs, xn, ps = SympyInputs(s), NumpyInputs(s), PinScene(s)
        ex = sympy_solve(xs)
        T0 = float((xs.m * xs.vC.dot(xs.vC) + sum(j * wi * wi for j, wi in zip(xs.J, xs.w))) / 2)
        G = np.array(ex["G"].tolist(), dtype=float)
        no_slip = sympy_no_slip(s, ex)

        # -- agreement --------------------------------------------------------------------------
        agree, runners = {}, {}
        bad_py = []
        if py:
            sc = py.Scene.load(str(path))  # prebuilt, as every peer's inputs are
            d = compare_f64(from_python(py.solve(sc), float), ref64, T0)
            agree["py_f64"] = f"{d:.1e}"
            agree["py_f64_read"] = "(same)"
            pex = from_python(py.solve(sc, exact=True), lambda x: sp.sympify(str(x)))  # Fraction → Rational
            pex["G"] = sp.Matrix(pex["G"])
            bad_py = compare_exact(pex, refex)
            agree["py_exact"] = "exact ==" if not bad_py else "DIFFERS: " + ", ".join(bad_py)
            agree["py_exact_read"] = "(same)"
            runners["py_f64"] = lambda sc=sc: py.solve(sc)
            runners["py_f64_read"] = lambda sc=sc: read_outputs(py.solve(sc))
            runners["py_exact"] = lambda sc=sc: py.solve(sc, exact=True)
            runners["py_exact_read"] = lambda sc=sc: read_outputs(py.solve(sc, exact=True))
        agree["numpy"] = f"{compare_f64(numpy_solve(xn), ref64, T0):.1e}"
        runners["numpy"] = lambda xn=xn: numpy_solve(xn)
        agree["pin_alg"] = f"{compare_f64(ps.algebra(), ref64, T0):.1e}"
        runners["pin_alg"] = ps.algebra
        if s.equal_k:
            agree["pin_id"] = f"{compare_f64(ps.impulse_dynamics(), ref64, T0, with_G=False):.1e}"
            runners["pin_id"] = ps.impulse_dynamics
            Jn = ps.normal_jacobian()
            agree["pin_id_call"] = "(same)"
            runners["pin_id_call"] = lambda ps=ps, Jn=Jn: ps.impulse_dynamics_call(Jn)
        if s.name in cpp:
            d = compare_f64(pinocchio_cpp_outputs(s, cpp[s.name]), ref64, T0, with_G=False)
            agree["pin_cpp"] = f"{d:.1e}"
            runners["pin_cpp"] = None  # timed in C++ (pinocchio_call.cpp)
        if no_slip:
            r3 = ps.contact3d()
            d = compare_f64(r3, ref64, T0, with_G=False)
            tang = r3["newton"]["tangential_impulse"] / max(np.abs(r3["newton"]["impulses"]).max(), 1e-300)
            agree["pin_3d"] = f"{max(d, tang):.1e}"
            runners["pin_3d"] = ps.contact3d
        bad = compare_exact(ex, refex)
        agree["sympy"] = "exact ==" if not bad else "DIFFERS: " + ", ".join(bad)
        runners["sympy"] = lambda xs=xs: sympy_solve(xs)

        exact_keys = ("sympy", "py_exact")
        failed = [k for k, v in agree.items()
                  if (k == "sympy" and bad) or (k == "py_exact" and bad_py)
                  or (k not in exact_keys and v != "(same)" and float(v) > RTOL)]
        all_ok &= not failed

        # -- timing -----------------------------------------------------------------------------
        ref = {}
        # the lean path (impact::lean, impulses and twist; null where its route refuses the
        # scene), the cheapest generic path (impulses and twist asked for), every output
        for key in ("f64/lean-newton", "f64/lean", "f64/impulses,twist", "f64", "exact"):
            if ns and ns.get(key) is not None:
                ref[key] = ns[key] * 1e-9
                inert_times[key].append(ref[key])
        measured = {}
        if s.name in cpp:
            measured["pin_cpp"] = cpp[s.name]["ns"] * 1e-9
        for key in ("py_f64", "py_exact"):  # the Python references first
            if key in runners:
                measured[key] = time_per_call(runners[key], args.repeat, args.min_time)
                ref[key] = measured[key]

        ks = ", ".join(str(c.k_newton) if c.k_newton == c.k_poisson else f"{c.k_newton}/{c.k_poisson}"
                       for c in s.contacts)
        print(f"── {s.name}: {s.description}")
        print(f"   m = {s.mass}, J = ({', '.join(map(str, s.inertia))}), k = ({ks}), "
              f"cond₂(G) = {np.linalg.cond(G):.3g}, Δ = {ex['det']}")
        hdr = (f"   {'method':<40} {'time/solve':>11} " + " ".join(f"{h:>{REF_W}}" for _, h in REFS)
               + "  agreement")
        print(hdr)
        print("   " + "─" * (len(hdr) - 3))
        if ns:
            for key in ("f64/lean-newton", "f64/lean", "f64/impulses,twist", "f32", "f64", "double-double",
                        "exact"):
                if key in ns and ns[key] is not None:
                    t = ns[key] * 1e-9
                    print(f"   {'inertance ' + key + ' (Rust, bench)':<40} {fmt_time(t):>11} "
                          f"{ratio_cols(t, ref)}  (reference)")
        else:
            print(f"   {'inertance (Rust, bench)':<40} inertance timing unavailable: {bench_reason}")
        if not py:
            print(f"   {'inertance (Python package)':<40} unavailable: {py_why}")
        for key, label in all_methods:
            if key not in runners:
                if key.startswith("py_"):
                    continue
                why_na = {"pin_id": "n/a: one r_coeff only, k differ",
                          "pin_id_call": "n/a",
                          "pin_cpp": "n/a" if s.equal_k else "n/a: one r_coeff only",
                          "pin_3d": "n/a: 3-D contacts would also stop sliding"}[key]
                print(f"   {label:<40} {'—':>11} " + " ".join(f"{'—':>{REF_W}}" for _ in REFS)
                      + f"  {why_na}")
                continue
            if key in measured:
                t = measured[key]
            else:
                reps = args.repeat if key not in ("sympy", "py_exact_read") else max(3, args.repeat // 2)
                t = time_per_call(runners[key], reps, args.min_time)
            times[key].append(t)
            for k, _ in REFS:
                if ref.get(k):
                    ratios[key][k].append(t / ref[k])
            flag = "  ✗ FAIL" if key in failed else ""
            print(f"   {label:<40} {fmt_time(t):>11} {ratio_cols(t, ref)}  {agree[key]}{flag}")
        print()

    # -- summary ----------------------------------------------------------------------------------
    def gmean(v):
        return math.exp(sum(math.log(x) for x in v) / len(v)) if v else None

    print(f"── summary over {len(scenes)} scenes (geometric means; a peer's mean is over the scenes it solves)")
    hdr = (f"   {'method':<40} {'scenes':>6} {'time/solve':>11} "
           + " ".join(f"{h:>{REF_W}}" for _, h in REFS))
    print(hdr)
    print("   " + "─" * (len(hdr) - 3))
    for key in ("f64/lean-newton", "f64/lean", "f64/impulses,twist", "f64", "exact"):
        if inert_times[key]:
            print(f"   {'inertance ' + key + ' (Rust, bench)':<40} {len(inert_times[key]):>6} "
                  f"{fmt_time(gmean(inert_times[key])):>11}")
    for key, label in all_methods:
        if not times[key]:
            continue
        cols = " ".join(f"{fmt_ratio(gmean(ratios[key][k])):>{REF_W}}" for k, _ in REFS)
        print(f"   {label:<40} {len(times[key]):>6} {fmt_time(gmean(times[key])):>11} {cols}")
    print()
    if not cpp_bin:
        print(f"Pinocchio from C++ unavailable: {cpp_why}.")
    if bench_reason:
        print(f"inertance timing unavailable: {bench_reason}; the Rust ratios were not computed.")
    if not py:
        print(f"inertance Python package unavailable ({py_why}); the Python ratios were not computed.")
    print("agreement: " + ("every peer agrees with inertance" if all_ok else "SOME PEER DISAGREES (see ✗)"))
    print()
    if args.corpus_scenes > 0:
        all_ok &= corpus_compare(py, binary, CORPUS, args.corpus_scenes, max(1, args.corpus_rounds), outdir)
        if args.doubles_scenes:
            all_ok &= corpus_compare(py, binary, CORPUS, args.doubles_scenes, max(1, args.corpus_rounds), outdir,
                                     doubles=True)
    if py and args.batch_points > 1:
        batch_compare(py, binary, args.batch_points, max(1, args.batch_rounds))
    if args.keep:
        print(f"scenes kept in {outdir}")
    tmp.cleanup()
    return 0 if all_ok else 1


if __name__ == "__main__":
    sys.exit(main())
