//! Henrici's product and sum (stated in the docs of [`super`]) on big-integer numerator and
//! denominator pairs, for the values that do not fit machine words.
//!
//! The gcds are of the operands' parts, not of the result's, and most of them have one small
//! argument (a word operand, or a denominator built from the scene's few small primes): such a
//! gcd costs one remainder of the big argument by a word, then a word gcd ([`gcd`]).

use num_bigint::{BigInt, BigUint, Sign};
use num_traits::{One, ToPrimitive, Zero};

use super::word;

/// A fraction as its two big-integer parts, in lowest terms with a positive denominator.
pub(crate) type Parts = (BigInt, BigInt);

/// gcd(x, y) ≥ 0: by a word remainder when either argument fits a word, in 128-bit integers
/// when both fit them, else by Lehmer's method ([`lehmer`]).
pub(crate) fn gcd(x: &BigInt, y: &BigInt) -> BigInt {
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
            _ => BigInt::from(lehmer(x.magnitude(), y.magnitude())),
        },
    }
}

/// gcd(x, y) by Lehmer's method (Knuth, *TAOCP* vol. 2, §4.5.2, Algorithm L): Euclid's
/// quotients are found from the leading 62 bits of the two numbers, in machine integers, for
/// as long as the quotients of (x̂ + A)/(ŷ + C) and (x̂ + B)/(ŷ + D) agree — then each is the
/// true quotient — and the cosequence (A, B; C, D) they build is applied to the big numbers
/// at once, (x, y) ← (A x + B y, C x + D y): one pass of multiply-adds for some 30–60 bits of
/// Euclid's steps, where the binary gcd (num-integer's) shifts and subtracts the whole
/// numbers bit by bit. A step whose first quotient cannot be decided is a full division.
/// Once y fits 128 bits: one remainder, then [`word::gcd_u128`]. On the exact values of
/// doubles the gcds of 100–500-bit parts were two thirds of an exact solve's instructions
/// (callgrind, benches/peers/README.md).
fn lehmer(x: &BigUint, y: &BigUint) -> BigUint {
    let (mut a, mut b) = if x >= y {
        (x.clone(), y.clone())
    } else {
        (y.clone(), x.clone())
    };
    loop {
        if b.is_zero() {
            return a;
        }
        if let Some(bv) = b.to_u128() {
            let r = (&a % &b)
                .to_u128()
                .expect("a remainder by a 128-bit integer fits one");
            return BigUint::from(word::gcd_u128(bv, r));
        }
        // a ≥ b > 2¹²⁸: the leading 62 bits of a, and b's at the same place — x̂ + A and every
        // cosequence entry then stay within 2⁶² (Knuth's bounds), so i64 holds them and its
        // division is the machine's (i128's is a library call, a fifth of the time)
        let shift = a.bits() - 62;
        let top = |v: &BigUint| (v >> shift).to_u64().expect("62 bits") as i64;
        let (mut xh, mut yh) = (top(&a), top(&b));
        let (mut ca, mut cb, mut cc, mut cd) = (1i64, 0i64, 0i64, 1i64);
        loop {
            // (every sum in range by Knuth's bounds; checked all the same, stopping the
            // single-precision steps where one would not be)
            let (Some(ly), Some(ry)) = (yh.checked_add(cc), yh.checked_add(cd)) else {
                break;
            };
            if ly <= 0 || ry <= 0 {
                break;
            }
            let (Some(nx), Some(mx)) = (xh.checked_add(ca), xh.checked_add(cb)) else {
                break;
            };
            let q = nx / ly;
            if q != mx / ry {
                break;
            }
            let next = |u: i64, v: i64| v.checked_mul(q).and_then(|qv| u.checked_sub(qv));
            let (Some(nc), Some(nd), Some(ny)) = (next(ca, cc), next(cb, cd), next(xh, yh)) else {
                break;
            };
            (ca, cc) = (cc, nc);
            (cb, cd) = (cd, nd);
            (xh, yh) = (yh, ny);
        }
        if cb == 0 {
            let r = &a % &b;
            a = b;
            b = r;
        } else {
            let na = combine(ca, &a, cb, &b);
            let nb = combine(cc, &a, cd, &b);
            a = na;
            b = nb;
        }
    }
}

/// p a + q b, which is ≥ 0, for p and q of opposite signs (or one of them 0).
fn combine(p: i64, a: &BigUint, q: i64, b: &BigUint) -> BigUint {
    let pa = a * p.unsigned_abs();
    let qb = b * q.unsigned_abs();
    if q <= 0 { pa - qb } else { qb - pa }
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
pub(crate) fn mul(a: &BigInt, b: &BigInt, c: &BigInt, d: &BigInt) -> Parts {
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
pub(crate) fn add(a: &BigInt, b: &BigInt, c: &BigInt, d: &BigInt) -> Parts {
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
    use num_integer::Integer;

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

    /// Lehmer's gcd equals num-integer's binary one on products of random words with common
    /// factors (sizes 130–700 bits, quotients large and small, one argument a multiple of the
    /// other, equal arguments).
    #[test]
    fn lehmers_gcd_agrees_with_the_binary_one() {
        use proptest::prelude::*;
        let word = || any::<u64>().prop_map(|w| BigInt::from(w | 1));
        let big = proptest::collection::vec(word(), 1..6)
            .prop_map(|ws| ws.into_iter().fold(BigInt::one(), |acc, w| acc * w));
        proptest!(|(g in big.clone(), x in big.clone(), y in big, shift in 0u32..40)| {
            let x = (&g * x) << shift;
            let y = &g * y;
            prop_assert_eq!(gcd(&x, &y), x.gcd(&y));
            prop_assert_eq!(gcd(&y, &x), x.gcd(&y));
            let m = &x * BigInt::from(3u8);
            prop_assert_eq!(gcd(&m, &x), x.clone());
            prop_assert_eq!(gcd(&x, &x), x.clone());
        });
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
