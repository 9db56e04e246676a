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
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use super::poly::Poly;
use super::symbols::{self, Key, Table};

/// Trial division bound for radicands: a cofactor left after dividing out every prime up to
/// it is accepted as prime when below its square, as a square when it is one, and refused
/// otherwise (its prime factorisation, which canonical forms need, is not known).
const TRIAL_LIMIT: u64 = 1 << 20;

/// The trial division bound for radicands of more than [`LARGE_RADICAND_BITS`] bits: such
/// numbers come from hostile or degenerate inputs (a subnormal f64 written as a rational,
/// 2⁻¹⁰⁷⁴, gives a radicand of 4,300 bits), where trial division to 2²⁰ costs about 0.2 s each
/// and a derivation asks for dozens. Lowering the bound can only refuse more radicands
/// (`None`), never give a wrong factorization: a cofactor is accepted as prime only below the
/// square of the bound used.
const LARGE_TRIAL_LIMIT: u64 = 1 << 14;

/// See [`LARGE_TRIAL_LIMIT`].
const LARGE_RADICAND_BITS: u64 = 512;

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
    let (square_root, primes) = square_free_cached(&num * &den)?;
    Some((BigRational::new(square_root, den), primes))
}

/// [`square_free`], remembered per thread for radicands beyond a machine word: a derivation
/// asks for the same large radicand many times (a normal's length in every entry it reaches),
/// and trial division of a number of thousands of bits costs a fraction of a second.
fn square_free_cached(n: BigInt) -> Option<(BigInt, Vec<BigInt>)> {
    use std::cell::RefCell;
    use std::collections::HashMap;
    type Memo = HashMap<BigInt, Option<(BigInt, Vec<BigInt>)>>;
    thread_local!(static MEMO: RefCell<Memo> = RefCell::new(HashMap::new()));
    if n.bits() <= 128 {
        return square_free(&n);
    }
    if let Some(hit) = MEMO.with(|m| m.borrow().get(&n).cloned()) {
        return hit;
    }
    let result = square_free(&n);
    MEMO.with(|m| {
        let mut m = m.borrow_mut();
        if m.len() >= 4096 {
            m.clear();
        }
        m.insert(n, result.clone());
    });
    result
}

/// n = s² · Π p_i (distinct primes): `(s, [p_i])` for n > 0.
fn square_free(n: &BigInt) -> Option<(BigInt, Vec<BigInt>)> {
    let trial_limit = if n.bits() > LARGE_RADICAND_BITS {
        LARGE_TRIAL_LIMIT
    } else {
        TRIAL_LIMIT
    };
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
        // Remainders by a machine word, over 64-bit digits (most significant first; a 128 by
        // 64-bit division per digit): one pass each, no allocation; a division only when d
        // divides.
        let mut m = n.clone();
        let mut digits: Vec<u64> = m.magnitude().to_u64_digits();
        let mut d: u64 = 2;
        loop {
            if d > trial_limit || BigInt::from(d) * BigInt::from(d) > m {
                break;
            }
            let rem = |digits: &[u64]| {
                digits
                    .iter()
                    .rev()
                    .fold(0u128, |r, &w| ((r << 64) | u128::from(w)) % u128::from(d))
            };
            let mut e = 0;
            while rem(&digits) == 0 {
                m /= d;
                digits = m.magnitude().to_u64_digits();
                e += 1;
            }
            if e > 0 {
                add(BigInt::from(d), e, &mut s);
            }
            d += if d == 2 { 1 } else { 2 };
        }
        (m, d > trial_limit)
    };
    if rest > BigInt::one() {
        let limit = BigInt::from(trial_limit);
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
/// radical), with each √prime enclosed to within 2^−bits: `(lo·d, hi·d, d)` over one positive
/// denominator d; `None` if `p` has another symbol.
///
/// With s = ⌊√(prime·4^bits)⌋ and S = 2^bits, √prime lies in [s/S, (s + 1)/S], so a term
/// c·Π √p_i^{e_i} lies between c·Π s_i^{e_i}/S^E and c·Π (s_i + 1)^{e_i}/S^E (E = Σ e_i; the
/// ends swap for c < 0). Over d = lcm(denominators of c)·S^{E_max} every end is an integer:
/// the sums take no gcd, and the roots s are remembered per radical and precision.
fn enclosure(table: &Table, p: &Poly, bits: u32) -> Option<(BigInt, BigInt, BigInt)> {
    let mut ends = Vec::with_capacity(p.len());
    let mut lcm = BigInt::one();
    let mut top = 0u64;
    for (m, c) in p.terms() {
        let mut lo = BigInt::one();
        let mut hi = BigInt::one();
        let mut degree = 0u64;
        for &(v, e) in m.vars() {
            let s = root(table, v, bits)?;
            let s1 = &s + 1u32;
            for _ in 0..e {
                lo *= &s;
                hi *= &s1;
            }
            degree += u64::from(e);
        }
        if !lcm.is_multiple_of(c.denom()) {
            lcm = lcm.lcm(c.denom());
        }
        top = top.max(degree);
        ends.push((c, degree, lo, hi));
    }
    let (mut lo, mut hi) = (BigInt::zero(), BigInt::zero());
    for (c, degree, tlo, thi) in ends {
        let k = (c.numer() * (&lcm / c.denom())) << (u64::from(bits) * (top - degree));
        if k.is_negative() {
            lo += &k * thi;
            hi += k * tlo;
        } else {
            lo += &k * tlo;
            hi += k * thi;
        }
    }
    Some((lo, hi, lcm << (u64::from(bits) * top)))
}

/// ⌊√(p·4^bits)⌋ for the radical r_p with id `v`, remembered per thread up to 4096 bits;
/// `None` if `v` is not a radical.
fn root(table: &Table, v: u32, bits: u32) -> Option<BigInt> {
    use std::cell::RefCell;
    use std::collections::HashMap;
    thread_local!(static ROOTS: RefCell<HashMap<(u32, u32), BigInt>> = RefCell::new(HashMap::new()));
    if let Some(s) = ROOTS.with(|r| r.borrow().get(&(v, bits)).cloned()) {
        return Some(s);
    }
    let prime = table.radicand(v)?;
    let s = (prime << (2 * u64::from(bits))).sqrt();
    if bits > 4096 {
        // Only a sign that nearly cancels gets here, once: not worth holding its root.
        return Some(s);
    }
    ROOTS.with(|r| {
        let mut r = r.borrow_mut();
        if r.len() >= 4096 {
            r.clear();
        }
        r.insert((v, bits), s.clone());
    });
    Some(s)
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
        let (lo, hi, _) = enclosure(&table, p, bits)?;
        if lo.is_positive() {
            return Some(1);
        }
        if hi.is_negative() {
            return Some(-1);
        }
        last = Some(lo + hi);
    }
    // Not reached in practice: a nonzero reduced constant is a nonzero real number, which
    // the shrinking enclosures separate from 0. Past 2³⁰ bits, the midpoint's sign.
    last.map(|twice_mid| rational_sign(&BigRational::from_integer(twice_mid)))
}

/// The value of a constant `p` (radicals only) in f64: the midpoint (rounded once) of the
/// first enclosure narrower than 2^−60 of the midpoint's magnitude, trying 64 bits, then 128,
/// 256, …; NaN if `p` has another symbol.
pub(crate) fn to_f64(p: &Poly) -> f64 {
    if let Some(c) = p.constant_value() {
        return crate::number::rational_to_f64(&c);
    }
    let table = symbols::snapshot();
    let mut mid = None;
    for bits in precisions().filter(|&b| b >= 64) {
        let Some((lo, hi, d)) = enclosure(&table, p, bits) else {
            return f64::NAN;
        };
        // mid = (lo + hi)/2d; width = (hi − lo)/d ≤ |mid|/2⁶⁰ iff (hi − lo)·2⁶¹ ≤ |lo + hi|.
        let width = (&hi - &lo) << 61u32;
        let sum = lo + hi;
        let m = BigRational::new_raw(sum.clone(), d << 1u32);
        if width <= sum.abs() {
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
pub(super) mod tests {
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

    #[test]
    fn large_radicands_are_split_by_word_remainders_or_refused() {
        // Beyond 128 bits the trial division runs on u64 digits; beyond 512 bits to 2¹⁴.
        let big = |e: u32| BigInt::one() << e;
        // 2⁶⁰⁰·3³·5·7² (smooth, > 512 bits): √ = 2³⁰⁰·3·7 · √3·√5.
        let n = big(600) * 27 * 5 * 49;
        assert_eq!(
            sqrt_parts(&BigRational::from_integer(n)),
            Some((BigRational::from_integer(big(300) * 21), ints(&[3, 5])))
        );
        // 200 bits, a prime factor under 2²⁰ found by word remainders: 2²⁰⁰·1048573.
        let n = big(200) * 1_048_573u64;
        assert_eq!(
            sqrt_parts(&BigRational::from_integer(n)),
            Some((BigRational::from_integer(big(100)), ints(&[1_048_573])))
        );
        // |n|² for n = (2, 1, 2⁻¹⁰⁷⁴) (the fuzz finding derive-subnormal-number): 5 + 2⁻²¹⁴⁸,
        // whose cofactor stays far beyond the square of the bound: refused, and again (the memo).
        let q = BigRational::from_integer(5.into()) + BigRational::new(1.into(), big(2148));
        assert_eq!(sqrt_parts(&q), None);
        assert_eq!(sqrt_parts(&q), None);
        // A perfect square of thousands of bits is still recognised: (2²¹⁰⁰ + 1)²/4.
        let r = big(2100) + 1;
        let q = BigRational::new(&r * &r, 4.into());
        assert_eq!(
            sqrt_parts(&q),
            Some((BigRational::new(r, 2.into()), vec![]))
        );
    }

    /// The enclosures as they were computed before (one `BigRational` sum per end, each
    /// product reduced): the reference the integer enclosures must equal, end for end.
    fn rational_enclosure(p: &Poly, bits: u32) -> (BigRational, BigRational) {
        let table = symbols::snapshot();
        let scale = BigInt::one() << bits;
        let (mut lo, mut hi) = (BigRational::zero(), BigRational::zero());
        for (m, c) in p.terms() {
            let (mut tlo, mut thi) = (BigRational::one(), BigRational::one());
            for &(v, e) in m.vars() {
                let s = (table.radicand(v).unwrap() * &scale * &scale).sqrt();
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
        (lo, hi)
    }

    /// `to_f64` as it was computed before, from [`rational_enclosure`].
    fn rational_to_f64(p: &Poly) -> f64 {
        if let Some(c) = p.constant_value() {
            return crate::number::rational_to_f64(&c);
        }
        let mut mid = None;
        for bits in precisions().map(|b| b.max(64)) {
            let (lo, hi) = rational_enclosure(p, bits);
            let m = (&lo + &hi) / BigRational::from_integer(2.into());
            let tolerance = m.abs() / BigRational::from_integer(BigInt::one() << 60u32);
            if hi - lo <= tolerance {
                return crate::number::rational_to_f64(&m);
            }
            mid = Some(m);
        }
        crate::number::rational_to_f64(&mid.unwrap())
    }

    /// Constants of ℚ(√2, √3, √5, √7) with coefficients of up to 120 bits, some nearly
    /// cancelling (a + b√2 with a/b close to −√2), from a fixed linear congruential sequence.
    fn constants() -> Vec<Poly> {
        let roots: Vec<Poly> = [2, 3, 5, 7]
            .iter()
            .map(|&p| radical_symbol(&BigInt::from(p)))
            .collect();
        let mut state = 0x2026_1129_u64;
        let mut next = move |bound: u64| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 33) % bound
        };
        let mut out = Vec::new();
        for k in 0..300 {
            let big = BigInt::one() << (k % 4 * 30) as u32;
            let mut p = Poly::zero();
            for subset in 0..16u32 {
                if next(3) == 0 {
                    continue;
                }
                let num = (BigInt::from(next(2001)) - 1000) * &big + next(1000);
                let den = BigInt::from(next(97) + 1);
                let mut t = Poly::constant(BigRational::new(num, den));
                for (i, r) in roots.iter().enumerate() {
                    if subset >> i & 1 == 1 {
                        t = &t * r;
                    }
                }
                p = &p + &t;
            }
            out.push(p);
        }
        // Near cancellation: 665857 − 470832·√2 ≈ 7.5·10⁻⁷, and its square's tiny value.
        let near = &Poly::from_integer(665_857) - &(&Poly::from_integer(470_832) * &roots[0]);
        out.push(&near * &near);
        out.push(near);
        out
    }

    #[test]
    fn integer_enclosures_equal_the_rational_ones() {
        for p in constants() {
            let table = symbols::snapshot();
            for bits in [32, 64, 256] {
                let (lo, hi, d) = enclosure(&table, &p, bits).unwrap();
                let (rlo, rhi) = rational_enclosure(&p, bits);
                let d = BigRational::from_integer(d);
                assert_eq!(BigRational::from_integer(lo) / &d, rlo, "{p}");
                assert_eq!(BigRational::from_integer(hi) / &d, rhi, "{p}");
            }
            assert_eq!(to_f64(&p).to_bits(), rational_to_f64(&p).to_bits(), "{p}");
            let (lo, hi) = rational_enclosure(&p, 1 << 10);
            let expected = if lo.is_positive() {
                1
            } else if hi.is_negative() {
                -1
            } else {
                0
            };
            assert_eq!(sign(&p), Some(expected), "{p}");
        }
    }

    #[test]
    fn enclosures_refuse_free_symbols() {
        let x = &Poly::symbol("x") + &radical_symbol(&BigInt::from(2));
        assert_eq!(sign(&x), None);
        assert!(to_f64(&x).is_nan());
    }

    /// Every value an exact solve of the posed scenes gives — the tilted box of
    /// `examples/tilted-box.toml` at 15°, 30°, 45° and 60° (two contacts) and the box striking a
    /// floor and a wall (`tests/posed/box-floor-wall.toml`, four contacts) at 30° and 60° —
    /// under Newton's and Poisson's laws: impulses, compression impulses, the twist after
    /// impact, contact velocities after, both energies.
    pub(in crate::scalar::symbolic) fn posed_values() -> Vec<super::super::RatFun> {
        use super::super::RatFun;
        use crate::impact::restitution::Model;
        use crate::impact::solve::{Impact, Outcome};
        let tilted = include_str!("../../../examples/tilted-box.toml");
        let corner = include_str!("../../../tests/posed/box-floor-wall.toml");
        let mut out = Vec::new();
        for (text, deg) in [
            (tilted, 15),
            (tilted, 30),
            (tilted, 45),
            (tilted, 60),
            (corner, 30),
            (corner, 60),
        ] {
            let text = text.replace("\"30 deg\"", &format!("\"{deg} deg\""));
            let scene = crate::scene::Scene::parse(&text, "posed").unwrap();
            let problem = scene.problem::<RatFun>().unwrap();
            let mut impact = Impact::assemble(&problem).unwrap();
            for model in [Model::Newton, Model::Poisson] {
                let mut o = Outcome::default();
                impact.solve(model, &mut o).unwrap();
                out.extend(o.impulses_hat.iter().cloned());
                out.extend(o.compression_hat.iter().cloned());
                out.extend(o.velocity.0.iter().cloned());
                out.extend(o.after_hat.iter().flatten().cloned());
                out.push(o.lost_velocity_energy.clone());
                out.push(o.kinetic_energy_loss.clone());
            }
        }
        out
    }

    #[test]
    fn posed_scenes_values_convert_as_before() {
        use crate::scalar::Scalar;
        let values = posed_values();
        let radicals = values.iter().filter(|v| v.to_rational().is_none()).count();
        assert!(radicals >= 40, "{radicals} values with radicals");
        for v in &values {
            let p = v.numer();
            assert!(v.is_constant(), "{v}");
            assert_eq!(to_f64(p).to_bits(), rational_to_f64(p).to_bits(), "{v}");
            let (lo, hi) = rational_enclosure(p, 256);
            let reference = if p.is_zero() {
                0
            } else if lo.is_positive() {
                1
            } else {
                assert!(hi.is_negative(), "{v}: 256 bits decide every sign here");
                -1
            };
            assert_eq!(sign(p), Some(reference), "{v}");
        }
    }
}
