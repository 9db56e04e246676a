"""PyBullet (``pip install pybullet``): Bullet's sequential-impulse solver with restitution.

Bullet combines two objects' restitutions (and frictions) by their product: each obstacle gets
its contacts' e (and μ) and each body 1, or what the products require between bodies
(:func:`~inertance.engines._geometry.product_restitutions`). The settings are those Bullet's
author gives for clean restitution (bullet3 issue #3094, PR #1701): ``restitutionVelocityThreshold
= 0`` (else slow contacts get e = 0), ``warmStartingFactor = 0``, ``useSplitImpulse = 1``
(penetration recovery that adds no velocity), ``contactSlop = 0``, ``enableConeFriction = 0``,
and per object ``contactProcessingThreshold = 0`` (no speculative contacts), no damping,
maximal coordinates. Gravity off, time step 1/240 s (Bullet's default), 50 solver iterations
(the default). The run steps until no contact point approaches (relative normal velocity below
−10⁻⁹ m/s) — neither one of Bullet's nor one of the scene's contacts against an obstacle that
still touches (:func:`~inertance.engines._geometry.pending_contacts`: Bullet's manifold finds a
face's corners one per step, so after the first step the others still approach) — at least one
step, at most ``max_steps``, and reads each body's base velocity (the
centre of mass, world axes).
"""

from __future__ import annotations

import numpy as np

import pybullet

from ._geometry import pending_contacts, product_restitutions
from .catalogue import Twist
from .scene import EngineScene, Plane, SceneUnsupported, Support
from .scene import _quaternion


def _xyzw(r) -> list:
    w, x, y, z = _quaternion(r)
    return [x, y, z, w]


class PyBulletAdapter:
    name = "pybullet"

    def __init__(self, timestep: float = 1 / 240, iterations: int = 50, max_steps: int = 240):
        self.timestep, self.iterations, self.max_steps = timestep, iterations, max_steps
        self.version = f"{getattr(pybullet, '__version__', '')} (API {pybullet.getAPIVersion()})".strip()
        try:
            from importlib.metadata import version
            self.version = version("pybullet")
        except Exception:
            pass
        self.settings = {"timestep": timestep, "numSolverIterations": iterations, "gravity": "0",
                         "restitutionVelocityThreshold": 0, "warmStartingFactor": 0, "useSplitImpulse": 1,
                         "contactSlop": 0, "contactProcessingThreshold": 0, "enableConeFriction": 0,
                         "restitution": "product of both objects'", "stop": "no contact approaching"}

    def run(self, scene: EngineScene) -> list:
        rb, ro = product_restitutions(scene, "restitution")
        fb, fo = product_restitutions(scene, "friction")
        c = pybullet.connect(pybullet.DIRECT)
        try:
            return self._run(scene, c, rb, ro, fb, fo)
        finally:
            pybullet.disconnect(c)

    def _run(self, scene, c, rb, ro, fb, fo):
        p = pybullet
        p.setGravity(0, 0, 0, physicsClientId=c)
        p.setTimeStep(self.timestep, physicsClientId=c)
        p.setPhysicsEngineParameter(restitutionVelocityThreshold=0, warmStartingFactor=0, useSplitImpulse=1,
                                    contactSlop=0, enableConeFriction=0, numSolverIterations=self.iterations,
                                    physicsClientId=c)

        def dyn(uid, r, mu):
            p.changeDynamics(uid, -1, restitution=r, lateralFriction=mu, rollingFriction=0, spinningFriction=0,
                             linearDamping=0, angularDamping=0, contactProcessingThreshold=0, physicsClientId=c)

        for j, o in enumerate(scene.obstacles):
            if isinstance(o, Plane):
                shape = p.createCollisionShape(p.GEOM_PLANE, planeNormal=list(o.normal), physicsClientId=c)
                pos = list(o.point)
            elif isinstance(o, Support):
                shape = p.createCollisionShape(p.GEOM_SPHERE, radius=o.radius, physicsClientId=c)
                pos = list(o.centre)
            else:
                raise SceneUnsupported(scene.file, f"obstacle[{j}]", "unknown obstacle")
            uid = p.createMultiBody(0, shape, -1, basePosition=pos, useMaximalCoordinates=True, physicsClientId=c)
            dyn(uid, ro[j], fo[j])
        ids = []
        for i, b in enumerate(scene.bodies):
            if b.shape == "box":
                shape = p.createCollisionShape(p.GEOM_BOX, halfExtents=list(np.array(b.size) / 2), physicsClientId=c)
            elif b.shape == "sphere":
                shape = p.createCollisionShape(p.GEOM_SPHERE, radius=b.size[0], physicsClientId=c)
            elif b.shape == "cylinder":
                shape = p.createCollisionShape(p.GEOM_CYLINDER, radius=b.size[0], height=b.size[1], physicsClientId=c)
            else:
                raise SceneUnsupported(scene.file, f"body[{i}].shape", f"no Bullet shape for {b.shape}")
            uid = p.createMultiBody(b.mass, shape, -1, basePosition=list(b.position), baseOrientation=_xyzw(b.rotation),
                                    useMaximalCoordinates=True, physicsClientId=c)
            dyn(uid, rb[i], fb[i])
            # Bullet computes the inertia from the shape (a solid box, sphere or cylinder: the same
            # formulas); setting localInertiaDiagonal on a maximal-coordinates body makes PyBullet
            # 3.2.7 return NaN velocities after the first step, so the computed one is checked instead.
            got = np.array(p.getDynamicsInfo(uid, -1, physicsClientId=c)[2])
            if not np.allclose(got, np.diag(b.inertia), rtol=1e-9, atol=0):
                raise SceneUnsupported(scene.file, f"body[{i}]",
                                       f"Bullet's inertia {got} is not the body's {np.diag(b.inertia)}")
            p.resetBaseVelocity(uid, list(b.velocity), list(b.angular_velocity), physicsClientId=c)
            ids.append(uid)

        def velocity_at(uid, point):
            if uid not in ids:
                return np.zeros(3)
            v, w = p.getBaseVelocity(uid, physicsClientId=c)
            pos, _ = p.getBasePositionAndOrientation(uid, physicsClientId=c)
            return np.array(v) + np.cross(w, np.array(point) - np.array(pos))

        for _ in range(self.max_steps):
            p.stepSimulation(physicsClientId=c)
            approaching = False
            for uid in ids:
                for cp in p.getContactPoints(bodyA=uid, physicsClientId=c):
                    a, bb, pa, pb, n = cp[1], cp[2], cp[5], cp[6], np.array(cp[7])  # n: on B, toward A
                    rel = velocity_at(a, pa) - velocity_at(bb, pb)
                    if rel @ n < -1e-9:
                        approaching = True
            if not approaching:
                poses, twists = [], []
                for uid in ids:
                    pos, q = p.getBasePositionAndOrientation(uid, physicsClientId=c)
                    poses.append((np.array(pos), np.array(p.getMatrixFromQuaternion(q)).reshape(3, 3)))
                    twists.append(tuple(np.array(x) for x in p.getBaseVelocity(uid, physicsClientId=c)))
                if not pending_contacts(scene, poses, twists):
                    break
        out = []
        for uid in ids:
            v, w = p.getBaseVelocity(uid, physicsClientId=c)
            out.append(Twist.of(v, w))
        return out
