//! Exact rationals as numbers: their text (`p/q`, `c*sqrt(r)`), their correctly rounded f64
//! values, and exact roots — the arithmetic below the expression grammar, shared by every layer
//! that prints or converts an exact value.

use num_bigint::{BigInt, BigUint};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::scalar::Exact;

/// Square factors are found by trial division up to this bound (plus a perfect-square test of the rest).
const TRIAL_DIVISION_BOUND: u32 = 10_000;

/// "p/q" or "p" (reduced, sign on numerator), e.g. "-3/4", "5".
pub fn format_rational(q: &BigRational) -> String {
    // Word-sized parts already in lowest terms (every ratio built by `new`) print as they are.
    if let (Some(n), Some(d)) = (q.numer().to_i64(), q.denom().to_i64())
        && d > 0
        && crate::scalar::rational::gcd_u128(n.unsigned_abs().into(), d as u128) == 1
    {
        return if d == 1 {
            n.to_string()
        } else {
            format!("{n}/{d}")
        };
    }
    // Rebuild through `new` so that a hand-made unreduced ratio still prints canonically.
    let q = if q.denom().is_zero() {
        q.clone()
    } else {
        BigRational::new(q.numer().clone(), q.denom().clone())
    };
    if q.denom().is_one() {
        q.numer().to_string()
    } else {
        format!("{}/{}", q.numer(), q.denom())
    }
}

/// The canonical exact form of coeff*sqrt(radicand), e.g. "3/17*sqrt(17)", "-2*sqrt(3)".
///
/// Square factors are pulled out so the radicand is a square-free positive integer
/// (`sqrt(p/q) = sqrt(p*q)/q`); renders "0" when coeff or radicand is 0, "c" when the radicand
/// is 1, "sqrt(r)" / "-sqrt(r)" for coefficients 1 / -1, else "c*sqrt(r)" with c from
/// [`format_rational`]. Square-freeness is up to the limits described at [`canonical_surd`].
pub fn format_surd(coeff: &BigRational, radicand: &BigRational) -> String {
    let (c, r) = canonical_surd(coeff, radicand);
    if c.is_zero() {
        "0".to_string()
    } else if r.is_one() {
        format_rational(&c)
    } else if c.is_one() {
        format!("sqrt({})", r.numer())
    } else if (-&c).is_one() {
        format!("-sqrt({})", r.numer())
    } else {
        format!("{}*sqrt({})", format_rational(&c), r.numer())
    }
}

/// Canonicalise coeff*sqrt(radicand) into (c, r) with r a square-free integer, same rule as [`format_surd`].
///
/// Zero (either part zero) is (0, 1), so r == 1 always means "the value is the rational c".
/// Square factors are found by trial division by primes up to 10 000 and a perfect-square test of
/// what remains; a large square-free-looking rest stays under the root (still correct, just less
/// reduced). A negative radicand (outside the contract) keeps its sign: sqrt(-12) -> (2, -3).
pub fn canonical_surd(coeff: &BigRational, radicand: &BigRational) -> (BigRational, BigRational) {
    if coeff.is_zero() || radicand.is_zero() || radicand.denom().is_zero() {
        return (BigRational::zero(), BigRational::one());
    }
    // sqrt(p/q) = sqrt(p*q)/q, so the radicand becomes an integer.
    let q = radicand.denom().abs();
    let n = radicand.numer().abs() * &q;
    let (square_root, free) = split_square(&n);
    // In the exact scalar's arithmetic (word-sized parts, Henrici's reductions): same value.
    let c = (Exact::from(coeff.clone()) * Exact::new(square_root, q)).to_big_rational();
    let r = if radicand.is_negative() { -free } else { free };
    (c, BigRational::from_integer(r))
}

/// f64 value of coeff*sqrt(radicand), accurate to about 1 ulp even when the parts are huge.
///
/// Neither part is converted to f64 first (that overflows or loses digits): the root is taken
/// in integers, scaled to at least 70 significant bits, and the quotient rounded once.
/// NaN for a negative radicand (outside the contract).
pub fn surd_to_f64(coeff: &BigRational, radicand: &BigRational) -> f64 {
    if coeff.is_zero() || radicand.is_zero() {
        return 0.0;
    }
    if radicand.is_negative() || radicand.denom().is_zero() || coeff.denom().is_zero() {
        return f64::NAN;
    }
    let q = radicand.denom().abs();
    let n = radicand.numer().abs() * &q;
    // floor(sqrt(n * 4^m)) with at least 70 bits has relative error below 2^-70.
    let m = 140u64.saturating_sub(n.bits()).div_ceil(2);
    let root = (n << (2 * m)).sqrt();
    let num = coeff.numer() * root;
    let den = (coeff.denom() * q) << m;
    rational_to_f64(&BigRational::new_raw(num, den))
}

/// Correctly rounded f64 of a BigRational (ties to even), also for huge numerators/denominators.
///
/// Converting numerator and denominator separately would give inf/inf = NaN for huge parts and
/// round twice; instead one integer division yields 66 significant bits plus a sticky bit.
/// Overflows to ±inf, underflows to 0 (subnormals are rounded correctly).
pub fn rational_to_f64(q: &BigRational) -> f64 {
    let (n, d) = (q.numer(), q.denom());
    if n.is_zero() {
        return 0.0;
    }
    if d.is_zero() {
        return f64::NAN;
    }
    let negative = n.is_negative() != d.is_negative();
    let magnitude = positive_ratio_to_f64(n.magnitude(), d.magnitude());
    if negative { -magnitude } else { magnitude }
}

/// n/d for n, d > 0, correctly rounded.
fn positive_ratio_to_f64(n: &BigUint, d: &BigUint) -> f64 {
    // Both held exactly by an f64 (below 2^53): IEEE division is correctly rounded, ties to
    // even, and cannot leave [2^-53, 2^53] — the scene's fractions (1/5, 3/10), which a posed
    // scene converts at every step of combining its numbers.
    if n.bits() <= 53
        && d.bits() <= 53
        && let (Some(a), Some(b)) = (n.to_u64(), d.to_u64())
    {
        return a as f64 / b as f64;
    }
    positive_ratio_by_division(n, d)
}

/// n/d for n, d > 0, correctly rounded: one integer division to 66 significant bits.
fn positive_ratio_by_division(n: &BigUint, d: &BigUint) -> f64 {
    // The value lies in [2^(k-1), 2^(k+1)).
    let k = n.bits() as i64 - d.bits() as i64;
    if k >= 1025 {
        return f64::INFINITY;
    }
    if k <= -1077 {
        return 0.0; // below half the smallest subnormal
    }
    // Scale so the integer quotient has 65 or 66 bits.
    let shift = 65 - k;
    let (num, den) = if shift >= 0 {
        (n << shift as u64, d.clone())
    } else {
        (n.clone(), d << (-shift) as u64)
    };
    let quo_big = &num / &den;
    let sticky = !(num - &quo_big * &den).is_zero();
    let Some(quo) = quo_big.to_u128() else {
        return f64::NAN; // unreachable: the quotient has at most 66 bits
    };
    let top = 127 - i64::from(quo.leading_zeros()); // exponent of the leading bit of quo
    let exponent = top - shift;
    // The weight of the last kept bit: 52 bits below the leading one, or the subnormal floor.
    let ulp_exp = (exponent - 52).max(-1074);
    let drop = (ulp_exp + shift) as u32; // in 12..=67 given the bounds on k
    let mut kept = quo >> drop;
    let rest = quo & ((1u128 << drop) - 1);
    let half = 1u128 << (drop - 1);
    if rest > half || (rest == half && (sticky || kept & 1 == 1)) {
        kept += 1;
    }
    // Biased exponent and mantissa add up directly, also for subnormals and a carry into 2^53.
    let bits = (((ulp_exp + 1074) as u64) << 52) + kept as u64;
    if bits >= f64::INFINITY.to_bits() {
        f64::INFINITY
    } else {
        f64::from_bits(bits)
    }
}

/// Split n > 0 into (s, f) with n = s^2 * f and f square-free up to the trial-division bound:
/// every prime p ≤ 10 000 leaves p^⌊e/2⌋ in s and p^(e mod 2) in f (e its exponent in n); what
/// remains, with only larger prime factors, goes to s when it is a perfect square, else to f.
///
/// The primes ≤ 10 000 that divide n are found at once as g = gcd(n, Π p) — one remainder of
/// the primorial Π p by n, then a gcd of n's size — and then only g is trial-divided, which
/// ends as soon as d² > g: a product of a few distinct small primes. Trial division of n
/// itself by every odd d up to 10 000 took ~17 M instructions for a 60-bit square-free n.
fn split_square(n: &BigInt) -> (BigInt, BigInt) {
    if n.is_one() {
        return (BigInt::one(), BigInt::one()); // a unit normal's squared length, the usual case
    }
    // A report takes the same few radicands again and again (every velocity of a contact is
    // over the norm of the same axis): the last few splits are remembered, per thread.
    thread_local! {
        static RECENT: std::cell::RefCell<Vec<(BigInt, (BigInt, BigInt))>> =
            const { std::cell::RefCell::new(Vec::new()) };
    }
    const REMEMBERED: usize = 16;
    if let Some(split) =
        RECENT.with_borrow(|r| r.iter().find(|(m, _)| m == n).map(|(_, x)| x.clone()))
    {
        return split;
    }
    let split = split_square_uncached(n);
    RECENT.with_borrow_mut(|r| {
        if r.len() == REMEMBERED {
            r.remove(0);
        }
        r.push((n.clone(), split.clone()));
    });
    split
}

/// [`split_square`] without its memory of recent splits.
fn split_square_uncached(n: &BigInt) -> (BigInt, BigInt) {
    let mut rest = n.magnitude().clone();
    let (mut s, mut f) = (BigUint::one(), BigUint::one());
    let mut g = small_prime_factors(&rest);
    let mut d = 2u32;
    while !g.is_one() {
        let p = if BigUint::from(d) * d > g {
            g.clone() // a prime: its smaller factors are gone
        } else if (&g % d).is_zero() {
            BigUint::from(d)
        } else {
            d = if d == 2 { 3 } else { d + 2 };
            continue;
        };
        let mut e = 0u32;
        loop {
            let (q, r) = rest.div_rem(&p);
            if !r.is_zero() {
                break;
            }
            rest = q;
            e += 1;
        }
        s *= p.pow(e / 2);
        if e % 2 == 1 {
            f *= &p;
        }
        g /= &p;
    }
    if rest > BigUint::one() {
        let root = rest.sqrt();
        if &root * &root == rest {
            s *= root;
        } else {
            f *= rest;
        }
    }
    (BigInt::from(s), BigInt::from(f))
}

/// The product of the distinct primes ≤ 10 000 dividing n > 0: gcd(n, Π_{p ≤ 10 000} p).
fn small_prime_factors(n: &BigUint) -> BigUint {
    let primorial = primorial();
    if n > primorial {
        return n.gcd(primorial);
    }
    let r = primorial % n;
    match (n.to_u128(), r.to_u128()) {
        (Some(a), Some(b)) => BigUint::from(crate::scalar::rational::gcd_u128(a, b)),
        _ => n.gcd(&r),
    }
}

/// Π p over the primes p ≤ 10 000 (1 229 primes, about 14 000 bits), computed once.
fn primorial() -> &'static BigUint {
    static PRIMORIAL: std::sync::OnceLock<BigUint> = std::sync::OnceLock::new();
    PRIMORIAL.get_or_init(|| {
        let bound = TRIAL_DIVISION_BOUND as usize;
        let mut composite = vec![false; bound + 1];
        let mut product = BigUint::one();
        for i in 2..=bound {
            if !composite[i] {
                product *= i as u32;
                for j in (i * i..=bound).step_by(i) {
                    composite[j] = true;
                }
            }
        }
        product
    })
}

/// The exact q-th root of x >= 0 when x is a perfect q-th power.
pub(crate) fn exact_root(x: &BigInt, q: u32) -> Option<BigInt> {
    if q < 2 || *x <= BigInt::one() {
        return Some(x.clone());
    }
    if u64::from(q) >= x.bits() {
        return None; // 1 < root < 2
    }
    let root = x.nth_root(q);
    (root.pow(q) == *x).then_some(root)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// The plain trial division `split_square` replaced: every d ≤ 10 000 while d² ≤ the rest.
    fn split_square_by_trial_division(n: &BigInt) -> (BigInt, BigInt) {
        let mut rest = n.clone();
        let (mut s, mut f) = (BigInt::one(), BigInt::one());
        let mut d: u32 = 2;
        while d <= TRIAL_DIVISION_BOUND && BigInt::from(u64::from(d) * u64::from(d)) <= rest {
            let mut e = 0u32;
            while (&rest % d).is_zero() {
                rest /= d;
                e += 1;
            }
            s *= BigInt::from(d).pow(e / 2);
            if e % 2 == 1 {
                f *= d;
            }
            d = if d == 2 { 3 } else { d + 2 };
        }
        if rest > BigInt::one() {
            let root = rest.sqrt();
            if &root * &root == rest {
                s *= root;
            } else {
                f *= rest;
            }
        }
        (s, f)
    }

    /// Numbers built from small primes (some squared), primes near and beyond 10 000, and a
    /// large cofactor (a square or not).
    fn radicand() -> impl Strategy<Value = BigInt> {
        let small = prop::sample::select(vec![2u32, 3, 5, 7, 11, 13, 97, 9_973, 10_007, 65_537]);
        (
            prop::collection::vec((small, 0u32..4), 0..6),
            1u64..u64::MAX,
            any::<bool>(),
        )
            .prop_map(|(factors, big, square)| {
                let mut n = factors
                    .iter()
                    .fold(BigInt::one(), |n, &(p, e)| n * BigInt::from(p).pow(e));
                let big = BigInt::from(big);
                n *= if square { &big * &big } else { big };
                n
            })
    }

    proptest! {
        #[test]
        fn split_square_equals_trial_division(n in radicand()) {
            prop_assert_eq!(split_square(&n), split_square_by_trial_division(&n));
            // Again, from the memory of recent splits.
            prop_assert_eq!(split_square(&n), split_square_by_trial_division(&n));
        }

        #[test]
        fn split_square_of_small_numbers(n in 1u64..1_000_000) {
            let n = BigInt::from(n);
            prop_assert_eq!(split_square(&n), split_square_by_trial_division(&n));
        }
    }

    #[test]
    fn split_square_at_the_edges() {
        for n in [
            1u64,
            2,
            4,
            9_973 * 9_973,
            10_007 * 10_007,
            9_973 * 10_007,
            1 << 63,
        ] {
            let n = BigInt::from(n);
            assert_eq!(split_square(&n), split_square_by_trial_division(&n), "{n}");
        }
        // The largest prime ≤ 10 000 divides the primorial, the next prime does not.
        assert!((primorial() % 9_973u32).is_zero());
        assert!(!(primorial() % 10_007u32).is_zero());
    }

    proptest! {
        /// The shortcut for word-sized parts is the integer division's rounding.
        #[test]
        fn small_ratios_round_as_the_division_does(
            n in 1u64..(1 << 53),
            d in 1u64..(1 << 53),
            shift in 0u32..53,
        ) {
            for (n, d) in [(n, d), (n >> shift | 1, d), (n, d >> shift | 1), ((1 << 53) - 1, d)] {
                let (bn, bd) = (BigUint::from(n), BigUint::from(d));
                prop_assert_eq!(
                    positive_ratio_to_f64(&bn, &bd).to_bits(),
                    positive_ratio_by_division(&bn, &bd).to_bits(),
                    "{}/{}", n, d
                );
            }
        }
    }

    #[test]
    fn formats_word_and_big_ratios_alike() {
        let q = |n: i64, d: i64| BigRational::new_raw(BigInt::from(n), BigInt::from(d));
        assert_eq!(format_rational(&q(-3, 4)), "-3/4");
        assert_eq!(format_rational(&q(6, 8)), "3/4");
        assert_eq!(format_rational(&q(5, 1)), "5");
        assert_eq!(format_rational(&q(3, -4)), "-3/4");
        assert_eq!(format_rational(&q(i64::MIN, 2)), "-4611686018427387904");
    }
}
