//! The exact scalar ([`Exact`] = [`Rational`], machine words with Henrici's reductions and a
//! big-integer fallback) against plain `BigRational`, for exact equality: every operation on
//! operands drawn around the places a shortcut could go wrong — zero, ±1, the 2⁵³ edge of
//! `to_f64`'s fast path, both sides of the i64 boundary, 2¹²⁸, numbers of several hundred bits,
//! and operands sharing prime factors (so that Henrici's gcds are not 1) — then the whole solver
//! and the whole pipeline (reports of `run` and `analyze`) on random and stored scenes.

mod common;

use std::cmp::Ordering;
use std::path::Path;

use common::*;
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::number::{format_rational, rational_to_f64};
use inertance::scalar::rational::Rational;
use inertance::scalar::{Exact, Scalar};
use inertance::scene::Scene;
use num_bigint::{BigInt, Sign};
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};
use proptest::prelude::*;

// ---------------------------------------------------------------------------------------------
// Operands

/// An integer from one of the regions where the word path changes behaviour.
fn integer() -> impl Strategy<Value = BigInt> {
    let near = |base: BigInt| (-3i64..=3).prop_map(move |k| &base + k);
    let two = BigInt::from(2);
    prop_oneof![
        Just(BigInt::zero()),
        (-1i64..=1).prop_map(BigInt::from),
        (-1000i64..=1000).prop_map(BigInt::from),
        any::<i32>().prop_map(BigInt::from),
        any::<i64>().prop_map(BigInt::from),
        // The f64 fast path: parts up to 2⁵³ exactly.
        near(two.pow(53u32)),
        near(-two.pow(53u32)),
        // The word boundary: i64::MAX, i64::MIN (not a word here: −i64::MIN is not), ±2⁶³, 2⁶⁴.
        near(BigInt::from(i64::MAX)),
        near(BigInt::from(i64::MIN)),
        near(two.pow(64u32)),
        near(-two.pow(64u32)),
        // The 128-bit gcd and beyond.
        near(two.pow(127u32)),
        near(two.pow(128u32)),
        near(-two.pow(128u32)),
        // Huge: up to 320 bits.
        (prop::collection::vec(any::<u32>(), 1..=10), any::<bool>()).prop_map(|(digits, neg)| {
            BigInt::from_slice(if neg { Sign::Minus } else { Sign::Plus }, &digits)
        }),
        // Smooth numbers: many small prime factors shared between operands.
        (
            0u32..40,
            0u32..25,
            0u32..17,
            0u32..12,
            0u32..8,
            any::<bool>()
        )
            .prop_map(|(a, b, c, d, e, neg)| {
                let n = BigInt::from(2).pow(a)
                    * BigInt::from(3).pow(b)
                    * BigInt::from(5).pow(c)
                    * BigInt::from(7).pow(d)
                    * BigInt::from(17).pow(e);
                if neg { -n } else { n }
            }),
    ]
}

/// A rational p/q from the regions of [`integer`] (reduced by `BigRational::new`).
fn rational_q() -> impl Strategy<Value = BigRational> {
    (integer(), integer().prop_filter("q ≠ 0", |q| !q.is_zero()))
        .prop_map(|(p, q)| BigRational::new(p, q))
}

/// Whether a reduced rational fits the word representation (|n|, d ≤ 2⁶³ − 1).
fn fits_words(q: &BigRational) -> bool {
    let word = |x: &BigInt| x.abs().to_i64().is_some();
    word(q.numer()) && word(q.denom())
}

/// `got` is exactly `want`, stored canonically (in words exactly when it fits them).
fn same(got: &Rational, want: &BigRational) -> Result<(), TestCaseError> {
    prop_assert_eq!(&got.to_big_rational(), want);
    prop_assert_eq!(got, &Rational::from(want.clone()));
    prop_assert_eq!(
        got.is_word(),
        fits_words(want),
        "canonical form of {}",
        want
    );
    Ok(())
}

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config(2048))]

    /// + − × ÷ and negation, by value and by reference and in place, equal BigRational's.
    #[test]
    fn arithmetic_equals_big_rational(x in rational_q(), y in rational_q()) {
        let (a, b) = (Rational::from(x.clone()), Rational::from(y.clone()));
        same(&a, &x)?;
        same(&(&a + &b), &(&x + &y))?;
        same(&(a.clone() + b.clone()), &(&x + &y))?;
        same(&(&a - &b), &(&x - &y))?;
        same(&(a.clone() - &b), &(&x - &y))?;
        same(&(&a * &b), &(&x * &y))?;
        same(&(a.clone() * b.clone()), &(&x * &y))?;
        same(&(&a * &a), &(&x * &x))?;
        same(&(&a - &a), &BigRational::zero())?;
        same(&-a.clone(), &-x.clone())?;
        same(&-&b, &-y.clone())?;
        if !y.is_zero() {
            same(&(&a / &b), &(&x / &y))?;
            same(&(a.clone() / b.clone()), &(&x / &y))?;
        }
        let mut c = a.clone();
        c += &b;
        c *= b.clone();
        c -= &a;
        let mut z = x.clone();
        z += &y;
        z *= &y;
        z -= &x;
        same(&c, &z)?;
        if !x.is_zero() {
            c /= a.clone();
            z /= &x;
            same(&c, &z)?;
        }
    }

    /// Order, signs, zero tests and magnitudes compare as BigRational's do.
    #[test]
    fn comparisons_equal_big_rational(x in rational_q(), y in rational_q()) {
        let (a, b) = (Rational::from(x.clone()), Rational::from(y.clone()));
        prop_assert_eq!(a.cmp(&b), x.cmp(&y));
        prop_assert_eq!(a == b, x == y);
        prop_assert_eq!(a.signum_i8(), x.signum_i8());
        prop_assert_eq!(a.is_zero(), x.is_zero());
        prop_assert_eq!(a.abs_gt(&b), x.abs_gt(&y));
        prop_assert_eq!(a.abs_gt(&b), x.abs().cmp(&y.abs()) == Ordering::Greater);
        same(&a.abs(), &x.abs())?;
    }

    /// Conversions out are those of BigRational: the f64 bit for bit (correctly rounded), the
    /// text, the exact square root.
    #[test]
    fn conversions_equal_big_rational(x in rational_q()) {
        let a = Rational::from(x.clone());
        prop_assert_eq!(a.to_f64().to_bits(), rational_to_f64(&x).to_bits());
        prop_assert_eq!(a.exact_text(), Some(format_rational(&x)));
        prop_assert_eq!(a.to_string(), x.to_string());
        prop_assert_eq!(a.to_rational(), Some(x.clone()));
        prop_assert_eq!(a.numer(), x.numer().clone());
        prop_assert_eq!(a.denom(), x.denom().clone());
        let square = &a * &a;
        prop_assert_eq!(
            square.sqrt_exact().map(|r| r.to_big_rational()),
            (&x * &x).sqrt_exact()
        );
        prop_assert_eq!(a.sqrt_exact().map(|r| r.to_big_rational()), x.sqrt_exact());
        prop_assert_eq!(Exact::from_rational(&x), a);
    }

    /// Sums and products over many terms (where the word path hands over to big integers
    /// and back) equal BigRational's.
    #[test]
    fn long_sums_and_products(xs in prop::collection::vec(rational_q(), 1..12)) {
        let rs: Vec<Rational> = xs.iter().cloned().map(Rational::from).collect();
        let sum: BigRational = xs.iter().cloned().sum();
        same(&rs.iter().sum::<Rational>(), &sum)?;
        let product: BigRational = xs.iter().cloned().product();
        same(&rs.iter().cloned().product::<Rational>(), &product)?;
        // A dot product, as the solver forms them: Σ x_i x_{i+1}.
        let mut dot = Rational::zero();
        let mut want = BigRational::zero();
        for (i, r) in rs.iter().enumerate() {
            let next = &rs[(i + 1) % rs.len()];
            dot += r.clone() * next;
            want += &xs[i] * &xs[(i + 1) % xs.len()];
        }
        same(&dot, &want)?;
    }
}

#[test]
fn the_word_boundary_exactly() {
    let max = BigInt::from(i64::MAX);
    let q = |n: &BigInt, d: &BigInt| BigRational::new(n.clone(), d.clone());
    let one = BigInt::one();
    // i64::MAX is a word, i64::MAX + 1 and i64::MIN are not.
    assert!(Rational::from(q(&max, &one)).is_word());
    assert!(!Rational::from(q(&(&max + 1), &one)).is_word());
    assert!(!Rational::from_i64(i64::MIN).is_word());
    assert!(!Rational::from(q(&one, &(&max + 1))).is_word());
    // Word operands whose results cross it, both ways.
    let m = Rational::from_i64(i64::MAX);
    let sum = &m + &Rational::one();
    assert_eq!(sum.to_big_rational(), q(&(&max + 1), &one));
    assert!(!sum.is_word());
    assert!((&sum - &Rational::one()).is_word());
    assert_eq!(-(&m) - Rational::one(), Rational::from_i64(i64::MIN));
    let square = &m * &m;
    assert_eq!(square.to_big_rational(), q(&(&max * &max), &one));
    assert!((&square / &m).is_word());
}

#[test]
#[should_panic(expected = "division by zero")]
fn division_by_zero_panics_like_big_rational() {
    let _ = Rational::one() / Rational::zero();
}

// ---------------------------------------------------------------------------------------------
// The whole solver

/// Every output of assemble + Newton + Poisson, as BigRationals.
fn outputs<T: Scalar>(p: &Problem<T>) -> Option<Vec<BigRational>> {
    let mut impact = Impact::assemble(p).ok()?;
    let mut v: Vec<T> = impact.g_hat().to_vec();
    v.extend(impact.g_yx_hat().iter().cloned());
    v.extend(impact.g_zx_hat().iter().cloned());
    v.push(impact.det_hat().clone());
    v.push(impact.kinetic_before().clone());
    v.extend(impact.before_hat().iter().flatten().cloned());
    for model in [Model::Newton, Model::Poisson] {
        let mut out = Outcome::default();
        if impact.solve(model, &mut out).is_err() {
            v.push(T::zero() - T::one()); // singular: the same refusal in both types
            continue;
        }
        v.extend(out.impulses_hat.iter().cloned());
        v.extend(out.compression_hat.iter().cloned());
        v.extend(out.velocity.as_slice().iter().cloned());
        v.extend(out.after_hat.iter().flatten().cloned());
        v.push(out.lost_velocity_energy.clone());
        v.push(out.kinetic_energy_loss.clone());
    }
    Some(v.iter().map(|x| x.to_rational().expect("exact")).collect())
}

/// A rational with parts up to ~10¹⁵ / 10⁹: products leave the word range at once.
fn wide(scale: i64) -> impl Strategy<Value = Exact> {
    (-scale..=scale, 1..=1_000_000_007i64)
        .prop_map(|(n, d)| Exact::new(BigInt::from(n), BigInt::from(d)))
}

fn wide_positive() -> impl Strategy<Value = Exact> {
    (1..=1_000_000_000_000_000i64, 1..=1_000_000_007i64)
        .prop_map(|(n, d)| Exact::new(BigInt::from(n), BigInt::from(d)))
}

fn wide_vec() -> impl Strategy<Value = Vec3<Exact>> {
    let s = 1_000_000_000_000_000;
    (wide(s), wide(s), wide(s)).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A free-body problem whose numbers have ~50–90 bits: the solve runs mostly on big integers.
fn wide_problem(max: usize) -> impl Strategy<Value = Problem<Exact>> {
    let contact = (wide_vec(), direction(), coefficient()).prop_map(|(point, normal, k)| Contact {
        point,
        normal,
        tangent: None,
        k_newton: k.clone(),
        k_poisson: k.clone(),
        k_energetic: k,
        mu: Exact::zero(),
    });
    (
        wide_positive(),
        (wide_positive(), wide_positive(), wide_positive()),
        wide_vec(),
        wide_vec(),
        prop::collection::vec(contact, 1..=max),
    )
        .prop_map(|(mass, (a, b, c), w, v, contacts)| {
            let body = RigidBody::principal(mass, Vec3::new(a, b, c));
            Problem::new(body, Screw::new(w, v), contacts).expect("valid by construction")
        })
}

proptest! {
    #![proptest_config(config(96))]

    /// The exact solve of random scenes (small numbers: the word path) in `Exact` equals the
    /// solve in plain `BigRational`, output for output.
    #[test]
    fn solver_equals_big_rational(p in problem(5)) {
        let reference = outputs(&convert::<BigRational>(&p));
        prop_assert_eq!(outputs(&p), reference);
    }

    /// The same on scenes with wide numbers (the big-integer path and the way back to words).
    #[test]
    fn solver_equals_big_rational_on_wide_numbers(p in wide_problem(3)) {
        let reference = outputs(&convert::<BigRational>(&p));
        prop_assert_eq!(outputs(&p), reference);
    }
}

// ---------------------------------------------------------------------------------------------
// The whole pipeline: reports

/// `run` and `analyze` reports (JSON) of `scene` in `Exact` and in `BigRational`, or their
/// error messages.
fn reports<T: Scalar>(scene: &Scene) -> (String, String) {
    let run = match inertance::scene::pipeline::run::<T>(scene, None) {
        Ok(s) => s.report.to_json().to_string(),
        Err(e) => format!("error: {e}"),
    };
    let analysis = match inertance::tools::analyze::analyze_scene::<T>(scene, None) {
        Ok(a) => format!("{a:?}"),
        Err(e) => format!("error: {e}"),
    };
    (run, analysis)
}

fn scenes_in(dir: &Path) -> Vec<Scene> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort();
    files.iter().filter_map(|f| Scene::load(f).ok()).collect()
}

/// Every stored scene (examples, hard cases, the fuzz corpus, modelled scenes) and every 20th
/// scene of the peer corpus: the same reports, to the character, in both exact types.
#[test]
fn reports_equal_big_rational_on_stored_scenes() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut scenes = Vec::new();
    for dir in [
        "examples",
        "tests/hard_cases",
        "tests/fuzz_corpus",
        "tests/modelled",
    ] {
        scenes.extend(scenes_in(&root.join(dir)));
    }
    let corpus = std::fs::read_to_string(root.join("benches/peers/corpus.txt")).unwrap();
    let corpus = inertance::tools::corpus::parse(&corpus).unwrap();
    scenes.extend(corpus.into_iter().step_by(20));
    assert!(scenes.len() > 80, "{} scenes", scenes.len());
    for scene in &scenes {
        assert_eq!(
            reports::<Exact>(scene),
            reports::<BigRational>(scene),
            "{}",
            scene.file
        );
    }
}
