"""A catalogue scene as an engine sees it: shapes, masses, poses, twists, planes, coefficients.

:func:`load` reads a scene file of ``benches/engines/scenes/`` (inertance's world-frame scene
format, guide/scenes.md) into an :class:`EngineScene` — plain numbers (floats, numpy arrays),
nothing of inertance in it — so an adapter needs no knowledge of inertance to set its engine
up. The file is read twice: by inertance itself (which validates it and gives the exact
answer, :mod:`inertance.engines.catalogue`) and here, with the subset of the format the engines
can build (solid boxes, spheres and cylinders centred on their body origin; plane obstacles;
contacts given by ``corner``, ``point``, ``body_point`` or found from the obstacle). Anything
else is refused with a :class:`SceneUnsupported` naming the key, never guessed.

Numbers are inertance's expressions (``"30 deg"``, ``"-7/3"``, ``"cos(15 deg)"``) evaluated in
f64 by :func:`evaluate`; ``tests/test_engines.py`` checks the result against inertance's own
reading of the same file (the world inertia tensor and the contact points from the centre of
mass), so the two readings cannot drift apart silently.
"""

from __future__ import annotations

import ast
import math
import operator
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Optional, Sequence

import numpy as np

try:  # Python ≥ 3.11
    import tomllib as _toml
except ImportError:  # pragma: no cover - Python 3.9/3.10
    try:
        import tomli as _toml  # type: ignore
    except ImportError:
        _toml = None


class SceneUnsupported(ValueError):
    """A catalogue scene uses a part of the scene format the engine suite cannot build."""

    def __init__(self, file: str, key: str, message: str):
        super().__init__(f"{file}: key `{key}`: {message}")
        self.file, self.key, self.message = file, key, message


# ---------------------------------------------------------------------------------------------
# Numbers: inertance's expression grammar, evaluated in f64.

_FUNCS = {"sqrt": math.sqrt, "sin": math.sin, "cos": math.cos, "tan": math.tan}
_BINOPS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
           ast.Div: operator.truediv, ast.Pow: operator.pow}


def evaluate(value: Any, names: Optional[dict] = None) -> float:
    """A scene number as a float: a TOML int/float, or an expression string of inertance's grammar
    (``+ - * / ^``, parentheses, ``pi``, ``sqrt``, ``sin``, ``cos``, ``tan``, ``deg``; ``names``:
    the scene's parameters). ``deg`` multiplies the product or quotient before it by π/180, which
    is what ``*(pi/180)`` does in left-associative arithmetic. Raises ``ValueError`` naming the
    text on anything else."""
    if isinstance(value, bool):
        raise ValueError(f"a number, not {value!r}")
    if isinstance(value, (int, float)):
        return float(value)
    if not isinstance(value, str):
        raise ValueError(f"a number or an expression string, not {value!r}")
    text = value.replace("^", "**")
    text = re.sub(r"\bdeg\b", "*(pi/180)", text)
    try:
        tree = ast.parse(text, mode="eval")
    except SyntaxError as e:
        raise ValueError(f"cannot read the number {value!r}: {e.msg}") from None
    names = dict(names or {})
    names.setdefault("pi", math.pi)

    def ev(node):
        if isinstance(node, ast.Expression):
            return ev(node.body)
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) \
                and not isinstance(node.value, bool):
            return float(node.value)
        if isinstance(node, ast.BinOp) and type(node.op) in _BINOPS:
            return _BINOPS[type(node.op)](ev(node.left), ev(node.right))
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            v = ev(node.operand)
            return -v if isinstance(node.op, ast.USub) else v
        if isinstance(node, ast.Name) and node.id in names:
            return float(names[node.id])
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) \
                and node.func.id in _FUNCS and len(node.args) == 1 and not node.keywords:
            return _FUNCS[node.func.id](ev(node.args[0]))
        raise ValueError(f"cannot read the number {value!r}: `{ast.unparse(node)}` is not part of the grammar")

    out = ev(tree)
    if not math.isfinite(out):
        raise ValueError(f"the number {value!r} is not finite")
    return out


def _vec(value: Any, names: dict, n: int = 3) -> np.ndarray:
    if not isinstance(value, (list, tuple)) or len(value) != n:
        raise ValueError(f"a list of {n} numbers, not {value!r}")
    return np.array([evaluate(v, names) for v in value], dtype=float)


def rotation(pose: Any, names: dict) -> np.ndarray:
    """R (body axes → world axes) from a ``pose`` value: axis/angle (Rodrigues), a quaternion
    ``[w, x, y, z]`` of any length, a matrix by rows, or a list of these applied in turn (the
    first applied first: R = R_n ⋯ R_1)."""
    if isinstance(pose, list):
        r = np.eye(3)
        for p in pose:
            r = rotation(p, names) @ r
        return r
    if not isinstance(pose, dict):
        raise ValueError(f"a pose is a table or a list of tables, not {pose!r}")
    if set(pose) == {"axis", "angle"}:
        a = _vec(pose["axis"], names)
        a = a / np.linalg.norm(a)
        t = evaluate(pose["angle"], names)
        k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
        return np.eye(3) + math.sin(t) * k + (1 - math.cos(t)) * k @ k
    if set(pose) == {"quaternion"}:
        w, x, y, z = _vec(pose["quaternion"], names, 4)
        n = w * w + x * x + y * y + z * z
        return np.array([
            [w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z]]) / n
    if set(pose) == {"matrix"}:
        return np.array([_vec(row, names) for row in pose["matrix"]])
    raise ValueError(f"a pose has `axis` and `angle`, `quaternion` or `matrix`, not {sorted(pose)}")


# ---------------------------------------------------------------------------------------------
# The neutral description.

@dataclass(frozen=True)
class Body:
    """A rigid body: ``shape`` ``"box"`` (``size`` = the three edge lengths along body x, y, z),
    ``"sphere"`` (``size`` = (r,)) or ``"cylinder"`` (``size`` = (r, h), axis body z); solid and
    uniform, its centre of mass at its geometric centre. ``inertia``: the central tensor in body
    axes (diagonal); ``rotation``: body axes → world; ``position``: the centre of mass in the
    world; ``velocity`` (of the centre of mass) and ``angular_velocity``: world axes, before
    impact."""

    name: str
    shape: str
    size: tuple
    mass: float
    inertia: np.ndarray
    rotation: np.ndarray
    position: np.ndarray
    velocity: np.ndarray
    angular_velocity: np.ndarray

    @property
    def inertia_world(self) -> np.ndarray:
        """R J Rᵀ: the central inertia tensor in world axes."""
        return self.rotation @ self.inertia @ self.rotation.T

    def quaternion(self) -> np.ndarray:
        """The pose as a unit quaternion (w, x, y, z)."""
        return _quaternion(self.rotation)


@dataclass(frozen=True)
class Plane:
    """A static half-space: ``normal`` (unit) points out of it toward the bodies; ``point`` lies
    on its surface."""

    name: str
    normal: np.ndarray
    point: np.ndarray


@dataclass(frozen=True)
class Support:
    """A point support: a contact the scene gives by a point and a normal with no obstacle. An
    engine models it as a small static sphere (``radius``, default 1 cm) touching the body at
    ``point``, its centre at ``point − radius·normal`` (``normal``: unit, out of the support
    toward the body)."""

    name: str
    normal: np.ndarray
    point: np.ndarray
    radius: float = 0.01

    @property
    def centre(self) -> np.ndarray:
        return self.point - self.radius * self.normal


@dataclass(frozen=True)
class Contact:
    """One contact of the scene: ``bodies`` — one body index (against ``obstacle``, an index of
    :attr:`EngineScene.obstacles`) or two (body–body); ``point`` (world); ``normal`` (unit): out
    of the first body, as inertance's (the impulse pushes the first body along −normal);
    ``restitution`` (Newton's e) and ``friction`` (Coulomb's μ)."""

    bodies: tuple
    obstacle: Optional[int]
    point: np.ndarray
    normal: np.ndarray
    restitution: float
    friction: float


@dataclass(frozen=True)
class EngineScene:
    """Everything an adapter needs: ``bodies``, ``obstacles`` (:class:`Plane` or
    :class:`Support`), ``contacts``; gravity is off and every contact is at zero gap."""

    name: str
    file: str
    bodies: tuple
    obstacles: tuple
    contacts: tuple

    @property
    def frictional(self) -> bool:
        return any(c.friction > 0 for c in self.contacts)

    def contact_pairs(self):
        """The distinct (body index, other) pairs in contact, ``other`` ``("body", j)`` or
        ``("obstacle", j)``, with the restitution and friction of their contacts (which must
        agree: an engine sets them per pair, not per point — else ``SceneUnsupported``)."""
        pairs: dict = {}
        for i, c in enumerate(self.contacts):
            key = (c.bodies[0], ("body", c.bodies[1]) if len(c.bodies) == 2 else ("obstacle", c.obstacle))
            e, mu = pairs.setdefault(key, (c.restitution, c.friction))
            if (e, mu) != (c.restitution, c.friction):
                raise SceneUnsupported(self.file, f"contact[{i}]",
                                       "the contacts between one pair of objects have different coefficients; "
                                       "an engine sets them per pair")
        return pairs


def _quaternion(r: np.ndarray) -> np.ndarray:
    """Unit quaternion (w, x, y, z) of a rotation matrix (Shepperd's method)."""
    t = np.trace(r)
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        q = [0.25 * s, (r[2, 1] - r[1, 2]) / s, (r[0, 2] - r[2, 0]) / s, (r[1, 0] - r[0, 1]) / s]
    elif r[0, 0] > r[1, 1] and r[0, 0] > r[2, 2]:
        s = math.sqrt(1.0 + r[0, 0] - r[1, 1] - r[2, 2]) * 2
        q = [(r[2, 1] - r[1, 2]) / s, 0.25 * s, (r[0, 1] + r[1, 0]) / s, (r[0, 2] + r[2, 0]) / s]
    elif r[1, 1] > r[2, 2]:
        s = math.sqrt(1.0 + r[1, 1] - r[0, 0] - r[2, 2]) * 2
        q = [(r[0, 2] - r[2, 0]) / s, (r[0, 1] + r[1, 0]) / s, 0.25 * s, (r[1, 2] + r[2, 1]) / s]
    else:
        s = math.sqrt(1.0 + r[2, 2] - r[0, 0] - r[1, 1]) * 2
        q = [(r[1, 0] - r[0, 1]) / s, (r[0, 2] + r[2, 0]) / s, (r[1, 2] + r[2, 1]) / s, 0.25 * s]
    q = np.array(q)
    return q / np.linalg.norm(q)


_BODY_KEYS = {"name", "shape", "mass", "density", "pose", "position", "velocity", "angular_velocity"}
_CONTACT_KEYS = {"obstacle", "body", "bodies", "corner", "point", "body_point", "normal", "tangent",
                 "k", "k_newton", "k_poisson", "k_energetic", "mu"}


def _body(file: str, key: str, t: dict, names: dict, default_name: str) -> Body:
    extra = set(t) - _BODY_KEYS
    if extra:
        raise SceneUnsupported(file, f"{key}.{sorted(extra)[0]}",
                               "the engine suite builds bodies from `shape`, `mass`/`density`, `pose`, "
                               "`position` and the twist only")
    shape = t.get("shape")
    if not isinstance(shape, dict) or len(shape) != 1:
        raise SceneUnsupported(file, f"{key}.shape", "an engine needs a shape: `box`, `sphere` or `cylinder`")
    (kind, dims), = shape.items()
    if kind == "box":
        size = tuple(_vec(dims, names))
        a, b, c = size
        volume = a * b * c
        moments = lambda m: m / 12 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
    elif kind == "sphere":
        r = evaluate(dims, names)
        size = (r,)
        volume = 4 / 3 * math.pi * r ** 3
        moments = lambda m: np.full(3, 2 / 5 * m * r * r)
    elif kind == "cylinder":
        r, h = _vec(dims, names, 2)
        size = (r, h)
        volume = math.pi * r * r * h
        moments = lambda m: np.array([m * (3 * r * r + h * h) / 12] * 2 + [m * r * r / 2])
    else:
        raise SceneUnsupported(file, f"{key}.shape.{kind}",
                               "the engine suite builds boxes, spheres and cylinders (a thin `rod` or point "
                               "masses have no engine geometry)")
    if "mass" in t:
        mass = evaluate(t["mass"], names)
    elif "density" in t:
        mass = evaluate(t["density"], names) * volume
    else:
        raise SceneUnsupported(file, f"{key}.mass", "a mass or a density is needed")
    rot = rotation(t["pose"], names) if "pose" in t else np.eye(3)
    return Body(
        name=str(t.get("name", default_name)), shape=kind, size=size, mass=mass,
        inertia=np.diag(moments(mass)), rotation=rot,
        position=_vec(t.get("position", [0, 0, 0]), names),
        velocity=_vec(t.get("velocity", [0, 0, 0]), names),
        angular_velocity=_vec(t.get("angular_velocity", [0, 0, 0]), names))


def _surface_point(body: Body, direction: np.ndarray) -> np.ndarray:
    """The body's point farthest along ``direction`` (unit, world): where a plane whose normal
    is −direction touches it (a box: its one extreme corner, refused if an edge or a face is)."""
    if body.shape == "sphere":
        return body.position + body.size[0] * direction
    if body.shape == "box":
        half = np.array(body.size) / 2
        corners = [np.array([sx, sy, sz]) for sx in (-1, 1) for sy in (-1, 1) for sz in (-1, 1)]
        heights = [direction @ (body.rotation @ (s * half)) for s in corners]
        top = max(heights)
        tol = 1e-12 * max(half)
        best = [s for s, h in zip(corners, heights) if h > top - tol]
        if len(best) != 1:
            raise ValueError(f"{len(best)} corners touch: name them with `corner`")
        return body.position + body.rotation @ (best[0] * half)
    raise ValueError(f"a {body.shape} needs the contact's `point`")


def load(path) -> EngineScene:
    """Read a catalogue scene file into an :class:`EngineScene` (see the module's docstring)."""
    if _toml is None:  # pragma: no cover
        raise RuntimeError("reading catalogue scenes needs Python ≥ 3.11 (tomllib) or the `tomli` package")
    path = Path(path)
    file = str(path)
    with open(path, "rb") as f:
        doc = _toml.load(f)
    for k in ("constraints", "surface", "joint"):
        if k in doc:
            raise SceneUnsupported(file, k, "joints, constraints and surfaces are not built by the engine suite yet")
    names: dict = {}
    for k, v in doc.get("params", {}).items():
        names[k] = evaluate(v, names)
    try:
        if "body" in doc and isinstance(doc["body"], list):
            bodies = [_body(file, f"body[{i}]", t, names, f"body {i}") for i, t in enumerate(doc["body"])]
        else:
            bodies = [_body(file, "body", doc.get("body", {}), names, "body")]
    except ValueError as e:
        if isinstance(e, SceneUnsupported):
            raise
        raise SceneUnsupported(file, "body", str(e)) from None
    index = {b.name: i for i, b in enumerate(bodies)}

    planes = []
    for j, o in enumerate(doc.get("obstacle", [])):
        extra = set(o) - {"name", "normal", "point", "partial"}
        if extra:
            raise SceneUnsupported(file, f"obstacle[{j}].{sorted(extra)[0]}", "an obstacle is a plane")
        n = _vec(o["normal"], names)
        planes.append((str(o.get("name", f"obstacle {j}")), n / np.linalg.norm(n),
                       _vec(o["point"], names) if "point" in o else None))
    obstacle_index = {name: j for j, (name, _, _) in enumerate(planes)}

    contacts_raw = []
    supports = []
    for i, c in enumerate(doc.get("contact", [])):
        key = f"contact[{i}]"
        extra = set(c) - _CONTACT_KEYS
        if extra:
            raise SceneUnsupported(file, f"{key}.{sorted(extra)[0]}", "not read by the engine suite")
        if "bodies" in c:
            who = tuple(index[n] for n in c["bodies"])
        elif "body" in c:
            who = (index[c["body"]],)
        else:
            who = (0,)
        body = bodies[who[0]]
        obstacle = c.get("obstacle")
        if obstacle is not None:
            obstacle = obstacle_index[obstacle] if isinstance(obstacle, str) else int(obstacle)
        if "k" in c:
            e = evaluate(c["k"], names)
        elif "k_newton" in c:
            e = evaluate(c["k_newton"], names)
        else:
            raise SceneUnsupported(file, f"{key}.k", "Newton's coefficient (`k` or `k_newton`) is needed")
        mu = evaluate(c.get("mu", 0), names)
        # the normal: out of the first body (the obstacle's −N, or as written)
        if "normal" in c:
            n = _vec(c["normal"], names)
            n = n / np.linalg.norm(n)
        elif obstacle is not None:
            n = -planes[obstacle][1]
        else:
            raise SceneUnsupported(file, f"{key}.normal", "a contact needs a normal or an obstacle")
        try:
            if "point" in c:
                p = _vec(c["point"], names)
            elif "body_point" in c:
                p = body.position + body.rotation @ _vec(c["body_point"], names)
            elif "corner" in c:
                if body.shape != "box":
                    raise ValueError("`corner` names a box corner")
                p = body.position + body.rotation @ (_vec(c["corner"], names) * np.array(body.size) / 2)
            else:
                p = _surface_point(body, n)
        except ValueError as err:
            raise SceneUnsupported(file, key, str(err)) from None
        if obstacle is None and len(who) == 1:
            supports.append(Support(name=f"support {len(supports)}", normal=-n, point=p))
            obstacle = ("support", len(supports) - 1)
        contacts_raw.append((who, obstacle, p, n, e, mu))

    # planes without a point pass through their contacts
    obstacles = []
    for j, (name, n, pt) in enumerate(planes):
        if pt is None:
            pts = [p for (_, o, p, _, _, _) in contacts_raw if o == j]
            if not pts:
                raise SceneUnsupported(file, f"obstacle[{j}].point", "an obstacle no contact touches needs a point")
            pt = pts[0]
        obstacles.append(Plane(name=name, normal=n, point=pt))
    offset = len(obstacles)
    obstacles += supports
    contacts = tuple(
        Contact(bodies=who, obstacle=(offset + o[1] if isinstance(o, tuple) else o), point=p, normal=n,
                restitution=e, friction=mu)
        for (who, o, p, n, e, mu) in contacts_raw)
    return EngineScene(name=str(doc.get("name", path.stem)), file=file, bodies=tuple(bodies),
                       obstacles=tuple(obstacles), contacts=contacts)
