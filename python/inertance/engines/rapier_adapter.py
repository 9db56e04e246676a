"""Rapier (``pip install rapier3d``: the Python bindings of dimforge's Rapier, 3D, f32).

Rapier's solver (soft-TGS/PGS with restitution on the velocity of a new contact) combines two
colliders' coefficients by a rule; both colliders here ask ``MULTIPLY``, so the product
assignment of :func:`~inertance.engines._geometry.product_restitutions` gives every contact its
e and μ. Gravity off, Rapier's default integration parameters (time step 1/60 s, 4 solver
iterations, its prediction distance and contact softness), sleeping off. Planes are half-spaces
on fixed bodies, point supports fixed balls. Each body's mass is set on its collider (Rapier
computes the inertia of the uniform solid: the adapter checks it against the scene's). The run
steps until none of the scene's contacts still touches and approaches
(:func:`~inertance.engines._geometry.pending_contacts`; for body–body contacts the relative
normal velocity at the contact point riding with the first body), at least one step, at most
``max_steps`` (scaled up when ``dt`` is smaller than the default), and reads each body's ``linvel`` (the centre of mass) and ``angvel`` (world).
A cylinder (axis body z in the scene, y in Rapier) is built on a body turned by a quarter turn
about x (R·Rx(90°) maps Rapier's y onto the scene's z; the twist is read in world axes, so the
turn does not show). ``iterations`` sets ``num_solver_iterations`` (default Rapier's, 4).
"""

from __future__ import annotations

import numpy as np

import rapier3d as rp

from ._geometry import pending_contacts, product_restitutions
from .catalogue import Twist
from .scene import EngineScene, Plane, SceneUnsupported, Support, _quaternion

#: Rx(90°): Rapier's cylinder axis (y) onto the scene's (z).
_QUARTER_X = np.array([[1.0, 0, 0], [0, 0, -1], [0, 1, 0]])


def _vec(v) -> np.ndarray:
    return np.array([v.x, v.y, v.z], dtype=float)


class RapierAdapter:
    name = "rapier"

    def __init__(self, max_steps: int = 120, dt: float = None, iterations: int = None):
        self.max_steps = max_steps
        self.dt = dt
        self.iterations = iterations
        try:
            from importlib.metadata import version
            self.version = version("rapier3d")
        except Exception:  # pragma: no cover
            self.version = "?"
        ip = rp.PhysicsWorld().integration_parameters
        self.settings = {"dt": dt if dt is not None else ip.dt,
                         "num_solver_iterations": iterations if iterations is not None else ip.num_solver_iterations, "gravity": "0",
                         "combine rule": "MULTIPLY (restitution and friction)", "precision": "f32",
                         "stop": "no scene contact touching and approaching"}

    def run(self, scene: EngineScene) -> list:
        rb, ro = product_restitutions(scene, "restitution")
        fb, fo = product_restitutions(scene, "friction")
        mul = rp.CoefficientCombineRule.MULTIPLY
        world = rp.PhysicsWorld(gravity=(0.0, 0.0, 0.0))
        if self.dt is not None:
            world.integration_parameters.dt = self.dt  # a live view of the world's parameters
            if abs(world.integration_parameters.dt - self.dt) > 1e-6 * self.dt:  # f32
                raise RuntimeError(f"Rapier kept dt = {world.integration_parameters.dt}, not {self.dt}")
        if self.iterations is not None:
            world.integration_parameters.num_solver_iterations = int(self.iterations)
            if world.integration_parameters.num_solver_iterations != int(self.iterations):
                raise RuntimeError(f"Rapier kept {world.integration_parameters.num_solver_iterations} iterations")

        def material(builder, r, mu):
            return (builder.restitution(float(r)).friction(float(mu))
                    .restitution_combine_rule(mul).friction_combine_rule(mul))

        for j, o in enumerate(scene.obstacles):
            if isinstance(o, Plane):
                col = rp.Collider.halfspace(tuple(float(x) for x in o.normal))
                at = o.point
            elif isinstance(o, Support):
                col = rp.Collider.ball(float(o.radius))
                at = o.centre
            else:
                raise SceneUnsupported(scene.file, f"obstacle[{j}]", "unknown obstacle")
            world.add_body(rp.RigidBody.fixed().translation(tuple(float(x) for x in at)), [material(col, ro[j], fo[j])])
        handles = []
        for i, b in enumerate(scene.bodies):
            if b.shape == "box":
                col = rp.Collider.cuboid(*(float(x) / 2 for x in b.size))
            elif b.shape == "sphere":
                col = rp.Collider.ball(float(b.size[0]))
            elif b.shape == "cylinder":
                col = rp.Collider.cylinder(float(b.size[1]) / 2, float(b.size[0]))
            else:
                raise SceneUnsupported(scene.file, f"body[{i}].shape", f"the Rapier adapter does not build a {b.shape} yet")
            r = b.rotation @ _QUARTER_X if b.shape == "cylinder" else b.rotation
            w, x, y, z = _quaternion(r)
            rot = rp.Rotation3.from_quaternion(float(w), float(x), float(y), float(z))
            builder = (rp.RigidBody.dynamic().translation(tuple(float(t) for t in b.position))
                       .rotation(tuple(float(t) for t in _vec(rot.scaled_axis)))
                       .linvel(tuple(float(t) for t in b.velocity)).angvel(tuple(float(t) for t in b.angular_velocity))
                       .can_sleep(False))
            h = world.add_body(builder, [material(col.mass(float(b.mass)), rb[i], fb[i])])
            got = np.sort(_vec(world.rigid_bodies[h].mass_properties.principal_inertia))
            if not np.allclose(got, np.sort(np.diag(b.inertia)), rtol=1e-5, atol=0):  # f32
                raise SceneUnsupported(scene.file, f"body[{i}]", f"Rapier's inertia {got} is not the body's")
            handles.append(h)

        def state():
            poses, twists = [], []
            for h in handles:
                body = world.rigid_bodies[h]
                poses.append((_vec(body.translation), np.array(body.rotation.to_matrix(), dtype=float).reshape(3, 3)))
                twists.append((_vec(body.linvel), _vec(body.angvel)))
            return poses, twists

        def body_body_approaching(poses, twists):
            """A body–body contact whose point, riding with its first body, still approaches."""
            for c in scene.contacts:
                if len(c.bodies) != 2:
                    continue
                b0 = scene.bodies[c.bodies[0]]
                p0, r0 = poses[c.bodies[0]]
                x = p0 + r0 @ (b0.rotation.T @ (c.point - b0.position))
                n = r0 @ (b0.rotation.T @ c.normal)
                v = [twists[bi][0] + np.cross(twists[bi][1], x - poses[bi][0]) for bi in c.bodies]
                if (v[0] - v[1]) @ n > 1e-9:
                    return True
            return False

        steps = self.max_steps if self.dt is None else int(self.max_steps * max(1.0, (1 / 60) / self.dt))
        for _ in range(steps):
            world.step()
            poses, twists = state()
            if not pending_contacts(scene, poses, twists) and not body_body_approaching(poses, twists):
                break
        poses, twists = state()
        return [Twist.of(v, w) for v, w in twists]
