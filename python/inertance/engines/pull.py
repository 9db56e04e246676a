"""An impulse that pulls: the contact impulses an engine's answer needs, derived from its twist change.

An engine reports twists after impact, not impulses. The impulses are recovered from the twist
change where it determines them: with W the contact wrench matrix (per contact a column per
impulse component: the normal, and where μ > 0 the two tangents; body a = the contact's first
body takes −p n, the second +p n, each with its moment about the centre of mass) and M the
bodies' mass matrix (m, and J in world axes), the impulses p solve

    W p = M (ξ − ξ⁰)

in least squares (in the metric M⁻¹, the kinetic-energy metric of the grades). All are
**determined** when W has full column rank (one contact; a bar on two supports; an edge). Where
it has not, a contact's normal impulse is still determined when no impulse set in W's null
space (impulses that change no twist) touches it — an edge with friction: the difference of
the two corners' tangential impulses along the edge is free, their normals are not. A normal
in the null space's support is **not determined** (``None`` in ``normal_impulses``; the flat
box: four normals on one face, rank 3; a ball pressed into a corner with friction): no pull is
graded there, and where no normal is determined ``pull`` is ``None`` and the report says "n.d."
— the exact answer itself is one of infinitely many impulse sets there.

``pull`` = −min over contacts of the normal impulse / P, P the impact's impulse scale: the
largest over the scene's contacts of the impulse that would stop that contact alone,
m_eff,c · (approach speed of c), m_eff,c = 1 / (w_cᵀ M⁻¹ w_c). Flagged ``!pull`` above
``PULL_TOLERANCE`` = 10⁻³ of P: the exact f64 answer's derived impulses are non-negative to
≈10⁻¹⁵ P (rounding through a least-squares solve whose condition number is below 10³ on the
catalogue), an f32 engine's rounding ≈10⁻⁷ P times that, so a flagged answer needs a contact to
pull by three orders more than rounding can explain (the same 0.1 % as ``+E`` and ``!sym``).

``unexplained`` = ‖M⁻¹(W p) − (ξ − ξ⁰)‖_M / ‖ξ* − ξ⁰‖_M: the part of the engine's twist change
that impulses at the scene's contacts (normal only where μ = 0) cannot produce — an impulse
elsewhere (another corner, a second impact), a tangential impulse in a frictionless scene, or
contact points that moved during a long soft contact. The derived impulses assume the scene's
contact points and normals; where ``unexplained`` is large the pull reading is the best fit, not
a measurement, and the report lists both numbers.
"""

from __future__ import annotations

from typing import Optional, Sequence

import numpy as np

#: The normal impulse below −PULL_TOLERANCE · P that is flagged ``!pull`` (see the docstring).
PULL_TOLERANCE = 1e-3

#: W's columns are independent when its smallest singular value (in the metric M⁻¹) exceeds this
#: fraction of its largest: far above f64 rounding, far below any catalogue geometry's conditioning.
RANK_TOLERANCE = 1e-9


def _tangents(n: np.ndarray) -> tuple:
    a = np.array([1.0, 0.0, 0.0]) if abs(n[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    t1 = np.cross(n, a)
    t1 /= np.linalg.norm(t1)
    return t1, np.cross(n, t1)


def wrench_matrix(engine) -> tuple:
    """(W, normal columns): W is 6·bodies × components, the generalised impulse (linear, angular
    about the centre of mass, world axes) of a unit impulse per component; ``normal columns`` the
    index of each contact's normal component."""
    nb = len(engine.bodies)
    cols, normals = [], []
    for c in engine.contacts:
        dirs = [c.normal] + (list(_tangents(c.normal)) if c.friction > 0 else [])
        normals.append(len(cols))
        for d in dirs:
            col = np.zeros(6 * nb)
            for k, i in enumerate(c.bodies):
                sign = -1.0 if k == 0 else 1.0
                r = c.point - engine.bodies[i].position
                col[6 * i:6 * i + 3] += sign * d
                col[6 * i + 3:6 * i + 6] += sign * np.cross(r, d)
            cols.append(col)
    return np.array(cols).T, normals


def mass_matrix(engine) -> np.ndarray:
    nb = len(engine.bodies)
    m = np.zeros((6 * nb, 6 * nb))
    for i, b in enumerate(engine.bodies):
        m[6 * i:6 * i + 3, 6 * i:6 * i + 3] = b.mass * np.eye(3)
        m[6 * i + 3:6 * i + 6, 6 * i + 3:6 * i + 6] = b.inertia_world
    return m


def _vector(twists) -> np.ndarray:
    return np.concatenate([np.concatenate([t.velocity, t.angular_velocity]) for t in twists])


def impulse_scale(engine, before) -> float:
    """P: the largest over the contacts of m_eff,c · approach speed_c (kg·m/s)."""
    w, normals = wrench_matrix(engine)
    minv = np.linalg.inv(mass_matrix(engine))
    v0 = _vector(before)
    best = 0.0
    for j in normals:
        col = w[:, j]
        approach = -(col @ v0)  # colᵀξ = −(velocity of the contact point along n, relative): approach > 0
        best = max(best, max(0.0, approach) / (col @ minv @ col))
    return best


def derive(engine, before: Sequence, after: Sequence, exact: Sequence) -> dict:
    """The normal impulses the twist change ``after − before`` needs at the scene's contacts:
    ``{"determined", "normal_impulses" (per contact, kg·m/s, positive pushes; None when not
    determined), "pull" (−min/P, or None), "unexplained", "scale" (P), "condition"}``."""
    w, normals = wrench_matrix(engine)
    m = mass_matrix(engine)
    minv = np.linalg.inv(m)
    # the metric M⁻¹ on impulses: scale rows by M^{-1/2} (M is block diagonal, symmetric positive)
    evals, evecs = np.linalg.eigh(minv)
    half = evecs @ np.diag(np.sqrt(evals)) @ evecs.T
    a = half @ w
    d = _vector(after) - _vector(before)
    b = half @ (m @ d)
    _, sv, vt = np.linalg.svd(a)
    rank = int(np.sum(sv > RANK_TOLERANCE * sv[0])) if len(sv) else 0
    null = vt[rank:]  # impulse sets that change no twist: a component they touch is not determined
    fixed = [bool(np.all(np.abs(null[:, j]) <= RANK_TOLERANCE)) for j in normals] if len(null) else [True] * len(normals)
    determined = all(fixed)
    p, *_ = np.linalg.lstsq(a, b, rcond=None)
    impact = float(np.sqrt(max(0.0, (_vector(exact) - _vector(before)) @ m @ (_vector(exact) - _vector(before)))))
    residual = minv @ (w @ p) - d
    unexplained = float(np.sqrt(max(0.0, residual @ m @ residual)) / impact) if impact > 0 else 0.0
    scale = impulse_scale(engine, before)
    out = {"determined": determined, "scale": scale, "unexplained": unexplained,
           "condition": float(sv[0] / sv[rank - 1]) if rank else float("inf")}
    pn = [float(p[j]) if f else None for j, f in zip(normals, fixed)]
    known = [x for x in pn if x is not None]
    out["normal_impulses"] = pn if known else None
    out["pull"] = (float(max(0.0, -min(known)) / scale) if scale > 0 else 0.0) if known else None
    return out
