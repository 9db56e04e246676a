//! The laws in inequality form, exactly in rationals over random free and constrained bodies
//! with 1–8 contacts: complementarity holds exactly, read from the velocities after impact
//! (computed through the inertances, not from the LCP's own w); the velocities after impact
//! are those of an independently enumerated solution (unique even where the impulses are not);
//! and where the paper's simultaneous answer is admissible the two laws agree exactly.

mod common;

use common::*;
use inertance::impact::solve::{Impact, Outcome};
use inertance::impact::unilateral::UnilateralError;
use inertance::mechanics::constraint::Joint;
use inertance::mechanics::screw::Screw;
use inertance::scalar::Exact;
use inertance::{Model, Problem};
use num_traits::{One, Zero};
use proptest::prelude::*;

/// (v̂_ix⁰, v̂_ix) per contact.
fn normal_velocities(impact: &Impact<Exact>, out: &Outcome<Exact>) -> Vec<(Exact, Exact)> {
    impact
        .before_hat()
        .iter()
        .zip(&out.after_hat)
        .map(|(b, a)| (b[0].clone(), a[0].clone()))
        .collect()
}

/// Moreau's Newton law, checked exactly: P ≥ 0, ξ = −v − k max(v⁰, 0) ≥ 0, P ξ = 0.
fn newton_holds(
    p: &Problem<Exact>,
    impact: &Impact<Exact>,
    out: &Outcome<Exact>,
) -> Result<(), TestCaseError> {
    for ((v0, v), (pi, c)) in normal_velocities(impact, out)
        .into_iter()
        .zip(out.impulses_hat.iter().zip(p.contacts()))
    {
        let approach = if v0.is_positive() {
            v0.clone()
        } else {
            Exact::zero()
        };
        let xi = -v - c.k_newton.clone() * approach;
        prop_assert!(!pi.is_negative(), "P ≥ 0");
        prop_assert!(!xi.is_negative(), "ξ ≥ 0");
        prop_assert!((pi.clone() * xi).is_zero(), "P ξ = 0");
    }
    Ok(())
}

/// Poisson in two phases, checked exactly: compression P^c ≥ 0 ⊥ Ĝ P^c − v⁰ ≥ 0, then
/// X = P − (1 + k)∘P^c ≥ 0 ⊥ −v ≥ 0.
fn poisson_holds(
    p: &Problem<Exact>,
    impact: &Impact<Exact>,
    out: &Outcome<Exact>,
) -> Result<(), TestCaseError> {
    let n = impact.contacts();
    let g = impact.g_hat();
    for i in 0..n {
        let pc = &out.compression_hat[i];
        let wc = (0..n).fold(-impact.before_hat()[i][0].clone(), |s, j| {
            s + g[i * n + j].clone() * &out.compression_hat[j]
        });
        prop_assert!(
            !pc.is_negative() && !wc.is_negative() && (pc.clone() * &wc).is_zero(),
            "compression at {}",
            i
        );
        let x = out.impulses_hat[i].clone() - (Exact::one() + &p.contacts()[i].k_poisson) * pc;
        let v = &out.after_hat[i][0];
        prop_assert!(
            !x.is_negative() && !v.is_positive() && (x * v).is_zero(),
            "expansion at {}",
            i
        );
    }
    Ok(())
}

/// The twist after impact from impulses P̂: {v⁰} − Σ P̂_j W{Ê_jx}.
fn twist(impact: &Impact<Exact>, p: &[Exact]) -> Screw<Exact> {
    let mut v = impact.problem().velocity().clone();
    for (pj, r) in p.iter().zip(impact.responses()) {
        v.add_scaled(&-pj.clone(), r);
    }
    v
}

/// Both laws on `p`: complementarity, the enumerated twist (Newton), agreement with the
/// simultaneous answer where that is admissible.
fn check(p: &Problem<Exact>) -> Result<(), TestCaseError> {
    let mut impact = Impact::assemble(p).unwrap();
    // Newton.
    let mut newton = Outcome::default();
    let q: Vec<Exact> = impact
        .before_hat()
        .iter()
        .zip(p.contacts())
        .map(|(b, c)| {
            let v0 = b[0].clone();
            let approach = if v0.is_positive() {
                v0.clone()
            } else {
                Exact::zero()
            };
            -(v0 + c.k_newton.clone() * approach)
        })
        .collect();
    match (
        impact.solve_unilateral(Model::Newton, &mut newton),
        enumerate(impact.g_hat(), &q),
    ) {
        (Ok(activity), Some((z, _))) => {
            newton_holds(p, &impact, &newton)?;
            // ΔE_c = ½ Σ P_i (v_ix⁰ − k_i max(v_ix⁰, 0)) (module docs), from the kinetic energies.
            let mut expected = Exact::zero();
            let mut pushed_while_receding = false;
            for ((b, pi), c) in impact
                .before_hat()
                .iter()
                .zip(&newton.impulses_hat)
                .zip(p.contacts())
            {
                let v0 = b[0].clone();
                let approach = if v0.is_positive() {
                    v0.clone()
                } else {
                    Exact::zero()
                };
                pushed_while_receding |= pi.is_positive() && v0.is_negative();
                expected += pi.clone() * (v0 - c.k_newton.clone() * approach);
            }
            prop_assert_eq!(
                newton.kinetic_energy_loss.clone() * Exact::from_integer(2.into()),
                expected
            );
            // The theorem: dissipative when every contact that takes an impulse approached.
            if !pushed_while_receding {
                prop_assert!(!newton.kinetic_energy_loss.is_negative());
            }
            prop_assert_eq!(&newton.velocity, &twist(&impact, &z), "the twist is unique");
            prop_assert_eq!(activity.singular, impact.singular());
            // Impulses that are not unique are reported as the least-norm member: no larger (in
            // Σ P_i² = Σ P̂_i² |n_i|²) than the enumerated vertex.
            let norm = |x: &[Exact]| -> Exact {
                x.iter()
                    .zip(impact.frames())
                    .map(|(p, f)| p.clone() * p * &f.norm2[0])
                    .sum()
            };
            if !activity.impulses_unique {
                prop_assert!(norm(&newton.impulses_hat) <= norm(&z));
            } else {
                prop_assert_eq!(&newton.impulses_hat, &z, "unique impulses");
            }
        }
        (Err(UnilateralError::Jammed { .. }), None) => {}
        (l, e) => prop_assert!(
            false,
            "Lemke {:?}, enumeration {:?}",
            l.is_ok(),
            e.is_some()
        ),
    }
    // Poisson.
    let mut poisson = Outcome::default();
    if impact
        .solve_unilateral(Model::Poisson, &mut poisson)
        .is_ok()
    {
        poisson_holds(p, &impact, &poisson)?;
    }
    // The simultaneous answer, where admissible, is the unilateral one.
    if impact.singular() {
        return Ok(());
    }
    let approaching = impact.before_hat().iter().all(|b| b[0].is_positive());
    for (model, unilateral) in [(Model::Newton, &newton), (Model::Poisson, &poisson)] {
        let mut simultaneous = Outcome::default();
        impact.solve(model, &mut simultaneous).unwrap();
        // The theorem for the simultaneous Newton law with one k: G P = (1 + k) v⁰ gives
        // E_p = ½ Pᵀ G P = ½ (1 + k) Pᵀ v⁰, so ΔE_c = Pᵀ v⁰ − E_p = ½ (1 − k) Pᵀ v⁰
        // = ½ (1 − k)(1 + k) v⁰ᵀ G⁻¹ v⁰ ≥ 0, whatever the signs of v⁰.
        let k = &p.contacts()[0].k_newton;
        if model == Model::Newton && p.contacts().iter().all(|c| &c.k_newton == k) {
            let work: Exact = simultaneous
                .impulses_hat
                .iter()
                .zip(impact.before_hat())
                .map(|(pi, b)| pi.clone() * &b[0])
                .sum();
            let half = Exact::new(1.into(), 2.into());
            prop_assert_eq!(
                &simultaneous.kinetic_energy_loss,
                &(half * (Exact::one() - k) * work)
            );
            prop_assert!(!simultaneous.kinetic_energy_loss.is_negative());
        }
        let admissible = approaching
            && simultaneous.impulses_hat.iter().all(|x| !x.is_negative())
            && simultaneous.after_hat.iter().all(|a| !a[0].is_positive());
        if admissible {
            prop_assert_eq!(
                &simultaneous.impulses_hat,
                &unilateral.impulses_hat,
                "{}",
                model
            );
            prop_assert_eq!(&simultaneous.velocity, &unilateral.velocity, "{}", model);
        }
    }
    Ok(())
}

/// A joint from a small set: a hinge, a slider, a ball.
fn joint() -> impl Strategy<Value = Joint<Exact>> {
    prop_oneof![
        (vec3(4, 2), direction()).prop_map(|(point, axis)| Joint::Revolute { point, axis }),
        direction().prop_map(|axis| Joint::Prismatic { axis }),
        vec3(4, 2).prop_map(|point| Joint::Spherical { point }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 160, ..ProptestConfig::default() })]

    #[test]
    fn free_bodies(p in problem(8)) {
        check(&p)?;
    }

    /// One coefficient for every contact: the simultaneous Newton theorem is exercised on
    /// every regular problem (see `check`).
    #[test]
    fn free_bodies_with_one_coefficient(p in problem(6), k in coefficient()) {
        check(&map_contacts(p, |c| c.k_newton = k.clone()))?;
    }

    /// A constrained body: the twist before impact is made allowed (v⁰ = D ξ⁰).
    #[test]
    fn constrained_bodies(p in problem(8), joints in prop::collection::vec(joint(), 1..=2), xi in prop::collection::vec(rational(4, 3), 6)) {
        let free: Vec<Screw<Exact>> = joints.iter().flat_map(Joint::free_screws).collect();
        let mut v0 = Screw::zero();
        for (s, x) in free.iter().zip(&xi) {
            v0.add_scaled(x, s);
        }
        let (body, _, contacts) = p.into_parts();
        let Ok(p) = valid(body, v0, contacts).with_joints(&joints) else { return Ok(()) };
        check(&p)?;
    }
}
