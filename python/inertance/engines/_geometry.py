"""Small geometry helpers shared by the adapters (no engine imported)."""

from __future__ import annotations

import numpy as np

from .scene import EngineScene, SceneUnsupported


def frame_with_z(n: np.ndarray) -> np.ndarray:
    """A rotation matrix whose third column is the unit vector ``n``."""
    n = np.asarray(n, dtype=float) / np.linalg.norm(n)
    a = np.eye(3)[int(np.argmin(np.abs(n)))]
    x = np.cross(a, n)
    x /= np.linalg.norm(x)
    y = np.cross(n, x)
    return np.column_stack([x, y, n])


def product_restitutions(scene: EngineScene, attribute: str = "restitution") -> tuple:
    """Per body and per obstacle a restitution r such that r_a · r_b is each contact's e (for the
    engines that combine two objects' coefficients by their product, as Bullet does; with
    ``attribute="friction"`` the same for Coulomb's μ, which Bullet combines likewise). Obstacles
    take their contacts' e, the bodies then what the products require (a body touching nothing
    fixed starts at 1). Raises :class:`SceneUnsupported` when no such assignment exists."""
    nb, no = len(scene.bodies), len(scene.obstacles)
    body = [None] * nb
    obst = [None] * no
    for i, c in enumerate(scene.contacts):
        if c.obstacle is not None:
            if obst[c.obstacle] is not None and obst[c.obstacle] != getattr(c, attribute):
                raise SceneUnsupported(scene.file, f"contact[{i}].k",
                                       f"contacts with one obstacle have different {attribute} coefficients")
            obst[c.obstacle] = getattr(c, attribute)
    changed = True
    while changed:
        changed = False
        for c in scene.contacts:
            a = c.bodies[0]
            other = obst[c.obstacle] if c.obstacle is not None else body[c.bodies[1]]
            if body[a] is None and other is not None and other > 0:
                body[a] = getattr(c, attribute) / other
                changed = True
            if len(c.bodies) == 2 and body[c.bodies[1]] is None and body[a] is not None and body[a] > 0:
                body[c.bodies[1]] = getattr(c, attribute) / body[a]
                changed = True
        if not changed and None in body:
            body[body.index(None)] = 1.0
            changed = True
    limit = 1.0 if attribute == "restitution" else float("inf")
    for i, c in enumerate(scene.contacts):
        other = obst[c.obstacle] if c.obstacle is not None else body[c.bodies[1]]
        if abs(body[c.bodies[0]] * other - getattr(c, attribute)) > 1e-12 or body[c.bodies[0]] > limit:
            raise SceneUnsupported(scene.file, f"contact[{i}].k",
                                   f"no {attribute} per object gives every contact's as a product")
    return body, [1.0 if r is None else r for r in obst]


def pending_contacts(scene: EngineScene, poses, twists, gap_tolerance: float = 1e-9) -> list:
    """The scene's contacts against obstacles that still touch and approach, at the bodies' current
    ``poses`` ((position, rotation) per body) and ``twists`` ((v, ω) per body, world): each
    contact point rides with its body from where the scene puts it; it "touches" when its gap
    to the obstacle (a plane, or a support's sphere) is below ``gap_tolerance`` times the body's
    size (penetrating counts), and "approaches" when its normal velocity toward the obstacle is
    above 10⁻⁹ m/s. Used by hard-contact adapters whose engine detects an edge's or a face's
    corners over several steps (Bullet): the run is not over while one of these remains.
    Body–body contacts are left to the engine's own contact list."""
    from .scene import Plane, Support

    out = []
    for i, c in enumerate(scene.contacts):
        if c.obstacle is None:
            continue
        b = scene.bodies[c.bodies[0]]
        pos, rot = poses[c.bodies[0]]
        v, w = twists[c.bodies[0]]
        local = b.rotation.T @ (c.point - b.position)
        x = np.asarray(pos) + np.asarray(rot) @ local
        o = scene.obstacles[c.obstacle]
        if isinstance(o, Plane):
            n = o.normal
            gap = n @ (x - o.point)
        elif isinstance(o, Support):
            d = x - o.centre
            n = d / np.linalg.norm(d)
            gap = np.linalg.norm(d) - o.radius
        else:
            continue
        size = max(b.size)
        vx = np.asarray(v) + np.cross(w, x - np.asarray(pos))
        if gap < gap_tolerance * size and vx @ n < -1e-9:
            out.append(i)
    return out
