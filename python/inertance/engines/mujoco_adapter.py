"""MuJoCo (``pip install mujoco``): soft contact, no coefficient of restitution.

MuJoCo's contact is a soft constraint whose reference acceleration is a damped spring,
a_ref = −b v − k r (r the penetration), applied through the impedance d ∈ (0, 1): with nothing
else acting (gravity off) the penetration obeys r̈ = −d (b ṙ + k r). It has no restitution
coefficient; a bounce is what that oscillator does in half a period. Two settings:

* ``tuned=False`` — MuJoCo's defaults (solref = (0.02, 1), solimp = (0.9, 0.95, 0.001, 0.5, 2),
  timestep 0.002 s): what a user gets without touching a knob. The asked e is ignored (no knob).
* ``calibrated=True`` (with ``tuned``) — the same oscillator, its damping ratio ζ found by
  measurement instead of the formula: bisection on ζ until a 1 kg ball dropped at 1 m/s on a
  plane with this pair's settings leaves at e m/s (to 10⁻⁴ m/s; :meth:`MuJoCoAdapter.calibrate`).
  The knob a user would turn after reading the tuned row; it fixes one contact and says
  nothing of how several contacts couple.
* ``tuned=True`` — e mapped through solref as MuJoCo's documentation allows: the direct form
  solref = (−k, −b) (stiffness and damping, mass-independent) with a constant impedance
  solimp = (d, d, …), d = 0.99, so that r̈ = −d (b ṙ + k r) is a linear oscillator whose
  restitution — the ratio of the speeds at which it leaves and reaches r = 0 — is
  e = exp(−ζπ/√(1 − ζ²)), ζ = d·b / (2√(d·k)). For the asked e: ζ = −ln e / √(π² + ln² e)
  (ζ = 1, critical damping, for e = 0); the contact lasts π/(ω_n√(1 − ζ²)); we choose the
  undamped half period π/ω_n = ``duration`` (2 ms, 20 steps of 0.1 ms) and set d·k = ω_n²,
  d·b = 2ζω_n. MuJoCo scales
  the direct form's k and b by its impedance internally (k by d/dmax², b by 1/dmax), so the
  effective e is measured, not assumed: the report's ball scenes show it.

Frictionless contacts use condim 1; frictional ones condim 3 with the elliptic cone and μ.
Every contact pair of the scene is an explicit ``<pair>`` (all geoms have contype = conaffinity
= 0) carrying its own solref: MuJoCo's per-pair parameters, no mixing of geoms' values. The
run stops when no contact is active (all released) or at a horizon (``horizon_steps``), and reads
each body's twist (free joint: v of the body origin = the centre of mass, world; ω in body
axes, rotated to world).
"""

from __future__ import annotations

import math

import numpy as np

import mujoco

from ._geometry import frame_with_z
from .catalogue import Twist
from .scene import EngineScene, Plane, SceneUnsupported, Support


def _v(x) -> str:
    return " ".join(repr(float(t)) for t in np.ravel(x))


def _quat(r) -> str:
    q = np.empty(4)
    mujoco.mju_mat2Quat(q, np.ascontiguousarray(r, dtype=float).ravel())
    return _v(q)


class MuJoCoAdapter:
    def __init__(self, tuned: bool = False, timestep: float = None, duration: float = 0.002,
                 impedance: float = 0.99, horizon: float = None, calibrated: bool = False):
        if calibrated and not tuned:
            raise ValueError("calibrated=True calibrates the tuned setting: pass tuned=True too")
        self.tuned = tuned
        self.calibrated = calibrated
        self._zeta: dict = {}
        self.name = "mujoco-calibrated" if calibrated else "mujoco-tuned" if tuned else "mujoco"
        self.version = mujoco.__version__
        self.timestep = timestep if timestep is not None else (1e-4 if tuned else 0.002)
        self.duration = duration
        self.impedance = impedance
        # defaults: 50 contact durations tuned; 0.5 s (25 time constants of 0.02 s) default
        self.horizon = horizon if horizon is not None else (50 * duration if tuned else 0.5)
        self.settings = {"timestep": self.timestep, "gravity": "0",
                         "horizon": f"{self.horizon} s or until no contact is active"}
        if calibrated:
            self.settings.update({"solref": f"direct (−k, −b), ζ calibrated on a ball to give e, contact duration {duration} s",
                                  "solimp": f"({impedance}, {impedance}, 0.001)"})
        elif tuned:
            self.settings.update({"solref": f"direct (−k, −b) from e, contact duration {duration} s",
                                  "solimp": f"({impedance}, {impedance}, 0.001)"})
        else:
            self.settings.update({"solref": "default (0.02, 1)", "solimp": "default (0.9, 0.95, 0.001, 0.5, 2)",
                                  "restitution": "none (MuJoCo has no coefficient)"})

    def solref(self, e: float) -> tuple:
        """(−k, −b) for restitution e (see the module's docstring)."""
        if not 0 <= e <= 1:
            raise ValueError(f"restitution {e} is not in [0, 1]")
        if self.calibrated:
            return self._solref_zeta(self.calibrate(e))
        zeta = 1.0 if e == 0 else -math.log(e) / math.sqrt(math.pi ** 2 + math.log(e) ** 2)
        return self._solref_zeta(zeta)

    def _ball_rebound(self, zeta: float) -> float:
        """The speed a 1 kg ball (r = 0.1 m) dropped at 1 m/s leaves a plane with, at damping ratio ζ."""
        k, b = self._solref_zeta(zeta)
        d = self.impedance
        xml = (f'<mujoco><option timestep="{self.timestep}" gravity="0 0 0"/><worldbody>'
               '<geom name="p" type="plane" size="0 0 1" contype="0" conaffinity="0"/>'
               '<body name="b" pos="0 0 0.1"><freejoint/><inertial pos="0 0 0" mass="1" diaginertia="0.004 0.004 0.004"/>'
               '<geom name="g" type="sphere" size="0.1" contype="0" conaffinity="0"/></body></worldbody>'
               f'<contact><pair geom1="p" geom2="g" condim="1" solref="{k!r} {b!r}" solimp="{d} {d} 0.001 0.5 2"/></contact>'
               '</mujoco>')
        model = mujoco.MjModel.from_xml_string(xml)
        data = mujoco.MjData(model)
        data.qvel[2] = -1.0
        touched = False
        for _ in range(int(round(self.horizon / self.timestep))):
            mujoco.mj_step(model, data)
            if data.ncon > 0:
                touched = True
            elif touched:
                break
        return float(data.qvel[2])

    def calibrate(self, e: float) -> float:
        """ζ at which the ball of :meth:`_ball_rebound` leaves at e m/s (bisection, to 1e-4 m/s;
        e = 0: the smallest rebound found on [0, 2], as MuJoCo's contact may never quite stop)."""
        if e in self._zeta:
            return self._zeta[e]
        lo, hi = 0.0, 2.0
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            if self._ball_rebound(mid) > e:
                lo = mid
            else:
                hi = mid
            if hi - lo < 1e-6:
                break
        self._zeta[e] = hi
        return hi

    def _solref_zeta(self, zeta: float) -> tuple:
        """(−k, −b) with d·k = ω_n², d·b = 2ζω_n, ω_n = π/duration."""
        wn = math.pi / self.duration
        d = self.impedance
        return (-(wn ** 2) / d, -(2 * zeta * wn) / d)

    def model_xml(self, scene: EngineScene) -> str:
        cone = "elliptic" if scene.frictional else "pyramidal"
        out = [f'<mujoco model="{scene.name}">',
               f'<option timestep="{self.timestep}" gravity="0 0 0" cone="{cone}"/>',
               "<worldbody>"]
        for j, o in enumerate(scene.obstacles):
            if isinstance(o, Plane):
                out.append(f'<geom name="o{j}" type="plane" size="0 0 1" pos="{_v(o.point)}" '
                           f'quat="{_quat(frame_with_z(o.normal))}" contype="0" conaffinity="0"/>')
            elif isinstance(o, Support):
                out.append(f'<geom name="o{j}" type="sphere" size="{o.radius}" pos="{_v(o.centre)}" '
                           'contype="0" conaffinity="0"/>')
            else:
                raise SceneUnsupported(scene.file, f"obstacle[{j}]", "unknown obstacle")
        for i, b in enumerate(scene.bodies):
            if b.shape == "box":
                geom = f'type="box" size="{_v(np.array(b.size) / 2)}"'
            elif b.shape == "sphere":
                geom = f'type="sphere" size="{b.size[0]}"'
            elif b.shape == "cylinder":
                geom = f'type="cylinder" size="{b.size[0]} {b.size[1] / 2}"'
            else:
                raise SceneUnsupported(scene.file, f"body[{i}].shape", f"no MuJoCo geom for {b.shape}")
            out.append(f'<body name="b{i}" pos="{_v(b.position)}" quat="{_quat(b.rotation)}">'
                       f'<freejoint/><inertial pos="0 0 0" mass="{b.mass!r}" diaginertia="{_v(np.diag(b.inertia))}"/>'
                       f'<geom name="g{i}" {geom} contype="0" conaffinity="0"/></body>')
        out.append("</worldbody><contact>")
        for (a, (kind, j)), (e, mu) in scene.contact_pairs().items():
            other = f"g{j}" if kind == "body" else f"o{j}"
            attrs = [f'geom1="{other}" geom2="g{a}"']
            if mu > 0:
                attrs.append(f'condim="3" friction="{mu!r} {mu!r} 0 0 0"')
            else:
                attrs.append('condim="1"')
            if self.tuned:
                k, bdamp = self.solref(e)
                d = self.impedance
                attrs.append(f'solref="{k!r} {bdamp!r}" solimp="{d} {d} 0.001 0.5 2"')
            out.append(f"<pair {' '.join(attrs)}/>")
        out.append("</contact></mujoco>")
        return "\n".join(out)

    def run(self, scene: EngineScene) -> list:
        model = mujoco.MjModel.from_xml_string(self.model_xml(scene))
        data = mujoco.MjData(model)
        for i, b in enumerate(scene.bodies):
            adr = model.jnt_dofadr[model.body_jntadr[model.body(f"b{i}").id]]
            data.qvel[adr:adr + 3] = b.velocity
            data.qvel[adr + 3:adr + 6] = b.rotation.T @ b.angular_velocity
        mujoco.mj_forward(model, data)
        steps = int(round(self.horizon / self.timestep))
        touched = False
        for _ in range(steps):
            mujoco.mj_step(model, data)
            if data.ncon > 0:
                touched = True
            elif touched:
                break
        out = []
        for i in range(len(scene.bodies)):
            bid = model.body(f"b{i}").id
            adr = model.jnt_dofadr[model.body_jntadr[bid]]
            r = data.xmat[bid].reshape(3, 3)
            out.append(Twist.of(data.qvel[adr:adr + 3].copy(), r @ data.qvel[adr + 3:adr + 6]))
        return out
