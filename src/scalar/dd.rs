//! Double-double arithmetic: a value hi + lo with |lo| ≤ ½ulp(hi), about 106 significant bits.
//!
//! Built from the error-free transformations two-sum (Knuth) and two-product (one fused
//! multiply-add), after Hida, Li and Bailey's QD library ("accurate" addition, so sums of
//! values of opposite sign stay accurate). A small type of our own rather than a crate
//! because the solver needs exactly what [`Scalar`] asks — field operations by value and by
//! reference, a correctly rounded conversion from an exact rational (hi = ○(q), lo = ○(q − hi)),
//! and the exact value back ([`Scalar::exact_value`]) to measure errors against exact results —
//! and no more (no transcendental functions).
//!
//! Unit roundoff 2⁻¹⁰⁴ ≈ 4.9·10⁻³² for +, −, ×; ÷ is accurate to a few units of it.

use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use num_rational::BigRational;
use num_traits::{One, Zero};

use crate::scalar::Scalar;

/// A double-double number hi + lo.
#[derive(Clone, Copy, PartialEq, Default)]
pub struct DoubleDouble {
    hi: f64,
    lo: f64,
}

/// s + e = a + b exactly (Knuth's two-sum).
#[inline]
fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// s + e = a + b exactly, for |a| ≥ |b|.
#[inline]
fn quick_two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    (s, b - (s - a))
}

/// p + e = a·b exactly (one fused multiply-add).
#[inline]
fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

impl DoubleDouble {
    /// hi + lo, normalised.
    pub fn new(hi: f64, lo: f64) -> Self {
        let (hi, lo) = two_sum(hi, lo);
        DoubleDouble { hi, lo }
    }

    /// The leading part.
    pub fn hi(self) -> f64 {
        self.hi
    }

    /// The trailing part.
    pub fn lo(self) -> f64 {
        self.lo
    }

    /// |self|.
    pub fn abs(self) -> Self {
        if self.hi < 0.0 || (self.hi == 0.0 && self.lo < 0.0) {
            -self
        } else {
            self
        }
    }

    /// self · 2^k, exactly (both parts scaled; k split so no factor overflows).
    fn ldexp(self, k: i32) -> Self {
        let (a, b) = (k / 2, k - k / 2);
        let (fa, fb) = (2f64.powi(a), 2f64.powi(b));
        DoubleDouble {
            hi: self.hi * fa * fb,
            lo: self.lo * fa * fb,
        }
    }

    /// e^self, to a few units of 2⁻¹⁰⁴ relative (Hida, Li and Bailey's QD `exp`): x = k ln 2 + r
    /// with |r| ≤ ln 2 / 2, e^r = (e^(r/2¹⁰))^(2¹⁰) with e^(r/2¹⁰) − 1 by its Taylor series to
    /// below 2⁻¹¹⁰ (|r/2¹⁰| < 3.4·10⁻⁴: nine terms), squared back as s ↦ 2s + s² ten times (so
    /// the 1 is added last and its rounding is not squared), then scaled by 2^k exactly.
    pub fn exp(self) -> Self {
        if self.hi > 709.8 {
            return DoubleDouble::new(f64::INFINITY, 0.0);
        }
        if self.hi < -745.2 {
            return DoubleDouble::zero();
        }
        let k = (self.hi / LN_2.hi).round();
        let r = (self - LN_2 * DoubleDouble::new(k, 0.0)).ldexp(-10);
        let (mut s, mut term) = (r, r);
        for i in 2..=12 {
            term = term * r / DoubleDouble::new(f64::from(i), 0.0);
            s += term;
            if term.hi.abs() <= 1e-36 * s.hi.abs() {
                break;
            }
        }
        for _ in 0..10 {
            s = s + s + s * s;
        }
        (s + DoubleDouble::one()).ldexp(k as i32)
    }

    /// ln self for self > 0 (NaN otherwise): one Newton step y + x e^(−y) − 1 from the f64
    /// logarithm y doubles its 53 correct bits (as QD's `log`).
    pub fn ln(self) -> Self {
        if self.hi.is_nan() || self.hi <= 0.0 {
            return DoubleDouble::new(f64::NAN, 0.0);
        }
        let y = DoubleDouble::new(self.hi.ln(), 0.0);
        y + self * (-y).exp() - DoubleDouble::one()
    }

    /// self^a for self ≥ 0 and a > 0: e^(a ln self), 0 at self = 0. Its relative error is a few
    /// units of 2⁻¹⁰⁴ times (1 + |a ln self|).
    pub fn powf(self, a: Self) -> Self {
        if self.hi == 0.0 {
            return DoubleDouble::zero();
        }
        (a * self.ln()).exp()
    }
}

/// ln 2 in double-double (QD's `dd_real::_log2`).
const LN_2: DoubleDouble = DoubleDouble {
    hi: std::f64::consts::LN_2,
    lo: 2.319_046_813_846_299_6e-17,
};

impl fmt::Debug for DoubleDouble {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "dd({:e} + {:e})", self.hi, self.lo)
    }
}

impl Add for DoubleDouble {
    type Output = Self;
    #[inline]
    fn add(self, b: Self) -> Self {
        let (s, e) = two_sum(self.hi, b.hi);
        let (t, f) = two_sum(self.lo, b.lo);
        let (s, e) = quick_two_sum(s, e + t);
        let (hi, lo) = quick_two_sum(s, e + f);
        DoubleDouble { hi, lo }
    }
}

impl Neg for DoubleDouble {
    type Output = Self;
    #[inline]
    fn neg(self) -> Self {
        DoubleDouble {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

impl Sub for DoubleDouble {
    type Output = Self;
    #[inline]
    fn sub(self, b: Self) -> Self {
        self + (-b)
    }
}

impl Mul for DoubleDouble {
    type Output = Self;
    #[inline]
    fn mul(self, b: Self) -> Self {
        let (p, e) = two_prod(self.hi, b.hi);
        let e = e + (self.hi * b.lo + self.lo * b.hi);
        let (hi, lo) = quick_two_sum(p, e);
        DoubleDouble { hi, lo }
    }
}

impl Div for DoubleDouble {
    type Output = Self;
    #[inline]
    fn div(self, b: Self) -> Self {
        // Three correction steps of long division on the leading parts.
        let q1 = self.hi / b.hi;
        let r = self - b * DoubleDouble { hi: q1, lo: 0.0 };
        let q2 = r.hi / b.hi;
        let r = r - b * DoubleDouble { hi: q2, lo: 0.0 };
        let q3 = r.hi / b.hi;
        let (hi, lo) = quick_two_sum(q1, q2);
        DoubleDouble { hi, lo } + DoubleDouble { hi: q3, lo: 0.0 }
    }
}

macro_rules! by_ref_and_assign {
    ($($tr:ident $m:ident $atr:ident $am:ident),*) => {$(
        impl<'a> $tr<&'a DoubleDouble> for DoubleDouble {
            type Output = DoubleDouble;
            #[inline]
            fn $m(self, b: &'a DoubleDouble) -> DoubleDouble { $tr::$m(self, *b) }
        }
        impl $atr for DoubleDouble {
            #[inline]
            fn $am(&mut self, b: DoubleDouble) { *self = $tr::$m(*self, b) }
        }
        impl<'a> $atr<&'a DoubleDouble> for DoubleDouble {
            #[inline]
            fn $am(&mut self, b: &'a DoubleDouble) { *self = $tr::$m(*self, *b) }
        }
    )*};
}

by_ref_and_assign!(Add add AddAssign add_assign, Sub sub SubAssign sub_assign, Mul mul MulAssign mul_assign, Div div DivAssign div_assign);

impl Zero for DoubleDouble {
    fn zero() -> Self {
        DoubleDouble { hi: 0.0, lo: 0.0 }
    }
    fn is_zero(&self) -> bool {
        self.hi == 0.0
    }
}

impl One for DoubleDouble {
    fn one() -> Self {
        DoubleDouble { hi: 1.0, lo: 0.0 }
    }
}

/// 2⁻¹⁰⁴: the unit roundoff of double-double arithmetic.
const EPSILON: f64 = 4.930380657631324e-32;

impl Scalar for DoubleDouble {
    const NAME: &'static str = "double-double";
    const IS_EXACT: bool = false;

    fn from_rational(q: &BigRational) -> Self {
        let hi = crate::number::rational_to_f64(q);
        let rest = match BigRational::from_float(hi) {
            Some(h) => q - h,
            None => return DoubleDouble { hi, lo: 0.0 },
        };
        DoubleDouble::new(hi, crate::number::rational_to_f64(&rest))
    }
    fn from_f64(x: f64) -> Option<Self> {
        Some(DoubleDouble { hi: x, lo: 0.0 })
    }
    fn to_f64(&self) -> f64 {
        self.hi + self.lo
    }
    fn to_rational(&self) -> Option<BigRational> {
        None
    }
    fn exact_value(&self) -> Option<BigRational> {
        Some(BigRational::from_float(self.hi)? + BigRational::from_float(self.lo)?)
    }
    fn is_negligible(&self, reference: &Self, n: usize) -> bool {
        let tol = (n.max(1) as f64) * EPSILON;
        self.abs().hi <= tol * reference.abs().hi
    }
    fn abs_gt(&self, other: &Self) -> bool {
        let (a, b) = (self.abs(), other.abs());
        match a.hi.partial_cmp(&b.hi) {
            Some(Ordering::Greater) => true,
            Some(Ordering::Equal) => a.lo > b.lo,
            _ => false,
        }
    }
    fn signum_i8(&self) -> i8 {
        if self.hi > 0.0 || (self.hi == 0.0 && self.lo > 0.0) {
            1
        } else if self.hi < 0.0 || (self.hi == 0.0 && self.lo < 0.0) {
            -1
        } else {
            0
        }
    }
    fn epsilon_f64() -> f64 {
        EPSILON
    }
    /// One Newton step from the f64 root, r = h + (x − h²)/(2h), doubles its 53 correct bits
    /// to the type's 106 (Karp and Markstein; as in the QD library's `sqrt`).
    fn sqrt_value(&self) -> Option<Self> {
        if self.signum_i8() < 0 {
            return None;
        }
        if self.hi == 0.0 {
            return Some(DoubleDouble::zero());
        }
        let h = DoubleDouble::new(self.hi.sqrt(), 0.0);
        Some(h + (*self - h * h) / (h + h))
    }
    fn is_finite(&self) -> bool {
        self.hi.is_finite() && self.lo.is_finite()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(BigInt::from(n), BigInt::from(d))
    }

    fn error(x: DoubleDouble, exact: &BigRational) -> f64 {
        let diff = x.exact_value().unwrap() - exact;
        (crate::number::rational_to_f64(&diff) / crate::number::rational_to_f64(exact)).abs()
    }

    #[test]
    fn one_third_to_106_bits() {
        let third = DoubleDouble::from_rational(&q(1, 3));
        assert!(error(third, &q(1, 3)) < 2.0 * EPSILON);
        let one = third + third + third;
        assert!(error(one, &q(1, 1)) < 4.0 * EPSILON);
        let x = DoubleDouble::one() / DoubleDouble::from_rational(&q(3, 1));
        assert!(error(x, &q(1, 3)) < 4.0 * EPSILON);
    }

    #[test]
    fn arithmetic_is_accurate_to_a_few_units_of_2_pow_minus_104() {
        // (1/7)·(22/7) − (1/3)/(5/11), computed in double-double against the exact value.
        let (a, b, c, d) = (q(1, 7), q(22, 7), q(1, 3), q(5, 11));
        let exact = a.clone() * &b - c.clone() / &d;
        let f = |r: &BigRational| DoubleDouble::from_rational(r);
        let dd = f(&a) * f(&b) - f(&c) / f(&d);
        assert!(error(dd, &exact) < 16.0 * EPSILON, "{}", error(dd, &exact));
    }

    /// e^(1/2)·e^(1/2) = e, ln e^x = x and 2^(3/2)·2^(3/2) = 8, each to a few units of
    /// 2⁻¹⁰⁴ (the exact values are not rational, so the identities stand in for them).
    #[test]
    fn exp_ln_and_powf_to_a_few_units_of_2_pow_minus_104() {
        let half = DoubleDouble::from_rational(&q(1, 2));
        let e = DoubleDouble::one().exp();
        let root = half.exp();
        assert!(((root * root - e) / e).abs().hi <= 8.0 * EPSILON);
        for x in [q(3, 7), q(-5, 2), q(40, 1), q(-1, 1000)] {
            let dd = DoubleDouble::from_rational(&x);
            let back = dd.exp().ln();
            assert!(
                error(back, &x) <= 64.0 * EPSILON,
                "{x}: {}",
                error(back, &x)
            );
        }
        let two = DoubleDouble::from_rational(&q(2, 1));
        let p = two.powf(DoubleDouble::from_rational(&q(3, 2)));
        assert!(
            error(p * p, &q(8, 1)) <= 32.0 * EPSILON,
            "{}",
            error(p * p, &q(8, 1))
        );
        let third = DoubleDouble::from_rational(&q(1, 3)).powf(two);
        assert!(error(third, &q(1, 9)) <= 32.0 * EPSILON);
        assert_eq!(DoubleDouble::zero().powf(two), DoubleDouble::zero());
    }

    #[test]
    fn cancellation_keeps_the_low_part() {
        let big = DoubleDouble::from_rational(&q(1, 1)) + DoubleDouble::from_f64(1e-20).unwrap();
        let diff = big - DoubleDouble::one();
        assert!((diff.to_f64() - 1e-20).abs() < 1e-36);
        assert_eq!(diff.signum_i8(), 1);
        assert!(
            DoubleDouble::from_f64(-2.0)
                .unwrap()
                .abs_gt(&DoubleDouble::one())
        );
    }
}
