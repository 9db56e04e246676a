//! Dual numbers: a value and one derivative, so that the unchanged solver computes
//! sensitivities by forward-mode automatic differentiation.
//!
//! A dual number is a + a′ε with ε² = 0 (Clifford, 1873). Its arithmetic is
//!
//! ```text
//! (a + a′ε) ± (b + b′ε) = (a ± b) + (a′ ± b′)ε
//! (a + a′ε)(b + b′ε)    = ab + (a′b + ab′)ε
//! (a + a′ε)/(b + b′ε)   = a/b + ((a′b − ab′)/b²)ε
//! √(a + a′ε)            = √a + (a′/(2√a))ε          (a > 0)
//! ```
//!
//! so every rational function (and square root) f satisfies f(x + x′ε) = f(x) + f′(x)x′ε: the
//! ε-part carries the chain rule through every operation (forward mode; Wengert 1964). Seed one
//! input with tangent 1 and every other with 0, run the solver over `Dual<T>`, and the tangent
//! of each output is its derivative with respect to that input — exactly in `Dual<Exact>`
//! (every operation on both parts is exact), to rounding in `Dual<f64>` (the tangent of each
//! operation is computed from rounded operands, an error of the order of the value's).
//!
//! **Branches.** Where the solver decides — a pivot is zero ([`Scalar::is_negligible`]), the
//! larger pivot ([`Scalar::abs_gt`]), a sign ([`Scalar::signum_i8`], [`Scalar::known_sign`]) —
//! a dual number answers for its value alone: a dual run takes the branch of its value, and
//! its tangent is the derivative of that branch's formula. Where the branch is the same on
//! both sides of the point (almost everywhere along a sweep) that is the derivative of the
//! output; at a branch point (a contact that starts or stops taking an impulse, a slip that
//! reverses, G turning singular) the output is continuous at best and its derivative is
//! one-sided: that of the branch the value selects.
//!
//! **Zero and equality are structural**: [`Zero::is_zero`] and `==` compare both parts, so
//! the solver's "skip a zero term" shortcuts never drop a derivative. A test `x.is_zero()`
//! that selects a model (μ = 0: no friction) therefore treats a zero value with a nonzero
//! tangent as nonzero — the side the tangent points into.
//!
//! **Inputs.** [`Scalar::from_number`] takes the value from the base type and the tangent
//! from [`Number::tangent`], an `f64` converted exactly (`BigRational::from_float`), so a
//! derivative seeded through a scene number is exact in `Dual<Exact>` whenever the seed is an
//! f64 (1, a power of two, …).

use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use num_rational::BigRational;
use num_traits::{One, Zero};

use crate::number::Number;
use crate::scalar::Scalar;

/// A dual number value + tangent·ε (ε² = 0) over the base scalar `T`: see the
/// [module docs](self).
#[derive(Clone, Debug, PartialEq)]
pub struct Dual<T: Scalar> {
    /// The value a.
    pub value: T,
    /// The derivative a′ (the coefficient of ε).
    pub tangent: T,
}

impl<T: Scalar> Dual<T> {
    /// value + tangent·ε.
    pub fn new(value: T, tangent: T) -> Self {
        Dual { value, tangent }
    }

    /// A constant: tangent 0.
    pub fn constant(value: T) -> Self {
        Dual {
            value,
            tangent: T::zero(),
        }
    }

    /// The independent variable at `value`: tangent 1.
    pub fn variable(value: T) -> Self {
        Dual {
            value,
            tangent: T::one(),
        }
    }
}

/// The name of `Dual<T>` from the name of `T` (a `const` cannot concatenate strings).
const fn dual_name(base: &str) -> &'static str {
    const fn same(a: &str, b: &str) -> bool {
        let (a, b) = (a.as_bytes(), b.as_bytes());
        if a.len() != b.len() {
            return false;
        }
        let mut i = 0;
        while i < a.len() {
            if a[i] != b[i] {
                return false;
            }
            i += 1;
        }
        true
    }
    if same(base, "f64") {
        "dual"
    } else if same(base, "exact") {
        "dual-exact"
    } else if same(base, "f32") {
        "dual-f32"
    } else if same(base, "double-double") {
        "dual-double-double"
    } else if same(base, "symbolic") {
        "dual-symbolic"
    } else {
        "dual-other"
    }
}

impl<T: Scalar> Zero for Dual<T> {
    fn zero() -> Self {
        Dual::constant(T::zero())
    }
    /// Both parts zero (see the module docs: structural).
    fn is_zero(&self) -> bool {
        self.value.is_zero() && self.tangent.is_zero()
    }
}

impl<T: Scalar> One for Dual<T> {
    fn one() -> Self {
        Dual::constant(T::one())
    }
}

impl<T: Scalar> Neg for Dual<T> {
    type Output = Self;
    fn neg(self) -> Self {
        Dual {
            value: -self.value,
            tangent: -self.tangent,
        }
    }
}

impl<T: Scalar> AddAssign<&Dual<T>> for Dual<T> {
    fn add_assign(&mut self, b: &Self) {
        self.value += &b.value;
        self.tangent += &b.tangent;
    }
}

impl<T: Scalar> SubAssign<&Dual<T>> for Dual<T> {
    fn sub_assign(&mut self, b: &Self) {
        self.value -= &b.value;
        self.tangent -= &b.tangent;
    }
}

impl<T: Scalar> MulAssign<&Dual<T>> for Dual<T> {
    /// (a + a′ε)(b + b′ε) = ab + (a′b + ab′)ε.
    fn mul_assign(&mut self, b: &Self) {
        let cross = self.value.clone() * &b.tangent;
        self.tangent *= &b.value;
        self.tangent += cross;
        self.value *= &b.value;
    }
}

impl<T: Scalar> DivAssign<&Dual<T>> for Dual<T> {
    /// (a + a′ε)/(b + b′ε) = q + ((a′ − q b′)/b)ε with q = a/b, which is (a′b − ab′)/b².
    fn div_assign(&mut self, b: &Self) {
        self.value /= &b.value;
        self.tangent -= self.value.clone() * &b.tangent;
        self.tangent /= &b.value;
    }
}

/// The by-value operators and assignments, from the by-reference assignment.
macro_rules! dual_ops {
    ($($tr:ident, $f:ident, $tra:ident, $fa:ident);*) => {$(
        impl<T: Scalar> $tra for Dual<T> {
            fn $fa(&mut self, b: Self) {
                <Self as $tra<&Self>>::$fa(self, &b);
            }
        }
        impl<T: Scalar> $tr<&Dual<T>> for Dual<T> {
            type Output = Self;
            fn $f(mut self, b: &Self) -> Self {
                <Self as $tra<&Self>>::$fa(&mut self, b);
                self
            }
        }
        impl<T: Scalar> $tr for Dual<T> {
            type Output = Self;
            fn $f(mut self, b: Self) -> Self {
                <Self as $tra<&Self>>::$fa(&mut self, &b);
                self
            }
        }
    )*};
}

dual_ops!(
    Add, add, AddAssign, add_assign;
    Sub, sub, SubAssign, sub_assign;
    Mul, mul, MulAssign, mul_assign;
    Div, div, DivAssign, div_assign
);

impl<T: Scalar> Dual<T> {
    /// √ of the value by `root` (the base type's exact or rounded square root), with
    /// d√x = dx/(2√x); `None` when the base has no root, and when the value is 0 but the
    /// tangent is not (√ has no derivative at 0).
    fn sqrt_with(&self, root: impl Fn(&T) -> Option<T>) -> Option<Self> {
        let r = root(&self.value)?;
        if self.tangent.is_zero() {
            return Some(Dual::constant(r));
        }
        if r.is_zero() {
            return None;
        }
        let tangent = self.tangent.clone() / (r.clone() + &r);
        Some(Dual { value: r, tangent })
    }
}

impl<T: Scalar> Scalar for Dual<T> {
    const NAME: &'static str = dual_name(T::NAME);
    const IS_EXACT: bool = T::IS_EXACT;
    const IS_DUAL: bool = true;

    fn from_rational(q: &BigRational) -> Self {
        Dual::constant(T::from_rational(q))
    }

    fn from_f64(x: f64) -> Option<Self> {
        T::from_f64(x).map(Dual::constant)
    }

    /// The value's.
    fn to_f64(&self) -> f64 {
        self.value.to_f64()
    }

    /// The value's.
    fn to_rational(&self) -> Option<BigRational> {
        self.value.to_rational()
    }

    /// The value's.
    fn exact_value(&self) -> Option<BigRational> {
        self.value.exact_value()
    }

    /// The value's decision (see the module docs: the branch is the value's).
    fn is_negligible(&self, reference: &Self, n: usize) -> bool {
        self.value.is_negligible(&reference.value, n)
    }

    /// The value's.
    fn abs_gt(&self, other: &Self) -> bool {
        self.value.abs_gt(&other.value)
    }

    /// The value's.
    fn signum_i8(&self) -> i8 {
        self.value.signum_i8()
    }

    fn epsilon_f64() -> f64 {
        T::epsilon_f64()
    }

    /// The value from the base type's [`Scalar::from_number`]; the tangent from
    /// [`Number::tangent`], converted from f64 exactly (so an exact base keeps it exact; a
    /// parameter seeded through `Number::tangent` carries an f64 derivative).
    fn from_number(n: &Number) -> Result<Self, String> {
        let value = T::from_number(n)?;
        if n.tangent == 0.0 {
            return Ok(Dual::constant(value));
        }
        let t = BigRational::from_float(n.tangent)
            .ok_or_else(|| format!("its derivative (tangent) {} is not finite", n.tangent))?;
        Ok(Dual {
            value,
            tangent: T::from_rational(&t),
        })
    }

    /// The value's.
    fn exact_text(&self) -> Option<String> {
        self.value.exact_text()
    }

    /// The value's.
    fn latex_text(&self) -> Option<String> {
        self.value.latex_text()
    }

    /// √ when the value's root is exact, with d√x = dx/(2√x).
    fn sqrt_exact(&self) -> Option<Self> {
        self.sqrt_with(T::sqrt_exact)
    }

    /// √ by the base type's [`Scalar::sqrt_value`], with d√x = dx/(2√x).
    fn sqrt_value(&self) -> Option<Self> {
        self.sqrt_with(T::sqrt_value)
    }

    /// Both parts finite.
    fn is_finite(&self) -> bool {
        self.value.is_finite() && self.tangent.is_finite()
    }

    /// The value's.
    fn known_sign(&self) -> Option<i8> {
        self.value.known_sign()
    }

    fn dual_parts(&self) -> Option<(Self, Self)> {
        Some((
            Dual::constant(self.value.clone()),
            Dual::constant(self.tangent.clone()),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Exact, int, ratio};

    type D = Dual<Exact>;

    fn d(v: (i64, i64), t: (i64, i64)) -> D {
        Dual::new(ratio(v.0, v.1), ratio(t.0, t.1))
    }

    #[test]
    fn arithmetic_is_the_chain_rule_exactly() {
        // x = 3/2 + ε; f(x) = (x² + 1)/(2x − 1), f′(x) = (2x(2x − 1) − 2(x² + 1))/(2x − 1)².
        let x = Dual::variable(ratio::<Exact>(3, 2));
        let one = D::one();
        let two = one.clone() + &one;
        let f = (x.clone() * &x + &one) / (two * &x - one);
        assert_eq!(f.value, ratio(13, 8)); // (9/4 + 1)/2
        assert_eq!(f.tangent, ratio(-1, 8)); // (3·2 − 2·13/4)/4
        // By value, by reference and assignments agree.
        let (a, b) = (d((2, 3), (1, 5)), d((-7, 4), (3, 1)));
        let mut c = a.clone();
        c *= &b;
        assert_eq!(c, a.clone() * b.clone());
        let q = ratio::<Exact>;
        assert_eq!(c.tangent, q(1, 5) * q(-7, 4) + q(2, 3) * int::<Exact>(3));
        let mut q = a.clone();
        q /= b.clone();
        assert_eq!(q.clone() * &b, a);
        assert_eq!(a.clone() - &b + &b, a);
        assert_eq!(-(-a.clone()), a);
    }

    #[test]
    fn decisions_are_the_values_and_zero_is_structural() {
        let z = d((0, 1), (1, 1));
        assert!(!z.is_zero());
        assert!(D::zero().is_zero());
        assert_eq!(z.signum_i8(), 0);
        assert!(z.is_negligible(&D::one(), 4));
        assert!(d((-1, 2), (9, 1)).abs_gt(&d((1, 3), (-100, 1))));
        assert_eq!(d((-1, 2), (9, 1)).known_sign(), Some(-1));
        assert_ne!(d((1, 2), (0, 1)), d((1, 2), (1, 1)));
    }

    #[test]
    fn square_roots_and_their_derivative() {
        // √(9/4 + ε) = 3/2 + ε/3.
        let r = d((9, 4), (1, 1)).sqrt_exact().unwrap();
        assert_eq!(r, d((3, 2), (1, 3)));
        assert_eq!(d((2, 1), (1, 1)).sqrt_exact(), None); // √2 is not rational
        assert_eq!(d((0, 1), (1, 1)).sqrt_value(), None); // no derivative at 0
        assert_eq!(d((0, 1), (0, 1)).sqrt_value(), Some(D::zero()));
        let f = Dual::variable(2.0f64).sqrt_value().unwrap();
        assert_eq!(f.value, 2f64.sqrt());
        assert!((f.tangent - 0.25 * 2f64.sqrt()).abs() <= 1e-16);
    }

    #[test]
    fn numbers_seed_their_tangent_exactly() {
        let mut n = crate::number::parse_number("0.1").unwrap();
        assert_eq!(D::from_number(&n).unwrap(), d((1, 10), (0, 1)));
        n.tangent = 1.0;
        assert_eq!(D::from_number(&n).unwrap(), d((1, 10), (1, 1)));
        n.tangent = 0.1; // the binary f64 0.1, exactly
        let t = D::from_number(&n).unwrap().tangent;
        assert_eq!(t, Exact::from(BigRational::from_float(0.1).unwrap()));
        assert_ne!(t, ratio(1, 10));
        let f = Dual::<f64>::from_number(&n).unwrap();
        assert_eq!((f.value, f.tangent), (0.1, 0.1));
        n.tangent = f64::NAN;
        assert!(D::from_number(&n).unwrap_err().contains("not finite"));
        assert!(!Dual::<f64>::new(1.0, f64::INFINITY).is_finite());
    }

    #[test]
    fn names_and_parts() {
        assert_eq!(<Dual<f64> as Scalar>::NAME, "dual");
        assert_eq!(<D as Scalar>::NAME, "dual-exact");
        assert_eq!(<Dual<f32> as Scalar>::NAME, "dual-f32");
        const { assert!(<D as Scalar>::IS_EXACT && <D as Scalar>::IS_DUAL) };
        const { assert!(!<Dual<f64> as Scalar>::IS_EXACT && !<f64 as Scalar>::IS_DUAL) };
        assert_eq!(d((1, 3), (2, 1)).exact_text().as_deref(), Some("1/3"));
        assert_eq!(d((1, 3), (2, 1)).to_f64(), 1.0 / 3.0);
        let (v, t) = d((1, 3), (2, 1)).dual_parts().unwrap();
        assert_eq!((v, t), (d((1, 3), (0, 1)), d((2, 1), (0, 1))));
        assert_eq!(ratio::<Exact>(1, 3).dual_parts(), None);
    }
}
