"""inertance: what happens when a rigid body strikes obstacles at several points at once.

Python bindings of the Rust library ``inertance``, after Dragna, Pandrea and Stănescu,
*Simultaneous Collision of the Rigid Body at Two Points* (Symmetry 13 (2021) 1924).
Every call converts its arguments, runs the validated Rust library and converts the result:

* :class:`Scene` — a scene (guide/scenes.md) from a TOML file or string or from Python
  values, read once and reused across calls;
* :func:`solve` — impulses (eq. 20, 23), velocities after impact (eq. 24), E_p (eq. 28) and
  ΔE_c (eq. 32), per restitution model; numpy arrays in f64, ``Fraction`` exactly; for a
  system of several bodies (``[[body]]`` tables) each body's twist and the joints' reactions
  (:class:`SystemSolution`);
* :func:`solve_batch` — many points of one scene from arrays of numbers, in parallel;
* :func:`sweep` — a grid of one or two varied numbers (as ``inertance sweep``);
  both take ``executor=`` to run their points in chunks on a ``concurrent.futures``
  executor (process pool, Dask, submitit on Slurm, …);
* :func:`analyze` — degenerate cases (§8): Δ, ranks, families, admissibility;
* :func:`derive` — closed forms over symbols, as SymPy expressions;
* :func:`check` — the paper's worked examples, value by value.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any, Mapping, Optional, Sequence, Union

from . import _inertance as _native
from ._inertance import (
    __version__,
    FormatError,
    InertanceError,
    LzbSolution,
    ModelSolution,
    Scene,
    SceneError,
    Solution,
    SolveError,
    SweepError,
    SystemModelSolution,
    SystemSolution,
)

__all__ = [
    "__version__", "Scene", "Solution", "ModelSolution", "SystemSolution", "SystemModelSolution",
    "LzbSolution",
    "Derivation", "CheckResult",
    "solve", "solve_batch", "sweep", "analyze", "derive", "check", "simulate", "Simulation",
    "InertanceError", "SceneError", "SolveError", "SweepError", "FormatError",
]

SceneLike = Union[Scene, Mapping[str, Any], str, "os.PathLike[str]"]


def _scene(scene: SceneLike, symbols: Optional[Sequence[str]] = None) -> Scene:
    """A :class:`Scene` from a Scene, a dict, TOML text or a path."""
    if isinstance(scene, Scene):
        if symbols is not None and list(symbols) != scene.symbols:
            return Scene.from_toml(scene.toml, symbols=list(symbols), file=scene.file)
        return scene
    syms = None if symbols is None else list(symbols)
    if isinstance(scene, Mapping):
        return Scene.from_dict(dict(scene), symbols=syms)
    if isinstance(scene, os.PathLike):
        return Scene.load(os.fspath(scene), symbols=syms)
    if isinstance(scene, str):
        if "\n" in scene or "=" in scene:
            return Scene.from_toml(scene, symbols=syms)
        return Scene.load(scene, symbols=syms)
    raise TypeError(f"a scene is a Scene, a dict, TOML text or a path, not {type(scene).__name__}")


def solve(scene: SceneLike, model: Union[str, Sequence[str], None] = None,
          law: Optional[str] = None, exact: bool = False,
          outputs: Union[str, Sequence[str], None] = None,
          tolerance: Optional[float] = None) -> Union[Solution, SystemSolution, LzbSolution]:
    """Solve the collision of ``scene`` (as ``inertance solve --json``).

    ``model``: ``"newton"`` (eq. 14–20), ``"poisson"`` (eq. 21–23), ``"both"`` or ``None``
    (the scene's ``[solve] models``); ``law``: ``"simultaneous"`` (the paper's, eq. 15,
    21–23), ``"unilateral"`` (complementarity) or ``"lzb"`` (see below); ``None``: the
    scene's. ``exact``: in
    rationals, or exact radicals when the scene has ``"2/sqrt(5)"``-like numbers.
    ``outputs``: a name or a list of ``"impulses"``, ``"twist"``, ``"normal-velocities"``,
    ``"tangential"``, ``"energies"``, ``"constraint-impulses"`` (or ``"all"``): only those are
    computed and reported (``[solve] outputs``); an output not asked for reads ``None``.
    ``tolerance``: the relative tolerance of a spatial frictional integration, between 0 and
    1 (``[solve] tolerance``, ``--tolerance``); ``None``: the scene's, else 3.7e-11 in f64.

    The result's attributes are the JSON report's keys: ``inertance`` (G, eq. 12), ``det``
    (Δ), ``frames``, and per model (``.newton``, ``.poisson``, ``.models``) ``impulses``
    (P_i), ``velocity`` and ``angular_velocity`` (eq. 24), ``lost_velocity_energy`` (E_p,
    eq. 28), ``kinetic_energy_loss`` (ΔE_c, eq. 32), … In f64 numbers are floats and vectors
    numpy arrays; exactly, rationals are ``fractions.Fraction`` and radicals strings such as
    ``"12/17*sqrt(17)"`` (``sympy.sympify`` reads them).

    A scene of several bodies (``scene.is_system``: ``[[body]]`` tables, contacts between
    bodies or against obstacles, ``[[joint]]`` tables) gives a :class:`SystemSolution`, as
    ``inertance solve`` reports it: ``bodies`` (names), ``inertance``, ``det``, ``free``,
    ``momentum_before``, and per model ``impulses`` (−P_i n_i on a contact's first body,
    +P_i n_i on its second), ``velocity(body)`` and ``angular_velocity(body)`` (by name or
    index; about each body's own centre of mass, world axes), ``velocities`` and
    ``angular_velocities`` (one row per body), ``kinetic_energies``, ``joint_reactions``
    (force and moment on the joint's first body at its anchor), ``momentum_after``,
    ``contact_velocities``, ``lost_velocity_energy``, ``kinetic_energy_loss``. ``outputs``
    does not apply to it (a system is reported whole).

    Under the LZB multiple-impact law (``law="lzb"``, or a scene's ``[solve] law = "lzb"``;
    guide/multiple-impacts.md) the result is an :class:`LzbSolution`, in f64 (``exact``,
    ``model`` and ``outputs`` are refused): per contact (indexed from 0) ``stiffness``,
    ``exponent``, ``restitution``, ``velocities_before``, ``impulses``, ``velocities_after``,
    ``max_energies``, ``work_compression``, ``work_expansion``, ``dissipation``; ``bodies``,
    ``velocities``, ``angular_velocities``, ``velocity(body)``; ``kinetic_energy_loss``,
    ``energy_residual``, ``events``, ``ending_order``, ``error_estimate``, ``tolerance``,
    ``stats``; ``history`` (numpy arrays per sample: ``tau``, ``primary``, ``impulses``,
    ``velocities``, ``energies``); ``to_json()``, the report of ``inertance solve --json``.

    Raises :class:`SceneError` for bad input and :class:`SolveError` when there is no answer
    (``kind == "singular"``: Δ = 0, §8; ``"jammed"`` under the unilateral law).
    """
    if type(scene) is not Scene:
        scene = _scene(scene)
    return _native.solve(scene, model, law, exact, outputs, tolerance)


def solve_batch(scene: SceneLike, vary: Mapping[str, Any], law: Optional[str] = None,
                executor: Any = None, chunk: Optional[int] = None) -> dict:
    """Solve ``scene`` in f64 at many points, without a Python loop (in parallel, GIL released).

    ``vary`` maps key paths (``"contact[1].k"``, ``"body.mass"``, ``"body.velocity[0]"``, …)
    to arrays of equal length: point p sets every path to its p-th value. Returns, per model
    solved, ``{"impulses": (P, N), "velocity": (P, 3), "angular_velocity": (P, 3),
    "lost_velocity_energy": (P,), "kinetic_energy_loss": (P,)}`` numpy arrays (NaN where the
    point has no answer; with friction also ``"friction_dissipation": (P,)``), and
    ``"status"``: per point ``"ok"``, ``"singular"``, ``"jammed"`` or the reasons the
    simultaneous answer is not physical joined by ``+`` (as :func:`sweep`'s ``status``).

    A scene of several bodies (``[[body]]`` tables; paths such as ``"body[0].mass"``,
    ``"contact[1].k"``) gives per model ``"impulses"`` (P, N), ``"bodies"``: per body name
    ``{"velocity": (P, 3), "angular_velocity": (P, 3)}`` (world axes, v at the body's centre),
    and the system's ``"lost_velocity_energy"`` and ``"kinetic_energy_loss"`` (P,) — the
    numbers :func:`solve` gives at each point, bit for bit.

    ``executor``: run the points as tasks on a ``concurrent.futures.Executor`` (a process or
    thread pool, Dask's ``client.get_executor()``, …; anything whose ``submit(fn, *args)``
    returns an object with ``result()``, e.g. submitit's executors). The points are split into
    contiguous chunks of at most ``chunk`` points (default: about four chunks per worker), one
    task each, sent the scene's TOML text and the chunk's values; the results are joined in
    point order and equal the in-process call's bit for bit. The scene, the paths and the law
    are checked in the caller first, so bad input raises here before anything is submitted;
    an exception in a task propagates as the executor delivers it (pools and Dask re-raise it,
    a :class:`SweepError` naming its point by its index in the whole batch; submitit wraps it
    in its ``FailedJobError``). Each task runs in parallel over its worker's cores.
    """
    import numpy as np

    if executor is not None:
        from . import _scale

        pairs = [(path, np.asarray(v, dtype=float).ravel()) for path, v in vary.items()]
        return _scale.solve_batch(_scene(scene), pairs, law, executor, chunk)
    if chunk is not None:
        raise ValueError("chunk= splits the points into tasks for an executor: give executor= too")
    pairs = [(path, np.asarray(v, dtype=float).ravel().tolist()) for path, v in vary.items()]
    return _native.solve_batch(_scene(scene), pairs, law)


def sweep(scene: SceneLike, vary: Mapping[str, Any], exact: bool = False,
          law: Optional[str] = None, threads: Optional[int] = None, frame: Optional[bool] = None,
          executor: Any = None, chunk: Optional[int] = None):
    """Sweep one or two numbers of ``scene`` over a grid, as ``inertance sweep`` (in parallel,
    GIL released, no subprocess).

    ``vary`` maps a key path to ``(start, stop, count)`` or ``"start:stop:count"``; start and
    stop are read exactly (``Fraction``, ``"1/3"``). Returns the sweep's CSV columns by name
    (``point``, the varied paths, ``newton_P1`` …, ``newton_dEc``, ``status``; with
    ``exact``, ``…_exact`` columns as ``Fraction``) as numpy arrays — or a pandas DataFrame
    when pandas is installed (``frame=False`` forces the dict).

    ``executor``: run the grid as tasks on a ``concurrent.futures.Executor`` (as for
    :func:`solve_batch`): chunk i of n solves the points ``inertance sweep --shard i/n``
    solves (at most ``chunk`` points each; default about four chunks per worker), with their
    global ``point`` index; the chunks' columns are joined in point order and equal the
    in-process sweep's bit for bit (``Fraction`` columns included). The sweep is checked in
    the caller first (scene, paths, both ends of every range), so bad input raises here before
    anything is submitted. ``threads`` caps each task's threads on its worker.
    """
    items = []
    for path, spec in vary.items():
        if isinstance(spec, str):
            start, stop, count = spec.split(":")
        else:
            start, stop, count = spec
        items.append((path, start, stop, int(count)))
    if executor is not None:
        from . import _scale

        columns = _scale.sweep(_scene(scene), items, exact, law, threads, executor, chunk)
    elif chunk is not None:
        raise ValueError("chunk= splits the points into tasks for an executor: give executor= too")
    else:
        columns = _native.sweep(_scene(scene), items, exact, law, threads)
    if frame is False:
        return columns
    try:
        import pandas
    except ImportError:
        if frame:
            raise
        return columns
    return pandas.DataFrame(columns)


@dataclass
class Simulation:
    """A sequence of impacts (``inertance simulate``; guide/simulate.md).

    ``log``: the report of ``inertance simulate --json`` as Python objects (``impacts``, each
    with ``t``, ``contacts`` — ``feature``, ``obstacle``, ``before``, ``after``, ``impulse`` —
    ``kinetic_before``/``kinetic_after``, ``verdicts``; ``events``; ``end``; ``error``; ``zeno``;
    ``steps`` …). ``samples``: numpy arrays, one row per sample (every ``output_step``): one body
    ``t`` (N,), ``x``, ``v``, ``omega`` (N, 3), ``q`` (N, 4: w, i, j, k), ``kinetic``,
    ``potential``, ``closed`` (N,); a system ``t``, ``x``, ``v`` and ``omega`` (N, B, 3) and ``q``
    (N, B, 4; a sphere's held) in the order of ``bodies``, ``kinetic``, ``potential``,
    ``closed``.
    """

    log: dict
    samples: dict
    bodies: Optional[list] = None

    @property
    def impacts(self) -> list:
        return self.log["impacts"]

    @property
    def events(self) -> list:
        return self.log["events"]

    @property
    def end(self) -> str:
        """``"duration"``, ``"impacts"``, ``"rest"`` or ``"stopped"`` (then ``error`` says why)."""
        return self.log["end"]

    @property
    def error(self) -> Optional[str]:
        return self.log.get("error")

    @property
    def zeno(self) -> Optional[dict]:
        return self.log.get("zeno")

    def to_json(self) -> str:
        """The log as ``inertance simulate --json`` prints it."""
        import json

        return json.dumps(self.log)


def simulate(scene: Union[str, "os.PathLike[str]"], law: Optional[str] = None) -> Simulation:
    """Simulate ``scene`` (a path, or TOML text with a ``[simulate]`` table) through every
    impact, as ``inertance simulate``: one body, or a system of spheres, boxes and thin rods
    (``[[body]]`` tables);
    ``law`` (``"simultaneous"``, ``"unilateral"`` or ``"lzb"``) replaces the scene's, keeping its
    restitution. A run that stops early (an impact without an answer, persistent contact
    undecided, a state that overflows) is returned with ``end == "stopped"`` and ``error`` —
    the history up to there kept, as the command prints it with status 3. Raises
    :class:`SceneError` for bad input (file, key, value) and ``ValueError`` for an unknown law.
    """
    if isinstance(scene, os.PathLike) or (isinstance(scene, str) and "\n" not in scene and "=" not in scene):
        text, file = None, os.fspath(scene)
    elif isinstance(scene, str):
        text, file = scene, "<string>"
    else:
        raise TypeError(f"a simulation scene is TOML text or a path, not {type(scene).__name__}")
    import json

    out = _native.simulate(text, file, law)
    return Simulation(log=json.loads(out["log"]), samples=out["samples"], bodies=out.get("bodies"))


def analyze(scene: SceneLike, model: Union[str, Sequence[str], None] = None,
            exact: bool = False) -> dict:
    """Degenerate cases (§5, §8, §11; ``inertance analyze --json``): per model ``det``,
    ``rank``, ``augmented_rank``, ``classification`` (Rouché–Capelli, eq. 61–68, 98–102),
    ``family`` for a singular compatible system, ``admissible`` (eq. 73–74), ``verdicts``; and
    ``newton_equals_poisson`` (eq. 50–55), ``condition_number``, ``coincident`` (eq. 69–72).
    """
    return _native.analyze(_scene(scene), model, exact)


@dataclass
class Derivation:
    """Closed forms derived by the same solver over symbols (``inertance derive``).

    ``expressions``: the JSON report's keys with SymPy expressions (strings without SymPy),
    e.g. ``expressions["models"]["poisson"]["impulses"][0]``; ``det`` (Δ), ``conditions``
    (where the formulas hold), ``json`` (plain strings), ``text`` and ``latex``.
    """

    expressions: dict
    json: dict
    text: str
    latex: str

    @property
    def det(self) -> Any:
        """Δ = det G."""
        return self.expressions["det"]

    @property
    def conditions(self) -> list:
        """The conditions the formulas assume (nonzero pivots, positive signs)."""
        return self.expressions["conditions"]

    def model(self, name: str) -> dict:
        """One model's expressions: ``impulses`` (eq. 20, 23), ``velocity``, … ."""
        return self.expressions["models"][name]


def derive(scene: SceneLike, symbols: Optional[Sequence[str]] = None,
           model: Union[str, Sequence[str], None] = None) -> Derivation:
    """Derive closed forms over ``symbols`` (``inertance derive --symbols …``): the same
    solver over rational functions; values may name the symbols (``mass = "m"``). Without
    ``symbols`` (and a :class:`Scene` built without them), the scene's ``[params]`` are the
    symbols, as for ``inertance derive``; a scene with neither raises :class:`SceneError`."""
    return Derivation(*_native.derive(_scene(scene, symbols), model))


@dataclass
class CheckResult:
    """The verdicts of ``check``: ``passed``, and per checked value a dict with ``file``,
    ``case``, ``quantity``, ``printed``, ``computed``, ``identity`` and ``verdict``
    (``"reproduced"``, ``"erratum"`` with its ``reason``, or ``"fail"``)."""

    passed: bool
    lines: list = field(default_factory=list)
    text: str = ""


def check(directory: Union[str, "os.PathLike[str]"] = "derivations") -> CheckResult:
    """Check the paper's worked examples in ``directory`` (``inertance check``): every printed
    value exactly, every closed form as an identity, errata from ``ERRATA.md``."""
    return CheckResult(*_native.check(os.fspath(directory)))
