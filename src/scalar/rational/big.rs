//! Henrici's product and sum (stated in the docs of [`super`]) on big-integer numerator and
//! denominator pairs, for the values that do not fit machine words.
//!
//! The gcds are of the operands' parts, not of the result's, and most of them have one small
//! argument (a word operand, or a denominator built from the scene's few small primes): such a
//! gcd costs one remainder of the big argument by a word, then a word gcd ([`gcd`]).

use num_bigint::{BigInt, BigUint, Sign};
use num_integer::Integer;
use num_traits::{One, ToPrimitive, Zero};

use super::word;

/// A fraction as its two big-integer parts, in lowest terms with a positive denominator.
pub(super) type Parts = (BigInt, BigInt);

/// gcd(x, y) ≥ 0: by a word remainder when either argument fits a word, in 128-bit integers
/// when both fit them, else num-integer's (binary) gcd.
pub(super) fn gcd(x: &BigInt, y: &BigInt) -> BigInt {
    if x.is_one() || y.is_one() {
        return BigInt::one();
    }
    match (x.magnitude().to_u64(), y.magnitude().to_u64()) {
        (Some(a), Some(b)) => BigInt::from(word::gcd(a, b)),
        (Some(0), None) => BigInt::from(y.magnitude().clone()),
        (None, Some(0)) => BigInt::from(x.magnitude().clone()),
        (Some(a), None) => BigInt::from(word::gcd(a, rem(y.magnitude(), a))),
        (None, Some(b)) => BigInt::from(word::gcd(rem(x.magnitude(), b), b)),
        (None, None) => match (x.magnitude().to_u128(), y.magnitude().to_u128()) {
            (Some(a), Some(b)) => BigInt::from(word::gcd_u128(a, b)),
            _ => x.gcd(y),
        },
    }
}

/// x mod m for m ≥ 1.
fn rem(x: &BigUint, m: u64) -> u64 {
    (x % m).to_u64().expect("a remainder by a word is a word")
}

/// x / g, skipping the division by one.
fn exact_div(x: &BigInt, g: &BigInt) -> BigInt {
    if g.is_one() { x.clone() } else { x / g }
}

/// a/b · c/d.
pub(super) fn mul(a: &BigInt, b: &BigInt, c: &BigInt, d: &BigInt) -> Parts {
    if a.is_zero() || c.is_zero() {
        return (BigInt::zero(), BigInt::one());
    }
    let g1 = gcd(a, d);
    let g2 = gcd(c, b);
    (
        exact_div(a, &g1) * exact_div(c, &g2),
        exact_div(b, &g2) * exact_div(d, &g1),
    )
}

/// a/b ÷ c/d for c ≠ 0.
pub(super) fn div(a: &BigInt, b: &BigInt, c: &BigInt, d: &BigInt) -> Parts {
    if c.sign() == Sign::Minus {
        mul(a, b, &-d, &-c)
    } else {
        mul(a, b, d, c)
    }
}

/// a/b + c/d.
pub(super) fn add(a: &BigInt, b: &BigInt, c: &BigInt, d: &BigInt) -> Parts {
    if b == d {
        let t = a + c;
        let g = gcd(&t, b);
        if t.is_zero() {
            return (t, BigInt::one());
        }
        return (exact_div(&t, &g), exact_div(b, &g));
    }
    let g1 = gcd(b, d);
    if g1.is_one() {
        return (a * d + c * b, b * d);
    }
    let (b1, d1) = (b / &g1, d / &g1);
    let t = a * &d1 + c * &b1;
    if t.is_zero() {
        return (t, BigInt::one());
    }
    let g2 = gcd(&t, &g1);
    (exact_div(&t, &g2), b1 * exact_div(d, &g2))
}

/// √x for x ≥ 0 when x is a perfect square: in 128-bit integers when x fits them.
pub(super) fn sqrt_exact(x: &BigInt) -> Option<BigInt> {
    let root = match x.magnitude().to_u128() {
        Some(v) => BigInt::from(v.isqrt()),
        None => x.sqrt(),
    };
    (&root * &root == *x).then_some(root)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn b(x: i128) -> BigInt {
        BigInt::from(x)
    }

    #[test]
    fn gcd_with_a_word_argument_agrees_with_the_general_one() {
        let big = b(3) * b(1 << 100) * b(7);
        for small in [0i128, 1, 2, 21, 1 << 62, -(1 << 62), -21] {
            assert_eq!(gcd(&big, &b(small)), big.gcd(&b(small)), "{small}");
            assert_eq!(gcd(&b(small), &big), big.gcd(&b(small)), "{small}");
        }
    }

    #[test]
    fn sums_and_products_in_lowest_terms() {
        assert_eq!(mul(&b(2), &b(3), &b(9), &b(4)), (b(3), b(2)));
        assert_eq!(add(&b(1), &b(6), &b(1), &b(10)), (b(4), b(15)));
        assert_eq!(add(&b(1), &b(6), &b(-1), &b(6)), (b(0), b(1)));
        assert_eq!(div(&b(1), &b(2), &b(-3), &b(4)), (b(-2), b(3)));
    }

    #[test]
    fn square_roots_of_squares_only() {
        let big = b(1 << 100) * b(3);
        assert_eq!(sqrt_exact(&(&big * &big)), Some(big.clone()));
        assert_eq!(sqrt_exact(&(&big * &big + 1)), None);
        assert_eq!(sqrt_exact(&b(u128::MAX as i128 >> 1)), None);
        let w = b((1 << 62) + 7);
        assert_eq!(sqrt_exact(&(&w * &w)), Some(w));
    }
}
