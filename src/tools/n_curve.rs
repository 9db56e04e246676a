//! The cost of `analyze` against the number of contacts N, up to 10⁵ in f64 and 10³ in exact
//! rationals, with the exponent of the fit t ∝ N^p (least squares on log t against log N).
//!
//! The analysis timed is the linear-cost route ([`crate::analysis::wrench_space`]): the
//! pivoted Gram–Schmidt of the N contact wrenches and, for Newton and Poisson, the
//! classification, the least-norm impulses, the twist, energies and admissibility (what
//! `analyze` computes beyond [`crate::tools::analyze::DENSE_CONTACTS`] contacts, scene
//! parsing and the report aside). The scenes are a body landing on uneven ground, as the
//! bench's growth table: N points over the body with normals [a, b, 1], built directly (not
//! parsed: a 10⁵-contact scene file takes longer to read than to analyse).

use std::time::{Duration, Instant};

use num_bigint::BigInt;
use num_rational::BigRational;

use crate::analysis::analyze_reduced;
use crate::analysis::wrench_space::WrenchSpace;
use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::mechanics::body::RigidBody;
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::{Screw, Vec3};
use crate::scalar::{Exact, Scalar};
use crate::tools::bench::Seeded;

/// The curve of one scalar type.
#[derive(Clone, Debug)]
pub struct NCurve {
    /// The scalar's name.
    pub scalar: &'static str,
    /// (N, ns per analysis of both models).
    pub points: Vec<(usize, f64)>,
    /// The fitted exponent p of t ∝ N^p over the points with N ≥ 100.
    pub exponent: Option<f64>,
}

/// A value n/10 in `T`.
fn tenths<T: Scalar>(n: i64) -> T {
    T::from_rational(&BigRational::new(BigInt::from(n), BigInt::from(10)))
}

/// A landing body with `n` contacts (module docs), every number a multiple of 1/10.
pub fn landing<T: Scalar>(seed: u64, n: usize) -> Problem<T> {
    let mut rng = Seeded(seed);
    let mut r = |lo: i64, hi: i64| tenths::<T>(lo + (rng.next() % (hi - lo + 1) as u64) as i64);
    let body = RigidBody::principal(r(10, 90), Vec3::new(r(10, 50), r(10, 50), r(10, 50)));
    let velocity = Screw::new(
        Vec3::new(r(-3, 3), r(-3, 3), r(-3, 3)),
        Vec3::new(r(-10, 10), r(-10, 10), r(10, 30)),
    );
    let contacts = (0..n)
        .map(|_| {
            let point = Vec3::new(r(-20, 20), r(-20, 20), r(-10, 10));
            let normal = Vec3::new(r(-5, 5), r(-5, 5), T::one());
            Contact::new(point, normal, T::zero()).with_coefficients(r(0, 10), r(0, 10))
        })
        .collect();
    Problem::new(body, velocity, contacts).expect("a valid landing")
}

/// ns per analysis (both models) of the landing with `n` contacts in `T`, within `budget`.
fn time<T: Scalar>(n: usize, budget: Duration) -> f64 {
    let p = landing::<T>(0x11_4ea2, n);
    let (mut reps, start) = (0u64, Instant::now());
    while start.elapsed() < budget || reps == 0 {
        let space = WrenchSpace::build(&p).expect("frames of a valid problem");
        std::hint::black_box(analyze_reduced(&space, &Model::ALL));
        reps += 1;
    }
    start.elapsed().as_nanos() as f64 / reps as f64
}

/// The least-squares slope of log t against log N over the points with N ≥ 100.
fn exponent(points: &[(usize, f64)]) -> Option<f64> {
    let xy: Vec<(f64, f64)> = points
        .iter()
        .filter(|(n, _)| *n >= 100)
        .map(|&(n, t)| ((n as f64).ln(), t.ln()))
        .collect();
    if xy.len() < 2 {
        return None;
    }
    let k = xy.len() as f64;
    let (mx, my) = (
        xy.iter().map(|p| p.0).sum::<f64>() / k,
        xy.iter().map(|p| p.1).sum::<f64>() / k,
    );
    let sxy: f64 = xy.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = xy.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    Some(sxy / sxx)
}

/// The curves: f64 to 10⁵ contacts (10⁴ when `quick`), exact to 10³ (10² when `quick`).
pub fn run(quick: bool) -> Vec<NCurve> {
    let budget = Duration::from_millis(if quick { 20 } else { 200 });
    let (f, e): (&[usize], &[usize]) = if quick {
        (&[10, 100, 1000, 10_000], &[10, 30, 100])
    } else {
        (&[10, 100, 1000, 10_000, 100_000], &[10, 30, 100, 300, 1000])
    };
    let curve = |scalar, points: Vec<(usize, f64)>| NCurve {
        scalar,
        exponent: exponent(&points),
        points,
    };
    vec![
        curve(
            "f64",
            f.iter().map(|&n| (n, time::<f64>(n, budget))).collect(),
        ),
        curve(
            "exact",
            e.iter().map(|&n| (n, time::<Exact>(n, budget))).collect(),
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_exponent_of_a_power_law_is_recovered() {
        let pts: Vec<(usize, f64)> = [10, 100, 1000, 10_000]
            .iter()
            .map(|&n| (n, 3.0 * (n as f64).powf(1.5)))
            .collect();
        assert!((exponent(&pts).unwrap() - 1.5).abs() < 1e-12);
    }
}
