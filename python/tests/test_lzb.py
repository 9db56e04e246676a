"""solve(law="lzb"): the LZB multiple-impact law's outputs. `to_json()` is the library's
`LzbReport::to_json`, which `inertance solve --json` prints (tests/lzb_cli.rs checks it against
the table); here the attributes are checked against it and against the physics."""

import numpy as np
import pytest

import inertance
from conftest import ROOT

CRADLE = ROOT / "examples" / "cradle-3-lzb.toml"
BAR = ROOT / "examples" / "bar-two-supports-lzb.toml"
PITCHING = ROOT / "examples" / "pitching-bar.toml"


def test_the_cradle_under_lzb_is_its_json_report():
    r = inertance.solve(str(CRADLE))
    assert isinstance(r, inertance.LzbSolution) and r.law == "lzb"
    j = r.to_json()
    assert j["law"] == "lzb" and [c["contact"] for c in j["contacts"]] == [1, 2]
    np.testing.assert_array_equal(r.impulses, [c["impulse"] for c in j["contacts"]])
    np.testing.assert_array_equal(r.velocities_after,
                                  [c["velocity_after"] for c in j["contacts"]])
    np.testing.assert_array_equal(r.max_energies,
                                  [c["max_potential_energy"] for c in j["contacts"]])
    np.testing.assert_allclose(r.dissipation, r.work_compression - r.work_expansion)
    assert r.bodies == ["striker", "ball 2", "ball 3"]
    assert r.velocities.shape == (3, 3)
    # The striker nearly stops, the last ball leaves with nearly all the velocity.
    assert abs(r.velocity("striker")[0]) < 0.1
    assert r.velocity(2)[0] > 0.99
    assert r.ending_order == [0, 1]
    assert r.kinetic_energy_loss == pytest.approx(0, abs=1e-8)
    assert abs(r.energy_residual) < 1e-8 and r.error_estimate < 1e-6
    assert len(r.events) == r.stats["events"]
    assert {e["kind"] for e in r.events} <= {
        "compression ends", "expansion ends", "compresses again", "engages", "becomes primary"}


def test_the_history_starts_at_rest_and_ends_at_the_impulses():
    r = inertance.solve(str(CRADLE))
    h = r.history
    n = len(h["tau"])
    assert h["impulses"].shape == (n, 2) and h["velocities"].shape == (n, 2)
    assert h["energies"].shape == (n, 2) and h["primary"].shape == (n,)
    np.testing.assert_array_equal(h["impulses"][0], [0, 0])
    np.testing.assert_array_equal(h["velocities"][0], r.velocities_before)
    np.testing.assert_array_equal(h["impulses"][-1], r.impulses)
    np.testing.assert_array_equal(h["velocities"][-1], r.velocities_after)
    assert np.all(np.diff(h["tau"]) >= 0) and np.all(h["energies"] >= 0)


def test_law_lzb_on_another_scene_and_the_symmetric_bar():
    r = inertance.solve(str(BAR))
    # Equal stiffnesses: the simultaneous Newton impulses (1 + e) v0 / (g11 + g12) = 0.75.
    np.testing.assert_allclose(r.impulses, [0.75, 0.75], atol=1e-8)
    newton = inertance.solve(str(BAR), law="simultaneous", model="newton").newton
    np.testing.assert_allclose(r.impulses, newton.impulses, atol=1e-8)
    np.testing.assert_allclose(r.velocity("body"), newton.velocity, atol=1e-8)
    p = inertance.solve(str(PITCHING), law="lzb", tolerance=1e-8)
    assert p.tolerance == 1e-8 and p.stiffness.tolist() == [1, 1]


def test_friction_under_lzb():
    # The rough bar: Coulomb friction along the LZB path; the energy balance closes with the
    # friction work, and a sliding contact's tangential impulse is within its cone.
    r = inertance.solve(str(ROOT / "examples" / "rough-bar.toml"), law="lzb")
    assert all(len(t) == 1 for t in r.tangential_impulses)
    assert all(w >= 0 for w in r.friction_dissipation)
    assert r.friction_dissipation.sum() > 0
    for t, p in zip(r.tangential_impulses, r.impulses):
        assert abs(t[0]) <= 1.0 * p * (1 + 1e-9)  # mu = 1 in the scene
    total = r.dissipation.sum() + r.friction_dissipation.sum()
    assert abs(r.kinetic_energy_loss - total) <= 1e-6 * max(1.0, abs(r.kinetic_energy_loss))
    assert abs(r.energy_residual) <= 1e-6 * max(1.0, abs(r.kinetic_energy_loss))


def test_what_lzb_does_not_take_is_refused():
    with pytest.raises(ValueError, match="exact"):
        inertance.solve(str(CRADLE), exact=True)
    with pytest.raises(ValueError, match="model"):
        inertance.solve(str(CRADLE), model="newton")
    with pytest.raises(inertance.SceneError) as e:
        s = inertance.Scene.load(str(CRADLE)).with_values({"contact[0].stiffness": -2})
        inertance.solve(s)
    assert e.value.key == "contact[0].stiffness"


def test_a_sweep_of_the_stiffness_under_lzb():
    s = inertance.sweep(str(BAR), {"contact[1].stiffness": (1, 4, 4)})
    cols = s if isinstance(s, dict) else {k: s[k].to_numpy() for k in s.columns}
    assert list(cols["status"]) == ["ok"] * 4
    np.testing.assert_allclose(cols["P1"][0], 0.75, atol=1e-8)
    assert all(cols["P2"][1:] < cols["P1"][1:])
    assert list(cols["order"])[0] in ("1 2", "2 1")
