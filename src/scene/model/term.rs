//! Arithmetic on scene numbers as expressions.
//!
//! Rotating a vector, taking a parallel-axis shift or a box's moments combines the numbers a
//! user wrote. Combined as *text* in the crate's one grammar, the result is read again like any
//! value of the scene — exact rationals, exact radicals (`cos(30 deg)`), symbols for `derive`,
//! f64, and a parameter's derivative all follow from the one text. Rational parts are folded
//! exactly as they are combined, so a pose by a rational rotation gives plain fractions.

use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use crate::number::{Number, format_rational};

/// A value as an expression: an exact rational, or a text of the grammar.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Term {
    /// An exact rational (folded).
    Rat(BigRational),
    /// Any other expression; names parameters or symbols, or is irrational.
    Text(String),
}

/// A vector of terms.
pub(crate) type Vec3 = [Term; 3];
/// A 3×3 matrix of terms, by rows.
pub(crate) type Mat3 = [[Term; 3]; 3];

impl Term {
    /// The integer `n`.
    pub(crate) fn int(n: i64) -> Term {
        Term::Rat(BigRational::from_integer(n.into()))
    }

    /// A number as read: its exact value when it has one and depends on nothing (no symbol, no
    /// seeded derivative), else its text as written (naming its parameters).
    pub(crate) fn of(n: &Number) -> Term {
        match &n.exact {
            Ok(q) if n.tangent == 0.0 => Term::Rat(q.clone()),
            _ => Term::Text(n.source.clone().unwrap_or_else(|| n.text.clone())),
        }
    }

    /// A text in the grammar.
    pub(crate) fn text(s: impl Into<String>) -> Term {
        Term::Text(s.into())
    }

    /// Whether it is exactly 0 (as a folded rational).
    pub(crate) fn is_zero(&self) -> bool {
        matches!(self, Term::Rat(q) if q.is_zero())
    }

    fn is_one(&self) -> bool {
        matches!(self, Term::Rat(q) if q.is_one())
    }

    /// The text, parenthesised to serve as an operand.
    fn operand(&self) -> String {
        match self {
            Term::Rat(q) if q.is_negative() || !q.denom().is_one() => {
                format!("({})", format_rational(q))
            }
            Term::Rat(q) => format_rational(q),
            Term::Text(t) => format!("({t})"),
        }
    }

    /// `f(self)` for a function of the grammar (`cos`, `sin`, `sqrt`).
    pub(crate) fn call(&self, f: &str) -> Term {
        Term::Text(format!("{f}({self})"))
    }

    /// self².
    pub(crate) fn square(&self) -> Term {
        self * self
    }
}

impl fmt::Display for Term {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Term::Rat(q) => write!(f, "{}", format_rational(q)),
            Term::Text(t) => write!(f, "{t}"),
        }
    }
}

impl Add for &Term {
    type Output = Term;
    fn add(self, b: &Term) -> Term {
        match (self, b) {
            (Term::Rat(x), Term::Rat(y)) => Term::Rat(x + y),
            (a, b) if a.is_zero() => b.clone(),
            (a, b) if b.is_zero() => a.clone(),
            (a, b) => Term::Text(format!("{} + {}", a.operand(), b.operand())),
        }
    }
}

impl Sub for &Term {
    type Output = Term;
    fn sub(self, b: &Term) -> Term {
        match (self, b) {
            (Term::Rat(x), Term::Rat(y)) => Term::Rat(x - y),
            (a, b) if b.is_zero() => a.clone(),
            (a, b) if a.is_zero() => -b,
            (a, b) => Term::Text(format!("{} - {}", a.operand(), b.operand())),
        }
    }
}

impl Mul for &Term {
    type Output = Term;
    fn mul(self, b: &Term) -> Term {
        match (self, b) {
            (Term::Rat(x), Term::Rat(y)) => Term::Rat(x * y),
            (a, b) if a.is_zero() || b.is_zero() => Term::int(0),
            (a, b) if a.is_one() => b.clone(),
            (a, b) if b.is_one() => a.clone(),
            (a, b) => Term::Text(format!("{}*{}", a.operand(), b.operand())),
        }
    }
}

impl Div for &Term {
    type Output = Term;
    /// a/b; the caller has made sure b ≠ 0.
    fn div(self, b: &Term) -> Term {
        match (self, b) {
            (Term::Rat(x), Term::Rat(y)) if !y.is_zero() => Term::Rat(x / y),
            (a, _) if a.is_zero() => Term::int(0),
            (a, b) if b.is_one() => a.clone(),
            (a, b) => Term::Text(format!("{}/{}", a.operand(), b.operand())),
        }
    }
}

impl Neg for &Term {
    type Output = Term;
    fn neg(self) -> Term {
        match self {
            Term::Rat(x) => Term::Rat(-x),
            a => Term::Text(format!("-{}", a.operand())),
        }
    }
}

/// a·b.
pub(crate) fn dot(a: &Vec3, b: &Vec3) -> Term {
    &(&(&a[0] * &b[0]) + &(&a[1] * &b[1])) + &(&a[2] * &b[2])
}

/// a × b.
pub(crate) fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    [
        &(&a[1] * &b[2]) - &(&a[2] * &b[1]),
        &(&a[2] * &b[0]) - &(&a[0] * &b[2]),
        &(&a[0] * &b[1]) - &(&a[1] * &b[0]),
    ]
}

/// a + b.
pub(crate) fn add(a: &Vec3, b: &Vec3) -> Vec3 {
    [&a[0] + &b[0], &a[1] + &b[1], &a[2] + &b[2]]
}

/// a − b.
pub(crate) fn sub(a: &Vec3, b: &Vec3) -> Vec3 {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

/// s·a.
pub(crate) fn scale(s: &Term, a: &Vec3) -> Vec3 {
    [s * &a[0], s * &a[1], s * &a[2]]
}

/// M v.
pub(crate) fn apply(m: &Mat3, v: &Vec3) -> Vec3 {
    [dot(&m[0], v), dot(&m[1], v), dot(&m[2], v)]
}

/// Mᵀ.
pub(crate) fn transpose(m: &Mat3) -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| m[j][i].clone()))
}

/// A B.
pub(crate) fn product(a: &Mat3, b: &Mat3) -> Mat3 {
    let bt = transpose(b);
    std::array::from_fn(|i| std::array::from_fn(|j| dot(&a[i], &bt[j])))
}

/// The identity.
pub(crate) fn identity() -> Mat3 {
    std::array::from_fn(|i| std::array::from_fn(|j| Term::int(i64::from(i == j))))
}

/// The zero vector.
pub(crate) fn zero() -> Vec3 {
    [Term::int(0), Term::int(0), Term::int(0)]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Term {
        Term::Rat(BigRational::new(n.into(), d.into()))
    }

    #[test]
    fn rationals_fold_and_texts_parenthesise() {
        assert_eq!(&q(1, 2) + &q(1, 3), q(5, 6));
        let c = Term::text("cos(theta)");
        assert_eq!(&c * &Term::int(1), c);
        assert!((&c * &Term::int(0)).is_zero());
        assert_eq!((&c * &q(-1, 2)).to_string(), "(cos(theta))*(-1/2)");
        assert_eq!((&q(3, 1) - &c).to_string(), "3 - (cos(theta))");
        assert_eq!((-&c).to_string(), "-(cos(theta))");
    }

    #[test]
    fn vector_algebra_on_rationals() {
        let a = [Term::int(1), Term::int(2), Term::int(3)];
        let b = [Term::int(4), Term::int(5), Term::int(6)];
        assert_eq!(dot(&a, &b), Term::int(32));
        assert_eq!(cross(&a, &b), [Term::int(-3), Term::int(6), Term::int(-3)]);
        let m = identity();
        assert_eq!(apply(&m, &a), a);
        assert_eq!(product(&m, &m), m);
    }
}
