"""Systems of several bodies (`[[body]]` tables) from Python: `solve` gives a `SystemSolution`,
checked against closed forms derived here by hand, against the laws of momentum written in
the test (not read from the library), f64 against exact, and the CLI's JSON.

Conventions (src/mechanics/system): each body's twist is about its own centre of mass in world
axes; a contact's normal n points out of its first body; its impulse is −P n on the first body
and +P n on the second (an obstacle takes nothing); v_x > 0 is approaching; a joint's reaction
(force F, moment M about its anchor A) acts on its first body, the opposite on its second.
"""

import pathlib
from fractions import Fraction as F

import numpy as np
import pytest

import inertance
from conftest import ROOT, cli_json

# --- small exact vector algebra, written here so that the checks do not use the library -------


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def add(*vs):
    return [sum(xs, F(0)) for xs in zip(*vs)]


def scale(s, a):
    return [s * x for x in a]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return sum((x * y for x, y in zip(a, b)), F(0))


def matvec(m, v):
    return [dot(row, v) for row in m]


def diag(d):
    return [[d[0], 0, 0], [0, d[1], 0], [0, 0, d[2]]]


def kinetic(m, J, v, w):
    """½ m |v|² + ½ ωᵀ J ω."""
    return (m * dot(v, v) + dot(w, matvec(J, w))) / 2


def real(x):
    """A value of the report's exact mode as a float: a Fraction, or an exact radical such as
    "12/17*sqrt(17)" (a contact's tangential speed) evaluated by SymPy."""
    if isinstance(x, str):
        import sympy
        return float(sympy.sympify(x))
    return float(x)


# --- Newton's cradle ---------------------------------------------------------------------------
#
# Three equal balls (mass m, radius 1) in a row along x, touching; the first strikes the two at
# rest with speed v; both contacts have coefficient e. With the normals along +x (out of the
# left ball of each pair), the impulses P1, P2 give
#     v_s = v − P1/m,   v_m = (P1 − P2)/m,   v_l = P2/m,
# so the approach velocities (v_x = v_left − v_right) change by −G P with
#     G = [[2, −1], [−1, 2]] / m,   Δ = det G = 3/m².
# Newton's law for simultaneous impact, v_x after = −e v_x before with v_x before = (v, 0):
#     v_s − v_m = −e v,   v_m − v_l = 0   ⇒   P2 = (P1 − P2), P1 = 2 P2,  v − 3 P2/m = −e v
#     ⇒   (P1, P2) = (2/3, 1/3) (1 + e) m v,
#         (v_s, v_m, v_l) = ((1 − 2e)/3, (1 + e)/3, (1 + e)/3) v.
# Poisson's law: compression ends where v_x = 0 at both contacts, P^c = G⁻¹ (v, 0) =
# (2/3, 1/3) m v, and P = (1 + e) P^c — the same impulses. For e = 1 energy is conserved:
# (1 − 2e)² + 2 (1 + e)² = 9 when e = 1. (Not the textbook (0, 0, v): that is a sequence of
# two impacts; this is the simultaneous law of the paper, eq. 15, 21–23.)


def cradle(m=1, v=1, e=1):
    ball = lambda name, x, vx: {  # noqa: E731
        "name": name, "shape": {"sphere": 1}, "mass": m, "position": [x, 0, 0],
        "velocity": [vx, 0, 0], "angular_velocity": [0, 0, 0],
    }
    return {
        "name": "Newton's cradle",
        "body": [ball("striker", 0, v), ball("middle", 2, 0), ball("last", 4, 0)],
        "contact": [
            {"bodies": ["striker", "middle"], "point": [1, 0, 0], "normal": [1, 0, 0], "k": e},
            {"bodies": ["middle", "last"], "point": [3, 0, 0], "normal": [1, 0, 0], "k": e},
        ],
    }


CASES = [(F(1), F(1), F(1)), (F(2), F(3, 2), F(1, 2)), (F(1, 3), F(-5, 7), F(0)),
         (F(7, 2), F(4), F(9, 10))]


@pytest.mark.parametrize("m,v,e", CASES, ids=lambda x: str(x))
def test_cradle_exact_equals_the_closed_form(m, v, e):
    r = inertance.solve(cradle(m, v, e), exact=True)
    assert isinstance(r, inertance.SystemSolution) and r.scalar == "exact"
    assert r.bodies == ["striker", "middle", "last"]
    assert r.free and r.joints == []
    assert r.inertance == [[2 / m, -1 / m], [-1 / m, 2 / m]]
    assert r.det == 3 / m**2
    assert set(dict(r.models)) == {"newton", "poisson"}
    closed = [(1 - 2 * e) / 3 * v, (1 + e) / 3 * v, (1 + e) / 3 * v]
    for name, s in r.models:
        # A striker moving away (v < 0) gives negative impulses: the closed form still holds,
        # but the contacts would have to pull — not admissible (the unilateral law separates).
        assert s.law == "simultaneous" and s.admissible == (v > 0)
        assert {x["reason"] for x in s.inadmissible} == (set() if v > 0 else {"separating", "tensile"})
        assert s.impulses == [F(2, 3) * (1 + e) * m * v, F(1, 3) * (1 + e) * m * v], name
        assert s.velocities == [[x, 0, 0] for x in closed]
        assert s.angular_velocities == [[0, 0, 0]] * 3
        for b, name_b in enumerate(r.bodies):
            assert s.velocity(b) == s.velocity(name_b) == [closed[b], 0, 0]
            assert s.angular_velocity(name_b) == [0, 0, 0]
        # Newton's law at both contacts, read from the contact velocities after impact.
        assert [c[0] for c in s.contact_velocities] == [-e * v, 0]
        # Energies: per body ½ m v², E_p = ½ Σ m |Δv|² (eq. 28), ΔE_c = T⁰ − T (eq. 32).
        assert s.kinetic_energies == [m * x * x / 2 for x in closed]
        assert r.kinetic_energies_before == [m * v * v / 2, 0, 0]
        dv = sub(closed, [v, 0, 0])
        assert s.lost_velocity_energy == m * dot(dv, dv) / 2
        assert s.kinetic_energy_loss == m * v * v / 2 - sum(s.kinetic_energies)
        # A free system: momentum m v along x before and after, none about the origin (all on
        # the x axis).
        assert r.momentum_before == {"linear": [m * v, 0, 0], "angular": [0, 0, 0]}
        assert s.momentum_after == r.momentum_before
        assert s.energy_identity and s.momentum_conserved
    assert r.poisson.compression_impulses == [F(2, 3) * m * v, F(1, 3) * m * v]
    assert r.newton.compression_impulses is None
    if e == 1:
        assert r.newton.kinetic_energy_loss == 0


def test_cradle_exact_values_are_fractions_f64_values_numpy():
    e = inertance.solve(cradle(), exact=True)
    assert all(isinstance(x, F) for row in e.newton.velocities for x in row)
    assert all(isinstance(x, F) for x in e.newton.impulses)
    f = inertance.solve(cradle())
    assert f.scalar == "f64"
    assert isinstance(f.newton.velocities, np.ndarray) and f.newton.velocities.shape == (3, 3)
    assert f.newton.angular_velocities.shape == (3, 3)
    assert f.newton.contact_velocities.shape == (2, 3)
    assert isinstance(f.newton.impulses, np.ndarray) and f.newton.impulses.shape == (2,)
    assert isinstance(f.newton.velocity("middle"), np.ndarray)
    assert f.inertance.shape == (2, 2)
    assert isinstance(f.det, float) and isinstance(f.newton.lost_velocity_energy, float)


# --- f64 against exact ----------------------------------------------------------------------
#
# Every number the f64 solve reports, against the exact solve of the same scene. The f64 solve
# factors G (N ≤ 2 here) and, with joints, the joints' KKT system of six rows per body: each
# output is a short sum of products of the inputs (all exact binary fractions or within ½ ulp)
# through a well-conditioned elimination (κ(G) = 3 for the cradle; the bars' KKT below is
# O(10)), so its error is a few tens of roundings of the largest magnitude involved. We allow
# 64 ε times the largest magnitude of the exact outputs of the same kind (|impulses| for
# impulses, |velocities| for velocities, …), the bound the pipeline itself uses for momentum.

EPS = np.finfo(float).eps


def outputs(r):
    """Every numeric output of a system solution, by name, as lists of numbers."""
    out = {"inertance": [x for row in r.inertance for x in row], "det": [r.det],
           "momentum_before": list(r.momentum_before["linear"]) + list(r.momentum_before["angular"]),
           "kinetic_energies_before": list(r.kinetic_energies_before)}
    for name, s in r.models:
        out[f"{name}.impulses"] = list(s.impulses)
        out[f"{name}.velocities"] = [x for row in s.velocities for x in row]
        out[f"{name}.angular_velocities"] = [x for row in s.angular_velocities for x in row]
        out[f"{name}.kinetic_energies"] = list(s.kinetic_energies)
        out[f"{name}.energies"] = [s.lost_velocity_energy, s.kinetic_energy_loss]
        out[f"{name}.contact_velocities"] = [x for row in s.contact_velocities for x in row]
        out[f"{name}.momentum_after"] = list(s.momentum_after["linear"]) + list(s.momentum_after["angular"])
        for j, jr in enumerate(s.joint_reactions):
            out[f"{name}.joint{j}"] = list(jr["force"]) + list(jr["moment"])
    return out


def assert_f64_near_exact(scene, law=None):
    exact = outputs(inertance.solve(scene, exact=True, law=law))
    approx = outputs(inertance.solve(scene, law=law))
    assert exact.keys() == approx.keys()
    for key, xs in exact.items():
        xs = [real(x) for x in xs]
        tol = 64 * EPS * max(1.0, max(abs(x) for x in xs))
        np.testing.assert_allclose(approx[key], xs, rtol=0, atol=tol, err_msg=key)


@pytest.mark.parametrize("m,v,e", CASES, ids=lambda x: str(x))
def test_cradle_f64_against_exact(m, v, e):
    assert_f64_near_exact(cradle(m, v, e))


# --- two bars, pinned, striking the floor ------------------------------------------------------
#
# "upper" (m = 2, J = diag(1, 2, 2)) is pinned to the ground at O by a revolute joint about z and
# turns at ω = −1 about z: its centre (1, 0, 0) moves at (0, −1, 0) and its end A = (2, 0, 0) at
# (0, −2, 0). "lower" (m = 1, J = diag(1, 1, 2)) hangs from A by a second revolute joint, its
# centre at (7/2, −2, 0), turning at ω = −1: v_C = v_A + ω × (C − A) = (−2, −7/2, 0), and its
# tip T = (5, −4, 0) moves at (−4, −5, 0), striking the floor y = −4 (normal out of the body
# (0, −1, 0): v_x = 5, approaching) with e = 1/2.

BARS_TOML = """
name = "two bars, pinned, striking the floor"
[[body]]
name = "upper"
mass = 2
inertia = [1, 2, 2]
position = [1, 0, 0]
velocity = [0, -1, 0]
angular_velocity = [0, 0, -1]
[[body]]
name = "lower"
mass = 1
inertia = [1, 1, 2]
position = ["7/2", -2, 0]
velocity = [-2, "-7/2", 0]
angular_velocity = [0, 0, -1]
[[obstacle]]
name = "floor"
normal = [0, 1, 0]
point = [0, -4, 0]
[[contact]]
body = "lower"
obstacle = "floor"
point = [5, -4, 0]
k = "1/2"
[[joint]]
kind = "revolute"
bodies = ["upper"]
anchor = [0, 0, 0]
axis = [0, 0, 1]
[[joint]]
kind = "revolute"
bodies = ["upper", "lower"]
anchor = [2, 0, 0]
axis = [0, 0, 1]
"""

# The same scene as Python values: Fractions, numpy arrays, tuples.
BARS_DICT = {
    "name": "two bars, pinned, striking the floor",
    "body": [
        {"name": "upper", "mass": 2, "inertia": np.array([1, 2, 2]), "position": (1, 0, 0),
         "velocity": [0, -1, 0], "angular_velocity": [0, 0, -1]},
        {"name": "lower", "mass": 1.0, "inertia": [1, 1, 2], "position": [F(7, 2), -2, 0],
         "velocity": [-2, F(-7, 2), 0], "angular_velocity": np.array([0.0, 0.0, -1.0])},
    ],
    "obstacle": [{"name": "floor", "normal": [0, 1, 0], "point": [0, -4, 0]}],
    "contact": [{"body": "lower", "obstacle": "floor", "point": [5, -4, 0], "k": F(1, 2)}],
    "joint": [
        {"kind": "revolute", "bodies": ["upper"], "anchor": [0, 0, 0], "axis": [0, 0, 1]},
        {"kind": "revolute", "bodies": ["upper", "lower"], "anchor": [2, 0, 0], "axis": [0, 0, 1]},
    ],
}

BARS = {  # what the test knows of each body: m, J (world axes), C, v⁰, ω⁰
    "upper": (F(2), diag([F(1), F(2), F(2)]), [F(1), F(0), F(0)], [0, -1, 0], [0, 0, -1]),
    "lower": (F(1), diag([F(1), F(1), F(2)]), [F(7, 2), F(-2), F(0)], [-2, F(-7, 2), 0], [0, 0, -1]),
}


@pytest.fixture(scope="module")
def bars_file(tmp_path_factory):
    p = tmp_path_factory.mktemp("systems") / "bars.toml"
    p.write_text(BARS_TOML)
    return p


def test_a_system_scene_from_a_dict_equals_the_same_from_a_file(bars_file):
    from_file = inertance.Scene.load(bars_file)
    from_dict = inertance.Scene.from_dict(BARS_DICT)
    from_text = inertance.Scene.from_toml(BARS_TOML)
    for s in (from_file, from_dict, from_text):
        assert s.is_system and s.bodies == ["upper", "lower"]
        assert s.contacts == 1 and s.joints == 2
        assert "2 bodies, 1 contacts, 2 joints" in repr(s)
    for exact in (False, True):
        want = inertance.solve(from_file, exact=exact).to_json()
        assert inertance.solve(from_dict, exact=exact).to_json() == want
        assert inertance.solve(from_text, exact=exact).to_json() == want
        assert inertance.solve(str(bars_file), exact=exact).to_json() == want
        assert inertance.solve(BARS_DICT, exact=exact).to_json() == want


def test_a_one_body_scene_is_not_a_system(bar):
    assert not bar.is_system and bar.bodies is None and bar.joints is None
    assert isinstance(inertance.solve(bar), inertance.Solution)


def test_jointed_bars_momentum_balance_per_body_exactly():
    r = inertance.solve(BARS_DICT, exact=True)
    assert r.effects == ["joints", "newton", "poisson"] and not r.free
    assert r.joints == [{"kind": "revolute", "bodies": ["upper"]},
                        {"kind": "revolute", "bodies": ["upper", "lower"]}]
    tip, n, e = [F(5), F(-4), F(0)], [F(0), F(-1), F(0)], F(1, 2)
    for name, s in r.models:
        (P,) = s.impulses
        reactions = s.joint_reactions
        assert [(j["kind"], j["bodies"]) for j in reactions] == [
            ("revolute", ["upper"]), ("revolute", ["upper", "lower"])]
        assert [j["anchor"] for j in reactions] == [[0, 0, 0], [2, 0, 0]]
        # What acts on each body: (force, point of application or None for a moment alone).
        loads = {"upper": [], "lower": [(scale(-P, n), tip)]}  # −P n on the contact's body
        for j in reactions:
            first, *second = j["bodies"]
            loads[first].append((j["force"], j["anchor"], j["moment"]))
            for b in second:
                loads[b].append((scale(-1, j["force"]), j["anchor"], scale(-1, j["moment"])))
        for b, (m, J, C, v0, w0) in BARS.items():
            v, w = s.velocity(b), s.angular_velocity(b)
            # m Δv_C = Σ forces;  J Δω = Σ (r − C) × F + Σ M  (impulsive, about C).
            forces = add(*(f for f, *_ in loads[b]))
            moments = add(*(add(cross(sub(p, C), f), *rest) for f, p, *rest in loads[b]))
            assert scale(m, sub(v, v0)) == forces, (name, b)
            assert matvec(J, sub(w, w0)) == moments, (name, b)
        # The joints hold after impact: O does not move; A moves with both bars.
        vu, wu = s.velocity("upper"), s.angular_velocity("upper")
        vl, wl = s.velocity("lower"), s.angular_velocity("lower")
        at = lambda v, w, C, p: add(v, cross(w, sub(p, C)))  # noqa: E731
        assert at(vu, wu, BARS["upper"][2], [0, 0, 0]) == [0, 0, 0]
        A = [F(2), F(0), F(0)]
        assert at(vu, wu, BARS["upper"][2], A) == at(vl, wl, BARS["lower"][2], A)
        # Newton's law at the tip (both models: one contact, the same answer): v_x = −e · 5.
        v_tip = at(vl, wl, BARS["lower"][2], tip)
        assert dot(v_tip, n) == -e * 5 == s.contact_velocities[0][0]
        # Energies from the velocities, with the test's own masses and inertias.
        T0 = [kinetic(m, J, v0, w0) for m, J, _, v0, w0 in BARS.values()]
        T1 = [kinetic(m, J, s.velocity(b), s.angular_velocity(b)) for b, (m, J, *_) in BARS.items()]
        assert r.kinetic_energies_before == T0 and s.kinetic_energies == T1
        assert s.kinetic_energy_loss == sum(T0) - sum(T1)
        assert s.kinetic_energy_loss == -s.lost_velocity_energy + P * 5  # eq. 34
        assert s.energy_identity and s.momentum_conserved


def test_jointed_bars_f64_against_exact():
    assert_f64_near_exact(BARS_DICT)


def test_system_results_equal_the_cli_json(bars_file, tmp_path):
    cradle_file = tmp_path / "cradle.toml"
    cradle_file.write_text(inertance.Scene.from_dict(cradle(F(2), F(3, 2), F(1, 2))).toml)
    for f in (bars_file, cradle_file):
        assert inertance.solve(inertance.Scene.load(f), exact=True).to_json() == cli_json(
            "solve", f, "--exact")
        assert inertance.solve(inertance.Scene.load(f)).to_json() == cli_json("solve", f)


# --- a free system in space: momentum conserved ------------------------------------------------
#
# Two bodies with general inertia (one with products of inertia), spinning and translating,
# meeting at P = (1, 1, 1/2) with the unit normal n = (2, 2, −1)/3 out of "a" (there a moves at
# (−1/2, 5/2, −2), b at (−1, 1/2, 1/3): approaching at v_x = 22/9). Nothing else acts:
# the linear momentum Σ m v_C and the angular momentum about the origin Σ (J ω + C × m v_C) are
# the same before and after, and each body takes only the contact's impulse.

FREE_BODIES = {
    "a": (F(2), [[F(3), F(1, 2), F(0)], [F(1, 2), F(2), F(1, 4)], [F(0), F(1, 4), F(1)]],
          [F(0), F(0), F(0)], [F(1), F(1, 2), F(-1)], [F(0), F(1), F(2)]),
    "b": (F(3), diag([F(1), F(2), F(3)]), [F(2), F(1), F(0)], [F(-1), F(0), F(1, 3)],
          [F(1), F(0), F(-1)]),
}
FREE_POINT, FREE_NORMAL = [F(1), F(1), F(1, 2)], [F(2, 3), F(2, 3), F(-1, 3)]


def free_scene(k="2/3"):
    return {
        "name": "two bodies in space",
        "body": [{"name": b, "mass": m, "inertia": J, "position": C, "velocity": v,
                  "angular_velocity": w} for b, (m, J, C, v, w) in FREE_BODIES.items()],
        "contact": [{"bodies": ["a", "b"], "point": FREE_POINT, "normal": FREE_NORMAL, "k": k}],
    }


def momentum(vs, ws):
    p = add(*(scale(m, v) for (m, *_), v in zip(FREE_BODIES.values(), vs)))
    L = add(*(add(matvec(J, w), cross(C, scale(m, v)))
              for (m, J, C, *_), v, w in zip(FREE_BODIES.values(), vs, ws)))
    return p, L


@pytest.mark.parametrize("law", ["simultaneous", "unilateral"])
def test_a_free_system_conserves_momentum_exactly(law):
    r = inertance.solve(free_scene(), exact=True, law=law)
    assert r.free and r.contacts[0]["velocity_before"][0] == F(22, 9)
    p0, L0 = momentum([b[3] for b in FREE_BODIES.values()], [b[4] for b in FREE_BODIES.values()])
    assert r.momentum_before == {"linear": p0, "angular": L0}
    for name, s in r.models:
        assert s.law == law
        vs = [s.velocity(b) for b in FREE_BODIES]
        ws = [s.angular_velocity(b) for b in FREE_BODIES]
        assert momentum(vs, ws) == (p0, L0), name
        assert s.momentum_after == {"linear": p0, "angular": L0}
        assert s.momentum_conserved and s.energy_identity
        # Each body takes the contact's impulse alone: ∓P n at the point.
        (P,) = s.impulses
        assert P > 0
        for sign, (b, (m, J, C, v0, w0)) in zip((-1, 1), FREE_BODIES.items()):
            impulse = scale(sign * P, FREE_NORMAL)
            assert scale(m, sub(s.velocity(b), v0)) == impulse
            assert matvec(J, sub(s.angular_velocity(b), w0)) == cross(sub(FREE_POINT, C), impulse)


@pytest.mark.parametrize("law", ["simultaneous", "unilateral"])
def test_a_free_system_f64_against_exact(law):
    assert_f64_near_exact(free_scene(), law)


def test_a_normal_as_written_is_only_a_direction():
    # 3 n: the same unit normal, the same answer (P is along the unit normal).
    r = inertance.solve(free_scene(), exact=True).to_json()
    d = free_scene()
    d["contact"][0]["normal"] = scale(3, FREE_NORMAL)
    assert inertance.solve(d, exact=True).to_json() == r


def test_an_irrational_normal_runs_exactly_in_radicals_and_in_f64():
    # n along (1, 1, 0): the unit normal is (1, 1, 0)/√2, so P and the twists carry √2; the
    # exact solve gives them as radicals, SymPy reads them, and f64 agrees.
    d = free_scene()
    d["contact"][0]["normal"] = [1, 1, 0]
    r = inertance.solve(d, exact=True)
    (P,) = r.newton.impulses
    assert isinstance(P, str) and "sqrt(2)" in P and real(P) > 0
    assert_f64_near_exact(d)


# --- the laws: simultaneous against unilateral --------------------------------------------------
#
# The last ball already moves away at speed 1 while the striker hits the middle one: contact 2
# separates (v_x⁰ = −1). The simultaneous law still imposes v_x = −e v_x⁰ = +e there, which needs
# a pulling (negative) impulse, at a contact separating before impact: not admissible. Under the unilateral law contact 2 takes nothing
# and contact 1 is a two-ball impact: P1 = (1 + e) v / (1/m + 1/m) = (1 + e) m v / 2.


def separating_cradle(e):
    d = cradle(1, 1, e)
    d["body"][2]["velocity"] = [1, 0, 0]
    return d


@pytest.mark.parametrize("e", [F(0), F(1, 2), F(1)], ids=str)
def test_simultaneous_inadmissible_unilateral_separates(e):
    # Simultaneous, Newton: v_s − v_m = −e, v_m − v_l = −e (−1) = e with v_s = 1 − P1,
    # v_m = P1 − P2, v_l = 1 + P2 ⇒ P2 = −P1, 3 P1 − 1 = e: P = ((1 + e)/3, −(1 + e)/3).
    # Poisson: P^c = G⁻¹ v⁰ = (1/3, −1/3), P = (1 + e) P^c, the same.
    sim = inertance.solve(separating_cradle(e), exact=True)
    for name, s in sim.models:
        assert s.impulses == [(1 + e) / 3, -(1 + e) / 3], name
        assert not s.admissible
        assert {x["reason"] for x in s.inadmissible} >= {"separating", "tensile"}
    uni = inertance.solve(separating_cradle(e), exact=True, law="unilateral")
    assert "unilateral" in uni.effects and uni.failures == {}
    for name, s in uni.models:
        assert s.law == "unilateral" and s.active == [True, False]
        assert s.impulses == [(1 + e) / 2, 0], name
        assert s.velocities == [[(1 - e) / 2, 0, 0], [(1 + e) / 2, 0, 0], [1, 0, 0]]
        assert s.admissible


# --- parameters and with_values -----------------------------------------------------------------


def test_with_values_on_a_system_scene():
    s = inertance.Scene.from_dict(cradle())
    # A body's number by its key path, and a contact's coefficient.
    t = s.with_values({"body[0].velocity[0]": F(3, 2), "body[1].mass": 1, "contact[0].k": "1/2",
                       "contact[1].k": "1/2"})
    r = inertance.solve(t, exact=True)
    assert r.newton.impulses == [F(2, 3) * F(3, 2) * F(3, 2), F(1, 3) * F(3, 2) * F(3, 2)]
    # [params] in a system scene: the same closed form at every value set.
    d = cradle(m="m", v="v", e="e")
    d["params"] = {"m": 2, "v": "3/2", "e": "1/2"}
    p = inertance.Scene.from_dict(d)
    for m, v, e in [(F(2), F(3, 2), F(1, 2)), (F(5), F(1, 3), F(1, 4)), (F(1, 2), F(-2), F(1))]:
        q = p.with_values({"params.m": m, "params.v": v, "params.e": e})
        r = inertance.solve(q, exact=True)
        assert r.poisson.impulses == [F(2, 3) * (1 + e) * m * v, F(1, 3) * (1 + e) * m * v]
        assert r.newton.velocity("striker") == [(1 - 2 * e) / 3 * v, 0, 0]
        assert r.det == 3 / m**2


def test_with_values_names_a_missing_key():
    s = inertance.Scene.from_dict(cradle())
    with pytest.raises(inertance.SceneError) as err:
        s.with_values({"body[7].mass": 2})
    assert err.value.key == "body[7].mass"


# --- bad input ---------------------------------------------------------------------------------


def test_a_contact_naming_an_unknown_body():
    d = cradle()
    d["contact"][1]["bodies"] = ["middle", "ghost"]
    with pytest.raises(inertance.SceneError) as err:
        inertance.Scene.from_dict(d)
    e = err.value
    assert e.key == "contact[1].bodies[1]" and e.value == '"ghost"'
    assert "striker, middle, last" in e.message and "contact[1].bodies[1]" in str(e)


def test_a_joint_naming_an_unknown_body():
    d = dict(BARS_DICT, joint=[dict(BARS_DICT["joint"][0], bodies=["uper"])])
    with pytest.raises(inertance.SceneError) as err:
        inertance.Scene.from_dict(d)
    assert err.value.key == "joint[0].bodies[0]" and err.value.value == '"uper"'


def test_two_bodies_with_one_name():
    d = cradle()
    d["body"][2]["name"] = "middle"
    with pytest.raises(inertance.SceneError) as err:
        inertance.Scene.from_dict(d)
    assert err.value.key == "body[2].name"


def test_a_joint_the_bodies_violate_before_impact():
    d = dict(BARS_DICT, body=[BARS_DICT["body"][0], dict(BARS_DICT["body"][1], velocity=[0, 0, 0])])
    with pytest.raises(inertance.SceneError) as err:
        inertance.solve(d, exact=True)
    assert err.value.key == "joint[1]" and "upper" in err.value.message


def test_a_singular_system_raises_solve_error():
    # Two contacts at the same point with the same normal between the same balls: G = [[2, 2],
    # [2, 2]] / m, Δ = 0 (§8).
    d = cradle()
    d["contact"][1] = dict(d["contact"][0])
    with pytest.raises(inertance.SolveError) as err:
        inertance.solve(d, exact=True)
    assert err.value.kind == "singular"


def test_a_body_asked_for_by_an_unknown_name_or_index():
    s = inertance.solve(cradle(), exact=True).newton
    with pytest.raises(KeyError, match='"ghost".*"striker", "middle", "last"'):
        s.velocity("ghost")
    with pytest.raises(IndexError, match="3 bodies"):
        s.angular_velocity(3)
    with pytest.raises(IndexError):
        s.velocity(-1)
    with pytest.raises(TypeError):
        s.velocity(True)


def test_outputs_do_not_apply_to_a_system():
    with pytest.raises(ValueError, match="outputs="):
        inertance.solve(cradle(), outputs="impulses")


def test_a_system_with_friction_is_solved_or_refused_naming_mu():
    # Friction in a system is another piece of work: until it lands the pipeline refuses it,
    # naming the key; once it lands this solves. Either way: no crash, no silent μ = 0.
    d = cradle()
    d["contact"][0]["mu"] = F(1, 5)
    try:
        r = inertance.solve(d, exact=True)
    except inertance.SceneError as e:
        assert e.key == "contact[0].mu" and e.value == "1/5" and "friction" in e.message
    else:
        assert isinstance(r, inertance.SystemSolution)
        assert r.to_json() != inertance.solve(cradle(), exact=True).to_json()


def test_analyze_takes_a_system_and_agrees_with_solve():
    s = inertance.Scene.from_dict(cradle())
    a = inertance.analyze(s, exact=True)
    r = inertance.solve(s, exact=True)
    assert a["bodies"] == r.bodies
    for name in ("newton", "poisson"):
        m = a["models"][name]
        assert m["impulses"] == list(getattr(r, name).impulses)
        for body in m["twist_after"]:
            assert body["velocity"] == list(getattr(r, name).velocity(body["name"]))


def test_a_system_batch_equals_one_solve_per_point():
    s = inertance.Scene.from_dict(cradle())
    k = np.array([0.0, 0.25, 0.5, 1.0])
    mass = np.array([1.0, 2.0, 0.5, 3.0])
    b = inertance.solve_batch(s, {"contact[1].k": k, "body[1].mass": mass})
    assert set(b) == {"newton", "poisson", "status"}
    # k = 0 at the second contact, 1 at the first: the simultaneous answer is not physical there.
    assert b["status"][0] == "still-approaching+energy-gain" and b["status"][3] == "ok"
    for name in ("newton", "poisson"):
        m = b[name]
        assert m["impulses"].shape == (4, 2)
        assert set(m["bodies"]) == {"striker", "middle", "last"}
        assert "velocity" not in m
        for body in m["bodies"].values():
            assert body["velocity"].shape == (4, 3) and body["angular_velocity"].shape == (4, 3)
        assert m["lost_velocity_energy"].shape == (4,) and m["kinetic_energy_loss"].shape == (4,)
    for i in range(4):
        r = inertance.solve(s.with_values({"contact[1].k": float(k[i]), "body[1].mass": float(mass[i])}))
        for name in ("newton", "poisson"):
            m, want = b[name], getattr(r, name)
            np.testing.assert_array_equal(m["impulses"][i], want.impulses)
            for body in r.bodies:
                np.testing.assert_array_equal(m["bodies"][body]["velocity"][i], want.velocity(body))
                np.testing.assert_array_equal(m["bodies"][body]["angular_velocity"][i],
                                              want.angular_velocity(body))
            assert m["lost_velocity_energy"][i] == want.lost_velocity_energy
            assert m["kinetic_energy_loss"][i] == want.kinetic_energy_loss
    # The closed form at m = 1, v = 1, k = 1 (both contacts): P = (2/3, 1/3) (1 + k) m v / 2.
    one = inertance.solve_batch(s, {"contact[1].k": [1.0]})
    np.testing.assert_allclose(one["newton"]["impulses"][0], [4 / 3, 2 / 3], rtol=1e-15)
    np.testing.assert_allclose(one["newton"]["bodies"]["last"]["velocity"][0], [2 / 3, 0, 0],
                               rtol=1e-15)


def test_a_system_batch_statuses_friction_and_errors():
    s = inertance.Scene.from_dict(cradle())
    # A value that makes the scene invalid names its point, key and value.
    with pytest.raises(inertance.SweepError) as err:
        inertance.solve_batch(s, {"contact[1].k": [0.5, 1.5]})
    assert err.value.point == 1 and err.value.key == "contact[1].k" and err.value.value == "1.5"
    # The boxes under the simultaneous law: G singular, a status and NaN.
    boxes = inertance.solve_batch(ROOT / "examples/box-on-box.toml", {"contact[0].k": [0.5]},
                                  law="simultaneous")
    assert boxes["status"] == ["singular"] and np.isnan(boxes["newton"]["impulses"]).all()
    # A frictional system: each law integrated, with the energy friction dissipates.
    rough = inertance.solve_batch(ROOT / "examples/rough-pendulum.toml", {"contact[0].k": [0.5]})
    r = inertance.solve(ROOT / "examples/rough-pendulum.toml")
    p = rough["poisson"]
    assert p["impulses"][0][0] == r.to_json()["friction"]["poisson"]["contacts"][0]["normal_impulse"]
    assert p["friction_dissipation"].shape == (1,) and p["friction_dissipation"][0] > 0
    np.testing.assert_allclose(p["impulses"][0], [132 / 35], rtol=1e-12)


# --- one body as a system: the one-body solver is the reference ---------------------------------
#
# A one-body scene (the paper's, body axes at C) written as a system of one body at the origin,
# each contact against an obstacle whose normal is the body's reversed: the system's pipeline
# (its own Mechanism, src/mechanics/system) must give what the one-body solver gives.


def as_system(path):
    import tomllib

    d = tomllib.loads(path.read_text())
    obstacles, contacts = [], []
    for i, c in enumerate(d["contact"]):
        c = dict(c)
        n = c.pop("normal")
        obstacles.append({"name": f"support{i}", "normal": [-x for x in n], "point": c["point"]})
        contacts.append(dict(c, body="body", obstacle=f"support{i}"))
    return dict(d, body=[dict(d["body"], name="body", position=[0, 0, 0])], obstacle=obstacles,
                contact=contacts)


@pytest.mark.parametrize("name", ["planar-bar", "rod-between-walls"])
@pytest.mark.parametrize("exact", [False, True], ids=["f64", "exact"])
def test_one_body_as_a_system_equals_the_one_body_solver(name, exact):
    path = pathlib.Path(ROOT / "examples" / f"{name}.toml")
    one = inertance.solve(inertance.Scene.load(path), exact=exact)
    system = inertance.solve(as_system(path), exact=exact)
    assert isinstance(system, inertance.SystemSolution) and system.bodies == ["body"]
    assert [m for m, _ in system.models] == [m for m, _ in one.models]
    assert {m: f["status"] for m, f in system.failures.items()} == {
        m: f["status"] for m, f in one.failures.items()}
    for m, s in system.models:
        o = getattr(one, m)
        for a, b in [(s.impulses, o.impulses), (s.velocity("body"), o.velocity),
                     (s.angular_velocity(0), o.angular_velocity),
                     ([s.lost_velocity_energy, s.kinetic_energy_loss],
                      [o.lost_velocity_energy, o.kinetic_energy_loss])]:
            if exact:
                assert list(a) == list(b), m
            else:
                # Two f64 computations (the one-body solver works in scaled units): each within
                # a few roundings of outputs of magnitude ≤ 10 (E_p of the bar is 9.2 J).
                np.testing.assert_allclose(a, b, rtol=0, atol=64 * EPS * 10, err_msg=m)


# --- a partial answer: one model jams -----------------------------------------------------------
#
# Two balls in a row fitted exactly between two walls, both moving left at 2 m/s, k = 1/2. The
# chain cannot move: a cannot go left (the wall), b cannot go right (the wall), a cannot pass b.
# Newton's law would have a rebound from the left wall that the right wall forbids: no
# admissible impulses (jammed, the CLI's status 4 with Poisson's answer). Poisson's answer must
# leave both at rest, and the impulses on the chain, P1 (left wall, +x) − P3 (right wall, −x),
# equal its momentum change 2 · 1 · 2 = 4 N s; a's own balance: P1 − P2 = 2.


def chain():
    ball = lambda name, x: {"name": name, "mass": 1, "inertia": [1, 1, 1],  # noqa: E731
                            "position": [x, 0, 0], "velocity": [-2, 0, 0], "angular_velocity": [0, 0, 0]}
    return {
        "name": "two balls between two walls",
        "body": [ball("a", 0), ball("b", 2)],
        "obstacle": [{"name": "left", "normal": [1, 0, 0], "point": [-1, 0, 0]},
                     {"name": "right", "normal": [-1, 0, 0], "point": [3, 0, 0]}],
        "contact": [{"body": "a", "obstacle": "left", "point": [-1, 0, 0], "k": "1/2"},
                    {"bodies": ["a", "b"], "point": [1, 0, 0], "normal": [1, 0, 0], "k": "1/2"},
                    {"body": "b", "obstacle": "right", "point": [3, 0, 0], "k": "1/2"}],
        "solve": {"law": "unilateral"},
    }


@pytest.mark.parametrize("exact", [False, True], ids=["f64", "exact"])
def test_a_jammed_model_is_a_failure_beside_the_other_models_answer(exact):
    r = inertance.solve(chain(), exact=exact)
    assert r.newton is None and [m for m, _ in r.models] == ["poisson"]
    assert r.failures["newton"]["status"] == "jammed"
    assert "jam" in r.failures["newton"]["error"]
    p = r.poisson
    P1, P2, P3 = (float(x) for x in p.impulses)
    assert np.allclose(np.asarray(p.velocities, dtype=float), 0, atol=64 * EPS * 6)
    assert P1 - P3 == pytest.approx(4, abs=64 * EPS * 6) and P1 - P2 == pytest.approx(2, abs=64 * EPS * 6)
    assert "newton" in r.to_json()["models"] and r.to_json()["models"]["newton"]["status"] == "jammed"
