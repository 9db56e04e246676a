//! Joints in a simulated system (`[[joint]]` in a scene to simulate, issue 27;
//! `src/simulate/system/joints.rs`), each against what the code does not compute itself: a
//! compound pendulum against the exact period of a physical pendulum (the complete elliptic
//! integral by the arithmetic–geometric mean, here); two hinged boxes spinning in space against
//! the conservation of momentum and angular momentum; a leg of boxes landing on heel and toe
//! against the impact scene `examples/leg-heel-toe.toml` solved by the impact layer; a pendulum
//! striking a wall against Newton's law about a fixed pivot; a slider on an inclined prismatic
//! joint against uniform acceleration.

use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::scene::{AnySimulation, Scene};
use inertance::simulate::system::{SystemSample, SystemSetup, SystemSimulation, simulate_system};
use nalgebra::Vector3;

type V3 = Vector3<f64>;

const G: f64 = 9.81;

fn system(text: &str) -> SystemSetup {
    match AnySimulation::parse(text, "s.toml").expect("scene") {
        AnySimulation::System(s) => s.setup,
        AnySimulation::Body(_) => panic!("not a system"),
    }
}

fn run(setup: &SystemSetup) -> SystemSimulation {
    let sim = simulate_system(setup);
    assert!(sim.stopped.is_none(), "stopped: {:?}", sim.stopped);
    sim
}

/// K(k) = π / (2 AGM(1, √(1 − k²))), the complete elliptic integral of the first kind.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    while (a - b).abs() > 1e-16 * a {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    std::f64::consts::PI / (2.0 * a)
}

/// A uniform bar, 1 × 0.1 × 0.1 m and 1 kg, hinged to the ground about z at the centre of its
/// end face (the origin), released from rest at θ₀ = 60° from the downward vertical, without
/// contacts. A physical pendulum: I_O = m (a² + b²)/12 + m d² with d = 1/2 the pivot's distance
/// from the centre, period T = 4 √(I_O / (m g d)) K(sin(θ₀/2)). Sampled every T/8 over three
/// periods, the bar must be at ±θ₀ and at rest at every half period, and at θ = 0 moving at
/// the energy's speed, θ̇² = 2 m g d (cos θ − cos θ₀) / I_O, at every quarter.
///
/// Tolerances: the integrator holds each step's local error below 10⁻¹⁰ of the scales of the
/// motion (the length 1 m, the speed √(g L)), and the error accumulated over three periods of
/// a few hundred steps stays below 10⁻⁸ rad (and rad/s) — the claim checked here; the energy is
/// held to 10⁻⁹ of m g d (no projection changes it beyond the integrator's error); the anchor,
/// moved back onto the pivot after every step, is off it by the drift of one step at most,
/// 10⁻⁹ m in the samples read between steps.
#[test]
fn a_compound_pendulum_keeps_the_exact_period() {
    let (a, b, m) = (1.0, 0.1, 1.0);
    let d = 0.5;
    let theta0 = 60f64.to_radians();
    let io = m * (a * a + b * b) / 12.0 + m * d * d;
    let period = 4.0 * (io / (m * G * d)).sqrt() * elliptic_k((theta0 / 2.0).sin());
    let text = format!(
        "[[body]]\nname = \"bar\"\nshape = {{ box = [1, 0.1, 0.1] }}\nmass = 1\n\
         pose = [{{ axis = [0, 0, 1], angle = \"-30 deg\" }}]\n\
         position = [\"0.5 * sin(60 deg)\", \"-0.5 * cos(60 deg)\", 0]\nvelocity = [0, 0, 0]\n\
         [[joint]]\nkind = \"revolute\"\nbodies = [\"bar\"]\nanchor = [0, 0, 0]\naxis = [0, 0, 1]\n\
         [simulate]\ngravity = [0, -{G}, 0]\nduration = {}\noutput_step = {}\n",
        3.0 * period + 1e-9,
        period / 8.0
    );
    let sim = run(&system(&text));
    let angle = |s: &SystemSample| s.state.x[0].x.atan2(-s.state.x[0].y);
    let e0 = sim.samples[0].kinetic + sim.samples[0].potential;
    let mut checked = 0;
    for s in &sim.samples {
        let e = s.kinetic + s.potential;
        assert!(
            (e - e0).abs() <= 1e-9 * m * G * d,
            "t = {}: E {e} vs {e0}",
            s.t
        );
        let pivot = s.state.x[0] + s.state.rotation(0) * V3::new(-0.5, 0.0, 0.0);
        assert!(
            pivot.norm() <= 1e-9,
            "t = {}: anchor off by {}",
            s.t,
            pivot.norm()
        );
        let eighths = s.t / (period / 8.0);
        let n = eighths.round();
        if (eighths - n).abs() > 1e-6 || n == 0.0 {
            continue;
        }
        let (th, w) = (angle(s), s.state.w[0].z);
        match n as i64 % 4 {
            0 => {
                let want = if (n as i64 / 4) % 2 == 1 {
                    -theta0
                } else {
                    theta0
                };
                assert!((th - want).abs() <= 1e-8, "t = {}: θ {th} vs {want}", s.t);
                assert!(w.abs() <= 1e-8, "t = {}: θ̇ {w} at a turning point", s.t);
            }
            2 => {
                let speed = (2.0 * m * G * d * (1.0 - theta0.cos()) / io).sqrt();
                assert!(th.abs() <= 1e-8, "t = {}: θ {th} at the bottom", s.t);
                assert!(
                    (w.abs() - speed).abs() <= 1e-8,
                    "t = {}: θ̇ {w} vs {speed}",
                    s.t
                );
            }
            _ => continue,
        }
        checked += 1;
    }
    assert_eq!(checked, 12, "every quarter period of three periods");
    assert!(sim.drift <= 1e-9, "drift {}", sim.drift);
}

/// Σ m v and Σ (x × m v + R J Rᵀ ω) (about the origin) of a sample.
fn momenta(setup: &SystemSetup, s: &SystemSample) -> (V3, V3) {
    let mut p = V3::zeros();
    let mut l = V3::zeros();
    for (b, m) in setup.members.iter().enumerate() {
        let st = &s.state;
        let mv = st.v[b] * m.mass();
        p += mv;
        l += st.x[b].cross(&mv) + m.body.world_inertia(&st.rotation(b)) * st.w[b];
    }
    (p, l)
}

/// Two boxes hinged to each other in space, without gravity: a 2 kg box 0.4 × 0.2 × 0.1 m and
/// a 1 kg box 0.3 × 0.3 × 0.1 m, touching at the anchor (0.2, 0, 0) — the first one's face
/// centre, the second one's corner region — turning together at ω = (0.3, −0.5, 2) rad/s with
/// the second also turning about the hinge's axis (1, 1, 1)/√3 at 3 rad/s relative to the
/// first (for a spherical joint, about the same axis: any relative spin is allowed). The
/// joint's reactions are internal: Σ m v is constant (the integrator is exact on linear
/// invariants, so to rounding: 10⁻¹² of |p| + m|v| scales), and the angular momentum about
/// the origin is constant to the integrator's tolerance (10⁻⁹ of its size over 2 s; it is
/// quadratic in the state); the anchor stays shared to 10⁻⁹ m, and for the revolute joint the
/// axis stays common to 10⁻⁹ rad.
#[test]
fn two_hinged_boxes_spinning_in_space_conserve_momentum_and_angular_momentum() {
    let w1 = V3::new(0.3, -0.5, 2.0);
    let axis = V3::new(1.0, 1.0, 1.0).normalize();
    let w2 = w1 + axis * 3.0;
    let (x1, x2, p) = (
        V3::zeros(),
        V3::new(0.35, 0.05, 0.0),
        V3::new(0.2, 0.0, 0.0),
    );
    let v1 = V3::new(0.1, 0.2, -0.1);
    // the anchor moves as a point of each box
    let v2 = v1 + w1.cross(&(p - x1)) - w2.cross(&(p - x2));
    let f = |v: &V3| format!("[{}, {}, {}]", v.x, v.y, v.z);
    for kind in ["revolute", "spherical"] {
        let axis_line = if kind == "revolute" {
            "axis = [1, 1, 1]\n"
        } else {
            ""
        };
        let text = format!(
            "[[body]]\nname = \"a\"\nshape = {{ box = [0.4, 0.2, 0.1] }}\nmass = 2\n\
             position = {}\nvelocity = {}\nangular_velocity = {}\n\
             [[body]]\nname = \"b\"\nshape = {{ box = [0.3, 0.3, 0.1] }}\nmass = 1\n\
             position = {}\nvelocity = {}\nangular_velocity = {}\n\
             [[joint]]\nkind = \"{kind}\"\nbodies = [\"a\", \"b\"]\nanchor = {}\n{axis_line}\
             [simulate]\ngravity = [0, 0, 0]\nduration = 2\noutput_step = 0.01\n",
            f(&x1),
            f(&v1),
            f(&w1),
            f(&x2),
            f(&v2),
            f(&w2),
            f(&p),
        );
        let setup = system(&text);
        let sim = run(&setup);
        let (p0, l0) = momenta(&setup, &sim.samples[0]);
        let speed = 3.0 * (v1.norm() + v2.norm() + 5.0 * 0.3);
        for s in &sim.samples {
            let (p1, l1) = momenta(&setup, s);
            assert!(
                (p1 - p0).norm() <= 1e-12 * speed,
                "{kind} t = {}: p {p1} vs {p0}",
                s.t
            );
            assert!(
                (l1 - l0).norm() <= 1e-9 * l0.norm(),
                "{kind} t = {}: L {l1} vs {l0}",
                s.t
            );
            let st = &s.state;
            let pa = st.x[0] + st.rotation(0) * (p - x1);
            let pb = st.x[1] + st.rotation(1) * (p - x2);
            assert!(
                (pa - pb).norm() <= 1e-9,
                "{kind} t = {}: anchors {pa} {pb}",
                s.t
            );
            if kind == "revolute" {
                let (ua, ub) = (st.rotation(0) * axis, st.rotation(1) * axis);
                assert!(ua.cross(&ub).norm() <= 1e-9, "{kind} t = {}: axes", s.t);
            }
        }
        // it did turn: the relative spin is not trivial
        let last = &sim.samples.last().expect("samples").state;
        assert!((last.w[0] - w1).norm() > 0.1, "{kind}: ω never changed");
    }
}

/// The leg of `examples/leg-heel-toe.toml` — thigh, shank and foot hinged at the knee and the
/// ankle, in flight at the instant its foot lands flat — built of boxes with the example's
/// masses and in-plane inertias: thigh and shank 0.48 × 0.14 × 0.14 m (m (a² + b²)/12 =
/// m L²/12 with L = 1/2, the example's J, across; the inertia along a link does not enter the
/// planar motion), the foot 0.3 × 0.1 × 0.1 m (the example's 1/120 and 1/600 exactly), the
/// hinges at the example's anchors. The foot's four bottom corners are on the ground at t = 0
/// (heel and toe at x = −0.1 and 0.2), so all strike in the first impact, at t = 0. Its answer
/// must be the impact scene's, solved by the impact layer on the example (heel and toe at z =
/// 0; k = 1/5 at both, the simulation's one law for the ground): every body's v and ω to 10⁻⁹
/// (rounding of the two routes, on speeds of 1 m/s). The joints hold after it to rounding: the
/// anchors move alike. Then, to t = 0.2 s (the knee folds as the leg settles, rocking onto the
/// toe), the energy is never gained, at impacts or in flight (to 10⁻⁹ of m g L).
#[test]
fn a_leg_of_boxes_lands_on_heel_and_toe_as_the_impact_scene() {
    let text = "\
[[body]]
name = \"thigh\"
mass = 7
shape = { box = [0.48, 0.14, 0.14] }
pose = { matrix = [[\"3/5\", \"4/5\", 0], [\"-4/5\", \"3/5\", 0], [0, 0, 1]] }
position = [\"3/20\", \"7/10\", 0]
velocity = [\"11/10\", \"-37/40\", 0]
angular_velocity = [0, 0, \"1/2\"]
[[body]]
name = \"shank\"
mass = 3
shape = { box = [0.48, 0.14, 0.14] }
pose = { matrix = [[\"-3/5\", \"4/5\", 0], [\"-4/5\", \"-3/5\", 0], [0, 0, 1]] }
position = [\"3/20\", \"3/10\", 0]
velocity = [1, \"-7/10\", 0]
angular_velocity = [0, 0, -1]
[[body]]
name = \"foot\"
mass = 1
shape = { box = [0.3, 0.1, 0.1] }
position = [\"1/20\", \"1/20\", 0]
velocity = [\"33/40\", \"-21/40\", 0]
angular_velocity = [0, 0, \"1/2\"]
[[joint]]
kind = \"revolute\"
bodies = [\"thigh\", \"shank\"]
anchor = [\"3/10\", \"1/2\", 0]
axis = [0, 0, 1]
[[joint]]
kind = \"revolute\"
bodies = [\"shank\", \"foot\"]
anchor = [0, \"1/10\", 0]
axis = [0, 0, 1]
[[obstacle]]
name = \"ground\"
normal = [0, 1, 0]
[simulate]
gravity = [0, -9.81, 0]
duration = 0.2
output_step = 0.005
contact = { k = 0.2 }
";
    let setup = system(text);
    let sim = run(&setup);
    let first = &sim.impacts[0];
    assert_eq!(first.t, 0.0);
    assert_eq!(first.contacts.len(), 4, "heel and toe, both corners each");
    let after = sim
        .samples
        .iter()
        .rfind(|s| s.t == 0.0)
        .expect("the sample after the first impact");

    // The impact scene, heel and toe at k = 1/5.
    let example = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/examples/leg-heel-toe.toml"
    ))
    .expect("the example");
    assert_eq!(example.matches("\nk = 0\n").count(), 1, "the toe's k");
    let example = example.replace("\nk = 0\n", "\nk = 0.2\n");
    let scene = Scene::parse(&example, "leg-heel-toe.toml").expect("the impact scene");
    let sys = scene.system::<f64>().expect("its system");
    let mut impact = Impact::assemble(&sys).expect("assembles");
    let mut out = Outcome::default();
    impact.solve(Model::Newton, &mut out).expect("Newton's law");
    for (b, twist) in out.velocity.0.iter().enumerate() {
        let (w, v) = (twist.top(), twist.bottom());
        let (w, v) = (V3::new(w[0], w[1], w[2]), V3::new(v[0], v[1], v[2]));
        let name = &setup.members[b].name;
        assert!(
            (after.state.v[b] - v).norm() <= 1e-9,
            "{name}: v {} vs the impact scene's {v}",
            after.state.v[b]
        );
        assert!(
            (after.state.w[b] - w).norm() <= 1e-9,
            "{name}: ω {} vs the impact scene's {w}",
            after.state.w[b]
        );
    }
    // the joints hold after the impact: each anchor moves alike on both its members
    let st = &after.state;
    for (l, (a, b)) in setup.joints.iter().zip([(0, 1), (1, 2)]) {
        let (pa, _) = l.anchors(st);
        let va = st.v[a] + st.w[a].cross(&(pa - st.x[a]));
        let vb = st.v[b] + st.w[b].cross(&(pa - st.x[b]));
        assert!((va - vb).norm() <= 1e-12, "anchor rates {va} {vb}");
        assert!((st.w[a] - st.w[b]).cross(&V3::z()).norm() <= 1e-12);
    }
    // never a gain of energy
    let scale = 11.0 * G * 1.0;
    for i in &sim.impacts {
        assert!(i.kinetic_after <= i.kinetic_before + 1e-12 * scale, "{i:?}");
    }
    for pair in sim.samples.windows(2) {
        let (e0, e1) = (
            pair[0].kinetic + pair[0].potential,
            pair[1].kinetic + pair[1].potential,
        );
        assert!(e1 <= e0 + 1e-9 * scale, "t = {}: E {e0} → {e1}", pair[1].t);
    }
    assert!(sim.impacts.len() > 1, "the leg rocks onto its toe");
}

/// The bar of the compound pendulum released from θ₀ = −60° swings through the vertical into
/// a wall tilted about y (normal (−1, 0, −0.2)/|·|, through (0.6, 0, 0), k = 1/2), which one
/// corner of its end meets first, alone (the other, 0.02 m farther along the normal, 6 ms
/// later). About its fixed pivot the bar has one degree of freedom, θ, and the contact's rate is
/// J_c θ̇: Newton's law g⁺ = −k g⁻ is θ̇⁺ = −k θ̇⁻, to rounding (10⁻⁹ of θ̇); ω stays along the
/// hinge.
#[test]
fn a_pendulum_striking_a_wall_rebounds_at_minus_k_its_angular_velocity() {
    let text = format!(
        "[[body]]\nname = \"bar\"\nshape = {{ box = [1, 0.1, 0.1] }}\nmass = 1\n\
         pose = [{{ axis = [0, 0, 1], angle = \"-150 deg\" }}]\n\
         position = [\"-0.5 * sin(60 deg)\", \"-0.5 * cos(60 deg)\", 0]\nvelocity = [0, 0, 0]\n\
         [[joint]]\nkind = \"revolute\"\nbodies = [\"bar\"]\nanchor = [0, 0, 0]\naxis = [0, 0, 1]\n\
         [[obstacle]]\nname = \"wall\"\nnormal = [-1, 0, -0.2]\npoint = [0.6, 0, 0]\n\
         [simulate]\ngravity = [0, -{G}, 0]\nduration = 1\noutput_step = 0.01\nimpacts = 1\n\
         contact = {{ k = 0.5 }}\n"
    );
    let setup = system(&text);
    let sim = run(&setup);
    assert_eq!(sim.impacts.len(), 1);
    let i = &sim.impacts[0];
    assert_eq!(i.contacts.len(), 1, "one corner: {:?}", i.contacts);
    let at: Vec<&SystemSample> = sim.samples.iter().filter(|s| s.t == i.t).collect();
    let (before, after) = (at[0].state.w[0], at[1].state.w[0]);
    assert!(before.z > 1.0, "it swings into the wall: {before}");
    assert!(
        (after.z + 0.5 * before.z).abs() <= 1e-9 * before.z,
        "θ̇ {} → {}",
        before.z,
        after.z
    );
    assert!(
        after.xy().norm() <= 1e-9 * before.z,
        "ω off the hinge: {after}"
    );
    assert!((i.contacts[0].after + 0.5 * i.contacts[0].before).abs() <= 1e-9);
}

/// A 1 kg box on a prismatic joint to the ground along a = (cos 30°, −sin 30°, 0) (an incline),
/// released at rest under gravity −g y: it slides along a at g sin 30° = g/2 without turning,
/// x(t) = x₀ + ¼ g t² a, to the integrator's tolerance (10⁻⁹ m over 1 s; ω zero to 10⁻⁹
/// rad/s, the integrator's 10⁻¹⁰ of the speed scale over the box's reach, in the samples read
/// between two projections).
#[test]
fn a_box_on_an_inclined_prismatic_joint_slides_at_g_sin_the_slope() {
    let text = format!(
        "[[body]]\nname = \"slider\"\nshape = {{ box = [0.2, 0.1, 0.1] }}\nmass = 1\n\
         pose = [{{ axis = [0, 0, 1], angle = \"10 deg\" }}]\n\
         position = [0, 0, 0]\nvelocity = [0, 0, 0]\n\
         [[joint]]\nkind = \"prismatic\"\nbodies = [\"slider\"]\naxis = [\"cos(30 deg)\", \"-sin(30 deg)\", 0]\n\
         [simulate]\ngravity = [0, -{G}, 0]\nduration = 1\noutput_step = 0.05\n"
    );
    let sim = run(&system(&text));
    let a = V3::new(30f64.to_radians().cos(), -30f64.to_radians().sin(), 0.0);
    for s in &sim.samples {
        let want = a * (0.25 * G * s.t * s.t);
        assert!(
            (s.state.x[0] - want).norm() <= 1e-9,
            "t = {}: {} vs {want}",
            s.t,
            s.state.x[0]
        );
        assert!(
            s.state.w[0].norm() <= 1e-9,
            "t = {}: it turns, {}",
            s.t,
            s.state.w[0]
        );
    }
}

/// Bad joints: a kind not known, and velocities the joint forbids, each named by its key.
#[test]
fn a_joint_the_velocities_break_is_refused_by_its_key() {
    let scene = |joint: &str, velocity: &str| {
        format!(
            "[[body]]\nname = \"bar\"\nshape = {{ box = [1, 0.1, 0.1] }}\nmass = 1\n\
             position = [0.5, 0, 0]\nvelocity = {velocity}\n\
             [[joint]]\n{joint}\nbodies = [\"bar\"]\nanchor = [0, 0, 0]\naxis = [0, 0, 1]\n\
             [simulate]\ngravity = [0, -{G}, 0]\nduration = 1\n"
        )
    };
    let error = |text: String| match AnySimulation::parse(&text, "s.toml") {
        Err(e) => e.to_string(),
        Ok(_) => panic!("accepted: {text}"),
    };
    let e = error(scene("kind = \"hinge\"", "[0, 0, 0]"));
    assert!(e.contains("joint[0].kind") && e.contains("hinge"), "{e}");
    let e = error(scene("kind = \"revolute\"", "[1, 0, 0]"));
    assert!(e.contains("joint[0]") && e.contains("revolute"), "{e}");
    // the velocity the hinge allows is accepted
    assert!(AnySimulation::parse(&scene("kind = \"revolute\"", "[0, 0, 0]"), "s.toml").is_ok());
}
