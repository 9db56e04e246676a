"""The catalogue: scene files with their exact answers, computed by inertance itself.

A :class:`CatalogueScene` holds the file, the neutral :class:`~inertance.engines.scene.EngineScene`
an adapter builds, and :class:`Twist` before and after impact per body (world axes, v at the
centre of mass). The answer after impact is inertance's solve of the same file, in f64 (its
accuracy contract: guide/accuracy.md; the tests check it against ``exact=True`` wherever the
scene has an exact form):

* frictionless scenes — the scene's ``[solve] law``; the catalogue asks ``"unilateral"``:
  Newton's restitution per contact as a complementarity problem, which is the law the
  LCP/PGS engines state for simultaneous contacts;
* frictional scenes — inertance's impulse-space integration of Coulomb's law with Newton's
  restitution (guide/friction.md). That law compresses every contact together (the paper's
  hypothesis); an engine's velocity-level Coulomb LCP is another law, and the report says so.

``law`` records which one per scene.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Optional, Sequence

import numpy as np

from .scene import EngineScene, load as load_engine_scene
from .symmetry import symmetries

#: The catalogue's directory in a checkout: ``benches/engines/scenes/`` (the package run from
#: its source tree). An installed package has no catalogue: :func:`default_catalogue` then
#: looks at ``$INERTANCE_CATALOGUE`` and at ``benches/engines/scenes`` under the working directory.
CATALOGUE = Path(__file__).resolve().parents[3] / "benches" / "engines" / "scenes"


def default_catalogue() -> Path:
    """The first of ``$INERTANCE_CATALOGUE``, :data:`CATALOGUE` and ``./benches/engines/scenes``
    that is a directory (else :data:`CATALOGUE`, which :func:`scenes` reports missing)."""
    import os

    for d in (os.environ.get("INERTANCE_CATALOGUE"), CATALOGUE, Path.cwd() / "benches" / "engines" / "scenes"):
        if d and Path(d).is_dir():
            return Path(d)
    return CATALOGUE


@dataclass(frozen=True)
class Twist:
    """A body's twist: ``velocity`` of its centre of mass and ``angular_velocity``, world axes."""

    velocity: np.ndarray
    angular_velocity: np.ndarray

    @staticmethod
    def of(v, w) -> "Twist":
        v = np.asarray(v, dtype=float).reshape(3)
        w = np.asarray(w, dtype=float).reshape(3)
        return Twist(v, w)


@dataclass(frozen=True)
class CatalogueScene:
    """One catalogue entry: ``name`` (the file's stem), ``engine`` (what adapters read),
    ``before`` and ``exact`` (per body, :class:`Twist`), ``law`` (the law the exact answer is
    under), ``contact_velocities`` (per contact, the exact normal velocity after impact,
    positive = separating), ``kinetic_energy_before`` and ``kinetic_energy_after``, and
    ``symmetries`` (:class:`~inertance.engines.symmetry.Symmetry`, computed from the scene:
    the exact answer keeps them, an engine's may not)."""

    name: str
    path: Path
    engine: EngineScene
    before: tuple
    exact: tuple
    law: str
    separating: tuple
    kinetic_energy_before: float
    kinetic_energy_after: float
    symmetries: tuple = ()


def _vector(x) -> np.ndarray:
    """A vector of the report: a numpy array, a list, or the friction report's text ``"[a b c]"``."""
    if isinstance(x, str):
        return np.array([float(t) for t in x.strip("[]").split()], dtype=float)
    return np.asarray(x, dtype=float)


def kinetic_energy(engine: EngineScene, twists: Sequence[Twist]) -> float:
    """Σ ½ m |v|² + ½ ωᵀ J ω over the bodies (J in world axes)."""
    return sum(0.5 * b.mass * t.velocity @ t.velocity
               + 0.5 * t.angular_velocity @ b.inertia_world @ t.angular_velocity
               for b, t in zip(engine.bodies, twists))


def normal_velocities(engine: EngineScene, twists: Sequence[Twist]) -> np.ndarray:
    """Per contact, the relative normal velocity of the first body away from the other (positive:
    separating), for the given twists, at the scene's contact points."""
    out = []
    for c in engine.contacts:
        def point_velocity(i):
            b, t = engine.bodies[i], twists[i]
            return t.velocity + np.cross(t.angular_velocity, c.point - b.position)
        rel = point_velocity(c.bodies[0])
        if len(c.bodies) == 2:
            rel = rel - point_velocity(c.bodies[1])
        out.append(-(rel @ c.normal))  # normal is out of the first body: −n is "away"
    return np.array(out)


def solve_exact(path) -> tuple:
    """inertance's answer for the file: (law, per-body twists after impact)."""
    import inertance

    scene = inertance.Scene.load(str(path))
    sol = inertance.solve(scene, model="newton")
    if getattr(sol, "friction", None) is not None:
        fr = sol.friction.get("newton")
        if fr is None or "velocity" not in fr:
            raise ValueError(f"{path}: inertance gives no frictional Newton answer: {sol.failures}")
        return ("friction (Coulomb, Newton restitution, impulse-space integration)",
                (Twist.of(_vector(fr["velocity"]), _vector(fr["angular_velocity"])),))
    m = sol.newton
    if m is None:
        raise ValueError(f"{path}: inertance gives no Newton answer: {sol.failures}")
    law = m.law
    if scene.is_system:
        twists = tuple(Twist.of(v, w) for v, w in zip(m.velocities, m.angular_velocities))
    else:
        twists = (Twist.of(m.velocity, m.angular_velocity),)
    return law, twists


def load(path) -> CatalogueScene:
    """A catalogue scene with its exact answer."""
    path = Path(path)
    # inertance reads the file first: a bad scene gets its error (file, key, value, fix)
    law, after = solve_exact(path)
    engine = load_engine_scene(path)
    if len(after) != len(engine.bodies):
        raise ValueError(f"{path}: inertance reports {len(after)} bodies, the engine scene has {len(engine.bodies)}")
    before = tuple(Twist.of(b.velocity, b.angular_velocity) for b in engine.bodies)
    return CatalogueScene(
        name=path.stem, path=path, engine=engine, before=before, exact=after, law=law,
        separating=tuple(bool(v > 1e-9 * max(1.0, _speed(engine, before)))
                         for v in normal_velocities(engine, after)),
        kinetic_energy_before=kinetic_energy(engine, before),
        kinetic_energy_after=kinetic_energy(engine, after),
        symmetries=tuple(symmetries(engine)))


def _speed(engine: EngineScene, twists) -> float:
    """The largest approach speed among the contacts before impact (a velocity scale)."""
    return float(max(-normal_velocities(engine, twists)))


def scenes(directory=None, names: Optional[Sequence[str]] = None) -> list:
    """Every catalogue scene of ``directory`` (default :func:`default_catalogue`), sorted by name,
    or those named (stems); an unknown name is a ``KeyError`` listing the catalogue."""
    directory = Path(directory) if directory is not None else default_catalogue()
    if not directory.is_dir():
        raise FileNotFoundError(f"no catalogue directory {directory} (pass the path of benches/engines/scenes, "
                                "or set INERTANCE_CATALOGUE)")
    files = {p.stem: p for p in sorted(directory.glob("*.toml"))}
    if names:
        missing = [n for n in names if n not in files]
        if missing:
            raise KeyError(f"no catalogue scene {', '.join(missing)}; the catalogue has {', '.join(files)}")
        files = {n: files[n] for n in names}
    return [load(p) for p in files.values()]
