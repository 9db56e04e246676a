"""Pinocchio (``pip install pin``): ``impulseDynamics``, Newton's law on a bilateral contact set.

``pin.impulseDynamics(model, data, q, v_before, J, r_coeff, inv_damping)`` solves
J v⁺ = −e J v⁻ for the impulse, with one coefficient e for every contact and every contact
active (bilateral: it may pull). That is the paper's simultaneous Newton law, not the unilateral
one the catalogue grades: it agrees exactly where every contact stays active, and the report
shows where it does not (the pitching bar's tensile support). J's rows are the contact normals'
Jacobians, nᵀ(J₁(A) − J₂(A)) (a body against an obstacle: nᵀJ₁(A)), from Pinocchio's own
kinematics (one free-flyer joint per body, a frame at each contact point,
``LOCAL_WORLD_ALIGNED``). ``inv_damping = 0`` (the exact solve); a singular J M⁻¹ Jᵀ (a box
flat on four corners) is reported as Pinocchio answers it. A scene whose contacts have
different coefficients or any friction is refused by name: this call has neither.
"""

from __future__ import annotations

import numpy as np

import pinocchio as pin

from .catalogue import Twist
from .scene import EngineScene, SceneUnsupported


class PinocchioAdapter:
    name = "pinocchio"

    def __init__(self, damping: float = 0.0):
        self.damping = damping
        self.version = pin.__version__
        self.settings = {"call": "impulseDynamics(model, data, q, v, J_normal, e, inv_damping)",
                         "inv_damping": damping, "law": "simultaneous Newton, bilateral, one e"}

    def run(self, scene: EngineScene) -> list:
        es = {c.restitution for c in scene.contacts}
        if len(es) != 1:
            raise SceneUnsupported(scene.file, "contact.k", f"impulseDynamics takes one coefficient; the scene has {sorted(es)}")
        if scene.frictional:
            raise SceneUnsupported(scene.file, "contact.mu", "impulseDynamics has no friction")
        e = es.pop()
        model = pin.Model()
        joints = []
        for i, b in enumerate(scene.bodies):
            jid = model.addJoint(0, pin.JointModelFreeFlyer(), pin.SE3.Identity(), f"b{i}")
            model.appendBodyToJoint(jid, pin.Inertia(b.mass, np.zeros(3), b.inertia.copy()), pin.SE3.Identity())
            joints.append(jid)
        data = model.createData()
        q = np.zeros(model.nq)
        v = np.zeros(model.nv)
        for i, b in enumerate(scene.bodies):
            j = model.joints[joints[i]]
            w, x, y, z = b.quaternion()
            q[j.idx_q:j.idx_q + 7] = np.concatenate([b.position, [x, y, z, w]])
            v[j.idx_v:j.idx_v + 3] = b.rotation.T @ b.velocity
            v[j.idx_v + 3:j.idx_v + 6] = b.rotation.T @ b.angular_velocity
        pin.forwardKinematics(model, data, q)
        pin.computeJointJacobians(model, data, q)
        rows = []
        for c in scene.contacts:
            row = np.zeros(model.nv)
            for sign, bi in zip((1.0, -1.0), c.bodies):
                jid = joints[bi]
                # the contact point in the joint's frame, a frame there, its world-aligned Jacobian
                local = data.oMi[jid].actInv(c.point)
                fid = model.addFrame(pin.Frame(f"c{len(rows)}_{bi}", jid, pin.SE3(np.eye(3), local),
                                               pin.FrameType.OP_FRAME))
                fdata = pin.Data(model)
                pin.computeJointJacobians(model, fdata, q)
                pin.updateFramePlacements(model, fdata)
                jac = pin.getFrameJacobian(model, fdata, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)[:3]
                row += sign * (c.normal @ jac)
            rows.append(row)
        jn = np.array(rows)
        data = model.createData()
        v_after = pin.impulseDynamics(model, data, q, v, jn, float(e), float(self.damping))
        out = []
        for i, b in enumerate(scene.bodies):
            j = model.joints[joints[i]]
            out.append(Twist.of(b.rotation @ v_after[j.idx_v:j.idx_v + 3], b.rotation @ v_after[j.idx_v + 3:j.idx_v + 6]))
        return out
