import os
from dataclasses import dataclass
from typing import Any, Mapping, Optional, Sequence, Union

from ._inertance import (
    __version__ as __version__,
    FormatError as FormatError,
    InertanceError as InertanceError,
    LzbSolution as LzbSolution,
    ModelSolution as ModelSolution,
    Scene as Scene,
    SceneError as SceneError,
    Solution as Solution,
    SolveError as SolveError,
    SweepError as SweepError,
    SystemModelSolution as SystemModelSolution,
    SystemSolution as SystemSolution,
)

SceneLike = Union[Scene, Mapping[str, Any], str, os.PathLike[str]]
ModelArg = Union[str, Sequence[str], None]

def solve(scene: SceneLike, model: ModelArg = None, law: Optional[str] = None, exact: bool = False,
          outputs: Union[str, Sequence[str], None] = None,
          tolerance: Optional[float] = None) -> Union[Solution, SystemSolution, LzbSolution]: ...
# Per model: "impulses" (P, N); one body: "velocity", "angular_velocity" (P, 3); a system:
# "bodies": {name: {"velocity": (P, 3), "angular_velocity": (P, 3)}}; then
# "lost_velocity_energy", "kinetic_energy_loss" (P,) (and "friction_dissipation"); "status".
# executor: a concurrent.futures.Executor, or anything whose submit(fn, *args) returns an object
# with result() (Dask's client.get_executor(), submitit); chunk: the most points per task.
def solve_batch(scene: SceneLike, vary: Mapping[str, Any], law: Optional[str] = None,
                executor: Any = None, chunk: Optional[int] = None) -> dict[str, Any]: ...
def sweep(scene: SceneLike, vary: Mapping[str, Any], exact: bool = False, law: Optional[str] = None,
          threads: Optional[int] = None, frame: Optional[bool] = None,
          executor: Any = None, chunk: Optional[int] = None) -> Any: ...
def analyze(scene: SceneLike, model: ModelArg = None, exact: bool = False) -> dict[str, Any]: ...

@dataclass
class Simulation:
    log: dict[str, Any]
    samples: dict[str, Any]
    bodies: Optional[list[str]] = None
    @property
    def impacts(self) -> list[dict[str, Any]]: ...
    @property
    def events(self) -> list[dict[str, Any]]: ...
    @property
    def end(self) -> str: ...
    @property
    def error(self) -> Optional[str]: ...
    @property
    def zeno(self) -> Optional[dict[str, Any]]: ...
    def to_json(self) -> str: ...

def simulate(scene: Union[str, os.PathLike[str]], law: Optional[str] = None) -> Simulation: ...

@dataclass
class Derivation:
    expressions: dict[str, Any]
    json: dict[str, Any]
    text: str
    latex: str
    @property
    def det(self) -> Any: ...
    @property
    def conditions(self) -> list[Any]: ...
    def model(self, name: str) -> dict[str, Any]: ...

def derive(scene: SceneLike, symbols: Optional[Sequence[str]] = None, model: ModelArg = None) -> Derivation: ...

@dataclass
class CheckResult:
    passed: bool
    lines: list[dict[str, Any]]
    text: str

def check(directory: Union[str, os.PathLike[str]] = "derivations") -> CheckResult: ...
