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


def product_restitutions(scene: EngineScene) -> tuple:
    """Per body and per obstacle a restitution r such that r_a · r_b is each contact's e (for the
    engines that combine two objects' coefficients by their product, as Bullet does). Obstacles
    take their contacts' e, the bodies then what the products require (a body touching nothing
    fixed starts at 1). Raises :class:`SceneUnsupported` when no such assignment exists."""
    nb, no = len(scene.bodies), len(scene.obstacles)
    body = [None] * nb
    obst = [None] * no
    for i, c in enumerate(scene.contacts):
        if c.obstacle is not None:
            if obst[c.obstacle] is not None and obst[c.obstacle] != c.restitution:
                raise SceneUnsupported(scene.file, f"contact[{i}].k",
                                       "contacts with one obstacle have different restitutions")
            obst[c.obstacle] = c.restitution
    changed = True
    while changed:
        changed = False
        for c in scene.contacts:
            a = c.bodies[0]
            other = obst[c.obstacle] if c.obstacle is not None else body[c.bodies[1]]
            if body[a] is None and other is not None and other > 0:
                body[a] = c.restitution / other
                changed = True
            if len(c.bodies) == 2 and body[c.bodies[1]] is None and body[a] is not None and body[a] > 0:
                body[c.bodies[1]] = c.restitution / body[a]
                changed = True
        if not changed and None in body:
            body[body.index(None)] = 1.0
            changed = True
    for i, c in enumerate(scene.contacts):
        other = obst[c.obstacle] if c.obstacle is not None else body[c.bodies[1]]
        if abs(body[c.bodies[0]] * other - c.restitution) > 1e-12 or body[c.bodies[0]] > 1:
            raise SceneUnsupported(scene.file, f"contact[{i}].k",
                                   "no restitution per object in [0, 1] gives every contact's e as a product")
    return body, [1.0 if r is None else r for r in obst]
