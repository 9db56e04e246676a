"""Issue 28, item 2: one parameter, two units.

A parameter written in degrees (`theta = "30 deg"`) read a bare number as radians in
`--param` and `Scene.with_values`, and as degrees in `sweep` and `solve_batch`. One rule now
holds at every entry point: a bare number given to a parameter written in degrees is a number
of degrees; one in radians (mentioning `pi`) is refused with the fix. The tilted box's impulse
at 45° is 51/61 (derivations/modelled-tilted-box.md:
P1 = 51/(2(45 cos²θ − 24 cos θ sin θ + 20))).
"""

from fractions import Fraction
import math

import numpy as np
import pytest

import inertance

from conftest import BAR, cli_json

TILTED = BAR.parent / "tilted-box.toml"


def p1(theta):
    c, s = math.cos(theta), math.sin(theta)
    return 51 / (2 * (45 * c * c - 24 * c * s + 20))


def test_a_bare_number_is_degrees_at_every_entry_point():
    tilted = inertance.Scene.load(TILTED)
    exact = inertance.solve(tilted.with_values({"params.theta": 45}), exact=True)
    assert exact.newton.impulses == [Fraction(51, 61), Fraction(51, 61)]
    with_unit = inertance.solve(tilted.with_values({"params.theta": "45 deg"})).newton.impulses
    for value in (45, 45.0, "45", Fraction(45)):
        r = inertance.solve(tilted.with_values({"params.theta": value}))
        np.testing.assert_array_equal(r.newton.impulses, with_unit)
    # A fraction of a degree: (80/3)°, as the CLI reads `--param theta=80/3`.
    r = inertance.solve(tilted.with_values({"params.theta": Fraction(80, 3)}))
    assert r.newton.impulses[0] == pytest.approx(p1(math.radians(80 / 3)), rel=1e-14)
    assert r.to_json() == cli_json("solve", TILTED, "--param", "theta=80/3")
    b = inertance.solve_batch(tilted, {"params.theta": [45.0, 80 / 3]})
    assert b["newton"]["impulses"][0][0] == inertance.solve(
        tilted.with_values({"params.theta": 45})).newton.impulses[0]
    assert b["newton"]["impulses"][1][0] == pytest.approx(p1(math.radians(80 / 3)), rel=1e-14)
    s = inertance.sweep(tilted, {"params.theta": (45, 46, 2)})
    assert s["newton_P1"][0] == b["newton"]["impulses"][0][0]


def test_a_value_in_radians_for_a_parameter_in_degrees_is_refused():
    tilted = inertance.Scene.load(TILTED)
    with pytest.raises(inertance.SceneError) as e:
        tilted.with_values({"params.theta": "pi/4"})
    assert "45 deg" in str(e.value) and "radians" in str(e.value)


def test_notes_on_likely_slips_reach_python():
    text = TILTED.read_text().replace("box = [0.4, 0.2, 0.1]", "box = [200, 100, 50]")
    notes = inertance.Scene.from_toml(text).notes
    assert len(notes) == 1 and "millimetres" in notes[0]
    assert inertance.Scene.load(TILTED).notes == []


def test_a_jammed_model_does_not_hide_the_other():
    # Issue 28, item 10 (tests/regression_jam_hides_other_model.rs): a rod between two walls.
    jam = BAR.parent / "rod-between-walls.toml"
    r = inertance.solve(jam, exact=True)
    assert r.newton is None
    assert r.failures["newton"]["status"] == "jammed"
    assert r.poisson.impulses == [3, 1]
    assert inertance.solve(inertance.Scene.load(BAR)).failures == {}
