//! Lemke's method against an independent exact enumeration of active sets, over inertance
//! matrices of random bodies with 1–8 contacts (singular beyond six) and random semidefinite
//! matrices of every rank.
//!
//! The enumeration: for every support S ⊆ {1…n} with M_SS nonsingular, solve M_SS z_S = −q_S by
//! Gaussian elimination and keep z if z_S ≥ 0 and w = Mz + q ≥ 0 off S. For a symmetric
//! positive semidefinite M this finds a solution whenever one exists (the solution set is a
//! pointed polyhedron; at a vertex the columns M_·S are independent, i.e. M_SS is nonsingular),
//! and w is the same for every solution (see `inertance::linalg::lcp`). So Lemke must solve
//! exactly the problems the enumeration solves, with the same w, and end on a ray on the others.

mod common;

use common::*;
use inertance::impact::solve::Impact;
use inertance::linalg::lcp::{Lcp, LcpError, lemke};
use inertance::scalar::Exact;
use num_traits::{Signed, Zero};

use proptest::prelude::*;

/// Lemke agrees with the enumeration, and its solution is one exactly.
fn agree(m: &[Exact], q: &[Exact]) -> Result<(), TestCaseError> {
    let lemke = lemke(Lcp { m, q });
    match (enumerate(m, q).map(|(_, w)| w), lemke) {
        (Some(w), Ok(s)) => {
            prop_assert!(s.z.iter().all(|x| !x.is_negative()), "z ≥ 0: {:?}", s.z);
            prop_assert_eq!(&s.w, &residual(m, q, &s.z));
            prop_assert!(s.z.iter().zip(&s.w).all(|(z, w)| (z.clone() * w).is_zero()));
            prop_assert_eq!(s.w, w, "w is unique for a semidefinite M");
        }
        (None, Err(LcpError::Ray { .. })) => {}
        (e, l) => prop_assert!(false, "enumeration {:?}, Lemke {:?}", e.is_some(), l),
    }
    Ok(())
}

fn qs(n: usize) -> impl Strategy<Value = Vec<Exact>> {
    prop::collection::vec(rational(6, 3), n)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 192, ..ProptestConfig::default() })]

    /// M = Ĝ of a random free body with 1–8 contacts (rank ≤ 6).
    #[test]
    fn inertance_matrices((p, q) in problem(8).prop_flat_map(|p| { let n = p.contacts().len(); (Just(p), qs(n)) })) {
        let impact = Impact::assemble(&p).unwrap();
        agree(impact.g_hat(), &q)?;
    }

    /// M = AᵀA for a random integer A of 1–n rows: semidefinite of every rank.
    #[test]
    fn semidefinite_matrices(
        (n, a, q) in (1usize..=6).prop_flat_map(|n| {
            (Just(n), prop::collection::vec(prop::collection::vec(-3i64..=3, n), 1..=n), qs(n))
        })
    ) {
        let m: Vec<Exact> = (0..n * n)
            .map(|k| a.iter().map(|row| Exact::from_integer((row[k / n] * row[k % n]).into())).sum())
            .collect();
        agree(&m, &q)?;
    }

    /// The same in f64: where the exact LCP is solved, the float one is too, and its w agrees
    /// to 10⁻⁹ of max(1, |q|) on regular problems with cond(G) ≤ 10². Each pivot is a
    /// Gauss–Jordan step on the active block M_SS, so the final tableau is that of a backward
    /// stable solve of M_SS z_S = −q_S: |Δw| ≲ c·n·cond(M_SS)·ε·|q| with cond(M_SS) ≤ cond(G)
    /// (interlacing), n ≤ 5 and c ≈ 10³ for the O(n) pivots — about 10⁻¹⁰; 10⁻⁹ is the claim.
    #[test]
    fn floats_follow_the_exact_answer((p, q) in problem(5).prop_flat_map(|p| { let n = p.contacts().len(); (Just(p), qs(n)) })) {
        let exact = Impact::assemble(&p).unwrap();
        prop_assume!(!exact.singular() && well_conditioned(&exact));
        let Ok(e) = lemke(Lcp { m: exact.g_hat(), q: &q }) else { return Ok(()) };
        let pf = convert::<f64>(&p);
        let float = Impact::assemble(&pf).unwrap();
        let qf: Vec<f64> = q.iter().map(inertance::Scalar::to_f64).collect();
        let f = lemke(Lcp { m: float.g_hat(), q: &qf }).expect("solved in f64 too");
        let scale = qf.iter().map(|x| x.abs()).fold(1.0, f64::max);
        for (a, b) in f.w.iter().zip(&e.w) {
            prop_assert!((a - inertance::Scalar::to_f64(b)).abs() <= 1e-9 * scale, "{} vs {}", a, b);
        }
    }
}

/// cond(G) ≤ 10², estimated from the pivots as in `tests/properties.rs`: d_max / pivot_min
/// with pivot_min ≥ det / d_max^(N−1).
fn well_conditioned(impact: &Impact<Exact>) -> bool {
    let k = impact.contacts();
    let dmax = (0..k)
        .map(|i| inertance::Scalar::to_f64(&impact.g_hat()[i * k + i]))
        .fold(0.0, f64::max);
    let pivot_min = inertance::Scalar::to_f64(impact.det_hat()) / dmax.powi(k as i32 - 1);
    pivot_min > 0.0 && dmax / pivot_min <= 1e2
}
