"""The symmetries of a scene, computed, and the part of a twist that breaks them.

A scene is symmetric under an isometry S (x ↦ c + Q(x − c), Q orthogonal) when S maps it onto
itself: every body onto a body of the same shape, size, mass and pose (its surface features —
a box's corners, a cylinder's end centres, a sphere's centre — onto the other's), every contact
onto a contact of the same coefficients with its point and normal mapped, every plane onto a
plane, and the twists before impact onto the twists before impact. Then the exact answer is
symmetric too (the impact problem maps onto itself and the unilateral law's answer is unique
in the twist), and any part of an engine's answer that S does not fix is a symmetry the engine
broke — a box landing flat that leaves turning, rapier #668.

How a twist maps: the velocity of a centre of mass is a polar vector, v ↦ Q v; the angular
velocity an axial one, ω ↦ det(Q) Q ω; body i's twist goes to body π(i). The candidates tried
are the six isometries that fix the scene's centre of mass c and map the world axes onto
themselves up to sign — the three mirror planes through c normal to x, y, z and the three
half-turns about the axes through c — each an involution, so ξ − Sξ is twice the part of ξ
that S reverses. Scenes symmetric only about other planes or axes are not detected (the
catalogue is built in world axes; the random family is generically asymmetric).

**The symmetry grade** of an answer ξ: max over the scene's symmetries of
‖ξ − Sξ‖_M / (2 ‖ξ* − ξ⁰‖_M), the reversed part in the kinetic-energy metric relative to the
impact's size (the denominator of the error: :mod:`.grading`). The exact answer scores at the
rounding of the f64 solve; an answer that breaks no symmetry scores 0 whatever its error.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from .scene import EngineScene, Plane, Support


@dataclass(frozen=True)
class Symmetry:
    """An isometry x ↦ centre + Q (x − centre) of the scene, with the body permutation it induces
    (``permutation[i]`` is the body body i goes to)."""

    name: str
    q: np.ndarray
    centre: np.ndarray
    permutation: tuple

    def point(self, x) -> np.ndarray:
        return self.centre + self.q @ (np.asarray(x, float) - self.centre)

    def twists(self, twists: Sequence) -> list:
        """S applied to per-body twists ((v, ω) pairs or objects with ``velocity`` and
        ``angular_velocity``): body i's mapped twist lands at body π(i)."""
        det = float(np.sign(np.linalg.det(self.q)))
        out = [None] * len(twists)
        for i, t in enumerate(twists):
            v, w = (t.velocity, t.angular_velocity) if hasattr(t, "velocity") else t
            out[self.permutation[i]] = (self.q @ np.asarray(v, float), det * (self.q @ np.asarray(w, float)))
        return out


def _candidates():
    for k, axis in enumerate("xyz"):
        m = np.eye(3)
        m[k, k] = -1
        yield f"mirror {axis}", m
    for k, axis in enumerate("xyz"):
        m = -np.eye(3)
        m[k, k] = 1
        yield f"half-turn {axis}", m


def _features(b) -> list:
    """World points that pin a body's solid down up to its own symmetries."""
    if b.shape == "box":
        half = np.array(b.size) / 2
        return [b.position + b.rotation @ (np.array([sx, sy, sz]) * half)
                for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
    if b.shape == "cylinder":
        axis = b.rotation[:, 2] * b.size[1] / 2
        return [b.position + axis, b.position - axis]
    return [b.position]


def _same_points(a: Sequence, b: Sequence, tol: float) -> bool:
    """The same set of points (within ``tol``)."""
    if len(a) != len(b):
        return False
    left = list(b)
    for x in a:
        for j, y in enumerate(left):
            if np.linalg.norm(x - y) <= tol:
                del left[j]
                break
        else:
            return False
    return True


def _scale(scene: EngineScene) -> tuple:
    """(a length, a speed) of the scene: the tolerances' units."""
    length = max(max(b.size) for b in scene.bodies)
    for b in scene.bodies:
        length = max(length, float(np.linalg.norm(b.position)))
    speed = max(max(float(np.linalg.norm(b.velocity)),
                    float(np.linalg.norm(b.angular_velocity)) * max(b.size)) for b in scene.bodies)
    return length, max(speed, 1e-300)


def symmetries(scene: EngineScene, rtol: float = 1e-9) -> list:
    """The candidate isometries (module docstring) under which ``scene`` — bodies, contacts,
    obstacles and the twists before impact — maps onto itself, within ``rtol`` of the scene's
    size and speed (its numbers are read in f64: 1e-9 is far above their rounding and far below
    any geometric asymmetry worth a scene)."""
    length, speed = _scale(scene)
    xtol, vtol = rtol * length, rtol * speed
    masses = np.array([b.mass for b in scene.bodies])
    centre = sum(m * b.position for m, b in zip(masses, scene.bodies)) / masses.sum()
    found = []
    for name, q in _candidates():
        s = Symmetry(name, q, centre, ())
        perm = []
        for b in scene.bodies:
            image = [s.point(x) for x in _features(b)]
            match = [j for j, o in enumerate(scene.bodies)
                     if o.shape == b.shape and np.allclose(o.size, b.size, rtol=rtol, atol=0)
                     and math.isclose(o.mass, b.mass, rel_tol=rtol)
                     and np.allclose(o.inertia_world, q @ b.inertia_world @ q.T, rtol=0,
                                     atol=rtol * np.abs(b.inertia_world).max())
                     and np.linalg.norm(o.position - s.point(b.position)) <= xtol
                     and _same_points(image, _features(o), xtol)]
            if len(match) != 1:
                break
            perm.append(match[0])
        else:
            if len(set(perm)) != len(perm):
                continue
            s = Symmetry(name, q, centre, tuple(perm))
            mapped = s.twists(scene.bodies)
            if not all(np.linalg.norm(v - b.velocity) <= vtol and
                       np.linalg.norm(w - b.angular_velocity) * max(b.size) <= vtol
                       for (v, w), b in zip(mapped, scene.bodies)):
                continue
            if _contacts_map(scene, s, xtol) and _obstacles_map(scene, s, xtol):
                found.append(s)
    return found


def _contacts_map(scene: EngineScene, s: Symmetry, xtol: float) -> bool:
    left = list(scene.contacts)
    for c in scene.contacts:
        p, n = s.point(c.point), s.q @ c.normal
        bodies = tuple(s.permutation[i] for i in c.bodies)
        for j, d in enumerate(left):
            if (d.bodies == bodies and np.linalg.norm(d.point - p) <= xtol and np.linalg.norm(d.normal - n) <= 1e-9
                    and math.isclose(d.restitution, c.restitution, abs_tol=1e-12)
                    and math.isclose(d.friction, c.friction, abs_tol=1e-12)):
                del left[j]
                break
        else:
            return False
    return True


def _obstacles_map(scene: EngineScene, s: Symmetry, xtol: float) -> bool:
    for o in scene.obstacles:
        n = s.q @ o.normal
        ok = False
        for p in scene.obstacles:
            if type(p) is not type(o) or np.linalg.norm(p.normal - n) > 1e-9:
                continue
            if isinstance(o, Plane) and abs(p.normal @ (s.point(o.point) - p.point)) <= xtol:
                ok = True
            elif isinstance(o, Support) and np.linalg.norm(p.point - s.point(o.point)) <= xtol \
                    and math.isclose(p.radius, o.radius):
                ok = True
        if not ok:
            return False
    return True


def broken(scene: EngineScene, syms: Sequence[Symmetry], twists: Sequence, impact_norm: float) -> dict:
    """Per symmetry, ‖ξ − Sξ‖_M / (2 · impact_norm): the part of ``twists`` that each symmetry
    reverses, relative to the impact (``impact_norm`` = ‖ξ* − ξ⁰‖_M)."""
    out = {}
    for s in syms:
        mapped = s.twists(twists)
        sq = 0.0
        for b, t, (v, w) in zip(scene.bodies, twists, mapped):
            dv = np.asarray(t.velocity) - v
            dw = np.asarray(t.angular_velocity) - w
            sq += b.mass * dv @ dv + dw @ b.inertia_world @ dw
        out[s.name] = float(math.sqrt(max(sq, 0.0)) / (2 * impact_norm))
    return out
