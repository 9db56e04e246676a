"""Scenes from files, TOML strings and Python values, numbers kept exact."""

from fractions import Fraction

import numpy as np
import pytest

import inertance
from conftest import BAR

BAR_DICT = {
    "name": "planar bar on two supports",
    "body": {"mass": 1, "inertia": np.array([12, 1.6, 12]), "velocity": [3, 2, 0],
             "angular_velocity": (0, 0, Fraction(2, 5))},
    "contact": [
        {"point": [0, -2, 0], "normal": [1, 0, 0], "k": 0.3},
        {"point": [0, 4, 0], "normal": [1, 0, 0], "tangent": [0, 1, 0], "k": "1/5"},
    ],
    "solve": {"models": ["newton", "poisson"]},
}


def test_the_same_scene_three_ways():
    from_file = inertance.solve(inertance.Scene.load(BAR), exact=True)
    from_text = inertance.solve(BAR.read_text(), exact=True)
    from_dict = inertance.solve(BAR_DICT, exact=True)
    for r in (from_text, from_dict):
        assert r.newton.impulses == from_file.newton.impulses
        assert r.poisson.kinetic_energy_loss == from_file.poisson.kinetic_energy_loss


def test_scene_accessors(bar):
    assert bar.name == "planar bar on two supports"
    assert bar.contacts == 2 and bar.file.endswith("planar-bar.toml")
    assert ("contact[1].k_newton", "0.2") in bar.numbers()
    assert "[body]" in bar.toml and "Scene(" in repr(bar)
    assert inertance.solve(str(BAR)).newton is not None


def test_with_values_sets_numbers_exactly(bar):
    s = bar.with_values({"contact[1].k": Fraction(3, 10)})
    r = inertance.solve(s, exact=True)
    assert r.newton.impulses == r.poisson.impulses  # equal coefficients: Newton = Poisson
    s = bar.with_values({"contact[0].point[1]": "-2", "body.mass": 1.0})
    assert inertance.solve(s).newton.impulses[0] == pytest.approx(3.655556, abs=1e-6)


def test_a_3x3_inertia_tensor_from_numpy():
    # The principal moments as a diagonal tensor: the same body, the same impulses.
    d = dict(BAR_DICT, body=dict(BAR_DICT["body"], inertia=np.diag([12, 1.6, 12])))
    same = inertance.solve(d, exact=True)
    assert same.newton.impulses == inertance.solve(BAR_DICT, exact=True).newton.impulses
    # An entry off the diagonal is one number under the keys numbers() lists, set with its
    # mirror: J_yz = 1/2 couples the bar's spin to its axis, and changes the impulses.
    s = inertance.Scene.from_dict(d).with_values({"body.inertia[1][2]": Fraction(1, 2)})
    assert ("body.inertia[1][2]", "1/2") in s.numbers()
    assert inertance.solve(s, exact=True).newton.impulses != same.newton.impulses


def test_an_irrational_number_runs_in_f64_and_exactly():
    d = dict(BAR_DICT, contact=[dict(BAR_DICT["contact"][0], k="sqrt(2)/2"),
                                BAR_DICT["contact"][1]])
    r = inertance.solve(d)
    assert np.all(np.isfinite(r.newton.impulses))


@pytest.mark.parametrize("mutate, key, value", [
    (lambda d: d["body"].update(mass=-1), "body.mass", "-1"),
    (lambda d: d["contact"][1].update(k=1.5), "contact[1].k", "1.5"),
    (lambda d: d["contact"][0].update(normal=[0, 0, 0]), "contact[0].normal", None),
    (lambda d: d["body"].update(mas=1), "body.mas", None),
    (lambda d: d["body"].pop("inertia"), "body.inertia", None),
])
def test_bad_values_raise_scene_error_with_key_and_value(mutate, key, value):
    d = {k: (dict(v) if isinstance(v, dict) else [dict(c) for c in v] if k == "contact" else v)
         for k, v in BAR_DICT.items()}
    mutate(d)
    with pytest.raises(inertance.SceneError) as e:
        inertance.solve(inertance.Scene.from_dict(d))
    assert e.value.key == key
    if value is not None:
        assert e.value.value == value
    assert e.value.file == "<dict>" and e.value.message
    assert isinstance(e.value, inertance.InertanceError)


def test_bad_toml_and_missing_file():
    with pytest.raises(inertance.SceneError) as e:
        inertance.Scene.from_toml("[body\nmass = 1", file="bad.toml")
    assert e.value.file == "bad.toml"
    with pytest.raises(inertance.SceneError) as e:
        inertance.Scene.load("/nonexistent/scene.toml")
    assert "cannot read" in e.value.message


def test_irrational_input_in_exact_mode_names_key_and_value():
    d = dict(BAR_DICT, body=dict(BAR_DICT["body"], mass="sqrt(2)"))
    r = inertance.solve(d)
    assert r.newton is not None
    # Exact mode runs the irrational scene in exact radicals.
    e = inertance.solve(d, exact=True)
    assert isinstance(e.newton.lost_velocity_energy, (str, Fraction))


def test_bad_arguments():
    with pytest.raises(ValueError):
        inertance.solve(BAR_DICT, model="newtown")
    with pytest.raises(ValueError):
        inertance.solve(BAR_DICT, law="sometimes")
    with pytest.raises(TypeError):
        inertance.solve(42)
    with pytest.raises(inertance.SceneError) as e:
        inertance.Scene.load(BAR).with_values({"contact[5].k": 0.1})
    assert e.value.key == "contact[5].k"
    with pytest.raises(inertance.SceneError) as e:
        inertance.Scene.from_dict(dict(BAR_DICT, body=dict(BAR_DICT["body"], mass=True)))
    assert e.value.key == "body.mass" and e.value.value == "true"


def test_singular_and_jammed_are_solve_errors():
    coincident = BAR.read_text().replace("point = [0, 4, 0]", "point = [0, -2, 0]")
    with pytest.raises(inertance.SolveError) as e:
        inertance.solve(coincident)
    assert e.value.kind == "singular"
    jammed = """
[body]
mass = 1
inertia = [1, 1, 1]
velocity = [1, 0, 0]
angular_velocity = [0, 0, 0]
[[contact]]
point = [1, 0, 0]
normal = [1, 0, 0]
k = 1
[[contact]]
point = [-1, 0, 0]
normal = [-1, 0, 0]
k = 1
"""
    with pytest.raises(inertance.SolveError) as e:
        inertance.solve(jammed, law="unilateral", model="newton")
    assert e.value.kind == "jammed"


def test_a_scene_in_the_world_frame_with_a_parameter():
    tilted = inertance.Scene.load(BAR.parent / "tilted-box.toml")
    # At 45° the corners take 51/61 each (derivations/modelled-tilted-box.md).
    r = inertance.solve(tilted.with_values({"params.theta": "45 deg"}), exact=True)
    assert r.newton.impulses == [Fraction(51, 61), Fraction(51, 61)]
    assert r.newton.kinetic_energy_loss == Fraction(51, 122)
    # The same box from a dict: shape, pose and an obstacle, no hand rotation.
    d = {
        "params": {"theta": "45 deg"},
        "body": {"shape": {"box": [0.4, 0.2, 0.1]}, "mass": 2,
                 "pose": {"axis": [0, 1, 0], "angle": "theta"},
                 "velocity": [0, 0, -1], "angular_velocity": [0, 0, 0]},
        "obstacle": [{"name": "floor", "normal": [0, 0, 1]}],
        "contact": [{"obstacle": "floor", "corner": [1, s, -1], "k": 0.5} for s in (-1, 1)],
    }
    assert inertance.solve(d, exact=True).newton.impulses == r.newton.impulses
