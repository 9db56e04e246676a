//! The unilateral law with Coulomb friction in spatial scenes (issue 25): the adaptive
//! integrator's release and re-engagement ([`inertance::impact::friction::spatial`]) against
//! the exact planar answer, against its invariants, and with μ → 0 against the frictionless
//! unilateral law (Moreau's LCP, `src/impact/unilateral.rs`).
//!
//! A planar scene is taken out of the coordinate planes by turning it about the floor's normal
//! y by θ = 1 rad (cos θ and sin θ irrational): the solve then takes the spatial integrator,
//! whose twist, turned back, must match the exact planar one to its error estimate.

use inertance::impact::friction::{
    Frictional, Hypothesis, ModeLabel, Restitution, Verdict, solve_frictional_under,
};
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::dd::DoubleDouble;
use inertance::scalar::{Exact, Scalar, int, ratio};

/// x turned about y by the angle whose cosine and sine are `c`, `s`.
fn turn<T: Scalar>(c: &T, s: &T, x: Vec3<T>) -> Vec3<T> {
    Vec3::new(
        c.clone() * &x[0] + s.clone() * &x[2],
        x[1].clone(),
        -(s.clone() * &x[0]) + c.clone() * &x[2],
    )
}

/// The scene's numbers: Housner's block of tests/unilateral_friction.rs (half-width b,
/// half-height h, mass m, rocking at ω about its old corner A = (b, −h) on the floor y = −h;
/// contacts A then B = (−b, −h), normal −y, tangent +x), its centre's velocity shifted by
/// (u, w), a yaw rate `spin` about y, friction μ, restitution coefficients k_A, k_B.
#[derive(Clone, Copy)]
struct Block {
    b: (i64, i64),
    h: (i64, i64),
    m: (i64, i64),
    omega: (i64, i64),
    u: (i64, i64),
    w: (i64, i64),
    spin: (i64, i64),
    mu: (i64, i64),
    k: [(i64, i64); 2],
}

const HOUSNER: Block = Block {
    b: (3, 1),
    h: (4, 1),
    m: (3, 1),
    omega: (1, 1),
    u: (0, 1),
    w: (0, 1),
    spin: (0, 1),
    mu: (1, 2),
    k: [(0, 1), (0, 1)],
};

impl Block {
    /// The block turned by (c, s) about y, with an isotropic inertia m(b² + h²)/3 (so that
    /// turning it changes no inertia).
    fn problem<T: Scalar>(&self, c: &T, s: &T) -> Problem<T> {
        let r = |(p, q): (i64, i64)| ratio::<T>(p, q);
        let (b, h, m, omega) = (r(self.b), r(self.h), r(self.m), r(self.omega));
        let i = m.clone() * (b.clone() * &b + h.clone() * &h) / int::<T>(3);
        let corner = |x: T, k: T| {
            Contact::new(
                turn(c, s, Vec3::new(x, -h.clone(), T::zero())),
                Vec3::new(T::zero(), -T::one(), T::zero()),
                k,
            )
            .with_tangent(turn(c, s, Vec3::new(T::one(), T::zero(), T::zero())))
            .with_friction(r(self.mu))
        };
        Problem::new(
            RigidBody::principal(m, Vec3::new(i.clone(), i.clone(), i)),
            // v_C = ω ẑ × (C − A) = ω (−h, −b), plus (u, w).
            Screw::new(
                turn(c, s, Vec3::new(T::zero(), r(self.spin), omega.clone())),
                turn(
                    c,
                    s,
                    Vec3::new(
                        r(self.u) - omega.clone() * &h,
                        r(self.w) - omega * &b,
                        T::zero(),
                    ),
                ),
            ),
            vec![corner(b.clone(), r(self.k[0])), corner(-b, r(self.k[1]))],
        )
        .unwrap()
    }

    /// In the xy-plane, exactly (the planar solver, event by event).
    fn exact(&self, law: Restitution) -> Frictional<Exact> {
        let p = self.problem::<Exact>(&int(1), &int(0));
        solve_frictional_under(&p, law, Hypothesis::Unilateral, 0.0).unwrap()
    }

    /// Turned by θ = 1 rad, by the spatial integrator at the relative tolerance `tol`.
    fn turned(&self, law: Restitution, tol: f64) -> (Problem<f64>, Frictional<f64>) {
        let (s, c) = 1f64.sin_cos();
        let p = self.problem::<f64>(&c, &s);
        let f = solve_frictional_under(&p, law, Hypothesis::Unilateral, tol).unwrap();
        (p, f)
    }
}

/// The twist as six f64, the turned one turned back by −θ.
fn twist_back(f: &Frictional<f64>) -> [f64; 6] {
    let (s, c) = 1f64.sin_cos();
    let w = turn(&c, &(-s), f.velocity.top());
    let v = turn(&c, &(-s), f.velocity.bottom());
    [w[0], w[1], w[2], v[0], v[1], v[2]]
}

/// The turned integration's twist against the exact planar one: within the integrator's
/// estimate (which bounds the twist: module docs of `spatial`), plus the rounding of the
/// turn there and back (each component of a turned vector is a two-term sum of products,
/// 2ε relative to the vector's size per turn: 4ε × max|twist| for both).
fn matches_exact(block: &Block, law: Restitution, tol: f64) -> Frictional<f64> {
    let exact = block.exact(law);
    let (_, f) = block.turned(law, tol);
    let est = f.error_estimate.expect("the spatial integrator");
    let want: Vec<f64> = exact.velocity.0.iter().map(Scalar::to_f64).collect();
    let got = twist_back(&f);
    let size = want.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let bound = est + 4.0 * f64::EPSILON * size;
    for (g, x) in got.iter().zip(&want) {
        assert!(
            (g - x).abs() <= bound,
            "{law}, tol {tol:e}: twist {got:?} vs exact {want:?} (bound {bound:e})"
        );
    }
    // The histories agree: the spatial labels (`slide`) name no sense.
    for i in 0..2 {
        let planar: Vec<ModeLabel> = exact
            .history(i)
            .into_iter()
            .map(|m| match m {
                ModeLabel::SlidePlus | ModeLabel::SlideMinus => ModeLabel::Slide,
                m => m,
            })
            .collect();
        assert_eq!(
            f.history(i),
            planar,
            "{law}, tol {tol:e}, contact {}",
            i + 1
        );
    }
    f
}

#[test]
fn housner_block_turned_out_of_its_plane_keeps_the_ratio_23_over_50() {
    // b/h = 3/4: ω⁺/ω⁻ = 1 − (3/2)(3/5)² = 23/50 (Housner 1963); the exact planar solve gives
    // it exactly (tests/unilateral_friction.rs), the spatial one within its estimate.
    assert_eq!(
        HOUSNER.exact(Restitution::Newton).velocity.0[2],
        ratio(23, 50)
    );
    for tol in [1e-6, 1e-9] {
        let f = matches_exact(&HOUSNER, Restitution::Newton, tol);
        assert_eq!(f.history(0), vec![ModeLabel::Released]);
        // Released with no base rate, the old corner's impulse is exactly zero.
        assert_eq!(*f.normal_hat(0), 0.0);
        // The energetic law with k = 0 gives nothing back either: Housner again.
        let g = matches_exact(&HOUSNER, Restitution::Energetic, tol);
        assert_eq!(g.velocity.0, f.velocity.0);
    }
}

#[test]
fn a_turned_corner_re_engages_where_the_planar_one_does() {
    // tests/unilateral_friction.rs, `a_released_corner_re_engages_when_newtons_path_catches_it`:
    // A is released at s = 0 and re-engages on Newton's path at s = 32/17 — an event the
    // spatial integrator locates by its gap's margin.
    let block = Block {
        u: (-1, 1),
        w: (-2, 1),
        k: [(1, 1), (0, 1)],
        ..HOUSNER
    };
    let exact = block.exact(Restitution::Newton);
    let at: Vec<Exact> = exact.segments.iter().map(|g| g.from.clone()).collect();
    assert_eq!(at, vec![int(0), int(1), ratio(32, 17)]);
    for tol in [1e-6, 1e-9] {
        let f = matches_exact(&block, Restitution::Newton, tol);
        let est = f.error_estimate.unwrap();
        // The re-engagement is located within the estimate's reach of s = 32/17: A's normal
        // velocity, driven from there, ends at −k_A v_A⁰ = −2.
        assert!(
            (f.after[0] + 2.0).abs() <= est,
            "{} (est {est:e})",
            f.after[0]
        );
    }
    // Poisson's law: the planar answer, whatever its events.
    for tol in [1e-6, 1e-9] {
        matches_exact(&block, Restitution::Poisson, tol);
    }
}

#[test]
fn the_energetic_law_turned_out_of_its_plane_matches_the_planar_solve() {
    // k = 1/2 at both corners: the energetic stops are roots of quadratics (radicals), so the
    // planar reference is solved event by event in double-double, whose rounding (~10⁻³²
    // relative) is far below the f64 integration's estimate; the bound is that estimate plus
    // the rounding of the turn there and back, 4ε × max|twist|.
    for block in [
        Block {
            k: [(1, 2), (1, 2)],
            ..HOUSNER
        },
        Block {
            u: (-1, 1),
            w: (-2, 1),
            k: [(1, 1), (1, 5)],
            ..HOUSNER
        },
    ] {
        let (one, zero) = (int::<DoubleDouble>(1), int::<DoubleDouble>(0));
        let p = block.problem::<DoubleDouble>(&one, &zero);
        let planar =
            solve_frictional_under(&p, Restitution::Energetic, Hypothesis::Unilateral, 0.0)
                .unwrap();
        assert_eq!(planar.error_estimate, None, "the planar solver");
        let want: Vec<f64> = planar.velocity.0.iter().map(Scalar::to_f64).collect();
        let size = want.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        for tol in [1e-6, 1e-9] {
            let (_, f) = block.turned(Restitution::Energetic, tol);
            let est = f.error_estimate.unwrap();
            let got = twist_back(&f);
            let bound = est + 4.0 * f64::EPSILON * size;
            for (g, x) in got.iter().zip(&want) {
                assert!(
                    (g - x).abs() <= bound,
                    "tol {tol:e}: {got:?} vs {want:?} (bound {bound:e})"
                );
            }
        }
    }
}

/// The checks every outcome of the unilateral law must pass, to the estimate `est` (impulses
/// and velocities): the energy balance ΔE_c = Σ(W_c − W_r) + E_f with E_f ≥ 0, no contact
/// approaching after impact, every normal impulse ≥ 0 and every tangential one in its cone.
fn invariants(p: &Problem<f64>, f: &Frictional<f64>) {
    let est = f.error_estimate.expect("the spatial integrator");
    let kinetic = p.body().kinetic_energy(p.velocity());
    assert!(
        f.energy_balance_holds(&kinetic),
        "residual {}",
        f.energy_residual
    );
    let speed = f.blocks.v0.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    assert!(f.friction_dissipation >= -est * speed * 2.0 * f.blocks.len() as f64);
    assert!(
        !f.verdicts
            .iter()
            .any(|v| matches!(v, Verdict::StillApproaching { .. })),
        "{:?}",
        f.verdicts
    );
    for i in 0..f.blocks.contacts() {
        let off = f.blocks.offset[i];
        assert!(
            f.after[off] <= est,
            "contact {}: v = {}",
            i + 1,
            f.after[off]
        );
        let (_, t) = f.impulse_vectors(i);
        let pn = f.impulses[off];
        assert!(pn >= -est, "contact {}: p = {pn}", i + 1);
        let tau = (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt();
        let mu = f.blocks.mu[i];
        assert!(
            tau <= mu * pn + est,
            "contact {}: |τ| = {tau}, μp = {}",
            i + 1,
            mu * pn
        );
    }
}

#[test]
fn a_spinning_rocking_block_releases_its_old_corner_and_keeps_the_invariants() {
    // A yaw spin about the floor's normal makes both corners slip across the plane of the
    // rocking: a genuinely spatial impact. The friction of the two slips first presses the old
    // corner (it is driven, sliding, with p' ≥ 0) until its path needs a pull: a release
    // event in compression (s ≈ 0.06 for spin 1/2 rad/s); under Poisson's and the energetic
    // law it then takes its base rate k p^c > 0 in restitution, so it is labelled by its slip
    // there. The new corner slides.
    for law in [
        Restitution::Newton,
        Restitution::Poisson,
        Restitution::Energetic,
    ] {
        for spin in [(1, 2), (3, 1)] {
            let block = Block {
                spin,
                mu: (3, 10),
                k: [(1, 2), (1, 2)],
                ..HOUSNER
            };
            for tol in [1e-6, 1e-9] {
                let (p, f) = block.turned(law, tol);
                assert!(f.history(0).contains(&ModeLabel::Released), "{law}");
                assert!(f.history(1).contains(&ModeLabel::Slide), "{law}");
                invariants(&p, &f);
            }
        }
    }
}

#[test]
fn with_mu_to_zero_the_spinning_block_tends_to_moreaus_lcp() {
    // Frictionless, the unilateral integration of this landing is Moreau's LCP (one k at the
    // one approaching contact: derivations/unilateral-friction.md), which the yaw spin does not
    // touch (it moves neither corner along its normal). With μ > 0 the outcome is a smooth
    // function of μ near 0 with the same modes, so it differs from the LCP's by O(μ): the
    // difference must fall by a factor near 10 per decade of μ (≥ 5 is asserted, leaving the
    // O(μ²) term room) until it reaches the integrator's estimate.
    let block = Block {
        spin: (1, 1),
        k: [(1, 2), (1, 2)],
        ..HOUSNER
    };
    let (s, c) = 1f64.sin_cos();
    let lcp: Outcome<f64> = {
        let p = Block {
            mu: (0, 1),
            ..block
        }
        .problem::<f64>(&c, &s);
        let mut impact = Impact::assemble(&p).unwrap();
        let mut out = Outcome::default();
        impact.solve_unilateral(Model::Newton, &mut out).unwrap();
        out
    };
    let mut last: Option<f64> = None;
    for e in 2..=5 {
        let b = Block {
            mu: (1, 10i64.pow(e)),
            ..block
        };
        let (_, f) = b.turned(Restitution::Newton, 1e-11);
        let est = f.error_estimate.unwrap();
        let d = f
            .velocity
            .0
            .iter()
            .zip(lcp.velocity.0.iter())
            .fold(0.0f64, |a, (x, y)| a.max((x - y).abs()));
        if let Some(prev) = last {
            assert!(
                d <= (prev / 5.0).max(2.0 * est),
                "μ = 1e-{e}: {d:e} after {prev:e}"
            );
        }
        last = Some(d);
    }
}

/// `inertance solve` on `examples/rocking-block.toml` given a yaw rate of 1/2 rad/s about the
/// floor's normal: `[solve] law = "unilateral"` runs in the spatial integrator in f64 (the old
/// edge slides, then is released), and `--exact` refuses it with status 2 naming the fix.
#[test]
fn the_spinning_rocking_block_runs_the_unilateral_law_from_the_command_line() {
    let root = env!("CARGO_MANIFEST_DIR");
    let text = std::fs::read_to_string(format!("{root}/examples/rocking-block.toml")).unwrap();
    let spun = text.replace(
        "angular_velocity = [0, 1, 0]",
        "angular_velocity = [0, 1, 0.5]",
    );
    assert_ne!(spun, text, "the example's angular velocity line");
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("spinning-rocking.toml");
    std::fs::write(&path, spun).unwrap();
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
            .args(args)
            .arg(&path)
            .output()
            .unwrap()
    };
    let out = run(&["solve", "--json"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(j["effects"][0], "unilateral");
    let f = &j["friction"]["newton"];
    assert_eq!(f["method"], "spatial, adaptive RK5(4)", "{f}");
    let old = &f["contacts"][1];
    assert_eq!(
        old["modes"],
        serde_json::json!(["slide", "released"]),
        "{f}"
    );
    // Released, the old edge separates: its normal velocity after is negative (receding).
    let vn = old["normal_velocity_after"].as_f64().unwrap();
    assert!(vn < 0.0, "{vn}");
    assert_eq!(f["verdicts"], serde_json::json!([]), "{f}");
    let out = run(&["solve", "--exact"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("not planar") && err.contains("drop --exact"),
        "{err}"
    );
}
