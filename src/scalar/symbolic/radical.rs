//! Square roots as symbols, and exact sign decisions on constants built from them.
//!
//! √(p/q) = √(p·q)/q, and p·q = s²·p₁⋯p_k with distinct primes p_i, so every square root of a
//! rational is s/q · r_{p₁}⋯r_{p_k} with one symbol r_p (relation r_p² = p) per prime. The
//! square roots of distinct primes are linearly independent over ℚ, so ℚ[r_p…]/(r_p² − p) is
//! the field ℚ(√p…): a reduced constant is zero iff it is the zero polynomial, and its sign
//! is decided by rational enclosures ⌊√(p·4ᵏ)⌋/2ᵏ < √p < (⌊√(p·4ᵏ)⌋ + 1)/2ᵏ, refined (k
//! doubled) until the interval of the value excludes 0 — which happens, the value being
//! nonzero.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use super::poly::Poly;
use super::symbols::{self, Key, Table};

/// Trial division bound for radicands: a cofactor left after dividing out every prime up to
/// it is accepted as prime when below its square, as a square when it is one, and refused
/// otherwise (its prime factorisation, which canonical forms need, is not known).
const TRIAL_LIMIT: u64 = 1 << 20;

/// The symbol r_p for the prime p (relation r_p² = p).
pub(crate) fn radical_symbol(p: &BigInt) -> Poly {
    let relation = Poly::constant(BigRational::from_integer(p.clone()));
    Poly::var(symbols::intern(Key::Radical(p.clone()), Some(relation)))
}

/// √q = c · Π √p_i with distinct primes p_i: `(c, [p_i])`; `None` for q < 0 or a radicand
/// that cannot be factored (see [`TRIAL_LIMIT`]).
pub(crate) fn sqrt_parts(q: &BigRational) -> Option<(BigRational, Vec<BigInt>)> {
    if q.is_negative() {
        return None;
    }
    if q.is_zero() {
        return Some((BigRational::zero(), Vec::new()));
    }
    let (num, den) = (q.numer().clone(), q.denom().clone());
    let (square_root, primes) = square_free(&(&num * &den))?;
    Some((BigRational::new(square_root, den), primes))
}

/// n = s² · Π p_i (distinct primes): `(s, [p_i])` for n > 0.
fn square_free(n: &BigInt) -> Option<(BigInt, Vec<BigInt>)> {
    let mut s = BigInt::one();
    let mut primes = Vec::new();
    let mut add = |d: BigInt, e: u32, s: &mut BigInt| {
        *s *= d.pow(e / 2);
        if e % 2 == 1 {
            primes.push(d);
        }
    };
    // Trial division, in machine integers when n fits (the usual case).
    let (rest, exhausted) = if let Some(mut m) = n.to_u128() {
        let mut d: u64 = 2;
        while d <= TRIAL_LIMIT && u128::from(d) * u128::from(d) <= m {
            let mut e = 0;
            while m % u128::from(d) == 0 {
                m /= u128::from(d);
                e += 1;
            }
            if e > 0 {
                add(BigInt::from(d), e, &mut s);
            }
            d += if d == 2 { 1 } else { 2 };
        }
        (BigInt::from(m), d > TRIAL_LIMIT)
    } else {
        let mut m = n.clone();
        let mut d: u64 = 2;
        loop {
            let dd = BigInt::from(d);
            if d > TRIAL_LIMIT || &dd * &dd > m {
                break;
            }
            let mut e = 0;
            while (&m % &dd).is_zero() {
                m /= &dd;
                e += 1;
            }
            if e > 0 {
                add(dd, e, &mut s);
            }
            d += if d == 2 { 1 } else { 2 };
        }
        (m, d > TRIAL_LIMIT)
    };
    if rest > BigInt::one() {
        let limit = BigInt::from(TRIAL_LIMIT);
        let r = rest.sqrt();
        if &r * &r == rest {
            s *= r;
        } else if !exhausted || rest < &limit * &limit {
            // No prime factor up to min(√rest, limit): rest is prime.
            primes.push(rest);
        } else {
            return None;
        }
    }
    primes.sort();
    Some((s, primes))
}

/// A rational interval [lo, hi] containing the value of the constant `p` (every symbol a
/// radical), with each √prime enclosed to within 2^−bits; `None` if `p` has another symbol.
fn enclosure(table: &Table, p: &Poly, bits: u32) -> Option<(BigRational, BigRational)> {
    let scale = BigInt::one() << bits;
    let mut lo = BigRational::zero();
    let mut hi = BigRational::zero();
    for (m, c) in p.terms() {
        let mut tlo = BigRational::one();
        let mut thi = BigRational::one();
        for &(v, e) in m.vars() {
            let prime = table.radicand(v)?;
            let s = (prime * &scale * &scale).sqrt();
            let rlo = BigRational::new(s.clone(), scale.clone());
            let rhi = BigRational::new(s + 1, scale.clone());
            for _ in 0..e {
                tlo *= &rlo;
                thi *= &rhi;
            }
        }
        if c.is_negative() {
            lo += c * thi;
            hi += c * tlo;
        } else {
            lo += c * tlo;
            hi += c * thi;
        }
    }
    Some((lo, hi))
}

/// The bits of precision tried, doubling from 32. The precision a sign needs grows with the
/// size of the input (how closely its terms can cancel), so the doubling stops in practice
/// long before the last, 2³⁰-bit step.
fn precisions() -> impl Iterator<Item = u32> {
    (5..31).map(|k| 1u32 << k)
}

/// The exact sign of a constant `p` (radicals only, reduced): −1, 0 or 1; `None` if `p` has
/// a symbol that is not a radical.
pub(crate) fn sign(p: &Poly) -> Option<i8> {
    if let Some(c) = p.constant_value() {
        return Some(rational_sign(&c));
    }
    let table = symbols::snapshot();
    let mut last = None;
    for bits in precisions() {
        let (lo, hi) = enclosure(&table, p, bits)?;
        if lo.is_positive() {
            return Some(1);
        }
        if hi.is_negative() {
            return Some(-1);
        }
        last = Some((lo + hi) / BigRational::from_integer(2.into()));
    }
    // Not reached in practice: a nonzero reduced constant is a nonzero real number, which
    // the shrinking enclosures separate from 0. Past 2³⁰ bits, the midpoint's sign.
    last.map(|mid| rational_sign(&mid))
}

/// The value of a constant `p` (radicals only) in f64, from an enclosure narrower than
/// 2^−60 of its magnitude; NaN if `p` has another symbol.
pub(crate) fn to_f64(p: &Poly) -> f64 {
    if let Some(c) = p.constant_value() {
        return crate::number::rational_to_f64(&c);
    }
    let table = symbols::snapshot();
    let mut mid = None;
    for bits in precisions().map(|b| b.max(64)) {
        let Some((lo, hi)) = enclosure(&table, p, bits) else {
            return f64::NAN;
        };
        let m = (&lo + &hi) / BigRational::from_integer(2.into());
        let width = hi - lo;
        let tolerance = m.abs() / BigRational::from_integer(BigInt::one() << 60u32);
        if width <= tolerance {
            return crate::number::rational_to_f64(&m);
        }
        mid = Some(m);
    }
    mid.map_or(f64::NAN, |m| crate::number::rational_to_f64(&m))
}

/// The sign of a rational.
pub(crate) fn rational_sign(q: &BigRational) -> i8 {
    if q.is_positive() {
        1
    } else if q.is_negative() {
        -1
    } else {
        0
    }
}

/// cos(15°·t) for t = 0…6 (0° to 90°) as the rational coefficients (num, den) of 1, √2, √3
/// and √6: cos 15° = (√6 + √2)/4, cos 30° = √3/2, cos 45° = √2/2, cos 60° = 1/2,
/// cos 75° = (√6 − √2)/4, cos 90° = 0.
pub(crate) fn cos_first_quadrant(t: u32) -> [(i64, i64); 4] {
    match t {
        0 => [(1, 1), (0, 1), (0, 1), (0, 1)],
        1 => [(0, 1), (1, 4), (0, 1), (1, 4)],
        2 => [(0, 1), (0, 1), (1, 2), (0, 1)],
        3 => [(0, 1), (1, 2), (0, 1), (0, 1)],
        4 => [(1, 2), (0, 1), (0, 1), (0, 1)],
        5 => [(0, 1), (-1, 4), (0, 1), (1, 4)],
        _ => [(0, 1), (0, 1), (0, 1), (0, 1)],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(a: i64, b: i64) -> BigRational {
        BigRational::new(a.into(), b.into())
    }

    fn ints(v: &[i64]) -> Vec<BigInt> {
        v.iter().map(|&k| BigInt::from(k)).collect()
    }

    #[test]
    fn square_roots_split_into_primes() {
        assert_eq!(sqrt_parts(&q(12, 1)), Some((q(2, 1), ints(&[3]))));
        assert_eq!(sqrt_parts(&q(6, 1)), Some((q(1, 1), ints(&[2, 3]))));
        assert_eq!(sqrt_parts(&q(3, 31)), Some((q(1, 31), ints(&[3, 31]))));
        assert_eq!(sqrt_parts(&q(9, 4)), Some((q(3, 2), vec![])));
        assert_eq!(sqrt_parts(&q(-2, 1)), None);
        assert_eq!(sqrt_parts(&q(0, 1)), Some((q(0, 1), vec![])));
        // A prime beyond the trial bound, and its square.
        let p = BigInt::from(1_048_583u64);
        assert_eq!(
            sqrt_parts(&BigRational::from_integer(p.clone())),
            Some((q(1, 1), vec![p.clone()]))
        );
        assert_eq!(
            sqrt_parts(&BigRational::from_integer(&p * &p * 5)),
            Some((BigRational::from_integer(p.clone()), ints(&[5])))
        );
        // Two primes beyond the bound: refused rather than risk a non-canonical form.
        let p2 = BigInt::from(1_048_589u64);
        assert_eq!(sqrt_parts(&BigRational::from_integer(&p * &p2)), None);
    }
}
