"""Two adapters that need no engine: the runner's own yardsticks and tests.

* :class:`ExactAdapter` answers with inertance's own solve of the scene's file: it grades 0.
* :class:`NoImpactAdapter` answers with the twist before impact (the bodies pass through each
  other): it grades exactly 1 by the definition of the error (:mod:`inertance.engines.grading`).
"""

from __future__ import annotations

from .catalogue import Twist, solve_exact
from .scene import EngineScene


class ExactAdapter:
    name = "exact"
    settings = {"what": "inertance's own answer for the scene file"}

    @property
    def version(self) -> str:
        import inertance
        return inertance.__version__

    def run(self, scene: EngineScene) -> list:
        return list(solve_exact(scene.file)[1])


class NoImpactAdapter:
    name = "no-impact"
    settings = {"what": "the twist before impact, unchanged"}
    version = "-"

    def run(self, scene: EngineScene) -> list:
        return [Twist.of(b.velocity, b.angular_velocity) for b in scene.bodies]
