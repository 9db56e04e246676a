//! A box's edges and thin rods in a system (`src/simulate/system/gaps.rs`: edge on edge, a
//! sphere on an edge or a corner, a rod's segment and ends): each impact against its closed form
//! (derivations/system-edges.md) and the conservation laws, and runs that stopped on an overlap
//! before the edges were watched.
//!
//! Tolerances: in space (no gravity) flight is exact to rounding, and each impact is found
//! within the gap tolerance 10⁻¹¹ L of contact (L the run's length scale, ≤ 1 m here), so its
//! time is within 10⁻¹¹ L/v of the closed form's; one contact's impact is a 1 × 1 solve, so
//! its velocities are the closed form's to rounding, 10⁻¹² of the speeds.

use inertance::scene::AnySimulation;
use inertance::simulate::system::{SystemSetup, SystemSimulation, SystemState, simulate_system};
use nalgebra::{Matrix3, Vector3};

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

/// The states just before and just after impact `k` (0-based).
fn around(sim: &SystemSimulation, k: usize) -> (SystemState, SystemState) {
    let t = sim.impacts[k].t;
    let mut at = sim.samples.iter().filter(|p| p.t == t);
    let before = at.next().expect("before").state.clone();
    let after = at.next().expect("after").state.clone();
    (before, after)
}

/// Σ m v, Σ (x × m v + R J Rᵀ ω) about the origin, and Σ ½ m |v|² + ½ ωᵀ R J Rᵀ ω.
fn momenta(s: &SystemSetup, st: &SystemState) -> (V3, V3, f64) {
    let mut p = V3::zeros();
    let mut l = V3::zeros();
    for (b, m) in s.members.iter().enumerate() {
        let r = st.rotation(b);
        p += st.v[b] * m.mass();
        l += st.x[b].cross(&(st.v[b] * m.mass())) + m.body.world_inertia(&r) * st.w[b];
    }
    (p, l, st.kinetic_energy(&s.members))
}

/// The conservation checks of one frictionless impact: momentum and angular momentum to 10⁻¹²
/// of their scales, energy kept for k = 1, and the normal rate after −k times before.
fn conserves(s: &SystemSetup, sim: &SystemSimulation, k: f64) {
    let (before, after) = around(sim, 0);
    let ((p0, l0, e0), (p1, l1, e1)) = (momenta(s, &before), momenta(s, &after));
    let scale = p0.norm().max(l0.norm());
    assert!((p1 - p0).norm() <= 1e-12 * scale, "p {p0} → {p1}");
    assert!((l1 - l0).norm() <= 1e-12 * scale, "L {l0} → {l1}");
    if k == 1.0 {
        assert!((e1 - e0).abs() <= 1e-12 * e0, "energy {e0} → {e1}");
    } else {
        assert!(e1 < e0, "energy {e0} → {e1}");
    }
    let c = &sim.impacts[0].contacts[0];
    assert!(c.before < 0.0);
    assert!(
        (c.after + k * c.before).abs() <= 1e-12 * c.before.abs(),
        "{} → {}",
        c.before,
        c.after
    );
}

/// Two cubes (side 0.2 m; A of 2 kg, B of 3 kg) in space, A turned 45° about x and moving down
/// at v = 1 m/s onto B turned 45° about y, at rest: A's lowest edge (along x) crosses B's
/// highest (along y) at right angles, both through the line of the centres. The impulse is
/// along z through both centres: a central impact of two masses, at t = (d − 0.2√2)/v
/// (each edge 0.1√2 from its centre), after which v_A = −(m_A − k m_B) v/(m_A + m_B),
/// v_B = −(1 + k) m_A v/(m_A + m_B) along z and neither spins — for k = 1 and k = 1/2.
/// Times to 10⁻¹² s, velocities to 10⁻¹² m/s (module docs).
#[test]
fn crossed_cubes_strike_edge_on_edge_as_two_masses() {
    for k in [1.0, 0.5] {
        let s = system(&format!(
            r#"
[[body]]
name = "A"
shape = {{ box = [0.2, 0.2, 0.2] }}
mass = 2
pose = [{{ axis = [1, 0, 0], angle = "45 deg" }}]
position = [0, 0, 0.5]
velocity = [0, 0, -1]
[[body]]
name = "B"
shape = {{ box = [0.2, 0.2, 0.2] }}
mass = 3
pose = [{{ axis = [0, 1, 0], angle = "45 deg" }}]
position = [0, 0, 0]
velocity = [0, 0, 0]
[simulate]
gravity = [0, 0, 0]
duration = 0.5
law = "unilateral"
contact = {{ k = {k} }}
"#
        ));
        let sim = run(&s);
        assert_eq!(sim.impacts.len(), 1, "k = {k}");
        let i = &sim.impacts[0];
        let meet = 0.5 - 0.2 * 2f64.sqrt();
        assert!(
            (i.t - meet).abs() <= 1e-12,
            "k = {k}: t = {} vs {meet}",
            i.t
        );
        assert_eq!(i.contacts.len(), 1, "{:?}", i.contacts);
        assert_eq!(
            (i.contacts[0].feature.as_str(), i.contacts[0].plane.as_str()),
            ("A edge [*, -1, -1]", "B edge [-1, *, 1]")
        );
        let (_, after) = around(&sim, 0);
        let (ma, mb, v) = (2.0, 3.0, 1.0);
        let want = [
            -(ma - k * mb) * v / (ma + mb),
            -(1.0 + k) * ma * v / (ma + mb),
        ];
        for (b, want) in want.iter().enumerate() {
            let got = after.v[b];
            assert!(
                (got - V3::z() * *want).norm() <= 1e-12,
                "k = {k}, body {b}: {got} vs {want}"
            );
            assert!(after.w[b].norm() <= 1e-12, "k = {k}: ω {}", after.w[b]);
        }
        conserves(&s, &sim, k);
    }
}

/// Two cubes in space meeting edge on edge off their centres: A (2 kg) turned 45° about x and
/// yawed 20°, spinning about z and drifting, falls onto B (3 kg) turned 45° about y, so that
/// A's lowest edge crosses B's highest at 70°, about 0.03 m from both centres' vertical. One
/// frictionless contact, so momentum and angular momentum about the origin are kept, energy
/// too for k = 1, and the normal relative velocity after is −k times before (Newton's law),
/// each to 10⁻¹² — for k = 1 and k = 1/2. B starts to turn: the impulse has a moment about its
/// centre.
#[test]
fn an_off_centre_edge_impact_keeps_momentum_and_obeys_newton() {
    for k in [1.0, 0.5] {
        let s = system(&format!(
            r#"
[[body]]
name = "A"
shape = {{ box = [0.2, 0.2, 0.2] }}
mass = 2
pose = [{{ axis = [1, 0, 0], angle = "45 deg" }}, {{ axis = [0, 0, 1], angle = "20 deg" }}]
position = [0.03, -0.02, 0.5]
velocity = [0.05, 0, -1]
angular_velocity = [0.02, 0, 0.5]
[[body]]
name = "B"
shape = {{ box = [0.2, 0.2, 0.2] }}
mass = 3
pose = [{{ axis = [0, 1, 0], angle = "45 deg" }}]
position = [0, 0, 0]
velocity = [0, 0, 0]
[simulate]
gravity = [0, 0, 0]
duration = 0.5
law = "unilateral"
contact = {{ k = {k} }}
"#
        ));
        let sim = run(&s);
        assert!(!sim.impacts.is_empty());
        let i = &sim.impacts[0];
        assert_eq!(i.contacts.len(), 1, "{:?}", i.contacts);
        assert!(
            i.contacts[0].feature.starts_with("A edge")
                && i.contacts[0].plane.starts_with("B edge"),
            "{:?}",
            i.contacts[0]
        );
        let (before, after) = around(&sim, 0);
        assert!((after.w[1] - before.w[1]).norm() > 1e-3, "B does not turn");
        conserves(&s, &sim, k);
    }
}

/// A ball (radius 0.05 m, 0.5 kg) in space falling at 1 m/s past a box's top edge (along y at
/// x = 0.2, z = 0.1; the box 0.4 × 0.3 × 0.2 m, 4 kg, at rest, centred at the origin), its
/// centre a = 0.03 m beyond the box's side: it meets the edge where a² + (z − 0.1)² = ρ², at
/// n = (a, 0, √(ρ² − a²))/ρ from the edge to the centre. One frictionless contact: the impulse
/// P n with P = −(1 + k) m* (n · u), u = (0, 0, −1) the relative velocity and
/// 1/m* = 1/m_s + 1/m_b + (r × n) · J_b⁻¹ (r × n) (r = (0.2, 0, 0.1) the edge point from the
/// box's centre); the ball leaves at u + P n/m_s, the box at −P n/m_b turning at
/// −J_b⁻¹ (r × n) P. Time to 10⁻¹² s, velocities to 10⁻¹² m/s.
#[test]
fn a_ball_on_a_box_edge_rebounds_as_the_closed_form() {
    let (rho, a, z0, ms, mb): (f64, f64, f64, f64, f64) = (0.05, 0.03, 0.4, 0.5, 4.0);
    let k = 0.5;
    let s = system(&format!(
        r#"
[[body]]
name = "ball"
shape = {{ sphere = {rho} }}
mass = {ms}
position = [{x}, 0, {z0}]
velocity = [0, 0, -1]
[[body]]
name = "box"
shape = {{ box = [0.4, 0.3, 0.2] }}
mass = {mb}
position = [0, 0, 0]
velocity = [0, 0, 0]
[simulate]
gravity = [0, 0, 0]
duration = 0.5
law = "unilateral"
contact = {{ k = {k} }}
"#,
        x = 0.2 + a
    ));
    let sim = run(&s);
    assert_eq!(sim.impacts.len(), 1);
    let i = &sim.impacts[0];
    assert_eq!(
        (i.contacts[0].feature.as_str(), i.contacts[0].plane.as_str()),
        ("ball", "box edge [1, *, 1]")
    );
    let h = (rho * rho - a * a).sqrt();
    assert!((i.t - (z0 - 0.1 - h)).abs() <= 1e-12, "t = {}", i.t);
    let n = V3::new(a, 0.0, h) / rho;
    let r = V3::new(0.2, 0.0, 0.1);
    let j = |p: f64, q: f64| mb * (p * p + q * q) / 12.0;
    let jinv = Matrix3::from_diagonal(&V3::new(
        1.0 / j(0.3, 0.2),
        1.0 / j(0.4, 0.2),
        1.0 / j(0.4, 0.3),
    ));
    let rn = r.cross(&n);
    let mstar = 1.0 / (1.0 / ms + 1.0 / mb + rn.dot(&(jinv * rn)));
    let u = V3::new(0.0, 0.0, -1.0);
    let p = -(1.0 + k) * mstar * n.dot(&u);
    let (_, after) = around(&sim, 0);
    let want = [u + n * (p / ms), -n * (p / mb)];
    for (b, want) in want.iter().enumerate() {
        assert!(
            (after.v[b] - want).norm() <= 1e-12,
            "{b}: {} vs {want}",
            after.v[b]
        );
    }
    assert!(
        (after.w[1] + jinv * rn * p).norm() <= 1e-12,
        "{}",
        after.w[1]
    );
    conserves(&s, &sim, k);
}

/// A thin rod (L = 0.8 m, 1 kg) in space falling at 1 m/s crosswise onto a box's top edge
/// (along y at x = 0.2, z = 0.1; the box 0.4 × 0.3 × 0.2 m, 4 kg, at rest), the rod tilted
/// β = 30° up over the box (its axis d = (−cos β, 0, sin β)) with its centre 0.1 m beyond the
/// edge: the segment meets the edge at n = (sin β, 0, cos β) (⟂ both), at the point s from the
/// rod's centre along d where its line crosses the edge's. One frictionless contact: P =
/// −(1 + k) m* (n · u), 1/m* = 1/m_r + 12 s²/(m_r L²) + 1/m_b + (r_b × n) · J_b⁻¹ (r_b × n)
/// (the rod's moment s d × n has |d × n| = 1); the rod leaves at u + P n/m_r turning at
/// 12 s (d × n) P/(m_r L²) (derivations/system-edges.md). Time: the gap n · (c − p_e) closes at
/// v cos β. Time to 10⁻¹² s, velocities to 10⁻¹² (m/s, rad/s).
#[test]
fn a_rod_across_a_box_edge_rebounds_as_the_closed_form() {
    let (l, mr, mb, beta): (f64, f64, f64, f64) = (0.8, 1.0, 4.0, 30f64.to_radians());
    let k = 0.5;
    let d = V3::new(-beta.cos(), 0.0, beta.sin());
    let n = V3::new(beta.sin(), 0.0, beta.cos());
    let edge = V3::new(0.2, 0.0, 0.1);
    // the centre 0.1 m beyond the edge, and 0.2 m above the point of the line over the edge
    let c0 = V3::new(0.3, 0.0, 0.1 + 0.1 * beta.tan() + 0.2);
    let s = system(&format!(
        r#"
[[body]]
name = "stick"
shape = {{ rod = {l} }}
mass = {mr}
pose = [{{ axis = [0, 1, 0], angle = "{tilt} deg" }}]
position = [{}, {}, {}]
velocity = [0, 0, -1]
[[body]]
name = "box"
shape = {{ box = [0.4, 0.3, 0.2] }}
mass = {mb}
position = [0, 0, 0]
velocity = [0, 0, 0]
[simulate]
gravity = [0, 0, 0]
duration = 0.5
law = "unilateral"
contact = {{ k = {k} }}
"#,
        c0.x,
        c0.y,
        c0.z,
        // body z onto d: a turn of −(90° − β) about y takes z to (−cos β, 0, sin β)
        tilt = -(90.0 - 30.0),
    ));
    let sim = run(&s);
    assert!(!sim.impacts.is_empty());
    let i = &sim.impacts[0];
    assert_eq!(i.contacts.len(), 1, "{:?}", i.contacts);
    assert_eq!(
        (i.contacts[0].feature.as_str(), i.contacts[0].plane.as_str()),
        ("stick rod", "box edge [1, *, 1]")
    );
    let meet = n.dot(&(c0 - edge)) / beta.cos();
    assert!((i.t - meet).abs() <= 1e-12, "t = {} vs {meet}", i.t);
    let (before, after) = around(&sim, 0);
    // the point of the rod's line on the edge: c + s d with (c + s d − edge) ∥ y ⊥ …: its x
    // and z are the edge's (the lines cross at the impact)
    let c = before.x[0];
    let sd = (edge.x - c.x) / d.x;
    let rb = edge + V3::y() * c.y;
    let j = |p: f64, q: f64| mb * (p * p + q * q) / 12.0;
    let jinv = Matrix3::from_diagonal(&V3::new(
        1.0 / j(0.3, 0.2),
        1.0 / j(0.4, 0.2),
        1.0 / j(0.4, 0.3),
    ));
    let rn = rb.cross(&n);
    let rod_j = mr * l * l / 12.0;
    let mstar = 1.0 / (1.0 / mr + sd * sd / rod_j + 1.0 / mb + rn.dot(&(jinv * rn)));
    let u = V3::new(0.0, 0.0, -1.0);
    let p = -(1.0 + k) * mstar * n.dot(&u);
    assert!(
        (after.v[0] - (u + n * (p / mr))).norm() <= 1e-12,
        "{}",
        after.v[0]
    );
    let spin = d.cross(&n) * (sd * p / rod_j);
    assert!(
        (after.w[0] - spin).norm() <= 1e-12,
        "{} vs {spin}",
        after.w[0]
    );
    assert!(
        (after.v[1] + n * (p / mb)).norm() <= 1e-12,
        "{}",
        after.v[1]
    );
    assert!(
        (after.w[1] + jinv * rn * p).norm() <= 1e-12,
        "{}",
        after.w[1]
    );
    conserves(&s, &sim, k);
}

/// A vertical thin rod (L = 0.6 m, 1 kg) in space falling end first at 1 m/s onto a ball
/// (radius 0.1 m, 2 kg, at rest at the origin), its axis a = 0.04 m beside the ball's centre:
/// the lower end meets the ball where a² + z² = ρ², at n = (a, 0, √(ρ² − a²))/ρ from the ball's
/// centre to the end. One frictionless contact: P = −(1 + k) m* (n · u) with u the end's
/// velocity relative to the ball and 1/m* = 1/m_r + 1/m_s + (r × n) · J_r⁻¹ (r × n), r =
/// (0, 0, −L/2), |r × n|² = (L/2)² (a/ρ)²: the ball leaves at −P n/m_s. Time to 10⁻¹² s,
/// velocities to 10⁻¹² m/s; momentum, angular momentum, Newton's law (k = 1/2).
#[test]
fn a_rod_end_on_a_ball_rebounds_as_the_closed_form() {
    let (l, mr, rho, ms, a): (f64, f64, f64, f64, f64) = (0.6, 1.0, 0.1, 2.0, 0.04);
    let k = 0.5;
    let z0 = 0.3 + 0.2 + l / 2.0;
    let s = system(&format!(
        r#"
[[body]]
name = "ball"
shape = {{ sphere = {rho} }}
mass = {ms}
position = [0, 0, 0]
velocity = [0, 0, 0]
[[body]]
name = "rod"
shape = {{ rod = {l} }}
mass = {mr}
position = [{a}, 0, {z0}]
velocity = [0, 0, -1]
[simulate]
gravity = [0, 0, 0]
duration = 0.6
law = "unilateral"
contact = {{ k = {k} }}
"#
    ));
    let sim = run(&s);
    assert!(!sim.impacts.is_empty());
    let i = &sim.impacts[0];
    assert_eq!(i.contacts.len(), 1, "{:?}", i.contacts);
    assert_eq!(
        (i.contacts[0].feature.as_str(), i.contacts[0].plane.as_str()),
        ("ball", "rod end [0, 0, -1]")
    );
    let h = (rho * rho - a * a).sqrt();
    assert!((i.t - (z0 - l / 2.0 - h)).abs() <= 1e-12, "t = {}", i.t);
    // n from the end to the ball's centre (out of the rod), as the contact's normal
    let n = -V3::new(a, 0.0, h) / rho;
    let r = V3::new(0.0, 0.0, -l / 2.0);
    let rn = r.cross(&n);
    let rod_j = mr * l * l / 12.0;
    let mstar = 1.0 / (1.0 / mr + 1.0 / ms + rn.norm_squared() / rod_j);
    // the ball relative to the end: the ball is at rest, the end falls
    let u = V3::new(0.0, 0.0, 1.0);
    let p = -(1.0 + k) * mstar * n.dot(&u);
    let (_, after) = around(&sim, 0);
    assert!(
        (after.v[0] - n * (p / ms)).norm() <= 1e-12,
        "{}",
        after.v[0]
    );
    assert!(
        (after.v[1] - (-u - n * (p / mr))).norm() <= 1e-12,
        "{}",
        after.v[1]
    );
    conserves(&s, &sim, k);
}
