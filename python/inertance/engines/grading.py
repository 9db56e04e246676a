"""The grades of an engine's answer against the exact one.

**The error** of the twist after impact is measured in the kinetic-energy metric,

    error = ‖ξ − ξ*‖_M / ‖ξ* − ξ⁰‖_M,   ‖ξ‖_M² = Σ_bodies m |v|² + ωᵀ J ω  (J in world axes),

ξ the engine's twists after impact, ξ* the exact ones, ξ⁰ those before. Why this norm: M is the
metric of impulsive dynamics — an impulse changes the twist by M⁻¹ times its wrench and the
energy is ½‖ξ‖_M² — so it weighs linear and angular velocity in the body's own units, does not
depend on the world axes or the unit of length, and a velocity error of a heavy body counts
for more than of a light one. Why that denominator: ξ* − ξ⁰ is what the impact does, so the
grade is the fraction of the impact the engine got wrong — 0 is exact, an engine that lets the
bodies pass through each other (ξ = ξ⁰) scores exactly 1, whatever the scene's size or speed.
It is nonzero for every catalogue scene (every one has an impact).

**Energy**: ``energy_ratio`` = T/T⁰ for the engine and ``exact_energy_ratio`` for the exact
answer; with every e ≤ 1 no impact can gain energy, so ``energy_gain`` = max(0, T − T⁰)/T⁰
is a gain where none can be.

**Separation**: per contact the relative normal velocity after impact (positive: separating)
at the scene's contact points, engine against exact. A contact "should separate" when its exact
normal velocity exceeds ``SEPARATION_TOLERANCE`` times the scene's largest approach speed, and
"separates" in the engine by the same test. The tolerance is 1 %: well above the f64 solve's
rounding (≤ 10⁻¹² here) and far below the smallest separation speed in the catalogue that is
not zero (20 % of the approach speed: bar-pitching-e02's first support, e = 0.2); an engine's
residual velocity at a contact that stays (e = 0, or two cradle balls leaving together) counts
as separating only beyond it.

**Symmetry** (:mod:`.symmetry`): where the scene maps onto itself under a mirror or a half-turn
(computed from the scene, listed in the catalogue), the part of the engine's answer the
symmetry reverses, ‖ξ − Sξ‖_M / (2‖ξ* − ξ⁰‖_M), the largest over the scene's symmetries
(``symmetry_broken``; ``None`` for an asymmetric scene). Flagged ``!sym`` above
``SYMMETRY_TOLERANCE`` = 10⁻³ of the impact: the exact f64 answer scores ≤ 10⁻¹⁵ on the
catalogue and an f32 engine's rounding about 10⁻⁷, so a flagged answer turns or drifts in a
way the scene forbids by three orders more than rounding can explain (the same 0.1 % as ``+E``).

**Pull** (:mod:`.pull`): the normal impulses the engine's twist change needs at the scene's
contacts, solved in least squares where the contact wrench matrix has full column rank
(``normal_impulses``; ``None``: not determined), and ``pull`` = the most negative one over the
impact's impulse scale P (``impulse_scale``), flagged ``!pull`` above ``PULL_TOLERANCE`` = 10⁻³;
``unexplained`` is the fraction of the twist change no impulse at the scene's contacts produces.
"""


from __future__ import annotations

from dataclasses import asdict, dataclass, field
from typing import Optional, Sequence

import numpy as np

from .catalogue import CatalogueScene, Twist, kinetic_energy, normal_velocities
from .pull import PULL_TOLERANCE, derive as derive_impulses
from .symmetry import broken

#: A contact separates when its normal velocity exceeds this fraction of the scene's largest
#: approach speed before impact (see the module's docstring for why 1 %).
SEPARATION_TOLERANCE = 0.01

#: A symmetric scene's answer breaks its symmetry when the reversed part exceeds this fraction of
#: the impact (see the module's docstring).
SYMMETRY_TOLERANCE = 1e-3


def metric_norm(scene: CatalogueScene, twists: Sequence[Twist]) -> float:
    """‖ξ‖_M = sqrt(Σ m |v|² + ωᵀ J ω), J in world axes."""
    return float(np.sqrt(2 * kinetic_energy(scene.engine, twists)))


def _diff(a: Sequence[Twist], b: Sequence[Twist]) -> list:
    return [Twist(x.velocity - y.velocity, x.angular_velocity - y.angular_velocity) for x, y in zip(a, b)]


@dataclass
class Grade:
    """One engine on one scene (see the module's docstring for each number)."""

    scene: str
    engine: str
    law: str
    error: float
    energy_ratio: float
    exact_energy_ratio: float
    energy_gain: float
    should_separate: list
    separates: list
    normal_velocities: list
    exact_normal_velocities: list
    twists: list = field(default_factory=list)
    symmetries: list = field(default_factory=list)
    symmetry_broken: Optional[float] = None
    symmetry_by: dict = field(default_factory=dict)
    pull: Optional[float] = None
    normal_impulses: Optional[list] = None
    impulse_scale: float = 0.0
    unexplained: float = 0.0

    @property
    def pull_ok(self) -> bool:
        """No contact needs to pull beyond ``PULL_TOLERANCE`` of the impulse scale (:mod:`.pull`;
        True where the impulses are not determined by the twist change)."""
        return self.pull is None or self.pull <= PULL_TOLERANCE

    @property
    def symmetry_ok(self) -> bool:
        """No symmetry of the scene broken beyond ``SYMMETRY_TOLERANCE`` (asymmetric scene: True)."""
        return self.symmetry_broken is None or self.symmetry_broken <= SYMMETRY_TOLERANCE

    @property
    def separation_ok(self) -> bool:
        """Every contact that should separate does, and none that should stay does."""
        return self.should_separate == self.separates

    def to_json(self) -> dict:
        d = asdict(self)
        d["separation_ok"] = self.separation_ok
        d["symmetry_ok"] = self.symmetry_ok
        d["pull_ok"] = self.pull_ok
        d["impulses_determined"] = self.pull is not None
        return d


def grade(scene: CatalogueScene, engine: str, twists: Sequence[Twist]) -> Grade:
    """Grade ``twists`` (per body, after impact, world axes) against the scene's exact answer."""
    twists = [t if isinstance(t, Twist) else Twist.of(*t) for t in twists]
    if len(twists) != len(scene.engine.bodies):
        raise ValueError(f"{engine} on {scene.name}: {len(twists)} twists for {len(scene.engine.bodies)} bodies")
    for i, t in enumerate(twists):
        if not (np.all(np.isfinite(t.velocity)) and np.all(np.isfinite(t.angular_velocity))):
            raise ValueError(f"{engine} on {scene.name}: body {i}'s twist is not finite: {t}")
    impact = metric_norm(scene, _diff(scene.exact, scene.before))
    error = metric_norm(scene, _diff(twists, scene.exact)) / impact
    t0 = scene.kinetic_energy_before
    t = kinetic_energy(scene.engine, twists)
    speed = float(max(-normal_velocities(scene.engine, scene.before)))
    vn = normal_velocities(scene.engine, twists)
    vn_exact = normal_velocities(scene.engine, scene.exact)
    cut = SEPARATION_TOLERANCE * speed
    by = broken(scene.engine, scene.symmetries, twists, impact)
    imp = derive_impulses(scene.engine, scene.before, twists, scene.exact)
    return Grade(
        scene=scene.name, engine=engine, law=scene.law, error=float(error),
        energy_ratio=float(t / t0), exact_energy_ratio=float(scene.kinetic_energy_after / t0),
        energy_gain=float(max(0.0, t - t0) / t0),
        should_separate=[bool(v > cut) for v in vn_exact], separates=[bool(v > cut) for v in vn],
        normal_velocities=[float(v) for v in vn], exact_normal_velocities=[float(v) for v in vn_exact],
        twists=[{"velocity": x.velocity.tolist(), "angular_velocity": x.angular_velocity.tolist()} for x in twists],
        symmetries=[s.name for s in scene.symmetries], symmetry_broken=max(by.values()) if by else None,
        symmetry_by=by, pull=imp["pull"], normal_impulses=imp["normal_impulses"], impulse_scale=imp["scale"],
        unexplained=imp["unexplained"])
