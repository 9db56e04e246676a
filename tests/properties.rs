//! Property tests of the solver: invariants in exact rationals (equality is equality), then
//! f64 against the exact result.

mod common;

use common::*;
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome, SolveError};
use inertance::mechanics::body::inertance_eq57;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::{Exact, Scalar};
use num_traits::{One, Zero};
use proptest::prelude::*;

/// Assemble and solve both models exactly; `None` when G is singular (Δ = 0).
fn solve_exact(p: &Problem<Exact>) -> Option<(Impact<Exact>, Outcome<Exact>, Outcome<Exact>)> {
    let mut impact = Impact::assemble(p).expect("no imposed tangents");
    let (mut n, mut q) = (Outcome::default(), Outcome::default());
    match impact.solve(Model::Newton, &mut n) {
        Err(SolveError::Singular { .. }) => return None,
        other => other.expect("solve"),
    }
    impact.solve(Model::Poisson, &mut q).expect("same G");
    Some((impact, n, q))
}

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 192,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config())]

    /// eq. 34: ΔE_c = −E_p + Σ P_i v_ix⁰, with E_p from the velocity change (eq. 28) and
    /// ΔE_c from the kinetic energies (eq. 32) — two independent computations.
    #[test]
    fn energy_identity_holds_exactly(p in problem(4)) {
        let Some((impact, n, q)) = solve_exact(&p) else { return Ok(()) };
        for out in [&n, &q] {
            let work = impact.impulse_work(out);
            prop_assert_eq!(out.kinetic_energy_loss.clone(), work - &out.lost_velocity_energy);
        }
    }

    /// eq. 14: after a Newton impact v_ix = −k_i^N v_ix⁰ at every contact, checked on the
    /// contact-point velocity recomputed from the twist after impact (not from eq. 13).
    #[test]
    fn newton_post_condition_holds_exactly(p in problem(4)) {
        let Some((impact, n, _)) = solve_exact(&p) else { return Ok(()) };
        for (i, c) in p.contacts().iter().enumerate() {
            let after = impact.frames()[i].axes[0].reciprocal(&n.velocity);
            prop_assert_eq!(after, -(c.k_newton.clone() * &impact.before_hat()[i][0]));
        }
    }

    /// Poisson: the compression impulses bring every normal velocity to zero (eq. 21).
    #[test]
    fn poisson_compression_stops_every_contact(p in problem(4)) {
        let Some((impact, _, q)) = solve_exact(&p) else { return Ok(()) };
        let mut v = p.velocity().clone();
        for (pc, r) in q.compression_hat.iter().zip(impact.responses()) {
            v.add_scaled(&-pc.clone(), r);
        }
        for f in impact.frames() {
            prop_assert!(f.axes[0].reciprocal(&v).is_zero());
        }
    }

    /// eq. 10: M({v} − {v⁰}) = −Σ P_i {E_ix}, with M applied independently of M⁻¹.
    #[test]
    fn momentum_balance_holds_exactly(p in problem(4)) {
        let Some((impact, n, _)) = solve_exact(&p) else { return Ok(()) };
        let mut dv = n.velocity.clone();
        dv.add_scaled(&-Exact::one(), p.velocity());
        let lhs = p.body().momentum(&dv);
        let mut rhs = Screw::zero();
        for (pi, f) in n.impulses_hat.iter().zip(impact.frames()) {
            rhs.add_scaled(&-pi.clone(), &f.axes[0]);
        }
        prop_assert_eq!(lhs, rhs);
    }

    /// The inertances equal eq. (57) written out, G is symmetric, and the tangential
    /// velocities after impact by eq. (25–26) equal the frame components of the new twist.
    #[test]
    fn inertances_and_tangential_velocities(p in problem(3)) {
        let Some((impact, n, _)) = solve_exact(&p) else { return Ok(()) };
        let k = p.contacts().len();
        for i in 0..k {
            for j in 0..k {
                let gij = inertance_eq57(p.body(), &impact.frames()[i].axes[0], &impact.frames()[j].axes[0]);
                prop_assert_eq!(&impact.g_hat()[i * k + j], &gij);
                prop_assert_eq!(&impact.g_hat()[i * k + j], &impact.g_hat()[j * k + i]);
            }
            prop_assert_eq!(&n.after_hat[i], &impact.frames()[i].velocity(&n.velocity));
        }
    }

    /// The route float types take unless G is well conditioned (the wrenches orthogonalised
    /// in the metric ηM⁻¹, `impact::gram_schmidt`; `impact::route`) and the normal equations
    /// G x = b give the same outcome, every
    /// output equal in rationals: impulses, compression impulses, twist, the three velocity
    /// components at every contact and both energies.
    #[test]
    fn orthogonalised_wrenches_give_the_normal_equations_outcome(p in problem(4)) {
        let Some((mut impact, n, q)) = solve_exact(&p) else { return Ok(()) };
        for (m, expected) in [(Model::Newton, n), (Model::Poisson, q)] {
            let mut out = Outcome::default();
            impact.solve_orthogonal(m, &mut out).expect("G is regular");
            prop_assert_eq!(out, expected);
        }
    }

    /// Kinetic energy before minus after (written out here) equals the reported ΔE_c.
    #[test]
    fn kinetic_energy_loss_is_the_difference(p in problem(4)) {
        let Some((_, n, q)) = solve_exact(&p) else { return Ok(()) };
        let before = kinetic_energy(p.body(), p.velocity());
        for out in [&n, &q] {
            prop_assert_eq!(before.clone() - kinetic_energy(p.body(), &out.velocity), out.kinetic_energy_loss.clone());
        }
    }

    /// eq. 50–55: equal coefficients at every contact give Newton = Poisson.
    #[test]
    fn equal_coefficients_give_newton_equal_poisson(p in problem(4), k in coefficient()) {
        let p = map_contacts(p, |c| {
            c.k_newton = k.clone();
            c.k_poisson = k.clone();
        });
        let Some((_, n, q)) = solve_exact(&p) else { return Ok(()) };
        prop_assert_eq!(n.impulses_hat, q.impulses_hat);
        prop_assert_eq!(n.velocity, q.velocity);
    }

    /// §5.1: g_12 = 0 (perpendicular normals, one through C) gives Newton = Poisson even
    /// with different coefficients (eq. 35–36).
    #[test]
    fn zero_cross_inertance_gives_newton_equal_poisson(
        body in body(), w in vec3(5, 2), v in vec3(5, 2),
        n1 in direction(), t in rational(3, 2), p2 in vec3(4, 2), aux in direction(),
        k1 in coefficient(), k2 in coefficient(),
    ) {
        let n2 = n1.cross(&aux);
        prop_assume!(!n2.iter().all(|x| x.is_zero()));
        let contacts = [(n1.clone() * t, n1, k1), (p2, n2, k2)]
            .into_iter()
            .map(|(point, normal, k)| inertance::mechanics::contact::Contact::new(point, normal, k))
            .collect();
        let p = valid(body, Screw::new(w, v), contacts);
        let Some((impact, n, q)) = solve_exact(&p) else { return Ok(()) };
        prop_assert!(impact.g_hat()[1].is_zero());
        prop_assert_eq!(n.impulses_hat, q.impulses_hat);
    }

    /// Newton with every k = 1 conserves kinetic energy.
    #[test]
    fn perfectly_elastic_newton_conserves_energy(p in problem(4)) {
        let p = map_contacts(p, |c| c.k_newton = Exact::one());
        let Some((_, n, _)) = solve_exact(&p) else { return Ok(()) };
        prop_assert!(n.kinetic_energy_loss.is_zero());
    }

    /// Scaling a normal by any nonzero rational changes nothing physical: the twist after
    /// impact and both energies are identical (the solve is scale-invariant per contact).
    #[test]
    fn normal_scale_does_not_matter(p in problem(3), s in positive(7, 3)) {
        let Some((_, n, _)) = solve_exact(&p) else { return Ok(()) };
        let mut first = true;
        let scaled = map_contacts(p.clone(), |c| {
            if std::mem::take(&mut first) {
                c.normal *= s.clone();
            }
        });
        let Some((_, n2, _)) = solve_exact(&scaled) else { return Err(TestCaseError::fail("scaling made G singular")) };
        prop_assert_eq!(n.velocity, n2.velocity);
        prop_assert_eq!(n.lost_velocity_energy, n2.lost_velocity_energy);
    }
}

/// cond(G) ≤ 10², estimated by d_max / pivot_min: det = Π pivots ≤ d_max^(N−1)·pivot_min,
/// so pivot_min ≥ det / d_max^(N−1), and d_max/pivot_min bounds the pivot ratio, a lower
/// bound on cond(G) sharp within a factor N at these sizes.
fn well_conditioned(impact: &Impact<Exact>) -> bool {
    let k = impact.contacts();
    let dmax = (0..k)
        .map(|i| impact.g_hat()[i * k + i].to_f64())
        .fold(0.0, f64::max);
    let pivot_min = impact.det_hat().to_f64() / dmax.powi(k as i32 - 1);
    pivot_min > 0.0 && dmax / pivot_min <= 1e2
}

/// max_i (|n̂_i|·|v_C⁰| + |r_i × n̂_i|·|ω⁰|)·(1 + k_max) / max_j ĝ_jj: the size of the terms of
/// b = (1 + k) v̂⁰ over the largest inertance — the scale of an impulse's rounding error when
/// the impulses themselves cancel to zero.
fn impulse_floor(p: &Problem<Exact>, impact: &Impact<Exact>) -> f64 {
    let norm = |v: &Vec3<Exact>| v.iter().map(|x| x.to_f64().powi(2)).sum::<f64>().sqrt();
    let (w, v) = (norm(&p.velocity().top()), norm(&p.velocity().bottom()));
    let terms = impact
        .frames()
        .iter()
        .map(|f| norm(&f.axes[0].top()) * v + norm(&f.axes[0].bottom()) * w)
        .fold(0.0, f64::max);
    let n = impact.contacts();
    let gmax = (0..n)
        .map(|i| impact.g_hat()[i * n + i].to_f64())
        .fold(0.0, f64::max);
    if gmax > 0.0 { 2.0 * terms / gmax } else { 0.0 }
}

/// Relative distance |a − e| / max(|e|, scale).
fn rel(a: f64, e: f64, scale: f64) -> f64 {
    if a == e {
        0.0
    } else {
        (a - e).abs() / e.abs().max(scale)
    }
}

proptest! {
    #![proptest_config(config())]

    /// f64 agrees with exact to 1e-12 relative on well-conditioned scenes.
    ///
    /// The tolerance is a claim: the inputs are rounded once (½ε each), G is assembled with
    /// O(10) flops per entry, and pivoted LDLᵀ is backward stable, so the forward error is
    /// ≲ c·cond(G)·ε with c of order 10². We keep scenes with cond(G) ≤ 10² (estimated by the
    /// pivot ratio d_max/d_min of the exact factorization, a lower bound on cond that is sharp
    /// within a factor N for these sizes), giving ≲ 10⁴ ε ≈ 2·10⁻¹² — and compare norm-wise,
    /// relative to the largest entry of each quantity, where cancellation cannot inflate it.
    #[test]
    fn f64_matches_exact(p in problem(4)) {
        let Some((impact, ne, qe)) = solve_exact(&p) else { return Ok(()) };
        prop_assume!(well_conditioned(&impact));

        let pf = convert::<f64>(&p);
        let mut impact_f = Impact::assemble(&pf).unwrap();
        for (model, exact) in [(Model::Newton, &ne), (Model::Poisson, &qe)] {
            let mut out = Outcome::default();
            impact_f.solve(model, &mut out).unwrap();
            // The impulses' scale: their own size, or — when they cancel to (nearly) zero —
            // the size of the terms that cancel in b_i = (1 + k_i) v̂_ix⁰ over the largest
            // inertance, since f64 carries a rounding error of that size through G⁻¹.
            let pscale = exact.impulses_hat.iter().map(|x| x.to_f64().abs()).fold(impulse_floor(&p, &impact), f64::max);
            for (a, e) in out.impulses_hat.iter().zip(&exact.impulses_hat) {
                prop_assert!(rel(*a, e.to_f64(), pscale) <= 1e-12, "{model} impulse {a} vs {}", e.to_f64());
            }
            let vscale = exact.velocity.as_slice().iter().chain(p.velocity().as_slice()).map(|x| x.to_f64().abs()).fold(0.0, f64::max);
            for (a, e) in out.velocity.as_slice().iter().zip(exact.velocity.as_slice()) {
                prop_assert!(rel(*a, e.to_f64(), vscale) <= 1e-12);
            }
            let escale = impact.kinetic_before().to_f64() + exact.lost_velocity_energy.to_f64();
            prop_assert!(rel(out.lost_velocity_energy, exact.lost_velocity_energy.to_f64(), escale) <= 1e-12);
            prop_assert!(rel(out.kinetic_energy_loss, exact.kinetic_energy_loss.to_f64(), escale) <= 1e-12);
        }
    }

    /// f32 runs the same code: on the same well-conditioned scenes its error is the f64
    /// claim scaled by ε_f32/ε_f64 ≈ 5·10⁸: 10⁴·ε_f32 ≈ 1.2·10⁻³, so 2·10⁻³.
    #[test]
    fn f32_matches_exact_at_f32_precision(p in problem(3)) {
        let Some((impact, ne, _)) = solve_exact(&p) else { return Ok(()) };
        prop_assume!(well_conditioned(&impact));
        let pf = convert::<f32>(&p);
        let mut impact_f = Impact::assemble(&pf).unwrap();
        let mut out = Outcome::default();
        impact_f.solve(Model::Newton, &mut out).unwrap();
        let vscale = ne.velocity.as_slice().iter().map(|x| x.to_f64().abs()).fold(0.0, f64::max);
        for (a, e) in out.velocity.as_slice().iter().zip(ne.velocity.as_slice()) {
            prop_assert!(a.is_finite());
            prop_assert!(rel(*a as f64, e.to_f64(), vscale) <= 2e-3, "{a} vs {}", e.to_f64());
        }
    }
}

#[test]
fn singular_g_is_detected_exactly() {
    // Two contacts at the same point with the same normal: Δ = 0 exactly (§8, A1 ≡ A2).
    let c = inertance::mechanics::contact::Contact {
        point: Vec3::new(Exact::one(), Exact::zero(), Exact::zero()),
        normal: Vec3::new(Exact::one(), Exact::one(), Exact::zero()),
        tangent: None,
        k_newton: Exact::zero(),
        k_poisson: Exact::zero(),
        k_energetic: Exact::zero(),
        mu: Exact::zero(),
    };
    let p = valid(
        inertance::mechanics::body::RigidBody::principal(
            Exact::one(),
            Vec3::new(Exact::one(), Exact::one(), Exact::one()),
        ),
        Screw::new(
            Vec3::zeros(),
            Vec3::new(Exact::one(), Exact::zero(), Exact::zero()),
        ),
        vec![c.clone(), c],
    );
    let mut impact = Impact::assemble(&p).unwrap();
    assert!(impact.det_hat().is_zero());
    assert_eq!(impact.rank(), 1);
    let mut out = Outcome::default();
    assert_eq!(
        impact.solve(Model::Newton, &mut out),
        Err(SolveError::Singular {
            rank: 1,
            contacts: 2,
            rounded: false
        })
    );
}

proptest! {
    #![proptest_config(config())]

    /// Double-double runs the same code: on the same well-conditioned scenes its error is the
    /// f64 claim scaled by 2⁻¹⁰⁴/2⁻⁵³: 10⁴·2⁻¹⁰⁴ ≈ 5·10⁻²⁸, so 1e-27 — measured on the exact
    /// stored value (hi + lo), not on a rounding of it.
    #[test]
    fn double_double_matches_exact_to_about_106_bits(p in problem(4)) {
        use inertance::scalar::dd::DoubleDouble;
        let Some((impact, ne, _)) = solve_exact(&p) else { return Ok(()) };
        prop_assume!(well_conditioned(&impact));
        let pd = convert::<DoubleDouble>(&p);
        let mut impact_d = Impact::assemble(&pd).unwrap();
        let mut out = Outcome::default();
        impact_d.solve(Model::Newton, &mut out).unwrap();
        let scale = ne.velocity.as_slice().iter().map(|x| x.to_f64().abs()).fold(0.0, f64::max);
        for (a, e) in out.velocity.as_slice().iter().zip(ne.velocity.as_slice()) {
            let diff = a.exact_value().unwrap() - e.to_big_rational();
            let err = diff.to_f64().abs() / scale.max(f64::MIN_POSITIVE);
            prop_assert!(scale == 0.0 || err <= 1e-27, "{err:e}");
        }
    }
}
