"""solve: the attributes of the JSON contract, f64 as numpy, exact as Fraction, equal to the CLI."""

from fractions import Fraction

import numpy as np
import pytest

import inertance
from conftest import BAR, HARD, ROOT, cli_json


def test_example3_f64_matches_the_paper(bar):
    r = inertance.solve(bar)
    assert r.scalar == "f64"
    assert r.effects == ["newton", "poisson"]
    assert isinstance(r.newton.impulses, np.ndarray)
    np.testing.assert_allclose(r.newton.impulses, [3.655556, 0.197778], atol=1e-6)
    np.testing.assert_allclose(r.poisson.impulses, [3.64, 0.24], atol=1e-12)
    np.testing.assert_allclose(r.poisson.compression_impulses, [2.8, 0.2], atol=1e-12)
    assert r.newton.compression_impulses is None
    assert r.inertance.shape == (2, 2)
    assert r.det == pytest.approx(3)
    assert r.newton.lost_velocity_energy == pytest.approx(9.195356, abs=1e-6)
    assert r.poisson.kinetic_energy_loss == pytest.approx(4.976533, abs=1e-6)
    assert r.newton.velocity.shape == (3,) and r.newton.angular_velocity.shape == (3,)
    assert r.newton.angular_velocity[2] == pytest.approx(-0.143333, abs=1e-6)
    assert r.newton.admissible is True and r.newton.law == "simultaneous"
    assert set(dict(r.models)) == {"newton", "poisson"}


def test_example3_exact_is_fractions(bar):
    r = inertance.solve(bar, exact=True)
    assert r.scalar == "exact"
    assert r.newton.impulses == [Fraction(329, 90), Fraction(89, 450)]
    assert r.newton.lost_velocity_energy == Fraction(413791, 45000)
    assert r.det == 3 and isinstance(r.det, Fraction)
    assert r.inertance[0][1] == Fraction(1, 3)


@pytest.mark.parametrize("scene", [BAR, *sorted(HARD.glob("*.toml"))], ids=lambda p: p.stem)
def test_exact_results_equal_the_cli_json(scene):
    try:
        r = inertance.solve(inertance.Scene.load(scene), exact=True)
    except inertance.SolveError as e:
        assert e.kind == "singular"
        return
    assert r.to_json() == cli_json("solve", scene, "--exact")


def test_f64_results_equal_the_cli_json(bar):
    assert inertance.solve(bar).to_json() == cli_json("solve", BAR)


RADICAL = {
    "body": {"mass": 1, "inertia": [1, 1, 1], "velocity": [-1, 0, 0], "angular_velocity": [0, 0, 0]},
    "contact": [{"point": [-1, 0, 0], "normal": [-2, 1, 0], "k": "1/2"},
                {"point": [1, 1, 0], "normal": [0, 1, 0], "k": "1/5"}],
}


def _expected(x):
    """A value of `to_json()` as the attributes give it in exact mode (radicals stay strings)."""
    if isinstance(x, list):
        return [_expected(v) for v in x]
    if isinstance(x, str) and "sqrt" not in x:
        return Fraction(x)
    return x


@pytest.mark.parametrize("scene", [BAR, "radical", *sorted(HARD.glob("*.toml"))],
                         ids=lambda p: getattr(p, "stem", p))
@pytest.mark.parametrize("exact", [False, True], ids=["f64", "exact"])
def test_attributes_read_from_the_report_equal_its_json(scene, exact):
    """G, Δ, P̂ and P^c are read straight from the report (not through its JSON): same values."""
    sc = inertance.Scene.from_dict(RADICAL) if scene == "radical" else inertance.Scene.load(scene)
    try:
        r = inertance.solve(sc, exact=exact)
    except inertance.SolveError:
        return
    j = r.to_json()
    pairs = [(r.inertance, j["inertance"]), (r.inertance_yx, j["inertance_yx"]),
             (r.inertance_zx, j["inertance_zx"]), (r.det, j["det"])]
    for name, m in r.models:
        mj = j["models"][name]
        pairs += [(m.impulses_per_normal, mj["impulses_per_normal"]),
                  (m.compression_impulses, mj.get("compression_impulses"))]
    for got, want in pairs:
        if want is None:
            assert got is None
        elif exact:
            assert got == _expected(want)
        else:
            assert isinstance(got, (np.ndarray, float)) and np.array_equal(got, np.array(want, float))


def test_model_and_law_select_what_is_solved(bar):
    r = inertance.solve(bar, model="newton")
    assert r.poisson is None and r.effects == ["newton"]
    u = inertance.solve(bar, law="unilateral", exact=True)
    assert u.newton.law == "unilateral" and u.newton.active == [True, True]
    assert u.to_json() == cli_json("solve", BAR, "--exact", "--law", "unilateral")
    assert inertance.solve(bar, model=["newton", "poisson"]).effects == ["newton", "poisson"]


def test_a_tensile_answer_is_reported_not_hidden(bar):
    r = inertance.solve(bar.with_values({"body.angular_velocity[2]": 1}), model="newton")
    assert r.newton.admissible is False
    assert "tensile" in {v["reason"] for v in r.newton.inadmissible}


def test_radicals_stay_exact_strings_sympy_reads():
    sympy = pytest.importorskip("sympy")
    scene = inertance.Scene.from_dict({
        "body": {"mass": 1, "inertia": [1, 1, 1], "velocity": [-1, 0, 0],
                 "angular_velocity": [0, 0, 0]},
        "contact": [{"point": [-1, 0, 0], "normal": [-2, 1, 0], "k": "1/2"}],
    })
    r = inertance.solve(scene, exact=True)
    p = r.newton.impulses[0]
    assert isinstance(p, str) and "sqrt(5)" in p
    assert sympy.simplify(sympy.sympify(p) - sympy.sympify(p)) == 0
    assert float(sympy.sympify(p)) == pytest.approx(inertance.solve(scene).newton.impulses[0])


def test_constrained_scene_has_constraint_impulses():
    s = inertance.Scene.load(HARD / "constrained-near-singular-1e-4.toml")
    r = inertance.solve(s, exact=True)
    assert r.constraints is not None
    assert all(isinstance(q, Fraction) for q in r.newton.constraint_impulses)


ROUGH = """
[body]
mass = 1
inertia = [12, 1.6, 12]
velocity = [3, 2, 0]
angular_velocity = [0, 0, 0.4]
[[contact]]
point = [0, -2, 0]
normal = [1, 0, 0]
k = 0.3
mu = 1
[[contact]]
point = [0, 4, 0]
normal = [1, 0, 0]
k = 0.2
mu = 1
"""


def test_friction_readout_per_law(tmp_path):
    # derivations/friction-example-3.md: under Poisson the slip stops at s = 2/3 and both
    # contacts stick; under Newton A₂ pulls from s = 1 and carries no friction then.
    r = inertance.solve(ROUGH, exact=True)
    assert r.effects == ["friction", "newton", "poisson"]
    p = r.friction["poisson"]
    assert p["events"] == [Fraction(2, 3), 1]
    assert p["contacts"][0]["modes"] == ["slide+", "stick"]
    assert p["contacts"][0]["tangential_impulse"][1] == Fraction(-28, 15)
    assert p["friction_dissipation"] == 2
    n = r.friction["newton"]
    assert n["contacts"][1]["modes"] == ["slide+", "stick", "free"]
    assert n["kinetic_energy_loss"] == Fraction(313769, 45000)
    assert any("contact 2: negative normal impulse rate" in v for v in n["verdicts"])
    path = tmp_path / "rough.toml"
    path.write_text(ROUGH)
    assert r.to_json()["friction"] == cli_json("solve", path, "--exact")["friction"]


CORNER = (BAR.parent / "ball-in-corner.toml").read_text()


def test_friction_tolerance_as_the_cli(tmp_path):
    # A spatial scene: tolerance= is --tolerance; the tighter run agrees with the default one
    # within the default one's estimate; a tolerance outside (0, 1) is refused.
    path = tmp_path / "corner.toml"
    path.write_text(CORNER)
    tight = inertance.solve(CORNER, tolerance=1e-12).to_json()["friction"]["newton"]
    assert tight["tolerance"] == 1e-12
    assert tight == cli_json("solve", path, "--tolerance", "1e-12")["friction"]["newton"]
    loose = inertance.solve(CORNER).to_json()["friction"]["newton"]
    assert loose["tolerance"] > tight["tolerance"]
    assert abs(loose["contacts"][0]["normal_impulse"] - tight["contacts"][0]["normal_impulse"]) \
        <= loose["error_estimate"]
    with pytest.raises(ValueError, match="between 0 and 1"):
        inertance.solve(CORNER, tolerance=0.0)
    with pytest.raises(inertance.SceneError) as e:
        inertance.solve(CORNER.replace('models = ["newton"]', "tolerance = 2"))
    assert e.value.key == "solve.tolerance"
    assert e.value.value == "2"


@pytest.mark.parametrize("exact", [False, True])
def test_outputs_asked_for_equal_the_full_solve_and_the_rest_read_none(bar, exact):
    full = inertance.solve(bar, exact=exact)
    part = inertance.solve(bar, exact=exact, outputs=["impulses", "twist"])
    assert part.to_json()["outputs"] == "impulses,twist"
    for m in ("newton", "poisson"):
        a, b = getattr(full, m), getattr(part, m)
        assert list(b.impulses) == list(a.impulses)
        assert list(b.velocity) == list(a.velocity)
        assert list(b.angular_velocity) == list(a.angular_velocity)
        # Not asked for: None, never the zero of an empty slot.
        assert b.lost_velocity_energy is None and b.kinetic_energy_loss is None
    only = inertance.solve(bar, exact=exact, outputs="energies")
    assert only.newton.impulses is None and only.newton.velocity is None
    assert only.newton.kinetic_energy_loss == full.newton.kinetic_energy_loss
    assert only.poisson.compression_impulses is None


def test_outputs_names_are_checked(bar):
    with pytest.raises(ValueError, match="outputs"):
        inertance.solve(bar, outputs=["impulses", "velocity"])
    with pytest.raises(ValueError, match="outputs"):
        inertance.solve(bar, outputs=3)


TINY = """
[body]
mass = "1e-300"
inertia = ["12e-300", "1.6e-300", "12e-300"]
velocity = [3, 2, 0]
angular_velocity = [0, 0, 0.4]
[[contact]]
point = [0, -2, 0]
normal = [1, 0, 0]
k = 0.3
[[contact]]
point = [0, 4, 0]
normal = [1, 0, 0]
k = 0.2
"""


def test_delta_beyond_f64_is_a_decimal(tmp_path):
    """Example 3 with a body of 1e-300 kg: Δ = 3e600 kg⁻² is no float; the impulses are."""
    from decimal import Decimal

    scene = inertance.Scene.from_toml(TINY, file="tiny.toml")
    r = inertance.solve(scene)
    assert isinstance(r.det, Decimal)
    assert abs(r.det / Decimal("3e600") - 1) < Decimal("1e-14")
    np.testing.assert_allclose(r.newton.impulses, [3.655556e-300, 1.977778e-301], rtol=1e-6)
    assert r.inertance.shape == (2, 2)  # 1.3e300 kg⁻¹: floats
    # The CLI's JSON, read by Python's json module: Δ a string, nothing null or infinite.
    path = tmp_path / "tiny.toml"
    path.write_text(TINY)
    j = cli_json("solve", path)
    assert Decimal(j["det"]) == r.det
