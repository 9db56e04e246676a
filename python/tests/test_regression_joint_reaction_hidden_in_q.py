"""Regression: a joint's reaction was reported only as q, multipliers of constraint screws the
solver derives (tests/regression_joint_reaction_hidden_in_q.rs). Each model's result now has
``constraint_wrench`` (force and moment about C) and ``joint_reactions`` (per joint the force
and the moment about its anchor): exact as ``Fraction``, f64 as numpy arrays, as the CLI's JSON.

The rod: m = 3 kg, l = 2 m, J_C = 1 kg m² about z, pinned at O = (0, -1, 0), turning about O at
1 rad/s and struck at its free end with k = 1/2. By hand (the Rust test's doc): P = (1 + k) w J_O
/ l = 3 N s with J_O = J_C + m l²/4 = 4, the hinge force F_x = P (1 - m l²/(2 J_O)) = -3/2 N s,
no moment about O, and M_C = (0, 0, l F_x / 2) = (0, 0, -3/2) N m s."""

from fractions import Fraction

import numpy as np

import inertance
from conftest import cli_json

ROD = """
name = "rod pinned at one end, struck at the other"
[body]
mass = 3
inertia = [1, "1/100", 1]
velocity = [1, 0, 0]
angular_velocity = [0, 0, -1]
[[contact]]
point = [0, 1, 0]
normal = [1, 0, 0]
k = 0.5
[[constraints.joint]]
kind = "revolute"
point = [0, -1, 0]
axis = [0, 0, 1]
"""


def test_the_hinge_reaction_is_a_force_and_a_moment_at_the_hinge(tmp_path):
    scene = inertance.Scene.from_toml(ROD)
    exact = inertance.solve(scene, exact=True)
    for m in (exact.newton, exact.poisson):
        (hinge,) = m.joint_reactions
        assert (hinge["kind"], hinge["about"]) == ("revolute", "point")
        assert hinge["point"] == [0, -1, 0]
        assert hinge["force"] == [Fraction(-3, 2), 0, 0]
        assert hinge["moment"] == [0, 0, 0]
        assert m.constraint_wrench["moment"] == [0, 0, Fraction(-3, 2)]
    f = inertance.solve(scene)
    np.testing.assert_allclose(f.newton.joint_reactions[0]["force"], [-1.5, 0, 0], rtol=1e-15)
    assert isinstance(f.newton.constraint_wrench["force"], np.ndarray)
    path = tmp_path / "rod.toml"
    path.write_text(ROD)
    assert exact.to_json() == cli_json("solve", path, "--exact")


def test_a_free_body_has_no_reaction(bar):
    r = inertance.solve(bar)
    assert r.newton.constraint_wrench is None and r.newton.joint_reactions is None
