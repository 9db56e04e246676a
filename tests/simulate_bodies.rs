//! Systems of boxes (and spheres) through sequences of impacts (`src/simulate/system/`): a box
//! dropped flat on a box resting on the floor against its closed form, the box-on-box impact
//! of `examples/box-on-box.toml` against the closed form derived by hand in
//! derivations/systems.md, a box tumbling on a box against the single body's loop tumbling on
//! a floor (an independent formulation: one body and its planes against a system with the
//! base's closed contacts in every impact), two boxes colliding in space against the
//! conservation laws, edges meeting edges (crossed, and a box tipping off the base over its
//! edge), and the refusals (cylinders, Hertz at a corner).

use inertance::impact::friction::Restitution;
use inertance::scene::{AnySimulation, SimulationScene};
use inertance::simulate::Law;
use inertance::simulate::run::simulate_history;
use inertance::simulate::system::{SystemSetup, SystemSimulation, simulate_system};
use nalgebra::Vector3;

type V3 = Vector3<f64>;

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

/// A box `top` (its `[[body]]` lines) on a base of edges `edges` resting on the floor, under
/// gravity `g` (m/s², down), k = 1/2.
fn on_a_base(top: &str, edges: &str, g: f64, law: &str) -> String {
    format!(
        "[[body]]\nname = \"top\"\n{top}\n[[body]]\nname = \"base\"\nshape = {{ box = {edges} }}\n\
         mass = 5\nposition = [0, 0, 0.1]\nvelocity = [0, 0, 0]\n\
         [[obstacle]]\nname = \"floor\"\nnormal = [0, 0, 1]\n\
         [simulate]\ngravity = [0, 0, -{g}]\nduration = 2\nlaw = \"{law}\"\ncontact = {{ k = 0.5 }}\n"
    )
}

const FLAT: &str =
    "shape = { box = [0.2, 0.2, 0.1] }\nmass = 1\nposition = [0, 0, 0.3]\nvelocity = [0, 0, 0]";

/// The top box (1 kg) falls flat from 0.05 m onto the base, which rests on the floor: it lands
/// at t₁ = √(2·0.05/10) = 0.1 s at 1 m/s on its four lower corners, and the base, held by its
/// four closed floor contacts, cannot move, so the top rebounds as off a fixed floor: the n-th
/// impact at tₙ = 0.3 − 0.2/2ⁿ⁻¹ s, arriving at 2¹⁻ⁿ m/s and leaving at 2⁻ⁿ m/s, each corner's
/// impulse (1 + k) m u/4, the floor's four taking the same sum (the base's momentum unchanged).
/// After three impacts in the ratio k the run sums the rest in closed form (src/simulate/
/// system/zeno.rs): they accumulate at t∞ = t₃ + 2u₃/(g(1 − k)) = 0.25 + 2·(1/8)/(10·½) =
/// 0.3 s, dissipating ½ m u₃² = 1/128 J, and the run comes to rest there, 7.5 J of potential
/// energy left (1 kg at 0.25 m and 5 kg at 0.1 m under 10 m/s²). Under both laws that hold the
/// closed contacts (the simultaneous law on a basis of its singular G, and the unilateral
/// law). Times to 10⁻¹⁰ s (the events are located to 10⁻¹¹ of the length scale), speeds to
/// 10⁻⁹ m/s.
#[test]
fn a_box_dropped_flat_on_a_box_bounces_as_off_the_floor() {
    for law in [
        Law::Simultaneous(Restitution::Newton),
        Law::Unilateral(Restitution::Newton),
    ] {
        let mut s = system(&on_a_base(FLAT, "[0.6, 0.4, 0.2]", 10.0, "simultaneous"));
        s.law = law;
        let sim = run(&s);
        assert_eq!(sim.impacts.len(), 3, "{law:?}");
        for (n, i) in sim.impacts.iter().enumerate() {
            let n = n as i32 + 1;
            let want = 0.3 - 0.2 * 0.5f64.powi(n - 1);
            assert!((i.t - want).abs() <= 1e-10, "{law:?} #{n}: t = {}", i.t);
            let (mut top, mut floor) = (0.0, 0.0);
            for c in &i.contacts {
                if c.feature.starts_with("top") {
                    assert_eq!(c.plane, "base face +z");
                    assert!((c.before + 0.5f64.powi(n - 1)).abs() <= 1e-9, "{c:?}");
                    assert!((c.after - 0.5f64.powi(n)).abs() <= 1e-9, "{c:?}");
                    top += c.impulse;
                } else {
                    assert!(c.persisting && c.plane == "floor", "{c:?}");
                    assert!(c.after.abs() <= 1e-12, "{c:?}");
                    floor += c.impulse;
                }
            }
            let want = 1.5 * 0.5f64.powi(n - 1);
            assert!((top - want).abs() <= 1e-9 && (floor - want).abs() <= 1e-9);
        }
        let zeno = sim.zeno.as_ref().expect("the accumulation");
        assert_eq!(zeno.after, 3, "{law:?}");
        assert!((zeno.t_inf - 0.3).abs() <= 1e-10, "{}", zeno.t_inf);
        assert!((zeno.ratio - 0.5).abs() <= 1e-9, "{}", zeno.ratio);
        assert!(
            (zeno.dissipated - 1.0 / 128.0).abs() <= 1e-9,
            "{}",
            zeno.dissipated
        );
        assert_eq!(sim.end, inertance::simulate::End::Rest, "{law:?}");
        assert!((sim.t_end - 0.3).abs() <= 1e-10, "{}", sim.t_end);
        // the top rests flat on the base, its corners closed on the face
        assert!(
            (sim.state.x[0].z - 0.25).abs() <= 1e-10,
            "{}",
            sim.state.x[0]
        );
        let e = sim.state.kinetic_energy(&s.members)
            + sim.state.potential_energy(&s.members, &s.options.gravity);
        assert!((e - 7.5).abs() <= 1e-9, "{e}");
    }
}

/// A ball (r = 0.1 m, 1 kg) dropped from h = 0.2 m above the top of a box (2 × 2 × 0.2 m,
/// 5 kg) resting on the floor, drifting at 0.25 m/s, k = 0.8, g = 9.81 m/s²: the base held by
/// its closed floor contacts, the ball bounces as off a floor at z = 0.2 m. Closed form (the
/// bouncing ball of issue 27): it lands at t₁ = √(2h/g) at v₁ = √(2gh), the n-th rebound
/// leaves at kⁿ v₁, and the impacts accumulate at t∞ = t₁ + 2k v₁/(g(1 − k)), taken after the
/// third; the ball then slides on across the face (frictionless) until the run's end at 1.9 s,
/// before it reaches the edge (x = 1 m at 2 s). Checked against that and against the single
/// body's loop bouncing on the plane z = 0.2 m (its own Zeno): the same impact times to 10⁻¹⁰
/// s, the same t∞ and the ball's place at the end (x = 0.5 + 0.25·1.9 m, z = 0.3 m) to 10⁻¹⁰.
#[test]
fn a_ball_bouncing_on_a_box_accumulates_as_on_the_floor() {
    let text = |vx: &str, duration: &str| {
        format!(
            "[[body]]\nname = \"ball\"\nshape = {{ sphere = 0.1 }}\nmass = 1\n\
             position = [0.5, 0, 0.5]\nvelocity = [{vx}, 0, 0]\n\
             [[body]]\nname = \"base\"\nshape = {{ box = [2, 2, 0.2] }}\nmass = 5\n\
             position = [0, 0, 0.1]\nvelocity = [0, 0, 0]\n\
             [[obstacle]]\nname = \"floor\"\nnormal = [0, 0, 1]\n\
             [simulate]\ngravity = [0, 0, -9.81]\nduration = {duration}\nlaw = \"simultaneous\"\n\
             contact = {{ k = 0.8 }}\n"
        )
    };
    let (g, h, k) = (9.81f64, 0.2f64, 0.8f64);
    let (t1, v1) = ((2.0 * h / g).sqrt(), (2.0 * g * h).sqrt());
    let t_inf = t1 + 2.0 * k * v1 / (g * (1.0 - k));
    for law in [
        Law::Simultaneous(Restitution::Newton),
        Law::Unilateral(Restitution::Newton),
    ] {
        let mut s = system(&text("0.25", "1.9"));
        s.law = law;
        let sim = run(&s);
        let zeno = sim.zeno.as_ref().expect("the accumulation");
        assert_eq!((zeno.after, sim.impacts.len()), (3, 3), "{law:?}");
        assert!(
            (zeno.t_inf - t_inf).abs() <= 1e-10,
            "{} vs {t_inf}",
            zeno.t_inf
        );
        assert!((zeno.ratio - k).abs() <= 1e-9, "{}", zeno.ratio);
        let mut t = t1;
        for (n, i) in sim.impacts.iter().enumerate() {
            assert!((i.t - t).abs() <= 1e-10, "#{}: {} vs {t}", n + 1, i.t);
            let ball = i.contacts.iter().find(|c| !c.persisting).expect("ball");
            assert_eq!(
                (ball.feature.as_str(), ball.plane.as_str()),
                ("ball", "base face +z")
            );
            assert!(
                (ball.after - k.powi(n as i32 + 1) * v1).abs() <= 1e-9,
                "{ball:?}"
            );
            t += 2.0 * k.powi(n as i32 + 1) * v1 / g;
        }
        assert_eq!(sim.end, inertance::simulate::End::Duration, "{law:?}");
        let x = sim.state.x[0];
        assert!(
            (x.x - (0.5 + 0.25 * 1.9)).abs() <= 1e-10 && (x.z - 0.3).abs() <= 1e-10,
            "{x}"
        );
        // the base never moved
        assert!((sim.state.x[1] - V3::new(0.0, 0.0, 0.1)).norm() <= 1e-12);
    }
    // the single body on the plane at the box's top
    let single = SimulationScene::parse(
        "[body]\nshape = { sphere = 0.1 }\nmass = 1\nposition = [0.5, 0, 0.5]\n\
         velocity = [0.25, 0, 0]\nangular_velocity = [0, 0, 0]\n[[obstacle]]\nname = \"floor\"\nnormal = [0, 0, 1]\n\
         point = [0, 0, 0.2]\n[simulate]\ngravity = [0, 0, -9.81]\nduration = 1.9\n\
         law = \"simultaneous\"\ncontact = { k = 0.8 }\n",
        "single.toml",
    )
    .expect("scene");
    let alone = simulate_history(&single.setup);
    let sim = run(&system(&text("0.25", "1.9")));
    let (a, b) = (
        sim.zeno.as_ref().expect("zeno"),
        alone.zeno.as_ref().expect("zeno"),
    );
    assert!(
        (a.t_inf - b.t_inf).abs() <= 1e-10,
        "{} vs {}",
        a.t_inf,
        b.t_inf
    );
    for (i, j) in sim.impacts.iter().zip(&alone.impacts) {
        assert!((i.t - j.t).abs() <= 1e-10, "{} vs {}", i.t, j.t);
    }
    assert!((sim.state.x[0] - alone.state.x).norm() <= 1e-10);
    // drifting at 0.4 m/s the accumulation would carry the ball past the face's edge (x = 1 m
    // at t∞ ≈ 1.82 s): it is not taken, and the ball bounces on across the face (to 1.2 s,
    // before it reaches the edge at 1.25 s)
    let sim = run(&system(&text("0.4", "1.2")));
    assert!(sim.zeno.is_none(), "{:?}", sim.zeno);
    assert!(sim.impacts.len() > 3, "{}", sim.impacts.len());
    assert_eq!(sim.end, inertance::simulate::End::Duration);
}

/// A bead (r = 0.05 m) dropped 0.1 m onto a bead of the same size resting on the floor, right
/// above it, k = ½, g = 9.81: the lower bead, held by the floor, does not move, and the upper
/// one bounces along the line of centres as off a floor: the pair's normal stays put, and the
/// impacts accumulate at t∞ = t₁ + 2k v₁/(g(1 − k)) (the closed form above), to 10⁻¹⁰ s.
#[test]
fn a_bead_bouncing_on_a_bead_accumulates_along_the_line_of_centres() {
    let s = system(
        "[[body]]\nname = \"upper\"\nshape = { sphere = 0.05 }\nmass = 1\n\
         position = [0, 0, 0.25]\nvelocity = [0, 0, 0]\n\
         [[body]]\nname = \"lower\"\nshape = { sphere = 0.05 }\nmass = 1\n\
         position = [0, 0, 0.05]\nvelocity = [0, 0, 0]\n\
         [[obstacle]]\nname = \"floor\"\nnormal = [0, 0, 1]\n\
         [simulate]\ngravity = [0, 0, -9.81]\nduration = 2\nlaw = \"simultaneous\"\n\
         contact = { k = 0.5 }\n",
    );
    let sim = run(&s);
    let (g, h, k) = (9.81f64, 0.1f64, 0.5f64);
    let (t1, v1) = ((2.0 * h / g).sqrt(), (2.0 * g * h).sqrt());
    let zeno = sim.zeno.as_ref().expect("the accumulation");
    assert_eq!(zeno.after, 3);
    let t_inf = t1 + 2.0 * k * v1 / (g * (1.0 - k));
    assert!(
        (zeno.t_inf - t_inf).abs() <= 1e-10,
        "{} vs {t_inf}",
        zeno.t_inf
    );
    assert_eq!(sim.end, inertance::simulate::End::Rest);
    assert!(
        (sim.state.x[0].z - 0.15).abs() <= 1e-10,
        "{}",
        sim.state.x[0]
    );
    assert!(
        sim.events
            .iter()
            .any(|e| e.what.starts_with("Zeno") && e.what.contains("upper on lower persists")),
        "{:?}",
        sim.events
    );
}

/// `examples/box-on-box.toml` as a sequence (no gravity, so the state at the impact is the
/// example's): the unilateral law gives the closed form of derivations/systems.md — the base
/// stays at rest, each of the top box's corners takes P = (1 + k) v / (2/m + 2d²/J_y) =
/// 31875/68776 N s (d = 89/500 m, J_y = 17/600 kg m²), the floor's corners (P/2)(1 ± X/A)
/// (X = 39/500 m, A = 0.3 m: the least-norm member of their family), and the top box leaves at
/// v_C = (1/2, 0, −1 + 2P/m), ω = (0, −2Pd/J_y, 0). To 10⁻¹² (one f64 solve of a 6 × 6 system).
#[test]
fn the_box_on_box_impact_is_the_closed_form() {
    let text = std::fs::read_to_string("examples/box-on-box.toml").expect("reads");
    // the example's bodies and floor, simulated: no [[contact]] (the run watches them) and no
    // [solve]; the law in [simulate]
    let bodies =
        &text[text.find("[[body]]").expect("bodies")..text.find("[[contact]]").expect("contacts")];
    let scene = format!(
        "{bodies}[simulate]\ngravity = [0, 0, 0]\nduration = 0.01\nlaw = \"unilateral\"\ncontact = {{ k = 0.5 }}\n"
    );
    let s = system(&scene);
    let sim = run(&s);
    assert_eq!(sim.impacts.len(), 1);
    let p = 31875.0 / 68776.0;
    let (x, a) = (39.0 / 500.0, 0.3);
    for c in &sim.impacts[0].contacts {
        let want = match (c.feature.as_str(), c.plane.as_str()) {
            (f, "base face +z") if f.starts_with("top corner [1, ") => p,
            ("base corner [1, 1, -1]" | "base corner [1, -1, -1]", "floor") => {
                p / 2.0 * (1.0 + x / a)
            }
            ("base corner [-1, 1, -1]" | "base corner [-1, -1, -1]", "floor") => {
                p / 2.0 * (1.0 - x / a)
            }
            other => panic!("unexpected contact {other:?}"),
        };
        assert!((c.impulse - want).abs() <= 1e-12, "{c:?}: {want}");
    }
    let (d, jy, m) = (89.0 / 500.0, 17.0 / 600.0, 2.0);
    let top = 0;
    let v = sim.state.v[top];
    let w = sim.state.w[top];
    assert!(
        (v - V3::new(0.5, 0.0, -1.0 + 2.0 * p / m)).norm() <= 1e-12,
        "{v}"
    );
    assert!(
        (w - V3::new(0.0, -2.0 * p * d / jy, 0.0)).norm() <= 1e-12,
        "{w}"
    );
    assert!(sim.state.v[1].norm() <= 1e-12 && sim.state.w[1].norm() <= 1e-12);
}

/// `examples/simulate/box-on-box.toml`: a box tumbling onto a box resting on the floor. The
/// base cannot move (every impulse on it presses down inside its closed floor contacts), so the
/// top box's history is that of the single body tumbling on a floor at the base's top: the same
/// scene through the one-body loop (`src/simulate/run.rs`: its own contact phase, impact
/// problem and rest) with the floor at z = 0.2. Under the unilateral law the impacts agree
/// while the top box arrives faster than 10⁻³ m/s (the first 13: its rocking from corner to
/// corner down to a thousand times the rest speed): in time to 10⁻⁹ s and in the struck corners
/// and their rebound rates to 10⁻⁸ m/s (each run's steps held to 10⁻¹⁰ of the speed scale,
/// 1.8 m/s, over some hundred steps). Slower bounces part by the rounding of the two
/// formulations (the single body makes two more before it lands flat), and both come to rest
/// at the same time, to 10⁻⁵ s (the last bounces end at each loop's own rest speed).
#[test]
fn a_box_tumbling_on_a_box_is_the_body_tumbling_on_the_floor() {
    let text = std::fs::read_to_string("examples/simulate/box-on-box.toml").expect("reads");
    let s = system(&text);
    let sim = run(&s);
    let top = &text[text.find("name = \"a box").expect("name")
        ..text.find("[[body]]\nname = \"base\"").expect("base")];
    let rest = &text[text.find("[[obstacle]]").expect("floor")..];
    let single = format!(
        "{}{}",
        top.replace("[[body]]\nname = \"top\"\n", "[body]\n"),
        rest.replace(
            "normal = [0, 0, 1]",
            "normal = [0, 0, 1]\npoint = [0, 0, 0.2]"
        )
    );
    let one = SimulationScene::parse(&single, "single.toml").expect("scene");
    let alone = simulate_history(&one.setup);
    assert!(alone.stopped.is_none(), "{:?}", alone.stopped);
    let fast = alone
        .impacts
        .iter()
        .take_while(|i| i.contacts.iter().any(|c| c.before < -1e-3))
        .count();
    assert!(fast >= 13 && sim.impacts.len() >= fast, "{fast}");
    for (k, (a, b)) in sim
        .impacts
        .iter()
        .zip(&alone.impacts)
        .take(fast)
        .enumerate()
    {
        assert!(
            (a.t - b.t).abs() <= 1e-9,
            "impact {}: {} ≠ {}",
            k + 1,
            a.t,
            b.t
        );
        let struck: Vec<_> = a
            .contacts
            .iter()
            .filter(|c| c.feature.starts_with("top "))
            .collect();
        assert_eq!(struck.len(), b.contacts.len(), "impact {}", k + 1);
        for (c, d) in struck.iter().zip(&b.contacts) {
            assert_eq!(c.feature, format!("top {}", d.feature), "impact {}", k + 1);
            assert!(
                (c.after - d.after).abs() <= 1e-8,
                "impact {}: {c:?} {d:?}",
                k + 1
            );
        }
    }
    assert_eq!(sim.end, inertance::simulate::End::Rest);
    assert_eq!(alone.end, inertance::simulate::End::Rest);
    assert!(
        (sim.t_end - alone.t_end).abs() <= 1e-5,
        "{} {}",
        sim.t_end,
        alone.t_end
    );
    // under every law the boxes end at rest, the top flat on the base (its centre 0.05 m above
    // the base's top, its z axis vertical) and the base where it was: the potential energy
    // 9.81 (1 · 0.25 + 5 · 0.1) J and nothing else
    for law in [Law::Simultaneous(Restitution::Newton), Law::Lzb] {
        let mut s = s.clone();
        s.law = law;
        let sim = run(&s);
        assert_eq!(sim.end, inertance::simulate::End::Rest, "{law:?}");
        let e = sim.state.kinetic_energy(&s.members)
            + sim.state.potential_energy(&s.members, &s.options.gravity);
        assert!((e - 9.81 * (0.25 + 0.5)).abs() <= 1e-9, "{law:?}: {e}");
        assert!((sim.state.x[0].z - 0.25).abs() <= 1e-9 && (sim.state.x[1].z - 0.1).abs() <= 1e-9);
        let up = sim.state.rotation(0) * V3::z();
        assert!(up.x.abs() <= 1e-9 && up.y.abs() <= 1e-9, "{law:?}: {up}");
    }
}

/// Two boxes in space, one sliding into the other's corner (k = 1, one frictionless contact):
/// the total momentum, the angular momentum about the origin and the kinetic energy are the
/// same after the impact as before (Newton's law with k = 1 at one contact conserves energy),
/// to 10⁻¹² of their scales.
#[test]
fn two_boxes_colliding_in_space_keep_momentum_and_energy() {
    let s = system(
        r#"
[[body]]
name = "a"
shape = { box = [0.2, 0.2, 0.2] }
mass = 2
position = [0, 0, 0]
velocity = [1, 0.1, 0]
angular_velocity = [0, 0, 0.5]
[[body]]
name = "b"
shape = { box = [0.3, 0.2, 0.1] }
mass = 3
pose = [{ axis = [0, 0, 1], angle = "40 deg" }, { axis = [0, 1, 0], angle = "15 deg" }]
position = [0.45, 0.02, 0.01]
velocity = [0, 0, 0]
angular_velocity = [0.2, 0, 0]
[simulate]
gravity = [0, 0, 0]
duration = 0.5
law = "unilateral"
contact = { k = 1 }
"#,
    );
    let sim = run(&s);
    assert!(!sim.impacts.is_empty());
    let first = &sim.impacts[0];
    assert_eq!(first.contacts.len(), 1, "{:?}", first.contacts);
    let at = |k: usize| {
        sim.samples
            .iter()
            .filter(|p| p.t == first.t)
            .nth(k)
            .expect("sample")
    };
    let (before, after) = (&at(0).state, &at(1).state);
    let momenta = |st: &inertance::simulate::system::SystemState| {
        let mut p = V3::zeros();
        let mut l = V3::zeros();
        for (b, m) in s.members.iter().enumerate() {
            let r = st.rotation(b);
            p += st.v[b] * m.mass();
            l += st.x[b].cross(&(st.v[b] * m.mass())) + m.body.world_inertia(&r) * st.w[b];
        }
        (p, l)
    };
    let ((p0, l0), (p1, l1)) = (momenta(before), momenta(after));
    assert!((p1 - p0).norm() <= 1e-12 * p0.norm(), "{p0} {p1}");
    assert!(
        (l1 - l0).norm() <= 1e-12 * l0.norm().max(p0.norm()),
        "{l0} {l1}"
    );
    let (e0, e1) = (
        before.kinetic_energy(&s.members),
        after.kinetic_energy(&s.members),
    );
    assert!((e1 - e0).abs() <= 1e-12 * e0, "{e0} {e1}");
    assert!(first.contacts[0].after > 0.0);
}

/// Two cubes crossed edge on edge, one falling onto the other: no corner meets a face, and
/// the run used to stop where they first overlapped (status 3). Their edges are now a watched
/// contact: they strike when the centres are 0.2·√2 apart, at t = 0.5 − 0.2√2 (to 10⁻¹² s: flight
/// in space is exact to rounding, the impact found within the gap tolerance), edge on edge, and
/// the run goes on to its end (tests/simulate_system_edges.rs checks the velocities).
#[test]
fn boxes_meeting_edge_on_edge_strike_at_their_edges() {
    let s = system(
        r#"
[[body]]
name = "lower"
shape = { box = [0.2, 0.2, 0.2] }
mass = 1
pose = [{ axis = [0, 1, 0], angle = "45 deg" }]
position = [0, 0, 0]
velocity = [0, 0, 0]
[[body]]
name = "upper"
shape = { box = [0.2, 0.2, 0.2] }
mass = 1
pose = [{ axis = [1, 0, 0], angle = "45 deg" }]
position = [0, 0, 0.5]
velocity = [0, 0, -1]
[simulate]
gravity = [0, 0, 0]
duration = 1
"#,
    );
    let sim = run(&s);
    assert_eq!(sim.impacts.len(), 1);
    let i = &sim.impacts[0];
    let meet = 0.5 - 0.2 * 2f64.sqrt();
    assert!((i.t - meet).abs() <= 1e-12, "{} vs {meet}", i.t);
    assert_eq!(i.contacts.len(), 1, "{:?}", i.contacts);
    assert_eq!(
        (i.contacts[0].feature.as_str(), i.contacts[0].plane.as_str()),
        ("lower edge [-1, *, 1]", "upper edge [*, -1, -1]")
    );
}

/// The energy of a frictionless run never grows between impacts beyond what the integration
/// and the projection of the closed contacts may add: each step's error is held to the
/// relative tolerance of the energy's scale, and each projection moves a member by at most the
/// drift (so m g drift of potential energy per member); the impacts themselves never gain.
fn energy_never_gained(s: &SystemSetup, sim: &SystemSimulation) {
    let e0 = sim.samples[0].kinetic + sim.samples[0].potential;
    let weight: f64 = s
        .members
        .iter()
        .map(|m| m.mass() * s.options.gravity.norm())
        .sum();
    let steps = (sim.steps.0 + sim.steps.1) as f64;
    let bound = steps * s.options.tolerance * e0.abs() + weight * sim.drift;
    let mut lowest = f64::INFINITY;
    for p in &sim.samples {
        let e = p.kinetic + p.potential;
        assert!(
            e <= lowest + bound,
            "t = {}: {e} after {lowest} (± {bound})",
            p.t
        );
        lowest = lowest.min(e);
    }
    for i in &sim.impacts {
        assert!(
            i.kinetic_after <= i.kinetic_before * (1.0 + 1e-12),
            "impact {}: {} → {}",
            i.index,
            i.kinetic_before,
            i.kinetic_after
        );
    }
}

/// A system's mistakes name the file, the key and what to do.
#[test]
fn bad_box_systems_name_the_key_and_the_value() {
    let scene = |second: &str, simulate: &str| {
        format!(
            "[[body]]\nname = \"a\"\nshape = {{ box = [0.2, 0.2, 0.2] }}\nmass = 1\n\
             position = [0, 0, 0.1]\nvelocity = [0, 0, 0]\n\
             [[body]]\nname = \"b\"\n{second}mass = 1\nvelocity = [0, 0, 0]\n\
             [[obstacle]]\nname = \"floor\"\nnormal = [0, 0, 1]\n\
             [simulate]\nduration = 1\n{simulate}"
        )
    };
    let err = |text: String| {
        AnySimulation::parse(&text, "s.toml")
            .map(|_| ())
            .expect_err("refused")
            .to_string()
    };
    let e = err(scene(
        "shape = { cylinder = [0.1, 0.2] }\nposition = [0, 0, 1]\n",
        "",
    ));
    assert!(
        e.contains("s.toml")
            && e.contains("body[1].shape")
            && e.contains("cylinders move only alone"),
        "{e}"
    );
    let e = err(scene(
        "shape = { sphere = 0.1 }\nposition = [0, 0, 1]\nmaterial = { young = 2e11, poisson = 0.3 }\n",
        "law = \"lzb\"\ncontact = { stiffness = \"hertz\" }\n",
    ));
    assert!(
        e.contains("simulate.contact.stiffness") && e.contains("corners"),
        "{e}"
    );
    let e = err(scene(
        "shape = { box = [0.2, 0.2, 0.2] }\nposition = [0.15, 0.1, 0.15]\n",
        "",
    ));
    assert!(e.contains("starts inside"), "{e}");
}

/// A box sliding flat at 0.5 m/s off the edge of the base (frictionless): its two leading
/// corners let go of the face when they reach its edge, at t = (0.5 − 0.3)/0.5 = 0.4 s (the
/// leaving located as a crossing, to 10⁻⁹ s), and its two lower edges across the base's edge
/// close there (the run used to stop at that edge, status 3). It slides on over the edge until
/// its centre passes it, at t = 0.6 s, when its rear corners lift off (at the end of the step
/// past it: within 10⁻³ s, as measured, the steps being short as the box tips), tips over the
/// edge and falls to the floor, its energy never gained.
#[test]
fn a_box_sliding_off_a_box_tips_over_the_edge() {
    let s = system(&on_a_base(
        "shape = { box = [0.2, 0.1, 0.1] }\nmass = 1\nposition = [0.2, 0, 0.25]\nvelocity = [0.5, 0, 0]",
        "[1, 1, 0.2]",
        9.81,
        "unilateral",
    ));
    let sim = run(&s);
    let when = |what: &str| -> Vec<f64> {
        sim.events
            .iter()
            .filter(|e| e.what.contains(what))
            .map(|e| e.t)
            .collect()
    };
    let leaving: Vec<_> = sim
        .events
        .iter()
        .filter(|e| e.what.contains("leaves the face"))
        .collect();
    assert_eq!(leaving.len(), 2, "{:?}", sim.events);
    for e in &leaving {
        assert!(e.what.starts_with("top corner [1, "), "{}", e.what);
        assert!((e.t - 0.4).abs() <= 1e-9, "{}", e.t);
    }
    // an edge contact is watched from 10⁻⁹ of the reach (√0.51 m, the base's) before the end
    // of its edge: at 0.5 m/s, that much before 0.4 s
    let edges = when("on base edge [1, *, 1] closes");
    assert_eq!(edges.len(), 2, "{:?}", sim.events);
    let early = 1e-9 * 0.51f64.sqrt() / 0.5;
    assert!(
        edges.iter().all(|t| (t - (0.4 - early)).abs() <= 1e-9),
        "{edges:?}"
    );
    let lift = when("top corner [-1, 1, -1] on base face +z lifts off");
    assert_eq!(lift.len(), 1, "{:?}", sim.events);
    assert!(lift[0] >= 0.6 && lift[0] <= 0.601, "{lift:?}");
    // it lands on the floor
    assert!(
        sim.impacts.iter().any(|i| i
            .contacts
            .iter()
            .any(|c| c.feature.starts_with("top") && c.plane == "floor")),
        "{:?}",
        sim.events
    );
    energy_never_gained(&s, &sim);
}

/// A box tumbling onto the base with a drift of 0.2 m/s and a yaw from its tilt about two axes:
/// it rocks, spins slowly and slides to the base's edge, where a corner lets go of the face
/// with the body turning and its edges meet the base's (the run used to stop there, status 3).
/// Under the simultaneous and the unilateral laws it now tips over the edge and runs to its
/// end, its energy never gained. (Under LZB — 1689 impacts among the base's compliant floor
/// contacts, 11 minutes of a debug build — it stalls at t = 2.732 s, just after its edges lift
/// off the base's edge: not yet resolved, and not a test.)
#[test]
fn a_spinning_box_sliding_off_a_box_tips_over_the_edge() {
    let text = on_a_base(
        "shape = { box = [0.2, 0.1, 0.1] }\nmass = 1\n\
         pose = [{ axis = [0, 1, 0], angle = \"20 deg\" }, { axis = [1, 0, 0], angle = \"10 deg\" }]\n\
         position = [0, 0, 0.45]\nvelocity = [0.2, 0, 0]\nangular_velocity = [0, 2, 0]",
        "[1, 1, 0.2]",
        9.81,
        "unilateral",
    )
    .replace("duration = 2", "duration = 3");
    for law in [
        Law::Simultaneous(Restitution::Newton),
        Law::Unilateral(Restitution::Newton),
    ] {
        let mut s = system(&text);
        s.law = law;
        let sim = simulate_system(&s);
        assert!(sim.stopped.is_none(), "{law:?}: {:?}", sim.stopped);
        assert!(
            sim.events
                .iter()
                .any(|e| e.what.contains("leaves the face")),
            "{law:?}"
        );
        assert!(
            sim.events
                .iter()
                .any(|e| e.what.contains("on base edge") && e.what.ends_with("closes")),
            "{law:?}: {:?}",
            sim.events
        );
        energy_never_gained(&s, &sim);
    }
}
