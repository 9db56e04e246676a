"""`inertance.simulate`: the Python face of `inertance simulate` — the same log as the command's
`--json`, the samples as numpy arrays, against closed forms (the bouncing ball, Housner's block)
and against the command itself."""

import json
import math
import pathlib
import subprocess

import numpy as np
import pytest

import inertance
from inertance.engines import sequences as seq

ROOT = pathlib.Path(__file__).resolve().parents[2]
SIM = ROOT / "examples" / "simulate"
seq.REPO = ROOT


def test_the_bouncing_ball_meets_its_closed_forms_and_its_samples_the_parabola():
    """g = 10, k = 1/2, dropped from 5 m: impacts at t = 1, 2, 2.5 s at 10, 5, 2.5 m/s, the
    accumulation at t∞ = 3 s; the samples before the first impact on z = 5.1 − 5t² (the
    command's tolerance 1e-10 on the motion's scale, 5 m: bound 1e-9)."""
    sim = inertance.simulate(SIM / "bouncing-ball.toml")
    assert [round(i["t"], 9) for i in sim.impacts] == [1.0, 2.0, 2.5]
    assert [c["contacts"][0]["before"] for c in sim.impacts] == pytest.approx([-10, -5, -2.5], abs=1e-9)
    assert sim.zeno["t_inf"] == pytest.approx(3.0, abs=1e-9)
    assert sim.end == "rest" and sim.error is None
    s = sim.samples
    assert s["x"].shape == (len(s["t"]), 3) and s["q"].shape == (len(s["t"]), 4)
    early = s["t"] < 1.0 - 1e-9
    assert early.sum() == 100
    assert np.abs(s["x"][early, 2] - (5.1 - 5 * s["t"][early] ** 2)).max() <= 1e-9
    # energy: kinetic + potential = 51 J until the first impact
    assert np.abs(s["kinetic"][early] + s["potential"][early] - 51.0).max() <= 1e-8


def test_the_log_is_the_commands_json():
    """The same run as `inertance simulate --json`: the log compares equal (every number the
    same double: the same code, the same input)."""
    out = subprocess.run([*seq.cli(), "simulate", str(SIM / "rocking-block.toml"), "--json"], cwd=ROOT,
                         check=True, capture_output=True, text=True)
    assert inertance.simulate(SIM / "rocking-block.toml").log == json.loads(out.stdout)


def test_the_law_is_replaced_and_housners_ratio_holds():
    """Under the unilateral law (the scene's) each landing keeps ω⁺/ω⁻ = 23/50 (K⁺/K⁻ its
    square), to the stated 1e-7; under the simultaneous law the first landing is another one."""
    sim = inertance.simulate(SIM / "rocking-block.toml", law="unilateral")
    for imp in sim.impacts[:4]:
        assert math.sqrt(imp["kinetic_after"] / imp["kinetic_before"]) == pytest.approx(23 / 50, abs=1e-7)
    other = inertance.simulate(SIM / "rocking-block.toml", law="simultaneous")
    assert other.log["law"].startswith("simultaneous")
    r = other.impacts[0]["kinetic_after"] / other.impacts[0]["kinetic_before"]
    assert abs(math.sqrt(r) - 23 / 50) > 1e-3


def test_text_a_system_and_errors():
    """TOML text runs as a file would; a system of spheres gives per-body arrays (the cradle of
    three equal balls at 1 m/s under the simultaneous law, k = 1: both contacts in one impact,
    the closed form (−1/3, 2/3, 2/3) m/s, to 1e-12); a bad key raises SceneError naming it; an
    unknown law raises ValueError."""
    text = (SIM / "cradle-3.toml").read_text()
    sim = inertance.simulate(text)
    assert sim.bodies == ["striker", "ball 2", "ball 3"]
    assert sim.samples["x"].shape[1:] == (3, 3) and sim.samples["v"].shape == sim.samples["x"].shape
    assert sim.samples["v"][-1][:, 0] == pytest.approx([-1 / 3, 2 / 3, 2 / 3], abs=1e-12)
    assert sim.samples["v"][0][:, 0] == pytest.approx([1, 0, 0], abs=0)
    with pytest.raises(inertance.SceneError) as e:
        inertance.simulate((SIM / "bouncing-ball.toml").read_text().replace("duration = 4", "duration = -4"))
    assert e.value.key == "simulate.duration"
    with pytest.raises(ValueError, match="unknown law"):
        inertance.simulate(SIM / "bouncing-ball.toml", law="newtonian")
    with pytest.raises(inertance.SceneError):
        inertance.simulate(ROOT / "no-such-scene.toml")


def test_a_system_accumulates_its_bounces():
    """examples/simulate/box-dropped-on-box.toml: a box dropped flat from 0.05 m onto a box on
    the floor (k = 1/2, g = 10) bounces as off a floor, and after three impacts the rest are
    summed in closed form: t∞ = 0.25 + 2·(1/8)/(10·(1 − 1/2)) = 0.3 s (to 1e-10: the events are
    located to 1e-11 of the length scale), where it rests at z = 0.25 m."""
    sim = inertance.simulate(SIM / "box-dropped-on-box.toml")
    assert sim.zeno["after"] == 3
    assert sim.zeno["t_inf"] == pytest.approx(0.3, abs=1e-10)
    assert sim.zeno["ratio"] == pytest.approx(0.5, abs=1e-9)
    assert sim.end == "rest"
    assert sim.samples["x"][-1][0] == pytest.approx([0, 0, 0.25], abs=1e-10)


def test_a_ball_spins_up_to_rolling_on_a_box_on_ice():
    """examples/simulate/ball-on-box.toml: a ball (1 kg, r = 0.1 m) sliding at 1 m/s on a box
    (5 kg) on a frictionless floor, mu = 0.2 between them. Newton's laws: the ball's v falls at
    mu g, its spin rises at (5/2) mu g / r, the box's V rises at mu g m/M, until the slip
    v - omega r - V closes at t* = 1 / (mu g (7/2 + 1/5)); after it v = 27/37 m/s, omega r =
    25/37 m/s and V = 2/37 m/s (the momentum m v0 kept). The sphere's spin, integrated because a
    rough contact touches it, is in `omega` like a box's."""
    sim = inertance.simulate(SIM / "ball-on-box.toml")
    assert sim.bodies == ["ball", "box"]
    assert sim.end == "duration"
    v, w = sim.samples["v"][-1], sim.samples["omega"][-1]
    assert v[0][0] == pytest.approx(27 / 37, abs=1e-12)
    assert w[0][1] * 0.1 == pytest.approx(25 / 37, abs=1e-12)
    assert v[1][0] == pytest.approx(2 / 37, abs=1e-12)
    momentum = sim.samples["v"][:, 0, 0] + 5 * sim.samples["v"][:, 1, 0]
    assert np.abs(momentum - 1).max() <= 1e-12
    assert any(e["what"] == "ball on box face +z sticks" for e in sim.log["events"])


def test_a_system_of_boxes_gives_attitudes_and_spins():
    """A box dropped on a box on the floor (examples/simulate/box-on-box.toml): per-body
    attitudes `q` (N, B, 4) and spins `omega` (N, B, 3) beside `x` and `v`; every quaternion a
    unit one; the top box starts turning at 2 rad/s about y and ends at rest flat on the base
    (its centre at z = 0.25 m, the base's unmoved at 0.1 m), as the log's state says."""
    sim = inertance.simulate(SIM / "box-on-box.toml")
    assert sim.bodies == ["top", "base"]
    n = len(sim.samples["t"])
    assert sim.samples["q"].shape == (n, 2, 4) and sim.samples["omega"].shape == (n, 2, 3)
    assert np.allclose(np.linalg.norm(sim.samples["q"], axis=2), 1.0, atol=1e-12)
    assert sim.samples["omega"][0][0] == pytest.approx([0, 2, 0], abs=0)
    assert sim.end == "rest"
    assert sim.samples["x"][-1][:, 2] == pytest.approx([0.25, 0.1], abs=1e-9)
    assert np.abs(sim.samples["x"][:, 1, :] - [0, 0, 0.1]).max() <= 1e-9
    log_q = sim.log["state"]["q"]
    assert np.allclose(log_q, sim.samples["q"][-1], atol=1e-12)
