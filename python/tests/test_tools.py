"""analyze, check, derive, sweep and solve_batch."""

from fractions import Fraction

import numpy as np
import pytest

import inertance
from conftest import BAR, HARD, ROOT, cli_json

SYMBOLIC = """
name = "planar bar on two supports, symbolic"
[body]
mass = "m"
inertia = ["Jx", "Jy", "Jz"]
velocity = ["vx", "vy", 0]
angular_velocity = [0, 0, "omega"]
[[contact]]
point = [0, "y1", 0]
normal = [1, 0, 0]
tangent = [0, 1, 0]
k = "k1"
[[contact]]
point = [0, "y2", 0]
normal = [1, 0, 0]
tangent = [0, 1, 0]
k = "k2"
[solve]
models = ["poisson"]
"""
SYMBOLS = ["m", "Jx", "Jy", "Jz", "vx", "vy", "omega", "y1", "y2", "k1", "k2"]


def test_analyze_equals_the_cli():
    scene = HARD / "coincident-unequal-k.toml"
    a = inertance.analyze(scene, exact=True)
    assert a["models"]["newton"]["classification"] == "singular-incompatible"
    assert a["models"]["poisson"]["classification"] == "singular-compatible"
    assert a["det"] == 0 and isinstance(a["det"], Fraction)
    cli = cli_json("analyze", scene, "--exact")
    assert a["models"]["poisson"]["family"]["particular"] == [
        Fraction(x) for x in cli["models"]["poisson"]["family"]["particular"]]
    f = inertance.analyze(BAR)
    assert f["models"]["newton"]["classification"] == "unique"
    assert f["rank_tolerance"] > 0


def test_check_returns_its_verdicts():
    r = inertance.check(ROOT / "derivations")
    assert r.passed
    verdicts = {line["verdict"] for line in r.lines}
    assert verdicts <= {"reproduced", "erratum"} and "erratum" in verdicts
    assert len(r.lines) > 1000
    with pytest.raises(inertance.FormatError):
        inertance.check(ROOT / "no-such-directory")


def test_derive_gives_sympy_expressions():
    sympy = pytest.importorskip("sympy")
    d = inertance.derive(SYMBOLIC, symbols=SYMBOLS)
    m, Jz, y1, y2 = sympy.symbols("m Jz y1 y2")
    assert sympy.simplify(d.det - (y1 - y2) ** 2 / (Jz * m)) == 0
    P1 = d.model("poisson")["impulses"][0]
    vx, omega, k1 = sympy.symbols("vx omega k1")
    assert sympy.simplify(P1 + (k1 + 1) * (m * vx * y2 + Jz * omega) / (y1 - y2)) == 0
    # At Example 3's numbers the closed form gives the exact solver's value.
    at = {m: 1, Jz: 12, y1: -2, y2: 4, vx: 3, omega: sympy.Rational(2, 5), k1: sympy.Rational(3, 10)}
    exact = inertance.solve(BAR, model="poisson", exact=True).poisson.impulses[0]
    assert sympy.Rational(exact.numerator, exact.denominator) == P1.subs(at)
    assert d.conditions and "det =" in d.text and "\\begin{aligned}" in d.latex
    assert d.json["det"] == "(y1 - y2)^2/(Jz*m)"


def test_derive_errors():
    with pytest.raises(inertance.SceneError) as e:
        inertance.derive(SYMBOLIC, symbols=["m"])
    assert e.value.key == "body.inertia[0]" and e.value.value == '"Jx"' 


def test_sweep_returns_arrays_and_matches_exact_grid():
    cols = inertance.sweep(BAR, {"contact[1].k": (0, 1, 11)}, frame=False)
    assert list(cols["point"]) == list(range(11))
    np.testing.assert_allclose(cols["contact[1].k"], np.linspace(0, 1, 11))
    k = cols["contact[1].k"]
    at = np.argmin(abs(k - 0.3))
    assert cols["newton_P1"][at] == pytest.approx(cols["poisson_P1"][at], rel=1e-14)
    assert set(cols["status"]) <= {"ok", "tensile"}
    ex = inertance.sweep(BAR, {"contact[1].k": "0:1:3"}, exact=True, frame=False, threads=1)
    assert ex["contact[1].k_exact"] == [0, Fraction(1, 2), 1]
    assert ex["newton_P1_exact"][0] == inertance.solve(
        BAR, exact=True).newton.impulses[0] * 0 + inertance.solve(
        inertance.Scene.load(BAR).with_values({"contact[1].k": 0}), exact=True).newton.impulses[0]
    two = inertance.sweep(BAR, {"contact[0].k": (0, 1, 3), "contact[1].k": (0, 1, 4)}, frame=False)
    assert len(two["point"]) == 12


def test_sweep_errors():
    with pytest.raises(inertance.SweepError) as e:
        inertance.sweep(BAR, {"contact[1].k": (0, 1.5, 4)})
    with pytest.raises(inertance.SweepError) as e:
        inertance.sweep(BAR, {"contact[9].k": (0, 1, 4)})
    assert "contact[9].k" in str(e.value)


def test_batch_equals_one_solve_per_point(bar):
    k = np.linspace(0, 1, 21)
    b = inertance.solve_batch(bar, {"contact[1].k": k})
    assert b["newton"]["impulses"].shape == (21, 2)
    assert b["poisson"]["velocity"].shape == (21, 3)
    for i in (0, 7, 20):
        r = inertance.solve(bar.with_values({"contact[1].k": float(k[i])}))
        np.testing.assert_array_equal(b["newton"]["impulses"][i], r.newton.impulses)
        np.testing.assert_array_equal(b["poisson"]["angular_velocity"][i], r.poisson.angular_velocity)
        assert b["newton"]["lost_velocity_energy"][i] == r.newton.lost_velocity_energy
        assert b["poisson"]["kinetic_energy_loss"][i] == r.poisson.kinetic_energy_loss
    assert len(b["status"]) == 21


def test_batch_statuses_and_errors(bar):
    w = np.array([0.4, 1.0])
    b = inertance.solve_batch(bar, {"body.angular_velocity[2]": w})
    assert b["status"][0] == "ok" and b["status"][1].startswith("tensile")
    u = inertance.solve_batch(bar, {"body.angular_velocity[2]": w}, law="unilateral")
    assert u["status"] == ["ok", "ok"]
    with pytest.raises(inertance.SweepError) as e:
        inertance.solve_batch(bar, {"contact[1].k": [0.5, 1.5]})
    assert e.value.point == 1 and e.value.key == "contact[1].k" and e.value.value == "1.5"
    with pytest.raises(inertance.SweepError):
        inertance.solve_batch(bar, {"contact[1].k": [0.5], "body.mass": [1, 2]})
    coincident = BAR.read_text().replace("point = [0, 4, 0]", "point = [0, -2, 0]")
    s = inertance.solve_batch(coincident, {"contact[1].k": [0.3]})
    assert s["status"] == ["singular"] and np.isnan(s["newton"]["impulses"]).all()
