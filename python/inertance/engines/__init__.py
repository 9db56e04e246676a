"""The engine conformance suite: physics engines graded against inertance's exact answers.

What lives here (issue 26; nothing of it is imported by ``import inertance``, and no engine is
imported until an adapter is asked for by name):

* :mod:`.scene` — the neutral description of a catalogue scene an adapter builds its engine
  from (:class:`EngineScene`: bodies with shape, mass, inertia, pose, position and twist; plane
  obstacles and point supports; per contact the point, normal, restitution and friction);
* :mod:`.catalogue` — the catalogue (``benches/engines/scenes/*.toml``) with each scene's exact
  answer, solved by inertance under the law the engines implement (the unilateral law
  frictionless; Coulomb friction with Newton restitution where μ > 0);
* :mod:`.grading` — the grades: the error of the twist after impact in the kinetic-energy metric,
  relative to the exact impact's velocity change; energy gained; contacts that should
  separate and do not;
* :mod:`.runner` — runs adapters over scenes; the report in Markdown, JSON, SVG and HTML, the
  random family's summaries (``python -m inertance.engines``);
* :mod:`.symmetry` — the scene's mirrors and half-turns, computed, and the part of an answer
  that breaks them (the ``!sym`` grade);
* :mod:`.random_family` — the seeded random family of boxes and cylinders (1–4 contacts);
* :mod:`.convergence` — the sweeps of time step and solver iterations, the observed order;
* :mod:`.plot` — the report's SVG plots, written by hand;
* :mod:`.reference` — two pure-Python adapters that need no engine (the exact answer, and
  "nothing happens"), the runner's own tests;
* :mod:`.mujoco_adapter`, :mod:`.pybullet_adapter`, :mod:`.pinocchio_adapter`,
  :mod:`.rapier_adapter`, :mod:`.drake_adapter` — the engines, one module each (optional:
  ``pip install ./python[engines]``, and ``[drake]``).

The adapter protocol: an object with a ``name`` (str), optionally ``settings`` (dict, recorded
in the report) and ``version`` (str), and ``run(scene: EngineScene) -> list[Twist]`` giving each
body's twist after the impact (world axes, the velocity of the centre of mass). See
``benches/engines/README.md`` for a dozen-line adapter of your own engine.
"""

from .catalogue import CATALOGUE, CatalogueScene, Twist, scenes
from .grading import Grade, grade
from .scene import Body, Contact, EngineScene, Plane, SceneUnsupported, Support

#: Adapters shipped with inertance, by name: (module, class, constructor arguments). Importing
#: this package imports none of them; :func:`adapter` does, on demand.
ADAPTERS = {
    "exact": ("inertance.engines.reference", "ExactAdapter", {}),
    "no-impact": ("inertance.engines.reference", "NoImpactAdapter", {}),
    "mujoco": ("inertance.engines.mujoco_adapter", "MuJoCoAdapter", {"tuned": False}),
    "mujoco-tuned": ("inertance.engines.mujoco_adapter", "MuJoCoAdapter", {"tuned": True}),
    "mujoco-calibrated": ("inertance.engines.mujoco_adapter", "MuJoCoAdapter", {"tuned": True, "calibrated": True}),
    "pybullet": ("inertance.engines.pybullet_adapter", "PyBulletAdapter", {}),
    "pinocchio": ("inertance.engines.pinocchio_adapter", "PinocchioAdapter", {}),
    "rapier": ("inertance.engines.rapier_adapter", "RapierAdapter", {}),
    "drake": ("inertance.engines.drake_adapter", "DrakeAdapter", {}),
    "drake-tuned": ("inertance.engines.drake_adapter", "DrakeAdapter", {"variant": "tuned"}),
    "drake-calibrated": ("inertance.engines.drake_adapter", "DrakeAdapter", {"variant": "calibrated"}),
    "drake-hydroelastic": ("inertance.engines.drake_adapter", "DrakeAdapter", {"variant": "hydroelastic"}),
}


#: The engine each shipped adapter needs (a top-level module), for :func:`installed`.
ENGINE_MODULES = {"mujoco": "mujoco", "mujoco-tuned": "mujoco", "mujoco-calibrated": "mujoco",
                  "pybullet": "pybullet", "pinocchio": "pinocchio", "rapier": "rapier3d", "drake": "pydrake",
                  "drake-tuned": "pydrake", "drake-calibrated": "pydrake", "drake-hydroelastic": "pydrake"}


def installed() -> list:
    """The shipped engine adapters whose engine is installed (found, not imported)."""
    import importlib.util

    return [name for name, module in ENGINE_MODULES.items() if importlib.util.find_spec(module) is not None]


def adapter(name: str):
    """A shipped adapter by name (``ADAPTERS``); imports its engine now (``ImportError`` when
    the engine is not installed, naming the extra)."""
    import importlib

    if name not in ADAPTERS:
        raise KeyError(f"no adapter {name!r}; the shipped adapters are {', '.join(ADAPTERS)}")
    module, cls, kwargs = ADAPTERS[name]
    return getattr(importlib.import_module(module), cls)(**kwargs)


__all__ = ["CATALOGUE", "CatalogueScene", "Twist", "scenes", "Grade", "grade", "Body", "Contact",
           "EngineScene", "Plane", "Support", "SceneUnsupported", "ADAPTERS", "ENGINE_MODULES", "adapter",
           "installed"]
