//! The scalar types the solver runs in, and the few decisions that differ between them.
//!
//! The solver asks only for a **field** ([`Field`]: `+ − × ÷`, zero, one) plus three
//! capabilities gathered in [`Scalar`]: converting an exact input into the type, converting a
//! result out to `f64`, and deciding whether a pivot is zero. No square root is ever taken, so
//! exact rationals run the very same code as floats: contact axes are kept unnormalised and the
//! norms are applied when results are reported (see [`crate::mechanics::contact`]).
//!
//! Supported scalars (a closed set, as in Drake's `default_scalars`):
//!
//! | type | name | zero test |
//! |---|---|---|
//! | `f32` | `"f32"` | `|x| ≤ n·ε·|reference|` |
//! | `f64` | `"f64"` | `|x| ≤ n·ε·|reference|` |
//! | [`DoubleDouble`](crate::scalar::dd::DoubleDouble) | `"double-double"` | `|x| ≤ n·2⁻¹⁰⁴·|reference|` |
//! | [`Exact`] = [`Rational`](crate::scalar::rational::Rational) | `"exact"` | `x = 0` |
//! | `BigRational` (the plain num-rational type `Exact` is tested against) | `"exact"` | `x = 0` |
//! | [`RatFun`](crate::scalar::symbolic::RatFun) | `"symbolic"` | `x ≡ 0` (as a rational function) |
//! | [`Dual<T>`](crate::scalar::dual::Dual) over any of the above | `"dual"` (f64), `"dual-exact"`, … | the value's zero test |
//!
//! `Dual<T>` is a value and one derivative (forward-mode automatic differentiation): the
//! solver run over it gives each output's derivative with respect to the one input seeded
//! with a nonzero [`Number::tangent`] — the derivative of the branch the value takes
//! ([`dual`]).

use std::fmt::Debug;
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

pub mod dd;
pub mod dual;
pub mod rational;
pub mod symbolic;

use crate::number::Number;

/// Exact rational arithmetic: the reference scalar of the toolkit ([`rational::Rational`], the
/// same numbers as `BigRational` with a machine-word fast path).
pub type Exact = rational::Rational;

/// The arithmetic the solver needs: a field, with operations by value and by reference
/// (so big rationals are not cloned needlessly).
pub trait Field:
    Clone
    + PartialEq
    + Debug
    + 'static
    + Zero
    + One
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + MulAssign
    + DivAssign
    + for<'a> Add<&'a Self, Output = Self>
    + for<'a> Sub<&'a Self, Output = Self>
    + for<'a> Mul<&'a Self, Output = Self>
    + for<'a> Div<&'a Self, Output = Self>
    + for<'a> AddAssign<&'a Self>
    + for<'a> SubAssign<&'a Self>
    + for<'a> MulAssign<&'a Self>
    + for<'a> DivAssign<&'a Self>
{
}

impl<T> Field for T where
    T: Clone
        + PartialEq
        + Debug
        + 'static
        + Zero
        + One
        + Add<Output = T>
        + Sub<Output = T>
        + Mul<Output = T>
        + Div<Output = T>
        + Neg<Output = T>
        + AddAssign
        + SubAssign
        + MulAssign
        + DivAssign
        + for<'a> Add<&'a T, Output = T>
        + for<'a> Sub<&'a T, Output = T>
        + for<'a> Mul<&'a T, Output = T>
        + for<'a> Div<&'a T, Output = T>
        + for<'a> AddAssign<&'a T>
        + for<'a> SubAssign<&'a T>
        + for<'a> MulAssign<&'a T>
        + for<'a> DivAssign<&'a T>
{
}

/// A scalar the solver runs in: a [`Field`] that can be built from exact input, read out as
/// `f64`, and asked whether a value is zero relative to a reference magnitude.
pub trait Scalar: Field {
    /// The name used in reports (`"f32"`, `"f64"`, `"exact"`).
    const NAME: &'static str;
    /// Whether every operation is exact, so that a zero test is a proof.
    const IS_EXACT: bool;
    /// Whether a value carries a derivative ([`dual::Dual`]): a stage whose steps are not
    /// differentiable functions of its inputs (the adaptive spatial friction integrator)
    /// refuses such a type rather than return a wrong derivative.
    const IS_DUAL: bool = false;

    /// The value of an exact rational in this type (rounded for floats).
    fn from_rational(q: &BigRational) -> Self;

    /// The value of an `f64` in this type; `None` when the type is exact and so refuses to
    /// take a rounded input for an exact one.
    fn from_f64(x: f64) -> Option<Self>;

    /// An approximation in `f64`, for display and for comparison with printed values.
    fn to_f64(&self) -> f64;

    /// The exact rational value, for exact types.
    fn to_rational(&self) -> Option<BigRational>;

    /// The exact value of this representation (for floats, their binary value), to measure
    /// errors against an exact result; `None` for NaN and infinities.
    fn exact_value(&self) -> Option<BigRational> {
        self.to_rational()
    }

    /// Is `self` zero, relative to the magnitude `reference` of the quantities it was computed
    /// from, in a problem of dimension `n`? Exact types answer `self == 0`; floats answer
    /// `|self| ≤ n·ε·|reference|`, the rounding error of an `n`-term computation at that scale.
    fn is_negligible(&self, reference: &Self, n: usize) -> bool;

    /// `|self| > |other|`, used only to choose pivots (any choice is correct in exact
    /// arithmetic; in floats the larger pivot is the stable one).
    fn abs_gt(&self, other: &Self) -> bool;

    /// The sign of the value: −1, 0 or 1 (exact types decide exactly; floats by the bit sign
    /// of a nonzero value).
    fn signum_i8(&self) -> i8;

    /// Machine epsilon (zero for exact types): the unit of a tolerance claim.
    fn epsilon_f64() -> f64;

    /// The value of a scene number in this type. Exact types take its exact value and refuse
    /// an irrational one (the symbolic type evaluates radicals and symbols exactly); floats
    /// take the rounded value. The error says why, for a message that names key and value.
    fn from_number(n: &Number) -> Result<Self, String> {
        match &n.exact {
            Ok(q) => Ok(Self::from_rational(q)),
            Err(why) => Self::from_f64(n.approx).ok_or_else(|| {
                format!(
                    "not a rational number ({why}); exact mode reads every number exactly, so \
                     write it as a fraction or run without --exact"
                )
            }),
        }
    }

    /// The exact value as text (`p/q`; an expression for the symbolic type), `None` for floats.
    fn exact_text(&self) -> Option<String> {
        self.to_rational()
            .map(|q| crate::number::format_rational(&q))
    }

    /// The exact value in LaTeX, when the type has a form of its own (the symbolic type);
    /// `None` means the plain [`Scalar::exact_text`] serves.
    fn latex_text(&self) -> Option<String> {
        None
    }

    /// √self when it is exactly representable in this type (a rational square for
    /// rationals; any rational ≥ 0 for the symbolic type, as a radical); `None` otherwise and
    /// for floats (reports evaluate those instead).
    fn sqrt_exact(&self) -> Option<Self> {
        None
    }

    /// √self as a value of this type, for self ≥ 0: correctly rounded for floats, exact
    /// when representable for exact types ([`Scalar::sqrt_exact`]), `None` otherwise. How a
    /// quantity that carries an axis norm (an impulse P_i = P̂_i |n_i|) becomes one number.
    fn sqrt_value(&self) -> Option<Self> {
        self.sqrt_exact()
    }

    /// Whether the value is a finite number (false for NaN and ±∞; always true for exact types).
    fn is_finite(&self) -> bool {
        true
    }

    /// The sign when it is decided without assuming anything: −1, 0 or 1 for numbers; `None`
    /// for a symbolic expression whose sign depends on its symbols (the symbolic type records
    /// no assumption here, unlike [`Scalar::signum_i8`]).
    fn known_sign(&self) -> Option<i8> {
        Some(self.signum_i8())
    }

    /// A dual number's value and derivative, each as a number of this type with a zero
    /// derivative ([`dual::Dual`]); `None` for every other type. How a report reads a
    /// derivative out of a generic solve.
    fn dual_parts(&self) -> Option<(Self, Self)> {
        None
    }
}

/// A float scalar with the real functions a numerical integration takes — the LZB law's
/// forces u^η ([`crate::impact::multiple::lzb`]) and its slip directions' norms: `f64` and
/// [`DoubleDouble`](dd::DoubleDouble), the two types it runs in. Every `f64` is exactly a value
/// of the type ([`Real::of`]), so parameters given in `f64` enter without a second rounding.
pub trait Real: Scalar + Copy {
    /// The `f64` x, exactly.
    fn of(x: f64) -> Self;
    /// self^a for self ≥ 0 and a > 0 (0 at self = 0); the exponent in the type, so that
    /// 1/(η + 1) is not rounded to `f64` first.
    fn powf(self, a: Self) -> Self;
    /// √self for self ≥ 0.
    fn sqrt(self) -> Self;
    /// |self|.
    fn abs(self) -> Self;
}

impl Real for f64 {
    #[inline]
    fn of(x: f64) -> Self {
        x
    }
    #[inline]
    fn powf(self, a: Self) -> Self {
        f64::powf(self, a)
    }
    #[inline]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
    #[inline]
    fn abs(self) -> Self {
        f64::abs(self)
    }
}

impl Real for dd::DoubleDouble {
    fn of(x: f64) -> Self {
        dd::DoubleDouble::new(x, 0.0)
    }
    fn powf(self, a: Self) -> Self {
        dd::DoubleDouble::powf(self, a)
    }
    fn sqrt(self) -> Self {
        self.sqrt_value()
            .unwrap_or_else(|| dd::DoubleDouble::new(f64::NAN, 0.0))
    }
    fn abs(self) -> Self {
        dd::DoubleDouble::abs(self)
    }
}

macro_rules! float_scalar {
    ($t:ty, $name:literal) => {
        impl Scalar for $t {
            const NAME: &'static str = $name;
            const IS_EXACT: bool = false;

            fn from_rational(q: &BigRational) -> Self {
                crate::number::rational_to_f64(q) as $t
            }
            fn from_f64(x: f64) -> Option<Self> {
                Some(x as $t)
            }
            fn to_f64(&self) -> f64 {
                *self as f64
            }
            fn to_rational(&self) -> Option<BigRational> {
                None
            }
            fn exact_value(&self) -> Option<BigRational> {
                BigRational::from_float(*self)
            }
            fn is_negligible(&self, reference: &Self, n: usize) -> bool {
                self.abs() <= (n.max(1) as $t) * <$t>::EPSILON * reference.abs()
            }
            fn abs_gt(&self, other: &Self) -> bool {
                self.abs() > other.abs()
            }
            fn signum_i8(&self) -> i8 {
                if *self > 0.0 {
                    1
                } else if *self < 0.0 {
                    -1
                } else {
                    0
                }
            }
            fn epsilon_f64() -> f64 {
                <$t>::EPSILON as f64
            }
            fn sqrt_value(&self) -> Option<Self> {
                (*self >= 0.0).then(|| self.sqrt())
            }
            fn is_finite(&self) -> bool {
                <$t>::is_finite(*self)
            }
        }
    };
}

float_scalar!(f32, "f32");
float_scalar!(f64, "f64");

impl Scalar for BigRational {
    const NAME: &'static str = "exact";
    const IS_EXACT: bool = true;

    fn from_rational(q: &BigRational) -> Self {
        q.clone()
    }
    fn from_f64(_: f64) -> Option<Self> {
        None
    }
    fn to_f64(&self) -> f64 {
        crate::number::rational_to_f64(self)
    }
    fn to_rational(&self) -> Option<BigRational> {
        Some(self.clone())
    }
    fn is_negligible(&self, _reference: &Self, _n: usize) -> bool {
        self.is_zero()
    }
    fn abs_gt(&self, other: &Self) -> bool {
        self.abs() > other.abs()
    }
    fn signum_i8(&self) -> i8 {
        if self.is_positive() {
            1
        } else if self.is_negative() {
            -1
        } else {
            0
        }
    }
    fn epsilon_f64() -> f64 {
        0.0
    }
    fn sqrt_exact(&self) -> Option<Self> {
        if self.is_negative() {
            return None;
        }
        let (n, d) = (self.numer().sqrt(), self.denom().sqrt());
        let root = BigRational::new(n, d);
        (&root * &root == *self).then_some(root)
    }
}

/// The fraction p/q in any scalar type: exact in exact types, correctly rounded in floats.
///
/// # Panics
/// If q = 0, like [`BigRational::new`].
pub fn ratio<T: Scalar>(p: i64, q: i64) -> T {
    T::from_rational(&BigRational::new(BigInt::from(p), BigInt::from(q)))
}

/// A small integer in any scalar type (exact for every supported type).
pub fn int<T: Scalar>(n: i64) -> T {
    T::from_rational(&BigRational::from_integer(BigInt::from(n)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Exact {
        Exact::new(n.into(), d.into())
    }

    #[test]
    fn exact_zero_test_is_exact() {
        assert!(Exact::zero().is_negligible(&q(1, 1), 6));
        assert!(!q(1, 1_000_000_000_000).is_negligible(&q(1, 1), 6));
    }

    #[test]
    fn float_zero_test_scales_with_the_reference() {
        assert!(1e-17f64.is_negligible(&1.0, 1));
        assert!(!1e-17f64.is_negligible(&1e-3, 1));
        assert!(!1e-10f64.is_negligible(&1.0, 6));
    }

    #[test]
    fn conversions_round_trip_small_rationals() {
        assert_eq!(<f64 as Scalar>::from_rational(&ratio(1, 4)), 0.25);
        assert_eq!(<f32 as Scalar>::from_rational(&ratio(-3, 2)), -1.5f32);
        assert_eq!(q(1, 3).to_f64(), 1.0 / 3.0);
        assert_eq!(Exact::from_f64(0.5), None);
        assert_eq!(int::<Exact>(-7), q(-7, 1));
    }

    #[test]
    fn signs() {
        assert_eq!(q(-1, 3).signum_i8(), -1);
        assert_eq!(Exact::zero().signum_i8(), 0);
        assert_eq!(2.0f64.signum_i8(), 1);
        assert_eq!((-0.0f64).signum_i8(), 0);
    }
}
