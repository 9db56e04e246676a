"""Drake (``pip install drake``): MultibodyPlant, discrete contact, no restitution coefficient.

Drake's contact is compliant: point contact with a stiffness and Hunt–Crossley dissipation (or
hydroelastic, not used here), solved by its discrete solver (the plant's default settings). It has no coefficient of
restitution, so e is ignored (as for MuJoCo's defaults) and the grade says what its defaults do
to a rigid impact. Setup: ``MultibodyPlant`` with ``time_step`` (1 ms), gravity zero, point
contact (``ContactModel.kPoint``), one free body per body (``SpatialInertia`` from the mass
and the central moments, its frame at the centre of mass; a box, a sphere or a cylinder, whose
axis is z in Drake as in the scene), half-spaces and spheres welded to
the world, the proximity properties' friction μ (static = dynamic) and Drake's default
stiffness and dissipation. The run advances until no contact is active or ``horizon`` (0.5 s)
and reads each body's spatial velocity in the world (the body origin = the centre of mass).
"""

from __future__ import annotations

import numpy as np

import pydrake
from pydrake.geometry import Box, Cylinder, HalfSpace, ProximityProperties, Sphere
from pydrake.math import RigidTransform, RotationMatrix
from pydrake.multibody.plant import AddMultibodyPlantSceneGraph, ContactModel, CoulombFriction
from pydrake.multibody.tree import RotationalInertia, SpatialInertia
from pydrake.multibody.math import SpatialVelocity
from pydrake.systems.analysis import Simulator
from pydrake.systems.framework import DiagramBuilder

from .catalogue import Twist
from .scene import EngineScene, Plane, SceneUnsupported, Support


class DrakeAdapter:
    name = "drake"

    def __init__(self, time_step: float = 1e-3, horizon: float = 0.5):
        self.time_step, self.horizon = time_step, horizon
        try:
            from importlib.metadata import version
            self.version = version("drake")
        except Exception:  # pragma: no cover
            self.version = getattr(pydrake, "__version__", "?")
        self.settings = {"time_step": time_step, "contact model": "point (default stiffness, Hunt–Crossley)",
                         "restitution": "none (Drake has no coefficient)", "gravity": "0",
                         "horizon": f"{horizon} s or until no contact is active"}

    def run(self, scene: EngineScene) -> list:
        builder = DiagramBuilder()
        plant, _ = AddMultibodyPlantSceneGraph(builder, time_step=self.time_step)
        plant.set_contact_model(ContactModel.kPoint)
        plant.mutable_gravity_field().set_gravity_vector([0.0, 0.0, 0.0])

        def props(mu: float) -> ProximityProperties:
            p = ProximityProperties()
            p.AddProperty("material", "coulomb_friction", CoulombFriction(mu, mu))
            return p

        # per object the friction that makes each contact's (Drake combines two μ by 2μ₁μ₂/(μ₁+μ₂)):
        # give every object its contacts' μ when they all agree, else refuse
        mus = {c.friction for c in scene.contacts}
        if len(mus) != 1:
            raise SceneUnsupported(scene.file, "contact.mu", "the Drake adapter sets one μ for every object")
        mu = mus.pop()
        for j, o in enumerate(scene.obstacles):
            if isinstance(o, Plane):
                pose = HalfSpace.MakePose(np.asarray(o.normal, float), np.asarray(o.point, float))
                plant.RegisterCollisionGeometry(plant.world_body(), pose, HalfSpace(), f"o{j}", props(mu))
            elif isinstance(o, Support):
                plant.RegisterCollisionGeometry(plant.world_body(), RigidTransform(np.asarray(o.centre, float)),
                                                Sphere(o.radius), f"o{j}", props(mu))
            else:
                raise SceneUnsupported(scene.file, f"obstacle[{j}]", "unknown obstacle")
        bodies = []
        for i, b in enumerate(scene.bodies):
            jx, jy, jz = np.diag(b.inertia)
            m = SpatialInertia.MakeFromCentralInertia(b.mass, np.zeros(3), RotationalInertia(jx, jy, jz))
            body = plant.AddRigidBody(f"b{i}", m)
            if b.shape == "box":
                shape = Box(*[float(x) for x in b.size])
            elif b.shape == "sphere":
                shape = Sphere(float(b.size[0]))
            elif b.shape == "cylinder":
                shape = Cylinder(float(b.size[0]), float(b.size[1]))  # axis z, as the scene's
            else:
                raise SceneUnsupported(scene.file, f"body[{i}].shape", f"the Drake adapter does not build a {b.shape} yet")
            plant.RegisterCollisionGeometry(body, RigidTransform(), shape, f"g{i}", props(mu))
            bodies.append(body)
        plant.Finalize()
        diagram = builder.Build()
        context = diagram.CreateDefaultContext()
        pc = plant.GetMyMutableContextFromRoot(context)
        for b, body in zip(scene.bodies, bodies):
            plant.SetFreeBodyPose(pc, body, RigidTransform(RotationMatrix(np.asarray(b.rotation, float)),
                                                           np.asarray(b.position, float)))
            plant.SetFreeBodySpatialVelocity(pc, body, SpatialVelocity(np.asarray(b.angular_velocity, float),
                                                                       np.asarray(b.velocity, float)))
        sim = Simulator(diagram, context)
        sim.Initialize()
        touched = False
        t = 0.0
        while t < self.horizon:
            t += self.time_step
            sim.AdvanceTo(t)
            n = plant.get_contact_results_output_port().Eval(pc).num_point_pair_contacts()
            if n > 0:
                touched = True
            elif touched:
                break
        out = []
        for body in bodies:
            v = plant.EvalBodySpatialVelocityInWorld(pc, body)
            out.append(Twist.of(v.translational(), v.rotational()))
        return out
