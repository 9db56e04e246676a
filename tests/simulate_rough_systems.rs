//! Systems with Coulomb friction (`src/simulate/system/persist.rs`'s rough contacts, and the
//! frictional impact laws over a system): a box sliding to a stop on a box that slides on a
//! frictionless floor, and a ball that slides and spins up on such a box until it rolls, each
//! against its closed form from Newton's laws (derived below, not by the code); a rough box
//! tumbling on a box against the single body's loop tumbling on a rough floor (a different
//! formulation: its own contact phase and impact problem); and two boxes colliding in space
//! with friction against the conservation of momentum and angular momentum.

use inertance::impact::friction::Restitution;
use inertance::scene::{AnySimulation, SimulationScene};
use inertance::simulate::run::simulate_history;
use inertance::simulate::system::{SystemSetup, SystemSimulation, simulate_system};
use inertance::simulate::{End, Law};
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

/// A body `top` (its `[[body]]` lines) resting on a box base (5 kg, `edges`, its centre
/// 0.1 m above the floor), the two touching with μ = `mu` and k = 1/2, the base on a
/// frictionless floor: the base is free to slide.
fn on_a_sliding_base(top: &str, edges: &str, mu: f64, duration: f64) -> String {
    format!(
        "[[body]]\nname = \"top\"\n{top}\n[[body]]\nname = \"base\"\nshape = {{ box = {edges} }}\n\
         mass = 5\nposition = [0, 0, 0.1]\nvelocity = [0, 0, 0]\n\
         [[obstacle]]\nname = \"floor\"\nnormal = [0, 0, 1]\n\
         [simulate]\ngravity = [0, 0, -{G}]\nduration = {duration}\noutput_step = 0.01\n\
         law = \"unilateral\"\ncontact = {{ k = 0.5, mu = {mu} }}\n\
         [simulate.obstacle.floor]\nk = 0.5\nmu = 0\n"
    )
}

/// The time of the first event whose text ends with `what`.
fn first(sim: &SystemSimulation, what: &str) -> f64 {
    sim.events
        .iter()
        .find(|e| e.what.ends_with(what))
        .unwrap_or_else(|| panic!("no event `{what}`: {:?}", sim.events))
        .t
}

/// A box (m = 1 kg, 0.2 × 0.1 × 0.1 m) set sliding at v₀ = 1 m/s on the base (M = 5 kg), which
/// lies on a frictionless floor, μ = 0.3 between them. While it slides, the friction μ m g
/// slows the top and drives the base: v_top = v₀ − μ g t, V = μ g (m/M) t, so the slip closes at
/// μ g (1 + m/M) and stops at t* = v₀ / (μ g (1 + m/M)) = 0.283158 s; then both move at the
/// common velocity m v₀ / (m + M) = 1/6 m/s, the kinetic energy lost being ½ (m M/(m + M)) v₀²
/// = 5/12 J (the energy a perfectly inelastic collision of the two would lose).
///
/// Checked: at every sample before t*, both velocities to 10⁻⁹ m/s (the motion is a quadratic
/// in t, which the fifth-order steps reproduce to rounding); the horizontal momentum m v₀ at
/// every sample to 10⁻¹² N s; the four corners stick together (one alone would need the
/// friction of all four), within rest_speed / (μ g (1 + m/M)) of t* — the slip is declared
/// stopped when it is below the rest speed; after it, the common velocity and the energy lost
/// to the rest speed's share; the top stays flat on the base (no pitch from the friction's
/// moment: the normal forces shift forward, within the face).
#[test]
fn a_box_sliding_on_a_sliding_box_stops_as_newton_says() {
    let (m, big_m, mu, v0) = (1.0, 5.0, 0.3, 1.0);
    let top = "shape = { box = [0.2, 0.1, 0.1] }\nmass = 1\nposition = [0, 0, 0.25]\n\
               velocity = [1, 0, 0]";
    let s = system(&on_a_sliding_base(top, "[1, 1, 0.2]", mu, 1.0));
    let sim = run(&s);
    assert_eq!(sim.end, End::Duration);
    assert!(sim.impacts.is_empty());
    let closing = mu * G * (1.0 + m / big_m);
    let t_star = v0 / closing;
    let rest = s.options.rest_speed;
    let sticks: Vec<f64> = sim
        .events
        .iter()
        .filter(|e| e.what.starts_with("top corner") && e.what.ends_with("sticks"))
        .map(|e| e.t)
        .collect();
    assert_eq!(sticks.len(), 4, "{:?}", sim.events);
    assert!(sticks.iter().all(|&t| t == sticks[0]));
    assert!(
        (sticks[0] - t_star).abs() <= rest / closing + 1e-9,
        "{} ≠ {t_star}",
        sticks[0]
    );
    for sample in &sim.samples {
        let (v, vb) = (sample.state.v[0], sample.state.v[1]);
        assert!(
            (m * v.x + big_m * vb.x - m * v0).abs() <= 1e-12,
            "momentum at {}",
            sample.t
        );
        if sample.t < sticks[0] {
            assert!((v.x - (v0 - mu * G * sample.t)).abs() <= 1e-9, "{sample:?}");
            assert!((vb.x - mu * G * m / big_m * sample.t).abs() <= 1e-9);
        } else {
            let common = m * v0 / (m + big_m);
            assert!((v.x - common).abs() <= rest && (vb.x - common).abs() <= rest);
        }
        let up = sample.state.rotation(0) * V3::z();
        assert!(up.x.abs() <= 1e-9 && up.y.abs() <= 1e-9, "{up}");
        assert!(v.z.abs() <= 1e-9 && vb.z.abs() <= 1e-9);
    }
    let lost = sim.samples[0].kinetic - sim.samples.last().expect("samples").kinetic;
    let expected = 0.5 * m * big_m / (m + big_m) * v0 * v0;
    assert!(
        (lost - expected).abs() <= 2.0 * m * v0 * rest,
        "{lost} ≠ {expected}"
    );
}

/// A ball (m = 1 kg, r = 0.1 m, J = ⅖ m r²) set sliding without spin at v₀ = 1 m/s on the
/// base (M = 5 kg) on a frictionless floor, μ = 0.2. While it slips, the friction μ m g slows
/// its centre (v̇ = −μ g), spins it up (ω̇ r = μ m g r² / J = (5/2) μ g) and drives the base
/// (V̇ = μ g m/M); its contact point's slip v − ω r − V closes at μ g (7/2 + m/M), so it rolls
/// from t* = v₀ / (μ g (7/2 + m/M)) = 0.137752 s on (with M → ∞, the billiard ball's
/// 2 v₀/(7 μ g) and 5/7 v₀). Rolling on a base that no force then drives, it keeps
/// v = v₀ (1 − μ g t*), ω r = (5/2) μ g t*, V = μ g (m/M) t*.
///
/// Checked: the rolling event within rest_speed over the closing rate of t*; at every sample
/// the horizontal momentum to 10⁻¹² N s and, before t*, the ball's v and ω r and the base's V
/// against the closed form to 10⁻⁹; after it, the rolling velocities to the rest speed; the
/// ball's spin about y only (ω_x = ω_z = 0), as the reader's spinning sphere reports it.
#[test]
fn a_ball_sliding_on_a_sliding_box_rolls_as_newton_says() {
    let (m, big_m, mu, v0, r) = (1.0, 5.0, 0.2, 1.0, 0.1);
    let top = "shape = { sphere = 0.1 }\nmass = 1\nposition = [0, 0, 0.3]\nvelocity = [1, 0, 0]";
    let s = system(&on_a_sliding_base(top, "[2, 1, 0.2]", mu, 0.5));
    assert!(s.members[0].turns(), "a sphere on a rough contact spins");
    let sim = run(&s);
    let closing = mu * G * (3.5 + m / big_m);
    let t_star = v0 / closing;
    let rest = s.options.rest_speed;
    let rolls = first(&sim, "top on base face +z sticks");
    assert!((rolls - t_star).abs() <= rest / closing + 1e-9, "{rolls}");
    for sample in &sim.samples {
        let (v, vb, w) = (sample.state.v[0], sample.state.v[1], sample.state.w[0]);
        assert!((m * v.x + big_m * vb.x - m * v0).abs() <= 1e-12);
        assert!(w.x.abs() <= 1e-12 && w.z.abs() <= 1e-12, "{w}");
        let t = sample.t.min(t_star);
        let tol = if sample.t < rolls { 1e-9 } else { 2.0 * rest };
        assert!((v.x - (v0 - mu * G * t)).abs() <= tol, "{sample:?}");
        assert!((w.y * r - 2.5 * mu * G * t).abs() <= tol, "{sample:?}");
        assert!((vb.x - mu * G * m / big_m * t).abs() <= tol, "{sample:?}");
    }
}

/// The box-on-box example made rough (μ = 1/2 between the boxes, μ = 1 on the floor, which
/// holds the base) against the single body's loop tumbling on a rough floor at the base's top
/// (μ = 1/2), under the simultaneous law with friction (the spatial frictional impact of §14
/// over a system, with the base's four sticking floor contacts in every impact). The impacts
/// agree while the top box strikes faster than 0.1 m/s (the first 10; the next nine, down to
/// 10⁻² m/s, agree as well, but each six-contact frictional impact costs seconds in a debug
/// build): in time to 10⁻⁹ s, and in the struck corners and their rebound rates to 10⁻⁸ m/s.
#[test]
fn a_rough_box_tumbling_on_a_box_is_the_body_tumbling_on_a_rough_floor() {
    let text = std::fs::read_to_string("examples/simulate/box-on-box.toml")
        .expect("reads")
        .replace("law = \"unilateral\"", "law = \"simultaneous\"")
        .replace(
            "contact = { k = 0.5 }",
            "contact = { k = 0.5, mu = 0.5 }\n[simulate.obstacle.floor]\nk = 0.5\nmu = 1",
        );
    let top = &text[text.find("name = \"a box").expect("name")
        ..text.find("[[body]]\nname = \"base\"").expect("base")];
    let single = format!(
        "{}[[obstacle]]\nname = \"floor\"\nnormal = [0, 0, 1]\npoint = [0, 0, 0.2]\n\
         [simulate]\ngravity = [0, 0, -9.81]\nduration = 2\noutput_step = 0.005\n\
         law = \"simultaneous\"\ncontact = {{ k = 0.5, mu = 0.5 }}\n",
        top.replace("[[body]]\nname = \"top\"\n", "[body]\n"),
    );
    let one = SimulationScene::parse(&single, "single.toml").expect("scene");
    let alone = simulate_history(&one.setup);
    let fast = alone
        .impacts
        .iter()
        .take_while(|i| i.contacts.iter().any(|c| c.before < -1e-1))
        .count();
    let mut s = system(&text);
    // the fast impacts only: the face landings after them are the single body's μ-sweep's
    // (guide/simulate.md)
    s.options.max_impacts = fast;
    let sim = run(&s);
    assert!(fast >= 8 && sim.impacts.len() >= fast, "{fast}");
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
}

/// Two boxes in space (1 kg and 2 kg), the first sliding obliquely into the second's face at
/// one corner, k = 1/2 and μ = 0.4, under each law with friction (the simultaneous law with
/// Newton's and the energetic restitution, the unilateral law, and LZB): at every impact (the
/// first turns it, and another corner may strike after), the total momentum and the angular
/// momentum about the origin are the same after it as before, to 10⁻¹²
/// of their scales (the contact impulses are internal: equal and opposite, on one line), and
/// the kinetic energy does not grow.
#[test]
fn two_rough_boxes_colliding_keep_momentum() {
    let text = "[[body]]\nname = \"a\"\nshape = { box = [0.2, 0.2, 0.2] }\nmass = 1\n\
                pose = { axis = [1, 1, 0], angle = \"30 deg\" }\n\
                position = [-0.3, 0.02, 0.03]\nvelocity = [1, 0.3, -0.2]\n\
                angular_velocity = [0.5, -1, 2]\n\
                [[body]]\nname = \"b\"\nshape = { box = [0.3, 0.4, 0.5] }\nmass = 2\n\
                position = [0, 0, 0]\nvelocity = [0, 0, 0]\n\
                [simulate]\ngravity = [0, 0, 0]\nduration = 0.5\noutput_step = 0.01\n\
                law = \"simultaneous\"\ncontact = { k = 0.5, mu = 0.4 }\n";
    let base = system(text);
    for law in [
        Law::Simultaneous(Restitution::Newton),
        Law::Simultaneous(Restitution::Energetic),
        Law::Unilateral(Restitution::Newton),
        Law::Lzb,
    ] {
        let mut s = base.clone();
        s.law = law;
        let sim = run(&s);
        assert!(!sim.impacts.is_empty(), "{law:?}");
        let momenta = |state: &inertance::simulate::system::SystemState| {
            let mut p = V3::zeros();
            let mut l = V3::zeros();
            for (b, member) in s.members.iter().enumerate() {
                let mv = state.v[b] * member.mass();
                p += mv;
                let r = state.rotation(b);
                l += state.x[b].cross(&mv) + member.body.world_inertia(&r) * state.w[b];
            }
            (p, l)
        };
        for impact in &sim.impacts {
            assert!(impact.contacts.iter().any(|c| c.impulse > 0.0));
            let at: Vec<_> = sim.samples.iter().filter(|x| x.t == impact.t).collect();
            assert_eq!(at.len(), 2);
            let (p0, l0) = momenta(&at[0].state);
            let (p1, l1) = momenta(&at[1].state);
            assert!(
                (p1 - p0).norm() <= 1e-12 * p0.norm(),
                "{law:?}: {p0} → {p1}"
            );
            assert!(
                (l1 - l0).norm() <= 1e-12 * (l0.norm() + p0.norm()),
                "{law:?}: {l0} → {l1}"
            );
            assert!(
                impact.kinetic_after <= impact.kinetic_before * (1.0 + 1e-12),
                "{law:?}"
            );
        }
    }
}

/// A box resting flat on a rough floor (μ = 0.3) closes its four corners at t = 0 and is at
/// rest there: no impact, no step. Each corner alone would tip the box about it and slip (its
/// sticking force would leave the cone), so it closes sliding and the loop tries again with it
/// sliding; a loop one try short left every corner open, and the box fell 10⁻¹¹ m onto the
/// floor and bounced three times at 10⁻⁶ s before its contacts closed.
#[test]
fn a_box_resting_on_a_rough_floor_closes_at_once() {
    let s = system(
        "[[body]]\nname = \"box\"\nshape = { box = [1, 1, 0.2] }\nmass = 5\n\
         position = [0, 0, 0.1]\nvelocity = [0, 0, 0]\n\
         [[obstacle]]\nname = \"floor\"\nnormal = [0, 0, 1]\n\
         [simulate]\ngravity = [0, 0, -9.81]\nduration = 1\nlaw = \"unilateral\"\n\
         contact = { k = 0.5, mu = 0.3 }\n",
    );
    let sim = simulate_system(&s);
    assert!(sim.stopped.is_none(), "{:?}", sim.stopped);
    assert!(sim.impacts.is_empty(), "{:?}", sim.impacts);
    let closing: Vec<_> = sim
        .events
        .iter()
        .filter(|e| e.what.ends_with("closes"))
        .collect();
    assert_eq!(closing.len(), 4, "{:?}", sim.events);
    assert!(closing.iter().all(|e| e.t == 0.0));
    assert_eq!(sim.end, inertance::simulate::End::Rest);
    assert_eq!(sim.t_end, 0.0);
    assert!((sim.state.x[0] - nalgebra::Vector3::new(0.0, 0.0, 0.1)).norm() <= 1e-15);
}
