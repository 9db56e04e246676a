//! [`Rational`]: exact rational arithmetic with a machine-word fast path — the type
//! [`Exact`](crate::scalar::Exact) names.
//!
//! The same numbers as num-rational's `BigRational` (every result is the exact rational, in
//! lowest terms), computed faster where the solver spends its time:
//!
//! - **Words first.** A value whose numerator and denominator fit `i64` is stored in two words,
//!   with no allocation. An operation on two such values is computed in 128-bit integers, where
//!   it cannot overflow (a product of two words has at most 126 bits, a sum of two products at
//!   most 127), and its result is stored back in words when it fits, promoted to big integers
//!   otherwise — exact either way. The scenes of the peer corpus keep nearly every value in
//!   words.
//! - **No redundant reductions.** Sums and products are Henrici's (Knuth, TAOCP vol. 2,
//!   §4.5.1), reduced by gcds of the **operands'** parts — smaller than the result's, and
//!   often 1 — never by a gcd of the full-size result:
//!
//!   ```text
//!   a/b · c/d = (a/g₁ · c/g₂) / (b/g₂ · d/g₁),   g₁ = gcd(a, d),  g₂ = gcd(c, b)
//!   a/b + c/d = (t/g₂) / (b/g₁ · d/g₂),          g₁ = gcd(b, d),  t = a·(d/g₁) + c·(b/g₁),
//!                                                g₂ = gcd(t, g₁)
//!   ```
//!
//!   Both are in lowest terms when a/b and c/d are: in the product every prime of a numerator
//!   was cancelled against the other operand's denominator, and neither operand shares one
//!   with its own; in the sum a prime p of b/g₁ · d/g₁ divides exactly one of the two, say
//!   b/g₁, and then not t (p ∤ a, p ∤ d/g₁), so only the primes of g₁ can divide both t and the
//!   denominator — those g₂ removes. With g₁ = 1 the sum is (ad + bc)/(bd), with no gcd at
//!   all. `BigRational`'s `+` instead takes an lcm and then reduces the full-size result; its
//!   `×` cross-cancels as above and then reduces again, by a gcd that is always 1.
//! - **Cheap gcds.** In words, a binary gcd after one remainder when the sizes are far apart;
//!   on big values, a gcd with a word argument is one remainder and a word gcd, and one of two
//!   128-bit arguments a 128-bit binary gcd. Only larger ones go to num-integer's.
//!
//! The representation is canonical — a value that fits words is always stored in words — so
//! `==` compares representations. Conversions to and from `BigRational` are exact both ways,
//! and every operation is tested for exact equality with `BigRational`'s (`tests/rational.rs`).

mod big;
mod ops;
mod word;

pub(crate) use big::{add as big_add, gcd as big_gcd, mul as big_mul};
pub(crate) use word::gcd_u128;

use std::cmp::Ordering;
use std::fmt;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::scalar::Scalar;

/// An exact rational number: see the [module docs](self).
#[derive(Clone, PartialEq, Eq)]
pub struct Rational(Repr);

#[derive(Clone, PartialEq, Eq)]
enum Repr {
    /// n/d with d ≥ 1, gcd(|n|, d) = 1 and |n|, d ≤ 2⁶³ − 1.
    Word(i64, i64),
    /// In lowest terms with a positive denominator, and **not** representable as `Word`.
    Big(Box<BigRational>),
}

impl Rational {
    /// The integer n.
    pub fn from_i64(n: i64) -> Self {
        if n == i64::MIN {
            Rational::from_parts(BigInt::from(n), BigInt::one())
        } else {
            Rational(Repr::Word(n, 1))
        }
    }

    /// p/q, reduced.
    ///
    /// # Panics
    /// If q = 0, like [`BigRational::new`].
    pub fn new(p: BigInt, q: BigInt) -> Self {
        Rational::from(BigRational::new(p, q))
    }

    /// The integer n, like [`BigRational::from_integer`].
    pub fn from_integer(n: BigInt) -> Self {
        Rational::from_parts(n, BigInt::one())
    }

    /// The numerator in lowest terms (its sign is the value's).
    pub fn numer(&self) -> BigInt {
        match &self.0 {
            Repr::Word(n, _) => BigInt::from(*n),
            Repr::Big(q) => q.numer().clone(),
        }
    }

    /// The denominator in lowest terms (positive).
    pub fn denom(&self) -> BigInt {
        match &self.0 {
            Repr::Word(_, d) => BigInt::from(*d),
            Repr::Big(q) => q.denom().clone(),
        }
    }

    /// The same value as a `BigRational`.
    pub fn to_big_rational(&self) -> BigRational {
        match &self.0 {
            Repr::Word(n, d) => BigRational::new_raw(BigInt::from(*n), BigInt::from(*d)),
            Repr::Big(q) => (**q).clone(),
        }
    }

    /// Whether the value is held in machine words (for tests and measurements: the value is
    /// the same either way).
    pub fn is_word(&self) -> bool {
        matches!(self.0, Repr::Word(..))
    }

    /// |self|.
    pub fn abs(&self) -> Self {
        if self.is_negative() {
            -self.clone()
        } else {
            self.clone()
        }
    }

    /// self < 0.
    pub fn is_negative(&self) -> bool {
        self.signum_i8() < 0
    }

    /// self > 0.
    pub fn is_positive(&self) -> bool {
        self.signum_i8() > 0
    }

    /// −1, 0 or 1.
    fn sign(&self) -> i8 {
        match &self.0 {
            Repr::Word(n, _) => n.signum() as i8,
            Repr::Big(q) => {
                if q.is_negative() {
                    -1
                } else {
                    1 // a Big value is never zero
                }
            }
        }
    }

    /// Numerator and denominator already in lowest terms with a positive denominator, stored
    /// in words when they fit.
    fn from_parts(n: BigInt, d: BigInt) -> Self {
        debug_assert!(d.is_positive(), "a positive denominator");
        match (n.to_i64(), d.to_i64()) {
            (Some(n), Some(d)) if n != i64::MIN => Rational(Repr::Word(n, d)),
            _ => Rational(Repr::Big(Box::new(BigRational::new_raw(n, d)))),
        }
    }

    /// A wide result of [`word`] (lowest terms, positive denominator), in words when it fits.
    fn from_wide((n, d): word::Wide) -> Self {
        match (i64::try_from(n), i64::try_from(d)) {
            (Ok(n), Ok(d)) if n != i64::MIN => Rational(Repr::Word(n, d)),
            _ => Rational(Repr::Big(Box::new(BigRational::new_raw(
                BigInt::from(n),
                BigInt::from(d),
            )))),
        }
    }

    /// |self| compared with |other|.
    fn cmp_abs(&self, other: &Self) -> Ordering {
        match (&self.0, &other.0) {
            (Repr::Word(a, b), Repr::Word(c, d)) => {
                // |a|, |c| ≤ 2⁶³ − 1: their magnitudes are words too.
                word::cmp(a.abs(), *b, c.abs(), *d)
            }
            _ => self
                .to_big_rational()
                .abs()
                .cmp(&other.to_big_rational().abs()),
        }
    }
}

impl From<BigRational> for Rational {
    fn from(q: BigRational) -> Self {
        // BigRational keeps its values reduced with a positive denominator.
        let (n, d) = q.into_raw();
        Rational::from_parts(n, d)
    }
}

impl From<&Rational> for BigRational {
    fn from(q: &Rational) -> Self {
        q.to_big_rational()
    }
}

impl From<i64> for Rational {
    fn from(n: i64) -> Self {
        Rational::from_i64(n)
    }
}

impl Zero for Rational {
    fn zero() -> Self {
        Rational(Repr::Word(0, 1))
    }
    fn is_zero(&self) -> bool {
        matches!(self.0, Repr::Word(0, _))
    }
}

impl One for Rational {
    fn one() -> Self {
        Rational(Repr::Word(1, 1))
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Rational {
    fn cmp(&self, other: &Self) -> Ordering {
        match (&self.0, &other.0) {
            (Repr::Word(a, b), Repr::Word(c, d)) => word::cmp(*a, *b, *c, *d),
            _ => self.to_big_rational().cmp(&other.to_big_rational()),
        }
    }
}

/// `p/q`, or `p` for an integer — as `BigRational` prints.
impl fmt::Display for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            Repr::Word(n, 1) => write!(f, "{n}"),
            Repr::Word(n, d) => write!(f, "{n}/{d}"),
            Repr::Big(q) => write!(f, "{q}"),
        }
    }
}

impl fmt::Debug for Rational {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{self}")
    }
}

impl Scalar for Rational {
    const NAME: &'static str = "exact";
    const IS_EXACT: bool = true;

    fn from_rational(q: &BigRational) -> Self {
        Rational::from(q.clone())
    }
    fn from_f64(_: f64) -> Option<Self> {
        None
    }
    fn to_f64(&self) -> f64 {
        match &self.0 {
            Repr::Word(n, d) => word::to_f64(*n, *d)
                .unwrap_or_else(|| crate::number::rational_to_f64(&self.to_big_rational())),
            Repr::Big(q) => crate::number::rational_to_f64(q),
        }
    }
    fn to_rational(&self) -> Option<BigRational> {
        Some(self.to_big_rational())
    }
    fn is_negligible(&self, _reference: &Self, _n: usize) -> bool {
        self.is_zero()
    }
    fn abs_gt(&self, other: &Self) -> bool {
        self.cmp_abs(other) == Ordering::Greater
    }
    fn signum_i8(&self) -> i8 {
        self.sign()
    }
    fn epsilon_f64() -> f64 {
        0.0
    }
    fn exact_text(&self) -> Option<String> {
        Some(self.to_string())
    }
    fn sqrt_exact(&self) -> Option<Self> {
        match &self.0 {
            Repr::Word(n, d) => word::sqrt(*n, *d).map(|(n, d)| Rational(Repr::Word(n, d))),
            Repr::Big(q) => {
                // In lowest terms, √(n/d) is rational exactly when n and d are both squares.
                if q.is_negative() {
                    return None;
                }
                let rn = big::sqrt_exact(q.numer())?;
                let rd = big::sqrt_exact(q.denom())?;
                Some(Rational::from_parts(rn, rd))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Rational {
        Rational::new(n.into(), d.into())
    }

    #[test]
    fn values_that_fit_are_stored_in_words() {
        assert!(q(6, -4).is_word());
        assert_eq!(q(6, -4), Rational::from_wide((-3, 2)));
        let big = Rational::from_i64(i64::MAX) + Rational::one();
        assert!(!big.is_word());
        assert!((big - Rational::one()).is_word());
        assert!(!Rational::from_i64(i64::MIN).is_word());
    }

    #[test]
    fn text_as_big_rational_prints_it() {
        for x in [q(-3, 2), q(4, 1), q(0, 5)] {
            assert_eq!(x.to_string(), x.to_big_rational().to_string());
            assert_eq!(
                x.exact_text(),
                Some(crate::number::format_rational(&x.to_big_rational()))
            );
        }
    }

    #[test]
    fn square_roots_of_squares_only() {
        assert_eq!(q(9, 4).sqrt_exact(), Some(q(3, 2)));
        assert_eq!(q(2, 1).sqrt_exact(), None);
        assert_eq!(q(-4, 1).sqrt_exact(), None);
    }
}
