//! Arithmetic on scene numbers as expressions.
//!
//! Rotating a vector, taking a parallel-axis shift or a box's moments combines the numbers a
//! user wrote. Combined as *text* in the crate's one grammar, the result is read again like any
//! value of the scene — exact rationals, exact radicals (`cos(30 deg)`), symbols for `derive`,
//! f64, and a parameter's derivative all follow from the one text. Rational parts are folded
//! exactly as they are combined, so a pose by a rational rotation gives plain fractions.

use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::number::{Number, format_rational};

/// A value as an expression: an exact rational, or a text of the grammar with its f64 value
/// and a bound on that value's error carried along (NaN when it names a symbol), so that a
/// sign far from zero is decided without reading the text again.
///
/// The bound follows each operation to first order in ε (the unit roundoff u = ε/2 per
/// rounding, taken as ε): e(a ± b) = e_a + e_b + ε|a ± b|, e(ab) = |a| e_b + |b| e_a + ε|ab|,
/// e(a/b) = (e_a + |a/b| e_b)/|b| + ε|a/b|, e(f(a)) = |f′(a)| e_a + ε|f(a)| (|f′| ≤ 1 for sin
/// and cos, 1/(2√a) for √).
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Term {
    /// An exact rational (folded).
    Rat(BigRational),
    /// Any other expression — it names parameters or symbols, or is irrational — with its f64
    /// value and error bound.
    Text(String, f64, f64),
}

/// ε.
const EPS: f64 = f64::EPSILON;

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
            // An irrational number is evaluated in f64 by a handful of operations: 8ε of it.
            _ => Term::Text(
                n.source.clone().unwrap_or_else(|| n.text.clone()),
                n.approx,
                8.0 * EPS * n.approx.abs(),
            ),
        }
    }

    /// A constant of the grammar (`pi`, `4/3*pi`), read once.
    pub(crate) fn constant(s: &str) -> Term {
        let n = crate::number::parse_number(s).expect("a constant of the grammar");
        Term::of(&n)
    }

    /// The f64 value (NaN for a symbolic one).
    pub(crate) fn approx(&self) -> f64 {
        match self {
            Term::Rat(q) => crate::number::rational_to_f64(q),
            Term::Text(_, f, _) => *f,
        }
    }

    /// A bound on the error of [`Term::approx`].
    pub(crate) fn error(&self) -> f64 {
        match self {
            Term::Rat(_) => EPS * self.approx().abs(),
            Term::Text(_, _, e) => *e,
        }
    }

    /// A text of value v with error bound e.
    fn made(text: String, v: f64, e: f64) -> Term {
        Term::Text(text, v, e + EPS * v.abs())
    }

    /// Whether it is exactly 0 (as a folded rational).
    pub(crate) fn is_zero(&self) -> bool {
        matches!(self, Term::Rat(q) if q.is_zero())
    }

    fn is_one(&self) -> bool {
        matches!(self, Term::Rat(q) if q.is_one())
    }

    /// The text, parenthesised to serve as an operand, appended to `out`.
    fn push_operand(&self, out: &mut String) {
        match self {
            Term::Rat(q) if q.is_negative() || !q.denom().is_one() => {
                out.push('(');
                out.push_str(&format_rational(q));
                out.push(')');
            }
            Term::Rat(q) => out.push_str(&format_rational(q)),
            Term::Text(t, _, _) => {
                out.push('(');
                out.push_str(t);
                out.push(')');
            }
        }
    }

    /// `a op b` of two operands, in one allocation (formatting each operand apart made three
    /// strings for one): a read of a posed scene builds hundreds of these texts.
    fn join(a: &Term, op: &str, b: &Term) -> String {
        let len = |t: &Term| match t {
            Term::Text(t, _, _) => t.len() + 2,
            Term::Rat(_) => 16,
        };
        let mut out = String::with_capacity(len(a) + op.len() + len(b));
        a.push_operand(&mut out);
        out.push_str(op);
        b.push_operand(&mut out);
        out
    }

    /// `f(self)` for a function of the grammar: `cos`, `sin` or `sqrt`.
    pub(crate) fn call(&self, f: &str) -> Term {
        let (x, e) = (self.approx(), self.error());
        let (v, slope) = match f {
            "cos" | "sin" => (if f == "cos" { x.cos() } else { x.sin() }, 1.0),
            _ => (x.sqrt(), 0.5 / x.sqrt()),
        };
        Term::made(format!("{f}({self})"), v, slope * e)
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
            Term::Text(t, _, _) => write!(f, "{t}"),
        }
    }
}

impl Add for &Term {
    type Output = Term;
    fn add(self, b: &Term) -> Term {
        match (self, b) {
            (Term::Rat(x), Term::Rat(y)) => Term::Rat(rat_sum(x, y, false)),
            (a, b) if a.is_zero() => b.clone(),
            (a, b) if b.is_zero() => a.clone(),
            (a, b) => Term::made(
                Term::join(a, " + ", b),
                a.approx() + b.approx(),
                a.error() + b.error(),
            ),
        }
    }
}

impl Sub for &Term {
    type Output = Term;
    fn sub(self, b: &Term) -> Term {
        match (self, b) {
            (Term::Rat(x), Term::Rat(y)) => Term::Rat(rat_sum(x, y, true)),
            (a, b) if b.is_zero() => a.clone(),
            (a, b) if a.is_zero() => -b,
            (a, b) => Term::made(
                Term::join(a, " - ", b),
                a.approx() - b.approx(),
                a.error() + b.error(),
            ),
        }
    }
}

impl Mul for &Term {
    type Output = Term;
    fn mul(self, b: &Term) -> Term {
        match (self, b) {
            (Term::Rat(x), Term::Rat(y)) => Term::Rat(rat_product(x, y)),
            (a, b) if a.is_zero() || b.is_zero() => Term::int(0),
            (a, b) if a.is_one() => b.clone(),
            (a, b) if b.is_one() => a.clone(),
            (a, b) => Term::made(
                Term::join(a, "*", b),
                a.approx() * b.approx(),
                a.approx().abs() * b.error() + b.approx().abs() * a.error(),
            ),
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
            (a, b) => {
                let q = a.approx() / b.approx();
                Term::made(
                    Term::join(a, "/", b),
                    q,
                    (a.error() + q.abs() * b.error()) / b.approx().abs(),
                )
            }
        }
    }
}

impl Neg for &Term {
    type Output = Term;
    fn neg(self) -> Term {
        match self {
            Term::Rat(x) => Term::Rat(-x),
            a => {
                let mut text = String::from("-");
                a.push_operand(&mut text);
                Term::Text(text, -a.approx(), a.error())
            }
        }
    }
}

/// The numerator and denominator of q, when both fit a word.
fn words(q: &BigRational) -> Option<(i128, i128)> {
    Some((q.numer().to_i64()?.into(), q.denom().to_i64()?.into()))
}

/// n/d in lowest terms (d > 0, |n|, d < 2¹²⁷): the rational a big-rational operation gives.
fn reduced(n: i128, d: i128) -> BigRational {
    let (mut a, mut b) = (n.unsigned_abs(), d.unsigned_abs());
    while b != 0 {
        (a, b) = (b, a % b);
    }
    // a = gcd(|n|, d) ≥ 1, as d > 0.
    let g = a as i128;
    BigRational::new_raw(BigInt::from(n / g), BigInt::from(d / g))
}

/// x + y, or x − y: in machine words when both are fractions of words (a pose's and a
/// shape's rationals are), else in big rationals; the same reduced rational either way.
fn rat_sum(x: &BigRational, y: &BigRational, minus: bool) -> BigRational {
    match (words(x), words(y)) {
        (Some((a, b)), Some((c, d))) => {
            let c = if minus { -c } else { c };
            reduced(a * d + c * b, b * d)
        }
        _ if minus => x - y,
        _ => x + y,
    }
}

/// x·y, as [`rat_sum`].
fn rat_product(x: &BigRational, y: &BigRational) -> BigRational {
    match (words(x), words(y)) {
        (Some((a, b)), Some((c, d))) => reduced(a * c, b * d),
        _ => x * y,
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
        let c = Term::Text("cos(theta)".into(), f64::NAN, f64::NAN);
        assert_eq!((&c * &Term::int(1)).to_string(), c.to_string());
        assert!((&c * &Term::int(0)).is_zero());
        assert_eq!((&c * &q(-1, 2)).to_string(), "(cos(theta))*(-1/2)");
        assert_eq!((&q(3, 1) - &c).to_string(), "3 - (cos(theta))");
        assert_eq!((-&c).to_string(), "-(cos(theta))");
        assert_eq!((&c + &Term::int(2)).to_string(), "(cos(theta)) + 2");
        assert_eq!((&c / &c).to_string(), "(cos(theta))/(cos(theta))");
        assert_eq!((&q(-3, 1) * &c).to_string(), "(-3)*(cos(theta))");
    }

    #[test]
    fn the_error_bound_covers_the_f64_value() {
        let r2 = Term::constant("sqrt(2)");
        let r3 = Term::constant("sqrt(3)");
        // √2·√2 − 2 = 0 exactly: the f64 value is a rounding, within the bound, so no sign is
        // read from it.
        let zero = &(&r2 * &r2) - &Term::int(2);
        assert!(zero.approx().abs() <= zero.error());
        // (√3 + √2)(√3 − √2) = 1: the value is within its bound of 1.
        let one = &(&r3 + &r2) * &(&r3 - &r2);
        assert!((one.approx() - 1.0).abs() <= one.error());
        // About 100ε: 8ε per radical, grown through the sum, difference and product.
        assert!(one.error() < 200.0 * f64::EPSILON);
        let c = Term::constant("cos(3 deg)").call("sqrt");
        assert!((c.approx() - 3f64.to_radians().cos().sqrt()).abs() <= c.error());
    }

    /// Sums, differences and products of fractions of words, taken in words, are the big
    /// rationals' (reduced, the same numerator and denominator), down to the words' ends.
    #[test]
    fn rationals_in_words_are_the_big_rationals() {
        let mut seed = 0x7e_u64;
        let mut next = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            seed >> 33
        };
        let mut values: Vec<BigRational> = [(0, 1), (1, 1), (-1, 2), (1, 120), (-7, 3)]
            .map(|(n, d)| BigRational::new(BigInt::from(n), BigInt::from(d)))
            .to_vec();
        for _ in 0..300 {
            let n = (next() % 2001) as i64 - 1000;
            let d = (next() % 360) as i64 + 1;
            values.push(BigRational::new(n.into(), d.into()));
        }
        for (n, d) in [
            (i64::MAX, 1),
            (i64::MIN + 1, 3),
            (1, i64::MAX),
            (i64::MAX - 1, i64::MAX),
        ] {
            values.push(BigRational::new(n.into(), d.into()));
        }
        values.push(BigRational::new(BigInt::from(1) << 70, 3.into()));
        let same =
            |a: &BigRational, b: &BigRational| a.numer() == b.numer() && a.denom() == b.denom();
        for (i, x) in values.iter().enumerate() {
            for y in values.iter().skip(i % 7).step_by(7) {
                assert!(same(&rat_sum(x, y, false), &(x + y)), "{x} + {y}");
                assert!(same(&rat_sum(x, y, true), &(x - y)), "{x} - {y}");
                assert!(same(&rat_product(x, y), &(x * y)), "{x} * {y}");
            }
        }
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
