"""The engine conformance suite (python/inertance/engines, issue 26) without any engine: the
catalogue loads and reads as inertance reads it, every exact answer is computed and meets the
closed forms where they exist, the grades of two reference adapters are what their definitions
give, bad input is refused by name, and importing inertance imports no engine. The tests that
need an engine are at the end, skipped unless it is installed (python/engines.sh runs them)."""

import json
import math
import subprocess
import sys
from fractions import Fraction

import numpy as np
import pytest

import inertance
from inertance import engines
from inertance.engines import catalogue, grading, reference, runner, scene as escene
from inertance.engines._geometry import product_restitutions
from conftest import ROOT

CAT = ROOT / "benches" / "engines" / "scenes"
FILES = sorted(CAT.glob("*.toml"))


@pytest.fixture(scope="module")
def scenes():
    return {s.name: s for s in catalogue.scenes(CAT)}


def test_the_catalogue_has_the_scenes_of_the_brief():
    names = {p.stem for p in FILES}
    for want in ["bar-pitching-e02", "ball-floor-e0", "ball-floor-e05", "ball-floor-e1", "box-flat-e0", "box-flat-e05",
                 "box-flat-e1", "box-edge-45", "box-corner", "bar-pitching", "ball-corner",
                 "ball-corner-rough", "rod-rough-floor", "rod-slip-reverses", "rod-slip-sticks", "cradle-3",
                 "box-on-box", "rocking-block"]:
        assert want in names
    assert len([n for n in names if n.startswith("box-edge-")]) >= 3


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.stem)
def test_every_scene_loads_with_its_exact_answer(path):
    s = catalogue.load(path)
    assert len(s.exact) == len(s.engine.bodies) == len(s.before)
    assert s.engine.contacts
    for t in s.exact:
        assert np.all(np.isfinite(t.velocity)) and np.all(np.isfinite(t.angular_velocity))
    # every catalogue scene has an impact: the exact answer differs from the twist before
    assert grading.metric_norm(s, grading._diff(s.exact, s.before)) > 0
    # frictionless scenes are graded under the unilateral law, frictional ones under friction
    assert s.law == ("unilateral" if not s.engine.frictional else s.law)
    assert s.law.startswith("friction") == s.engine.frictional
    # no impact gains energy with every e ≤ 1 (the exact answer's own check; 1e-12: f64 rounding)
    assert s.kinetic_energy_after <= s.kinetic_energy_before * (1 + 1e-12)


def _one_body_numbers(path):
    sc = inertance.Scene.load(str(path))
    return {k: escene.evaluate(v) for k, v in sc.numbers()}


@pytest.mark.parametrize("path", [p for p in FILES if not inertance.Scene.load(str(p)).is_system],
                         ids=lambda p: p.stem)
def test_the_engine_reading_is_inertances_reading(path):
    """The neutral scene's world inertia tensor, contact points (from the centre of mass) and
    normals equal what inertance itself solves (Scene.numbers(), its expressions evaluated in
    f64). Tolerance 1e-12 of the scene's scale: both sides evaluate the same expressions in f64,
    a few roundings apart; a wrong pose, corner or sign is off by far more."""
    num = _one_body_numbers(path)
    s = escene.load(path)
    b = s.bodies[0]
    jw = b.inertia_world
    scale_j = np.max(np.abs(jw))
    for k in range(3):
        assert jw[k, k] == pytest.approx(num[f"body.inertia[{k}]"], abs=1e-12 * scale_j)
    for (i, j) in [(0, 1), (0, 2), (1, 2)]:
        key = f"body.inertia[{i}][{j}]"
        assert jw[i, j] == pytest.approx(num.get(key, 0.0), abs=1e-12 * scale_j), key
    assert b.mass == pytest.approx(num["body.mass"], rel=1e-15)
    size = max(b.size)
    for i, c in enumerate(s.contacts):
        r = np.array([num[f"contact[{i}].point[{k}]"] for k in range(3)])
        n = np.array([num[f"contact[{i}].normal[{k}]"] for k in range(3)])
        np.testing.assert_allclose(c.point - b.position, r, atol=1e-12 * size, rtol=0)
        np.testing.assert_allclose(c.normal, n / np.linalg.norm(n), atol=1e-12, rtol=0)
        assert c.restitution == num[f"contact[{i}].k_newton"]
        assert c.friction == num.get(f"contact[{i}].mu", 0.0)


@pytest.mark.parametrize("path", [p for p in FILES if inertance.Scene.load(str(p)).is_system],
                         ids=lambda p: p.stem)
def test_a_systems_reading_has_inertances_momentum_and_normals(path):
    """For a system, inertance's momentum before impact (linear, and angular about the origin)
    equals the neutral scene's Σ m v and Σ (x × m v + J ω): masses, positions, inertias and
    twists read alike; and the contact normals agree. 1e-12: f64 rounding of a few terms."""
    sol = inertance.solve(str(path))
    s = escene.load(path)
    lin = sum(b.mass * b.velocity for b in s.bodies)
    ang = sum(np.cross(b.position, b.mass * b.velocity) + b.inertia_world @ b.angular_velocity for b in s.bodies)
    np.testing.assert_allclose(lin, sol.momentum_before["linear"], atol=1e-12)
    np.testing.assert_allclose(ang, sol.momentum_before["angular"], atol=1e-12)
    for c, rc in zip(s.contacts, sol.contacts):
        n = catalogue._vector(rc["normal"])
        np.testing.assert_allclose(c.normal, n / np.linalg.norm(n), atol=1e-12)


def _float(x):
    if isinstance(x, Fraction):
        return float(x)
    return escene.evaluate(x)  # a radical string such as "1/88994*(22567 - 2448*sqrt(3))"


@pytest.mark.parametrize("path", [p for p in FILES if not escene.load(p).frictional], ids=lambda p: p.stem)
def test_the_f64_answers_are_the_exact_ones(path):
    """The graded answer is inertance's f64 solve; where the scene has an exact form (rational or
    radical poses) the exact solve agrees to 1e-12 of the velocity scale (the accuracy contract
    bounds these small, well-conditioned scenes far below that)."""
    sc = inertance.Scene.load(str(path))
    try:
        ex = inertance.solve(sc, model="newton", exact=True).newton
    except inertance.SceneError as e:
        pytest.skip(f"no exact form: {e}")
    law, f64 = catalogue.solve_exact(path)
    if sc.is_system:
        pairs = [(ex.velocity(i), ex.angular_velocity(i)) for i in range(len(f64))]
    else:
        pairs = [(ex.velocity, ex.angular_velocity)]
    for t, (v, w) in zip(f64, pairs):
        np.testing.assert_allclose(t.velocity, [_float(x) for x in v], atol=1e-12, rtol=0)
        np.testing.assert_allclose(t.angular_velocity, [_float(x) for x in w], atol=1e-11, rtol=0)


def test_closed_forms_of_the_oracle(scenes):
    """Where the answer has a closed form: a ball rebounds at e·v; a flat box at e·v without
    turning; the cradle at (1 − 2k)/3 v, (1 + k)/3 v, (1 + k)/3 v (guide/python.md); the
    frictionless ball in the corner bounces off each wall independently; the bar's second support
    separates under the unilateral law. Tolerance 1e-12 m/s: f64 rounding."""
    for e, name in [(0, "e0"), (0.5, "e05"), (1, "e1")]:
        for kind in ("ball-floor", "box-flat"):
            t = scenes[f"{kind}-{name}"].exact[0]
            np.testing.assert_allclose(t.velocity, [0, 0, e], atol=1e-12)
            np.testing.assert_allclose(t.angular_velocity, [0, 0, 0], atol=1e-12)
    c = scenes["cradle-3"].exact
    np.testing.assert_allclose([t.velocity[0] for t in c], [-1 / 3, 2 / 3, 2 / 3], atol=1e-12)
    np.testing.assert_allclose(scenes["ball-corner"].exact[0].velocity, [-1.2, 1, 1.8], atol=1e-12)
    bar = scenes["bar-pitching"]
    assert bar.separating == (True, True)
    sol = inertance.solve(str(bar.path), model="newton")
    assert sol.newton.impulses[1] == 0  # the unilateral law leaves the second support alone
    tensile = inertance.solve(str(bar.path), model="newton", law="simultaneous").newton
    assert tensile.impulses[1] < 0 and tensile.admissible is False


def _planar_rod(s):
    """The closed form of a rod landing on the edge of its end in its plane of symmetry (x–z):
    both corners carry equal impulses, so the edge is one contact at their midpoint r with the
    inertance matrix G of the directions t = x, n = z. Coulomb's law with Newton's restitution in
    impulse space is then piecewise linear in the normal impulse p: sliding (slip sign σ), the
    slip u and the normal velocity w change at du/dp = g_tn − σμ g_tt, dw/dp = g_nn − σμ g_nt
    until u = 0; then the end sticks (dτ/dp = −g_tn/g_tt, inside the cone when |g_tn/g_tt| ≤ μ)
    or slides back (σ → −σ); the impact ends when w = −e w⁰. Returns (sticks, μ* = |g_tn/g_tt|,
    the slip at the end, v, ω)."""
    b, (c1, c2) = s.engine.bodies[0], s.engine.contacts
    e, mu = c1.restitution, c1.friction
    r = (c1.point + c2.point) / 2 - b.position
    jinv = np.linalg.inv(b.inertia_world)
    x, z = np.array([1.0, 0, 0]), np.array([0, 0, 1.0])

    def dv(f):
        return f / b.mass + np.cross(jinv @ np.cross(r, f), r)

    g = np.array([[dv(x) @ x, dv(z) @ x], [dv(x) @ z, dv(z) @ z]])
    vp = b.velocity + np.cross(b.angular_velocity, r)
    u, w = vp @ x, vp @ z
    target, sigma = -e * w, np.sign(u)

    def rates(tau_rate):
        return g[0, 0] * tau_rate + g[0, 1], g[1, 0] * tau_rate + g[1, 1]

    du, dw = rates(-sigma * mu)
    p1 = -u / du
    assert p1 > 0 and w + dw * p1 < target  # the slip stops during the impact
    tau, p, w = -sigma * mu * p1, p1, w + dw * p1
    sticks = abs(g[0, 1] / g[0, 0]) <= mu
    tr = -g[0, 1] / g[0, 0] if sticks else sigma * mu
    du, dw = rates(tr)
    p2 = (target - w) / dw
    f = (tau + tr * p2) * x + (p + p2) * z
    return sticks, abs(g[0, 1] / g[0, 0]), du * p2, b.velocity + f / b.mass, b.angular_velocity + jinv @ np.cross(r, f)


def test_the_rods_slip_stops_then_reverses_or_sticks_as_the_closed_form_says(scenes):
    """rod-slip-reverses (μ = 0.6) and rod-slip-sticks (μ = 0.8) straddle the threshold μ* =
    |g_tn/g_tt| = 0.719 of their rod: the forward slip (0.04 m/s) stops, then reverses to
    −0.055 m/s, or sticks (0). inertance's integration (adaptive RK5(4), events at zero slip)
    against the closed form: tolerance 10⁻⁹ m/s on v and 5·10⁻⁹ rad/s on ω — inertance's own
    error estimate of the impulses (≤ 4.4·10⁻¹⁰ N·s, printed by ``inertance solve``) times 1/m
    = 1/kg and times the lever arm over the inertia, r/J ≤ 10/(kg·m) (measured: 8·10⁻¹²)."""
    rev, stick = scenes["rod-slip-reverses"], scenes["rod-slip-sticks"]
    for s, want_stick in ((rev, False), (stick, True)):
        sticks, threshold, slip, v, w = _planar_rod(s)
        assert sticks == want_stick and threshold == pytest.approx(0.719, abs=1e-3)
        np.testing.assert_allclose(s.exact[0].velocity, v, atol=1e-9, rtol=0)
        np.testing.assert_allclose(s.exact[0].angular_velocity, w, atol=5e-9, rtol=0)
        r = s.engine.contacts[0].point - s.engine.bodies[0].position
        u = (s.exact[0].velocity + np.cross(s.exact[0].angular_velocity, r))[0]
        assert u == pytest.approx(slip, abs=1e-9)
        assert (u < -0.05) if not want_stick else abs(u) < 1e-9


def test_the_exact_adapter_grades_zero(scenes):
    rep = runner.run([reference.ExactAdapter()], list(scenes.values()))
    assert not rep["failures"]
    assert len(rep["grades"]) == len(scenes)
    for g in rep["grades"]:
        assert g["error"] == 0.0  # the same numbers: zero, not small
        assert g["energy_ratio"] == g["exact_energy_ratio"]
        # e = 1 keeps the energy: its f64 answer may sit a rounding above (measured 4.4e-16)
        assert g["energy_gain"] <= 1e-15
        assert g["separation_ok"]


def test_the_no_impact_adapter_grades_one(scenes):
    """ξ = ξ⁰ gives ‖ξ⁰ − ξ*‖/‖ξ* − ξ⁰‖ = 1 (to rounding: 1e-15), its energy ratio is 1, and
    every contact that should separate does not."""
    rep = runner.run([reference.NoImpactAdapter()], list(scenes.values()))
    for g in rep["grades"]:
        assert g["error"] == pytest.approx(1, abs=1e-15)
        assert g["energy_ratio"] == pytest.approx(1, abs=1e-15)
        assert g["separation_ok"] == (not any(g["should_separate"]))
        assert not any(g["separates"])


def test_the_error_is_the_kinetic_energy_metric(scenes):
    """A known error, by hand: the ball (m = 1 kg, e = 0.5) leaving at 0.45 m/s instead of 0.5
    with a spin of 1 rad/s about x: ‖δ‖_M² = m·0.05² + J·1² with J = 2/5·m·r² = 0.004 kg m²,
    over the impact ‖Δξ*‖_M = m·1.5."""
    s = scenes["ball-floor-e05"]
    g = grading.grade(s, "hand", [catalogue.Twist.of([0, 0, 0.45], [1, 0, 0])])
    assert g.error == pytest.approx(math.sqrt(0.05 ** 2 + 0.004) / 1.5, rel=1e-14)
    assert g.energy_ratio == pytest.approx((0.45 ** 2 + 0.004) / 1, rel=1e-14)
    # a gain is reported where none can be
    up = grading.grade(s, "hand", [catalogue.Twist.of([0, 0, 1.2], [0, 0, 0])])
    assert up.energy_gain == pytest.approx(0.44, rel=1e-14) and up.separation_ok


def test_the_report_in_markdown_and_json(scenes, tmp_path):
    rep = runner.run([reference.ExactAdapter(), reference.NoImpactAdapter()], list(scenes.values()))
    md, js = runner.write(rep, tmp_path)
    data = json.loads(js.read_text())
    assert {g["scene"] for g in data["grades"]} == set(scenes)
    assert [e["name"] for e in data["engines"]] == ["exact", "no-impact"]
    text = md.read_text()
    for name in scenes:
        assert f"| {name} |" in text
    assert "!sep" in text  # the no-impact adapter misses every separation


def test_convergence_grades_each_step(scenes):
    """runner.convergence builds the adapter at each step and grades it: the exact adapter is 0 at
    every step, the no-impact one 1 (to rounding, 1e-15)."""
    steps = [1e-3, 1e-4]
    exact = runner.convergence(lambda h: reference.ExactAdapter(), scenes["box-edge-30"], steps)
    assert [r["step"] for r in exact] == steps and all(r["error"] == 0.0 for r in exact)
    none = runner.convergence(lambda h: reference.NoImpactAdapter(), scenes["box-edge-30"], steps)
    assert all(r["error"] == pytest.approx(1, abs=1e-15) and not r["separation_ok"] for r in none)


def test_an_adapter_that_fails_is_reported_not_hidden(scenes):
    class Broken:
        name = "broken"

        def run(self, scene):
            raise RuntimeError("engine exploded")

    class Wrong:
        name = "wrong"

        def run(self, scene):
            return []  # no twist for the body

    class Refuses:
        name = "refuses"

        def run(self, scene):
            raise escene.SceneUnsupported(scene.file, "contact.mu", "no friction here")

    rep = runner.run([Refuses()], [scenes["ball-floor-e05"]])
    assert rep["not_applicable"] == [{"scene": "ball-floor-e05", "engine": "refuses", "reason": "no friction here"}]
    assert "n/a" in runner.markdown(rep)
    rep = runner.run([Broken(), Wrong()], [scenes["ball-floor-e05"]])
    assert not rep["grades"]
    msgs = [f["error"] for f in rep["failures"]]
    assert "RuntimeError: engine exploded" in msgs[0]
    assert "0 twists for 1 bodies" in msgs[1]


def test_bad_input_is_refused_by_name(tmp_path):
    rod = tmp_path / "rod.toml"
    rod.write_text('[body]\nshape = { rod = 1 }\nmass = 1\nvelocity = [0, 0, -1]\nangular_velocity = [0, 0, 0]\n'
                   '[[obstacle]]\nnormal = [0, 0, 1]\npoint = [0, 0, -0.5]\n[[contact]]\nobstacle = 0\n'
                   'body_point = [0, 0, -0.5]\nk = 1\n')
    with pytest.raises(escene.SceneUnsupported, match=r"body.shape.rod"):
        escene.load(rod)
    with pytest.raises(KeyError, match="no catalogue scene nope"):
        catalogue.scenes(CAT, ["nope"])
    with pytest.raises(KeyError, match="no adapter 'nope'"):
        engines.adapter("nope")
    with pytest.raises(ValueError, match="not part of the grammar"):
        escene.evaluate("__import__('os')")
    typo = tmp_path / "typo.toml"
    typo.write_text((CAT / "ball-floor-e05.toml").read_text().replace("mass = 1", "mas = 1"))
    with pytest.raises(inertance.SceneError, match="mas"):  # inertance's own message, first
        catalogue.load(typo)
    with pytest.raises(FileNotFoundError, match="no catalogue directory"):
        catalogue.scenes(tmp_path / "missing")


def test_expressions_read_as_inertance_reads_them():
    assert escene.evaluate("30 deg") == pytest.approx(math.pi / 6, rel=1e-15)
    assert escene.evaluate("80/3 deg") == pytest.approx(80 / 3 * math.pi / 180, rel=1e-15)
    assert escene.evaluate("30 deg / 2") == pytest.approx(math.pi / 12, rel=1e-15)
    assert escene.evaluate("2^-3") == 0.125
    assert escene.evaluate("-7/3") == pytest.approx(-7 / 3, rel=1e-15)
    assert escene.evaluate("theta*2", {"theta": 1.5}) == 3.0


def test_restitutions_as_products():
    """Bullet multiplies two objects' coefficients: the assignment gives every contact its e."""
    for name in ["box-on-box", "cradle-3", "bar-pitching", "ball-corner-rough"]:
        s = escene.load(CAT / f"{name}.toml")
        for attr in ("restitution", "friction"):
            rb, ro = product_restitutions(s, attr)
            for c in s.contacts:
                other = ro[c.obstacle] if c.obstacle is not None else rb[c.bodies[1]]
                assert rb[c.bodies[0]] * other == pytest.approx(getattr(c, attr), abs=1e-15)


def test_importing_inertance_imports_no_engine():
    code = ("import sys, inertance; import inertance.engines; "
            "bad = [m for m in ('mujoco', 'pybullet', 'rapier3d', 'pinocchio', 'pydrake') if m in sys.modules]; "
            "print(bad)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"
    out = subprocess.run([sys.executable, "-c", "import sys, inertance; print('inertance.engines' in sys.modules)"],
                         capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_the_command_line_defaults_to_the_installed_engines(tmp_path):
    """Without --engines every installed engine runs and the others are named as skipped; with
    none installed the command says how to install them and exits 2."""
    have = engines.installed()
    out = subprocess.run([sys.executable, "-m", "inertance.engines", "--catalogue", str(CAT),
                          "--scenes", "ball-floor-e05", "--out", str(tmp_path)], capture_output=True, text=True)
    missing = [n for n in engines.ENGINE_MODULES if n not in have]
    if missing:
        assert f"not installed, skipped: {', '.join(missing)}" in out.stderr
    if not have:
        assert out.returncode == 2 and "pip install ./python[engines]" in out.stderr
    else:
        assert out.returncode == 0, out.stderr
        data = json.loads((tmp_path / "report.json").read_text())
        assert [e["name"] for e in data["engines"]] == have


def test_the_readme_adapter_example_runs(monkeypatch, capsys):
    """The dozen-line adapter of benches/engines/README.md, run as written from the repository's
    root: exact on the ball (1e-12: f64 rounding), wrong on the flat box (one pass of one contact
    at a time is not the simultaneous answer: its grade is what the README says it is)."""
    text = (ROOT / "benches" / "engines" / "README.md").read_text()
    code = text.split("```python\n", 1)[1].split("```", 1)[0]
    monkeypatch.chdir(ROOT)
    ns: dict = {}
    exec(compile(code, "README.md", "exec"), ns)
    grades = {g["scene"]: g["error"] for g in ns["report"]["grades"]}
    assert grades["ball-floor-e05"] < 1e-12
    assert grades["box-flat-e05"] > 0.1 and grades["box-edge-30"] > 0.01
    assert "| ball-floor-e05 |" in capsys.readouterr().out


def test_the_command_line(tmp_path):
    out = subprocess.run([sys.executable, "-m", "inertance.engines", "--engines", "exact,no-impact",
                          "--catalogue", str(CAT), "--scenes", "ball-floor-e05,cradle-3", "--out", str(tmp_path)],
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    data = json.loads((tmp_path / "report.json").read_text())
    assert len(data["grades"]) == 4
    bad = subprocess.run([sys.executable, "-m", "inertance.engines", "--engines", "nope", "--catalogue", str(CAT)],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "no adapter 'nope'" in bad.stderr


# --- engines: skipped unless installed (python/engines.sh installs them and runs these) -------

def test_pybullet_single_contacts_are_exact(scenes):
    """One contact at e = 0, 0.5, 1 and the ball in the corner: Bullet's impulse for an isolated
    contact is Newton's law exactly, so the adapter's mass, pose, sign and restitution product
    are caught by a tolerance of 1e-9 (its f64 solver: measured below 1e-15)."""
    pytest.importorskip("pybullet")
    a = engines.adapter("pybullet")
    for name in ["ball-floor-e0", "ball-floor-e05", "ball-floor-e1", "ball-corner", "box-corner"]:
        g = grading.grade(scenes[name], a.name, a.run(scenes[name].engine))
        assert g.error < 1e-9, (name, g.error)


def test_mujoco_tuned_ball_bounces_near_the_asked_e(scenes):
    """MuJoCo has no restitution: the tuned setting maps e through solref. On the ball, the
    adapter must bounce upward at about e·v; MuJoCo's impedance makes the measured e differ from
    the asked one (benches/engines/README.md), so the bound is the one measured with margin:
    error below 0.1 of the impact at e = 0.5 and 1 (measured 0.043 and 6.7e-4), and the ball
    leaves upward — a wrong sign or mass would score near 1 or above."""
    pytest.importorskip("mujoco")
    a = engines.adapter("mujoco-tuned")
    for name in ["ball-floor-e05", "ball-floor-e1", "ball-corner", "box-corner"]:
        g = grading.grade(scenes[name], a.name, a.run(scenes[name].engine))
        assert g.error < 0.1, (name, g.error)
    up = a.run(scenes["ball-floor-e1"].engine)[0]
    assert up.velocity[2] > 0.95


def test_pinocchio_agrees_where_every_contact_stays_active(scenes):
    """impulseDynamics is the simultaneous Newton law: where the unilateral answer keeps every
    contact active it is the same answer (to 1e-12 of the impact: a Cholesky solve of a small,
    well-conditioned G); on the pitching bar it pulls and disagrees; frictional scenes and two
    coefficients are refused by name, not graded."""
    pytest.importorskip("pinocchio")
    a = engines.adapter("pinocchio")
    for name in ["ball-floor-e05", "ball-corner", "box-corner", "box-edge-30", "cradle-3", "box-on-box"]:
        g = grading.grade(scenes[name], a.name, a.run(scenes[name].engine))
        assert g.error < 1e-12, (name, g.error)
    bar = scenes["bar-pitching-e02"]
    assert grading.grade(bar, a.name, a.run(bar.engine)).error > 0.1
    rep = runner.run([a], [scenes["bar-pitching"], scenes["rod-rough-floor"]])
    assert not rep["grades"] and not rep["failures"]
    assert [f["scene"] for f in rep["not_applicable"]] == ["bar-pitching", "rod-rough-floor"]


def test_rapier_single_contacts(scenes):
    """Rapier (f32) on one contact through the centre: Newton's law to its precision — 1e-6 of
    the impact, a few f32 roundings (measured ≤ 2e-8) — so a wrong mass, sign or combine rule
    is caught; and the frictionless corner's two decoupled contacts likewise."""
    pytest.importorskip("rapier3d")
    a = engines.adapter("rapier")
    for name in ["ball-floor-e0", "ball-floor-e05", "ball-floor-e1", "ball-corner"]:
        g = grading.grade(scenes[name], a.name, a.run(scenes[name].engine))
        assert g.error < 1e-6, (name, g.error)


def test_mujoco_calibrated_ball_bounces_at_the_asked_e(scenes):
    """The calibrated setting finds ζ by bisection so that the ball leaves at e: on the ball
    scenes at e = 0.5 and 1 the grade is the bisection's residue (ζ to 1e-6; measured 6.3e-7 and
    6.6e-7), bounded here by 1e-4; at e = 0 MuJoCo's contact cannot stop the ball (it leaves at
    about 0.05 m/s whatever ζ), so that scene is not bounded."""
    pytest.importorskip("mujoco")
    a = engines.adapter("mujoco-calibrated")
    for name in ["ball-floor-e05", "ball-floor-e1", "ball-corner"]:
        g = grading.grade(scenes[name], a.name, a.run(scenes[name].engine))
        assert g.error < 1e-4, (name, g.error)
    with pytest.raises(ValueError, match="tuned=True"):
        from inertance.engines.mujoco_adapter import MuJoCoAdapter
        MuJoCoAdapter(calibrated=True)


def test_drake_corner_is_a_rigid_impact_at_its_own_restitution(scenes, tmp_path):
    """Drake has no restitution coefficient: its ball leaves at some small e_D whatever e is asked
    (measured 0.020). With that e_D written into the box-corner scene, Drake's twist must be the
    exact answer's up to its soft contact (measured 0.039 of the impact; bound 0.1): a wrong pose,
    inertia or sign would not be."""
    pytest.importorskip("pydrake")
    a = engines.adapter("drake")
    e_d = float(a.run(scenes["ball-floor-e05"].engine)[0].velocity[2])
    assert 0 <= e_d < 0.1
    p = tmp_path / "box-corner.toml"
    p.write_text((CAT / "box-corner.toml").read_text().replace("k = 0.5", f"k = {e_d!r}"))
    s = catalogue.load(p)
    g = grading.grade(s, a.name, a.run(s.engine))
    assert g.error < 0.1, g.error


def test_drake_tuned_and_calibrated_bounce_the_ball_at_the_mapped_e(scenes):
    """The tuned map d = y(e)/v⁰ is the continuous Hunt–Crossley model's exact rebound (module
    docstring); Drake's discrete solver (0.1 ms, kLagged) leaves the ball at e = 0.5 with 4.8 %
    of the impact's error (measured 0.048; bound 0.1), at e = 1 with 10.8 % (the lagged
    dissipation is not zero at d = 0: measured 0.108; bound 0.15) — a wrong mass, sign or
    stiffness errs by the order of the impact. The calibrated variant bisects d on a 1 kg ball at
    the scene's speed; the catalogue's ball is that ball, so its grade is the bisection's residue
    (30 halvings of a 6-wide interval in ln d: 6·2⁻³⁰ ≈ 6e-9 relative in d; measured 2.8e-10;
    bound 1e-6) — except at e = 1, where d = 0 is the best the model has (calibration returns 0:
    same as tuned)."""
    pytest.importorskip("pydrake")
    tuned, calibrated = engines.adapter("drake-tuned"), engines.adapter("drake-calibrated")
    for name, bound in [("ball-floor-e05", 0.1), ("ball-floor-e1", 0.15)]:
        g = grading.grade(scenes[name], tuned.name, tuned.run(scenes[name].engine))
        assert g.error < bound, (name, g.error)
    g = grading.grade(scenes["ball-floor-e05"], calibrated.name, calibrated.run(scenes["ball-floor-e05"].engine))
    assert g.error < 1e-6, g.error


def test_drake_hydroelastic_is_hydroelastic_and_keeps_the_edges_symmetric(scenes):
    """The hydroelastic variant: the bodies compliant, the obstacles rigid (Drake computes no
    hydroelastic contact between a compliant half-space and a compliant body and falls back to
    point contact silently — the earlier version's mistake). Every run here must report
    hydroelastic contact and no point pair (the adapter refuses a run with one); the ball at
    e = 0.5 rebounds within 5 % of the impact (the tuned map on a pressure field: measured
    0.011); and the pressure spread over the edge's face keeps the box's mirror symmetry that
    every point-contact engine but MuJoCo breaks (measured 2.5e-5 of the impact on box-edge-30;
    bound 1e-3, the grade's `!sym` threshold)."""
    pytest.importorskip("pydrake")
    a = engines.adapter("drake-hydroelastic")
    for name in ["ball-floor-e05", "box-flat-e05", "box-edge-30", "cradle-3"]:
        twist = a.run(scenes[name].engine)
        assert a.last_run["hydroelastic"] > 0 and a.last_run["point"] == 0, (name, a.last_run)
        g = grading.grade(scenes[name], a.name, twist)
        if name == "ball-floor-e05":
            assert g.error < 0.05, g.error
        if name == "box-edge-30":
            assert g.symmetry_ok and g.symmetry_broken < 1e-3, g.symmetry_broken


def test_mujoco_default_runs_every_scene(scenes):
    """MuJoCo's defaults ignore e: every scene runs and gives a finite twist (no bound on the error:
    it is what the report measures)."""
    pytest.importorskip("mujoco")
    rep = runner.run([engines.adapter("mujoco")], list(scenes.values()))
    assert not rep["failures"], rep["failures"]
    assert len(rep["grades"]) == len(scenes)


# --- engines on the second slice's grades (symmetry, cylinders, convergence) ---------------

def test_pinocchio_and_mujoco_keep_symmetry_pybullet_and_rapier_break_the_flat_box(scenes):
    """The symmetry grade on real engines: Pinocchio's one linear solve and MuJoCo's simultaneous
    soft contacts keep the flat box's mirrors (below 1e-12: rounding of the solve, and of MuJoCo's
    symmetric solver); Bullet's manifold meets the corners one per step and Rapier's solver
    sweeps them in order, and both leave the box turning (rapier #668) — flagged `!sym`."""
    from inertance.engines import adapter

    s = scenes["box-flat-e05"]
    for name, broken in [("pinocchio", False), ("mujoco-calibrated", False), ("pybullet", True), ("rapier", True)]:
        module = engines.ENGINE_MODULES[name]
        pytest.importorskip(module)
        g = grading.grade(s, name, adapter(name).run(s.engine))
        if broken:
            assert not g.symmetry_ok and g.symmetry_broken > 0.01, (name, g.symmetry_broken)
        else:
            assert g.symmetry_broken < 1e-12, (name, g.symmetry_broken)


@pytest.fixture(scope="module")
def cylinders(tmp_path_factory):
    from inertance.engines import random_family

    family = random_family.scenes(2026, 12, tmp_path_factory.mktemp("cylinders"))
    return [s for s in family if "cylinder" in s.name]


@pytest.mark.parametrize("name,bound", [("pinocchio", 1e-12), ("rapier", 0.02), ("mujoco-calibrated", 0.02),
                                        ("pybullet", 0.1), ("drake", 1.0)])
def test_every_engine_builds_a_cylinder(cylinders, name, bound):
    """Each adapter builds the family's cylinders (on a rim point: one contact; on its side:
    two) and gets a finite answer better than no impact. Bounds on the one-contact rims:
    Pinocchio exact (1e-12: f64); Rapier and MuJoCo calibrated as on the catalogue's one-contact
    box corner (0.016 and 0.006 there: Rapier's first-order step error, MuJoCo's soft contact;
    here measured below 0.005) — a cylinder built on the wrong axis, with the wrong inertia or
    radius, errs by the order of the impact; PyBullet below 0.1 (its rims err by 4–5 % although
    the point Bullet finds is the scene's to 0.1 mm: not explained here); Drake only below 1
    (its defaults are nearly inelastic)."""
    from inertance.engines import adapter

    pytest.importorskip(engines.ENGINE_MODULES[name])
    a = adapter(name)
    assert len(cylinders) == 4
    for s in cylinders:
        g = grading.grade(s, name, a.run(s.engine))
        assert g.error < (bound if "rim" in s.name else 1.0), (s.name, g.error)


def test_refining_pybullets_and_rapiers_steps(scenes):
    """Convergence sweeps on real engines: an isolated contact is exact at every PyBullet time
    step and iteration count; on the flat box PyBullet and Rapier settle (the error changes by
    less than 15 % per halving): the sequence in which they meet the corners, not the step, sets
    it."""
    from inertance.engines import convergence

    pytest.importorskip("pybullet")
    pytest.importorskip("rapier3d")
    for knob, values, make in convergence.SWEEPS["pybullet"]:
        r = convergence.sweep("pybullet", knob, values, make, scenes["ball-floor-e05"])
        assert r["verdict"] == "exact"
    knob, values, make = convergence.SWEEPS["pybullet"][0]
    assert convergence.sweep("pybullet", knob, values, make, scenes["box-flat-e05"])["verdict"].startswith("settles")
    knob, values, make = convergence.SWEEPS["rapier"][0]
    assert convergence.sweep("rapier", knob, values, make, scenes["box-flat-e05"])["verdict"].startswith("settles")
