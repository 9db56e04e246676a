//! `simulate` against Siconos's event-driven rocking block (`siconos-tutorials`,
//! `examples/mechanics/RockingBlock/RockingBlockED_Lsodar_LZBimpact.cpp`, commit b6c9bfd of
//! 2024-07-24; its published output `RockingBlockED_Lsodar_LZBimpact.ref`, Apache 2.0, copied
//! verbatim into `tests/data/siconos/`). Siconos integrates the flight with Lsodar and each
//! impact with its LZB `MultipleImpact` (e = 0.8 at both corners, K = 10¹⁰, η = 1, impulse step
//! ΔP = 5·10⁻⁵ N s) and writes a row every 0.01 s plus two rows (before, after) at each impact.
//!
//! **The model as Siconos has it** (derivations/siconos-rocking-block.md): the mass matrix is
//! that of a 1 × 0.5 m block of 1 kg, J = m(L² + H²)/12 = 0.1041 6̅ kg m², but the gap
//! functions of its plugin (`RockingBlockPlugin.cpp`) are those of a 0.2 × 0.1 m block, and the
//! start places corner A of the *large* block on the floor at θ₀ = π/3. So the body starts
//! 0.45 m above the floor, falls without turning, and lands on one corner; every impact of the
//! run is a one-contact impact (the corners are 0.2 m apart, never both within the gap
//! tolerance). It is reproduced here as it is — a body with that inertia and those corners
//! (the scene format derives the inertia from the shape, so the body is built here) — and the
//! two-contact landing it does not exercise is added below with a consistent block.
//!
//! **What differs and by how much (the tolerance).** Flight is exact in both (a quadratic
//! in t; θ linear). Each of Siconos's impacts is integrated in steps of ΔP in the normal
//! impulse and ends at the first step past the end of expansion: its impulse is off by less
//! than ΔP, so v_y by less than ΔP/m_eff ≲ 5·10⁻⁵ m/s and ω by less than ΔP |r_x|/J (measured
//! at the first impact: 1.6·10⁻⁵ m/s and 1.0·10⁻⁶ rad/s, against the closed form of a
//! one-contact impact with e = 0.8, which this simulation reproduces to its tolerance). Those errors
//! carry into the next flight (its duration ~ 2v/g, a few 10⁻⁶ s per 10⁻⁵ m/s) and into where
//! the next corner strikes; the test holds each impact time, velocity and angle to
//! 10 ΔP/m_eff-scaled bounds stated with the checks, and reports the largest differences.

use inertance::scene::SimulationScene;
use std::f64::consts::PI;

use inertance::simulate::{Body, End, Feature, Shape, simulate};
use nalgebra::{Matrix3, UnitQuaternion, Vector3};

const REF: &str = include_str!("data/siconos/RockingBlockED_Lsodar_LZBimpact.ref");

/// The .ref's rows: t, x, y, θ, vx, vy, ω, gaps, relative velocities, forces (13 columns);
/// trailing all-zero rows (the unused rows of Siconos's preallocated table) dropped.
fn reference() -> Vec<[f64; 13]> {
    let mut rows: Vec<[f64; 13]> = REF
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .map(|x| x.parse().expect("a number"))
                .collect();
            v.try_into().expect("13 columns")
        })
        .collect();
    while rows.last().is_some_and(|r| r.iter().all(|x| *x == 0.0)) {
        rows.pop();
    }
    rows
}

/// Siconos's block in the scene's world: its (x, y) plane is our (x, z), its θ (counter-
/// clockwise in x–y) a rotation by −θ about our y.
const SCENE: &str = r#"
name = "Siconos's rocking block (RockingBlockED_Lsodar_LZBimpact)"
[body]
shape = { box = [0.2, 0.1, 0.1] }
mass = 1
pose = { axis = [0, 1, 0], angle = "-pi/3" }
position = ["0.5*cos(pi/3) - 0.25*sin(pi/3)", 0, "0.5*sin(pi/3) + 0.25*cos(pi/3)"]
velocity = [0, 0, 0]
angular_velocity = [0, 0, 0]
[[obstacle]]
name = "floor"
normal = [0, 0, 1]
point = [0, 0, 0]
[simulate]
gravity = [0, 0, -9.81]
duration = 2
output_step = 0.01
plane = [0, 1, 0]
law = "lzb"
contact = { k_energetic = 0.8, stiffness = 1e10, exponent = 1 }
"#;

/// θ (Siconos's sign) of a state's rotation about y.
fn theta(q: &UnitQuaternion<f64>) -> f64 {
    let x = q * Vector3::x();
    x.z.atan2(x.x)
}

#[test]
fn siconos_rocking_block_is_reproduced_impact_by_impact() {
    let mut scene = SimulationScene::parse(SCENE, "siconos-rocking-block.toml").expect("reads");
    // Siconos's mass matrix: the 1 × 0.5 m block's J about the axis of rotation.
    let j = 1.0 / 12.0 * (1.0 + 0.25);
    let half = match &scene.setup.body.shape {
        Shape::Box { half } => *half,
        _ => unreachable!("a box"),
    };
    scene.setup.body = Body::new(
        1.0,
        Matrix3::from_diagonal(&Vector3::new(j, j, j)),
        Shape::Box { half },
        Some(Vector3::y()),
    )
    .expect("invertible");
    // Siconos's two contacts only: the corners A = (−L/2, −H/2), B = (L/2, −H/2) of its plugin
    // (the top corners are not in its model, and the block turns past 90° before 2 s).
    scene.setup.body.features.retain(|f| match f {
        Feature::Point { at, .. } => at.z < 0.0,
        Feature::Sphere { .. } | Feature::Rim { .. } => false,
    });
    assert_eq!(scene.setup.body.features.len(), 2);
    let sim = simulate(&scene.setup).expect("the run ends");
    assert_eq!(sim.end, End::Duration);
    let rows = reference();
    // The impacts: the pairs of rows at one time (before, after).
    let pairs: Vec<(&[f64; 13], &[f64; 13])> = rows
        .windows(2)
        .filter(|w| w[0][0] == w[1][0] && w[0][0] > 0.0)
        .map(|w| (&w[0], &w[1]))
        .collect();
    assert_eq!(pairs.len(), 7, "Siconos's run has seven impacts");
    assert_eq!(
        sim.impacts.len(),
        pairs.len(),
        "one impact of ours per impact of Siconos's"
    );
    // The first impact against its closed form: one frictionless contact, e = 0.8, with
    // r_x = −(L/2) cos θ + (H/2) sin θ from C to corner A (Siconos's axes): P = −(1 + e) v_y /
    // (1/m + r_x²/J), v_y⁺ = v_y + P/m, ω⁺ = r_x P/J. Ours is the closed form to the integration's tolerance;
    // Siconos's is within ΔP/m_eff of it (its impulse steps).
    let (before, after) = pairs[0];
    let rx = -0.1 * (PI / 3.0).cos() + 0.05 * (PI / 3.0).sin();
    let p = -1.8 * before[5] / (1.0 + rx * rx / j);
    let (vy, w) = (before[5] + p, rx * p / j);
    let first = &sim
        .samples
        .iter()
        .find(|s| s.t > sim.impacts[0].t)
        .expect("a sample after");
    let dp = 5e-5; // Siconos's impulse step ΔP (N s)
    assert!(
        (after[5] - vy).abs() < dp,
        "Siconos's first rebound within ΔP/m of the closed form"
    );
    assert!((after[6] - w).abs() < dp * rx.abs() / j);
    // ours: the LZB integration to the relative tolerance 10⁻¹⁰ (one contact: no event inside)
    assert!(
        (-first.state.w.y - w).abs() < 1e-9 * w.abs(),
        "ours is the closed form to the tolerance: {}",
        -first.state.w.y
    );
    // Impact by impact: the time, and the twist before. Each of Siconos's impacts errs by less
    // than ΔP/m_eff ≈ 5·10⁻⁵ m/s in v (and ΔP |r_x|/J in ω; |r_x| ≤ 0.11 m, so 5·10⁻⁵ rad/s);
    // n impacts later the accumulated velocity error is below 2n ΔP/m_eff with the arm's
    // lever on ω (|r_x|/J ≤ 1.1, ≤ 2 per impact counting the flight's angle), and the time of
    // the next impact moves by (the error of the rebound speed)·2/g plus the angle's
    // share — a few 10⁻⁵ s. The bounds below are those, with a factor 2 for the flight's
    // geometry: 2·10⁻⁴ (k+1) m/s, 5·10⁻⁴ (k+1) rad/s, 2·10⁻⁵ (k+1) s at impact k (0-based).
    let mut worst = [0.0f64; 3];
    for (k, ((before, _), ours)) in pairs.iter().zip(&sim.impacts).enumerate() {
        let n = (k + 1) as f64;
        let dt = (ours.t - before[0]).abs();
        let state = sim
            .samples
            .iter()
            .rev()
            .find(|s| s.t <= ours.t)
            .expect("a sample before the impact");
        // the twist just before, flown from the last sample (ballistic, ω constant)
        let tau = ours.t - state.t;
        let vz = state.state.v.z - 9.81 * tau;
        let w = -state.state.w.y;
        let (dv, dw) = ((vz - before[5]).abs(), (w - before[6]).abs());
        assert!(
            dt < 2e-5 * n,
            "impact {}: t {} against {}",
            k + 1,
            ours.t,
            before[0]
        );
        assert!(
            dv < 2e-4 * n,
            "impact {}: v_y⁻ {vz} against {}",
            k + 1,
            before[5]
        );
        assert!(
            dw < 5e-4 * n,
            "impact {}: ω⁻ {w} against {}",
            k + 1,
            before[6]
        );
        worst = [worst[0].max(dt), worst[1].max(dv), worst[2].max(dw)];
    }
    // The trajectory at Siconos's rows every 0.01 s: positions within the velocity bound times
    // the time flown since the impact, plus the time shift times the speed (≤ 3 m/s).
    let mut dz_max = 0.0f64;
    for s in &sim.samples {
        let Some(r) = rows.iter().find(|r| (r[0] - s.t).abs() < 1e-12) else {
            continue;
        };
        let k = sim.impacts.iter().filter(|i| i.t <= s.t).count() as f64;
        let dz = (s.state.x.z - r[2]).abs();
        let dth = (theta(&s.state.q) - r[3]).abs();
        assert!(
            dz < (2e-4 * 0.5 + 3.0 * 2e-5) * (k + 1.0),
            "t {}: z {} against {}",
            s.t,
            s.state.x.z,
            r[2]
        );
        assert!(
            dth < 5e-4 * 0.5 * (k + 1.0),
            "t {}: θ against {}",
            s.t,
            r[3]
        );
        assert!(
            (s.state.x.x - r[1]).abs() < 1e-12,
            "no horizontal force: x stays"
        );
        dz_max = dz_max.max(dz);
    }
    eprintln!(
        "largest differences from Siconos: impact time {:.1e} s, v⁻ {:.1e} m/s, ω⁻ {:.1e} rad/s, \
         z {:.1e} m",
        worst[0], worst[1], worst[2], dz_max
    );
}

/// The landing Siconos's model does not exercise: the same block with consistent geometry
/// (1 × 0.5 m, the corners of its mass matrix), released at θ₀ = π/3 on corner A. On the
/// frictionless floor nothing pushes C sideways: x_C stays, A slides, and with A on the floor
/// y_C = (L/2) sin θ + (H/2) cos θ, so ẏ_C = ((L/2) cos θ − (H/2) sin θ) θ̇ and at θ = 0
/// energy gives ½ (m (L/2)² + J) ω² = m g (y_C(θ₀) − H/2): the block lands flat with that ω,
/// on B while A is closed — a two-contact impact, solved by LZB (e = 0.8, equal K, η = 1).
#[test]
fn the_consistent_block_lands_flat_on_both_corners_at_the_energy_s_speed() {
    let text = SCENE
        .replace("box = [0.2, 0.1, 0.1]", "box = [1, 0.5, 0.5]")
        .replace("duration = 2", "duration = 0.6");
    let scene = SimulationScene::parse(&text, "consistent-block.toml").expect("reads");
    let sim = simulate(&scene.setup).expect("the run ends");
    let landing = sim.impacts.first().expect("it lands");
    assert_eq!(
        landing.contacts.len(),
        2,
        "both corners of the lower face strike together"
    );
    let (m, g, l, h) = (1.0, 9.81, 1.0, 0.5);
    let j = m * (l * l + h * h) / 12.0;
    let drop = (l / 2.0) * (PI / 3.0).sin() + (h / 2.0) * (PI / 3.0).cos() - h / 2.0;
    let omega = (2.0 * m * g * drop / (m * l * l / 4.0 + j)).sqrt();
    // the twist just before, from the kinetic energy the log keeps: ½ (m (L/2)² + J) ω²
    let w_before = (2.0 * landing.kinetic_before / (m * l * l / 4.0 + j)).sqrt();
    // persistent sliding contact integrated to 10⁻¹⁰ per step over ~100 steps: 10⁻⁷
    assert!(
        (w_before - omega).abs() < 1e-7 * omega,
        "landing at ω = {w_before}, energy says {omega}"
    );
    assert!(landing.kinetic_after < landing.kinetic_before);
    assert!(landing.verdicts.is_empty());
}
