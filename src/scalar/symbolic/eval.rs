//! Exact evaluation of the grammar in [`RatFun`]: declared names are symbols, `sqrt` of a
//! rational constant is an exact radical, sin/cos/tan take a constant multiple of 15° or a
//! bare declared angle.

use std::cell::RefCell;
use std::collections::HashMap;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use super::{Poly, RatFun};
use crate::number::expr::{Func, Kind, MAX_DECIMAL_EXPONENT, Node, Op};
use crate::number::{self, MAX_EXACT_BITS, NumberError, exact_root};
use crate::scalar::Scalar;

/// Values with more terms than this (numerator and denominator factors together) are refused.
const MAX_TERMS: usize = 10_000;
/// A product whose operands' numerators have more term pairs than this is refused up front.
const MAX_PRODUCT_PAIRS: usize = 1_000_000;
/// Values of higher total degree (numerator, or the whole denominator) are refused.
const MAX_DEGREE: u64 = 10_000;
/// A square root of p/q with p·q wider than this (and no perfect square) is refused: it
/// could not be split into primes quickly.
const MAX_RADICAND_BITS: u64 = 256;
/// A divisor with radicals is rationalised by conjugates, doubling its size per radical:
/// (terms · 2^radicals) is limited to this.
const MAX_RATIONALISED_TERMS: u64 = 4096;

/// The exact value of `text` in [`RatFun`], with the names in `symbols` as symbols.
///
/// * Literals and `/` are exact (`0.1` is 1/10); a declared name is [`RatFun::symbol`].
/// * `sqrt(e)` and `e^(p/2)` need e to be a rational constant ≥ 0: an exact radical
///   ([`RatFun::sqrt`]: √12 = 2√3). `e^n` takes any integer n; `e^(p/q)` otherwise needs a
///   rational e that is a perfect q-th power.
/// * `sin`, `cos`, `tan` of a constant angle that is a multiple of 15° (`30 deg`, `pi/4`,
///   `-45 deg`, `0`) are exact radicals ([`RatFun::cos_deg`]); of a bare declared name θ they
///   are the angle symbols of [`RatFun::angle`] (sin²θ + cos²θ = 1).
/// * `pi` and `X deg` are angles: only sin, cos, tan (and ratios of angles) make them values.
///
/// Every [`RatFun::to_text`] output reads back to the same value with the declared names
/// [`symbol_names`] gives. Divisions by expressions with symbols record their ≠ 0 assumption
/// ([`crate::scalar::symbolic::take_assumptions`]), as every [`RatFun`] division does.
///
/// # Errors
/// [`NumberError::Syntax`] as [`crate::number::parse_number_with`] (first);
/// [`NumberError::NotFinite`] for nan/inf, division by an exact zero, roots of negative
/// numbers, tan at a pole; [`NumberError::Inexact`] for values without an exact form here
/// (`cos(20 deg)`, `sqrt(m)`, `cos(2*theta)`, `pi`, `2^(1/3)`) and beyond the size limits
/// (10 000 terms, degree 10 000, coefficients of 16 384 bits).
pub fn symbolic(text: &str, symbols: &[String]) -> Result<RatFun, NumberError> {
    let src = text.trim();
    let root = number::parse_checked(src, symbols)?;
    let eval = Eval {
        src,
        roots: RefCell::new(HashMap::new()),
    };
    match eval.eval(&root)? {
        Val::Num(r) => Ok(r),
        Val::Angle(_) => Err(eval.inexact(transcendental(src))),
    }
}

/// The names to declare so that [`symbolic`] reads `x.to_text()` back: the free symbols of
/// `x` and the names of its angles (`theta` for `cos(theta)`), sorted, without duplicates.
pub fn symbol_names(x: &RatFun) -> Vec<String> {
    let mut names: Vec<String> = x
        .symbols()
        .into_iter()
        .filter(|s| !s.starts_with("sqrt("))
        .map(|s| {
            ["cos(", "sin("]
                .iter()
                .find_map(|f| s.strip_prefix(f)?.strip_suffix(')'))
                .map_or_else(|| s.clone(), str::to_string)
        })
        .collect();
    names.sort_unstable();
    names.dedup();
    names
}

/// A value during evaluation.
enum Val {
    Num(RatFun),
    /// q·π with q ≠ 0 (radians): only trigonometry turns it into a value.
    Angle(BigRational),
}

struct Eval<'a> {
    src: &'a str,
    /// √q by q, so that a repeated radicand is split into primes once.
    roots: RefCell<HashMap<BigRational, RatFun>>,
}

fn transcendental(text: &str) -> String {
    format!(
        "pi is transcendental: an angle (pi, X deg) is exact only inside sin, cos or tan, \
         not in '{text}'"
    )
}

fn bits(q: &BigRational) -> u64 {
    q.numer().bits().max(q.denom().bits())
}

/// q·π as a value: 0 for q = 0.
fn angle(q: BigRational) -> Val {
    if q.is_zero() {
        Val::Num(RatFun::zero())
    } else {
        Val::Angle(q)
    }
}

/// The total degree of a polynomial.
fn degree(p: &Poly) -> u64 {
    p.terms()
        .iter()
        .map(|(m, _)| u64::from(m.degree()))
        .max()
        .unwrap_or(0)
}

impl Eval<'_> {
    fn text(&self, start: usize, end: usize) -> &str {
        self.src.get(start..end).unwrap_or(self.src)
    }

    fn inexact(&self, reason: String) -> NumberError {
        NumberError::Inexact {
            text: self.src.to_string(),
            reason,
        }
    }

    fn not_finite(&self, reason: String) -> NumberError {
        NumberError::NotFinite {
            text: self.src.to_string(),
            reason,
        }
    }

    /// `r`, unless it is beyond the size limits.
    fn sized(&self, r: RatFun, text: &str) -> Result<Val, NumberError> {
        let num = r.numer();
        let den = r.denom_factors();
        let terms = num.len() + den.iter().map(|(f, _)| f.len()).sum::<usize>();
        let den_degree: u64 = den.iter().map(|(f, e)| degree(f) * u64::from(*e)).sum();
        let wide = std::iter::once(num)
            .chain(den.iter().map(|(f, _)| f))
            .flat_map(Poly::terms)
            .any(|(_, c)| bits(c) > MAX_EXACT_BITS);
        if terms > MAX_TERMS {
            return Err(self.inexact(format!("'{text}' has more than {MAX_TERMS} terms")));
        }
        if degree(num).max(den_degree) > MAX_DEGREE {
            return Err(self.inexact(format!("'{text}' has a degree above {MAX_DEGREE}")));
        }
        if wide {
            return Err(self.inexact(format!(
                "'{text}' exceeds {MAX_EXACT_BITS} bits of exact precision"
            )));
        }
        Ok(Val::Num(r))
    }

    /// Evaluate children first, then combine in a separate (non-recursive) function, with
    /// `and_then` rather than `?`: every nesting level pays for this frame.
    fn eval(&self, node: &Node) -> Result<Val, NumberError> {
        let text = self.text(node.start, node.end);
        match &node.kind {
            Kind::Lit(lit) => match &lit.exact {
                Some(q) => Ok(Val::Num(RatFun::constant(q.clone()))),
                None => Err(self.inexact(format!(
                    "'{text}' is out of the exact range (decimal exponent beyond \
                     ±{MAX_DECIMAL_EXPONENT})"
                ))),
            },
            Kind::Pi => Ok(Val::Angle(BigRational::one())),
            Kind::NonFinite => Err(self.not_finite(format!("'{text}' is not a finite number"))),
            Kind::Name(name) => Ok(Val::Num(RatFun::symbol(name))),
            Kind::Neg(inner) => self.eval(inner).map(|v| match v {
                Val::Num(r) => Val::Num(-r),
                Val::Angle(q) => Val::Angle(-q),
            }),
            Kind::Chain(first, rest) => {
                rest.iter().fold(self.eval(first), |acc, (op, rhs)| {
                    // Quote the chain up to this operand, e.g. "2*3/0".
                    acc.and_then(|a| {
                        self.eval(rhs)
                            .and_then(|b| self.binary(*op, a, b, self.text(node.start, rhs.end)))
                    })
                })
            }
            Kind::Pow(base, exp) => self.eval(base).and_then(|b| {
                self.eval(exp)
                    .and_then(|e| self.power(b, e, text, self.text(exp.start, exp.end)))
            }),
            Kind::Deg(inner) => self.eval(inner).and_then(|v| self.degrees(v, text)),
            Kind::Call(Func::Sqrt, arg) => self
                .eval(arg)
                .and_then(|v| self.sqrt(v, text, self.text(arg.start, arg.end))),
            Kind::Call(func, arg) => match &arg.kind {
                Kind::Name(theta) => Ok(self.angle_trig(*func, theta)),
                _ => self
                    .eval(arg)
                    .and_then(|v| self.trig(*func, v, text, self.text(arg.start, arg.end))),
            },
        }
    }

    fn binary(&self, op: Op, a: Val, b: Val, text: &str) -> Result<Val, NumberError> {
        use Val::{Angle, Num};
        match (op, a, b) {
            (Op::Div, _, Num(y)) if y.is_zero() => {
                Err(self.not_finite(format!("division by zero in '{text}'")))
            }
            (Op::Add, Num(x), Num(y)) => self.sized(x + y, text),
            (Op::Sub, Num(x), Num(y)) => self.sized(x - y, text),
            (Op::Mul, Num(x), Num(y)) => self.multiply(&x, &y, text),
            (Op::Div, Num(x), Num(y)) => self.divide(&x, &y, text),
            // Sums of angles stay angles; rational multiples too.
            (Op::Add, Angle(x), Angle(y)) => Ok(angle(x + y)),
            (Op::Sub, Angle(x), Angle(y)) => Ok(angle(x - y)),
            (Op::Add | Op::Sub, Angle(x), Num(y)) if y.is_zero() => Ok(Angle(x)),
            (Op::Add, Num(x), Angle(y)) if x.is_zero() => Ok(Angle(y)),
            (Op::Sub, Num(x), Angle(y)) if x.is_zero() => Ok(Angle(-y)),
            (Op::Mul, Num(x), Angle(y)) | (Op::Mul, Angle(y), Num(x)) => match x.to_rational() {
                Some(q) => self.angle_checked(q * y, text),
                None => Err(self.inexact(transcendental(text))),
            },
            (Op::Div, Angle(x), Num(y)) => match y.to_rational() {
                Some(q) => self.angle_checked(x / q, text),
                None => Err(self.inexact(transcendental(text))),
            },
            (Op::Div, Angle(x), Angle(y)) => Ok(Num(RatFun::constant(x / y))),
            (Op::Div, Num(x), Angle(_)) if x.is_zero() => Ok(Num(x)),
            _ => Err(self.inexact(transcendental(text))),
        }
    }

    fn angle_checked(&self, q: BigRational, text: &str) -> Result<Val, NumberError> {
        if bits(&q) > MAX_EXACT_BITS {
            return Err(self.inexact(format!(
                "'{text}' exceeds {MAX_EXACT_BITS} bits of exact precision"
            )));
        }
        Ok(angle(q))
    }

    fn multiply(&self, x: &RatFun, y: &RatFun, text: &str) -> Result<Val, NumberError> {
        if x.numer().len().saturating_mul(y.numer().len()) > MAX_PRODUCT_PAIRS {
            return Err(self.inexact(format!("'{text}' has more than {MAX_TERMS} terms")));
        }
        self.sized(x * y, text)
    }

    fn divide(&self, x: &RatFun, y: &RatFun, text: &str) -> Result<Val, NumberError> {
        let radicals = y
            .numer()
            .symbols()
            .iter()
            .filter(|s| s.starts_with("sqrt("))
            .count();
        let size = u64::try_from(y.numer().len()).unwrap_or(u64::MAX);
        if radicals > 0
            && (radicals > 12 || size.saturating_mul(1 << radicals) > MAX_RATIONALISED_TERMS)
        {
            return Err(self.inexact(format!(
                "the divisor in '{text}' has too many radicals to rationalise"
            )));
        }
        self.sized(x / y, text)
    }

    fn power(&self, b: Val, e: Val, text: &str, exp_text: &str) -> Result<Val, NumberError> {
        let Val::Num(e) = e else {
            return Err(self.inexact(transcendental(text)));
        };
        let Some(q) = e.to_rational() else {
            return Err(self.inexact(format!(
                "the exponent '{exp_text}' of '{text}' is not a rational constant"
            )));
        };
        let b = match b {
            Val::Angle(a) if q.is_one() => return Ok(Val::Angle(a)),
            Val::Angle(_) if q.is_zero() => return Ok(Val::Num(RatFun::one())),
            Val::Angle(_) => return Err(self.inexact(transcendental(text))),
            Val::Num(b) => b,
        };
        if q.is_integer() {
            return self.integer_power(b, q.numer(), text);
        }
        let only = || {
            self.inexact(format!(
                "'{text}' has no exact form: a fractional exponent needs a rational constant \
                 base; declare the root as a symbol instead"
            ))
        };
        let Some(r) = b.to_rational() else {
            return Err(only());
        };
        let half = BigInt::from(2);
        let root = if *q.denom() == half {
            self.square_root(&r, text)?
        } else {
            if r.is_negative() && !q.denom().magnitude().bit(0) {
                return Err(self.not_finite(format!(
                    "a negative number has no real root of even order in '{text}'"
                )));
            }
            let exact = q.denom().to_u32().and_then(|k| {
                let n = exact_root(&r.numer().abs(), k)?;
                let d = exact_root(r.denom(), k)?;
                Some(BigRational::new(n, d))
            });
            match exact {
                Some(v) => RatFun::constant(if r.is_negative() { -v } else { v }),
                None => {
                    return Err(self.inexact(format!(
                        "{text} is irrational, and only square roots are exact radicals"
                    )));
                }
            }
        };
        self.integer_power(root, q.numer(), text)
    }

    fn integer_power(&self, b: RatFun, n: &BigInt, text: &str) -> Result<Val, NumberError> {
        if n.is_zero() {
            return Ok(Val::Num(RatFun::one()));
        }
        if b.is_zero() {
            if n.is_negative() {
                return Err(self.not_finite(format!("zero to a negative power in '{text}'")));
            }
            return Ok(Val::Num(b));
        }
        let too_wide = || {
            self.inexact(format!(
                "'{text}' exceeds {MAX_EXACT_BITS} bits of exact precision"
            ))
        };
        if let Some(r) = b.to_rational() {
            if r.abs().is_one() {
                let odd = n.magnitude().bit(0);
                return Ok(Val::Num(RatFun::constant(if odd { r } else { r.abs() })));
            }
            let k = n
                .magnitude()
                .to_u32()
                .filter(|&k| u64::from(k).saturating_mul(bits(&r)) <= MAX_EXACT_BITS)
                .ok_or_else(too_wide)?;
            let Ok(k) = i32::try_from(k) else {
                return Err(too_wide());
            };
            let p = if n.is_negative() { r.pow(-k) } else { r.pow(k) };
            return Ok(Val::Num(RatFun::constant(p)));
        }
        let own_degree = degree(b.numer()).max(
            b.denom_factors()
                .iter()
                .map(|(f, e)| degree(f) * u64::from(*e))
                .sum(),
        );
        let k = n
            .magnitude()
            .to_u64()
            .filter(|&k| k.saturating_mul(own_degree.max(1)) <= MAX_DEGREE)
            .ok_or_else(|| self.inexact(format!("'{text}' has a degree above {MAX_DEGREE}")))?;
        // Square and multiply, each step within the limits.
        let mut result: Option<RatFun> = None;
        let mut base = b;
        let mut k = k;
        while k > 0 {
            if k & 1 == 1 {
                result = Some(match result {
                    None => base.clone(),
                    Some(r) => self.product(&r, &base, text)?,
                });
            }
            k >>= 1;
            if k > 0 {
                base = self.product(&base, &base, text)?;
            }
        }
        let p = result.unwrap_or_else(RatFun::one);
        if n.is_negative() {
            self.divide(&RatFun::one(), &p, text)
        } else {
            Ok(Val::Num(p))
        }
    }

    /// x·y as a [`RatFun`], within the limits.
    fn product(&self, x: &RatFun, y: &RatFun, text: &str) -> Result<RatFun, NumberError> {
        match self.multiply(x, y, text)? {
            Val::Num(r) => Ok(r),
            Val::Angle(_) => Err(self.inexact(transcendental(text))),
        }
    }

    fn degrees(&self, v: Val, text: &str) -> Result<Val, NumberError> {
        match v {
            Val::Num(r) => match r.to_rational() {
                Some(q) => self.angle_checked(q / BigRational::from_integer(180.into()), text),
                None => Err(self.inexact(format!(
                    "'{text}': deg takes a rational number of degrees; for a symbolic angle \
                     declare it and write cos(theta), sin(theta)"
                ))),
            },
            Val::Angle(_) => Err(self.inexact(transcendental(text))),
        }
    }

    fn sqrt(&self, v: Val, text: &str, arg: &str) -> Result<Val, NumberError> {
        let q = match v {
            Val::Num(r) => r.to_rational(),
            Val::Angle(_) => return Err(self.inexact(transcendental(text))),
        };
        let Some(q) = q else {
            return Err(self.inexact(format!(
                "sqrt is exact only of a rational constant, not of '{arg}'; declare the root \
                 as a symbol instead"
            )));
        };
        self.square_root(&q, text).map(Val::Num)
    }

    /// √q for a rational q, as an exact radical.
    fn square_root(&self, q: &BigRational, text: &str) -> Result<RatFun, NumberError> {
        if q.is_negative() {
            return Err(self.not_finite(format!("square root of a negative number in '{text}'")));
        }
        if let Some(r) = self.roots.borrow().get(q) {
            return Ok(r.clone());
        }
        let root = match (exact_root(q.numer(), 2), exact_root(q.denom(), 2)) {
            (Some(n), Some(d)) => RatFun::constant(BigRational::new(n, d)),
            _ if (q.numer() * q.denom()).bits() > MAX_RADICAND_BITS => {
                return Err(self.inexact(format!(
                    "the radicand in '{text}' is too large to split into primes \
                     (more than {MAX_RADICAND_BITS} bits)"
                )));
            }
            _ => RatFun::sqrt(q).ok_or_else(|| {
                self.inexact(format!(
                    "the radicand in '{text}' cannot be split into primes"
                ))
            })?,
        };
        self.roots.borrow_mut().insert(q.clone(), root.clone());
        Ok(root)
    }

    /// sin, cos or tan of the declared angle θ.
    fn angle_trig(&self, func: Func, theta: &str) -> Val {
        let (c, s) = RatFun::angle(theta);
        Val::Num(match func {
            Func::Cos => c,
            Func::Sin => s,
            // cos θ is a symbol, never the zero polynomial.
            Func::Tan | Func::Sqrt => s / c,
        })
    }

    fn trig(&self, func: Func, v: Val, text: &str, arg: &str) -> Result<Val, NumberError> {
        let radians = match v {
            Val::Angle(q) => q,
            Val::Num(r) => match r.to_rational() {
                Some(z) if z.is_zero() => z,
                Some(_) => {
                    return Err(self.inexact(format!(
                        "{text} has no exact form: its argument is in radians, not a rational \
                         multiple of pi"
                    )));
                }
                None => {
                    return Err(self.inexact(format!(
                        "{text} is exact only of a constant angle (a multiple of 15°) or of a \
                         bare declared angle symbol, e.g. {}(theta), not of '{arg}'",
                        func.name()
                    )));
                }
            },
        };
        let full = BigRational::from_integer(360.into());
        let degrees = radians * BigRational::from_integer(180.into());
        let reduced = &degrees - (&degrees / &full).floor() * &full;
        let no_radical = || {
            self.inexact(format!(
                "{text} has no exact radical form: only multiples of 15° do"
            ))
        };
        let d = reduced
            .is_integer()
            .then(|| reduced.to_integer().to_i64())
            .flatten()
            .ok_or_else(no_radical)?;
        let (Some(c), Some(s)) = (RatFun::cos_deg(d), RatFun::sin_deg(d)) else {
            return Err(no_radical());
        };
        Ok(Val::Num(match func {
            Func::Cos => c,
            Func::Sin => s,
            Func::Tan | Func::Sqrt => {
                if c.is_zero() {
                    return Err(self.not_finite(format!("'{text}' is infinite")));
                }
                s / c
            }
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(list: &[&str]) -> Vec<String> {
        list.iter().map(|s| s.to_string()).collect()
    }

    fn value(text: &str, symbols: &[&str]) -> RatFun {
        match symbolic(text, &names(symbols)) {
            Ok(v) => v,
            Err(e) => panic!("{text}: {e}"),
        }
    }

    fn q(n: i64, d: i64) -> RatFun {
        RatFun::constant(BigRational::new(n.into(), d.into()))
    }

    fn sqrt(n: i64) -> RatFun {
        RatFun::sqrt(&BigRational::from_integer(n.into())).unwrap()
    }

    fn s(name: &str) -> RatFun {
        RatFun::symbol(name)
    }

    fn error(text: &str, symbols: &[&str]) -> NumberError {
        match symbolic(text, &names(symbols)) {
            Err(e) => e,
            Ok(v) => panic!("{text}: expected an error, got {v}"),
        }
    }

    fn inexact(text: &str, symbols: &[&str]) -> String {
        match error(text, symbols) {
            NumberError::Inexact { reason, .. } => reason,
            e => panic!("{text}: expected Inexact, got {e:?}"),
        }
    }

    fn not_finite(text: &str, symbols: &[&str]) -> String {
        match error(text, symbols) {
            NumberError::NotFinite { reason, .. } => reason,
            e => panic!("{text}: expected NotFinite, got {e:?}"),
        }
    }

    fn syntax(text: &str, symbols: &[&str]) -> String {
        match error(text, symbols) {
            NumberError::Syntax { reason, .. } => reason,
            e => panic!("{text}: expected Syntax, got {e:?}"),
        }
    }

    #[test]
    fn rationals_and_symbols() {
        assert_eq!(value("0.1", &[]), q(1, 10));
        assert_eq!(value("1/3 + 1_000.5 - 0x10", &[]), q(2 - 6 * 16 + 6003, 6));
        assert_eq!(value("2^-2 * 4^3", &[]), q(16, 1));
        assert_eq!(value("(9/4)^(1/2)", &[]), q(3, 2));
        assert_eq!(value("(-8)^(1/3)", &[]), q(-2, 1));
        assert_eq!(value("(-1)^12345678901234567890", &[]), q(1, 1));
        assert_eq!(value("0^0", &[]), q(1, 1));
        assert_eq!(value("pi/pi", &[]), q(1, 1));
        assert_eq!(
            value("m*Jz/k1 - m", &["m", "Jz", "k1"]),
            s("m") * s("Jz") / s("k1") - s("m")
        );
        assert_eq!(
            value("(m + 1)^-2", &["m"]),
            q(1, 1) / ((s("m") + q(1, 1)) * (s("m") + q(1, 1)))
        );
        assert_eq!(value("m - m", &["m"]), q(0, 1));
        assert_eq!(
            value("omega0^3/omega0", &["omega0"]),
            s("omega0") * s("omega0")
        );
    }

    #[test]
    fn radicals() {
        assert_eq!(value("sqrt(12)", &[]), q(2, 1) * sqrt(3));
        assert_eq!(value("sqrt(3/31)", &[]), sqrt(3) * sqrt(31) / q(31, 1));
        assert_eq!(value("sqrt(2)*sqrt(2)", &[]), q(2, 1));
        assert_eq!(value("2/sqrt(5)", &[]), q(2, 5) * sqrt(5));
        assert_eq!(value("12^(1/2)", &[]), q(2, 1) * sqrt(3));
        assert_eq!(value("2^(3/2)", &[]), q(2, 1) * sqrt(2));
        assert_eq!(value("sqrt(9/4)", &[]), q(3, 2));
        assert_eq!(value("sqrt(0)", &[]), q(0, 1));
        assert_eq!(value("1/(1 + sqrt(2))", &[]), sqrt(2) - q(1, 1));
        assert!(not_finite("sqrt(-1)", &[]).contains("'sqrt(-1)'"));
        assert!(not_finite("(-4)^(1/2)", &[]).contains("negative"));
        assert!(not_finite("(-16)^(1/4)", &[]).contains("even order"));
        let e = inexact("sqrt(m)", &["m"]);
        assert!(
            e.contains("rational constant, not of 'm'") && e.contains("declare the root"),
            "{e}"
        );
        assert!(inexact("m^(1/2)", &["m"]).contains("declare the root"));
        assert!(inexact("2^(1/3)", &[]).contains("irrational"));
        assert!(inexact("sqrt(sqrt(2))", &[]).contains("not of 'sqrt(2)'"));
        assert!(inexact("2^m", &["m"]).contains("exponent 'm'"));
    }

    #[test]
    fn angles() {
        assert_eq!(value("cos(30 deg)", &[]), sqrt(3) / q(2, 1));
        assert_eq!(value("sin(pi/6)", &[]), q(1, 2));
        assert_eq!(value("sin(-45 deg)", &[]), -sqrt(2) / q(2, 1));
        assert_eq!(value("cos(pi)", &[]), q(-1, 1));
        assert_eq!(value("cos(0)", &[]), q(1, 1));
        assert_eq!(value("tan(0)", &[]), q(0, 1));
        assert_eq!(value("tan(pi/3)", &[]), sqrt(3));
        assert_eq!(value("tan(-15 deg)", &[]), sqrt(3) - q(2, 1));
        assert_eq!(value("cos(15 deg)", &[]), (sqrt(6) + sqrt(2)) / q(4, 1));
        assert_eq!(value("cos(720 deg + 120 deg)", &[]), q(-1, 2));
        assert_eq!(value("sin(2*pi/3 - pi/4)", &[]), value("sin(75 deg)", &[]));
        let (c, sn) = RatFun::angle("theta");
        assert_eq!(value("cos(theta)", &["theta"]), c);
        assert_eq!(value("sin((theta))", &["theta"]), sn);
        assert_eq!(value("tan(theta)", &["theta"]), sn.clone() / &c);
        assert_eq!(value("sin(theta)^2 + cos(theta)^2", &["theta"]), q(1, 1));
        assert_eq!(
            value("theta*cos(theta)", &["theta"]),
            s("theta") * RatFun::angle("theta").0
        );
        assert!(not_finite("tan(90 deg)", &[]).contains("infinite"));
        assert!(not_finite("tan(-pi/2)", &[]).contains("infinite"));
        assert_eq!(
            inexact("cos(20 deg)", &[]),
            "cos(20 deg) has no exact radical form: only multiples of 15° do"
        );
        assert!(inexact("sin(pi/7)", &[]).contains("multiples of 15°"));
        assert!(inexact("sin(1)", &[]).contains("radians"));
        assert!(inexact("cos(2*theta)", &["theta"]).contains("bare declared angle"));
        assert!(inexact("cos(-theta)", &["theta"]).contains("bare declared angle"));
        assert!(inexact("m deg", &["m"]).contains("rational number of degrees"));
        for text in [
            "pi", "2*pi", "pi + 1", "30 deg", "sqrt(pi)", "pi^2", "2^pi", "m*pi",
        ] {
            assert!(
                inexact(text, &["m"]).contains("pi is transcendental"),
                "{text}"
            );
        }
    }

    #[test]
    fn errors() {
        let e = error("1/0", &[]);
        assert_eq!(
            e.to_string(),
            "'1/0' is not finite (division by zero in '1/0')"
        );
        assert!(not_finite("m/(m - m)", &["m"]).contains("division by zero in 'm/(m - m)'"));
        assert!(not_finite("0^-1", &[]).contains("zero to a negative power"));
        not_finite("nan", &[]);
        not_finite("-inf + m", &["m"]);
        assert_eq!(
            syntax("m + w", &["m", "k1"]),
            "unknown name 'w' at position 5 (known names: pi, deg, sqrt, sin, cos, tan; \
             declared symbols: k1, m)"
        );
        // Syntax errors come first, unknown names before value errors.
        assert!(syntax("1/0 + w", &[]).contains("unknown name 'w'"));
        assert!(syntax("w +", &[]).contains("end of input"));
        assert!(syntax("", &[]).contains("empty"));
        assert_eq!(
            error("sqrt(m)", &["m"]).to_string(),
            "'sqrt(m)' has no exact symbolic value: sqrt is exact only of a rational constant, \
             not of 'm'; declare the root as a symbol instead"
        );
        assert!(inexact("1e-9999", &[]).contains("exact range"));
    }

    #[test]
    fn limits() {
        assert!(inexact("2^100000", &[]).contains("bits"));
        assert!(inexact("m^100000", &["m"]).contains("degree"));
        assert!(inexact("((m^100)^100)^100", &["m"]).contains("degree"));
        assert!(inexact("(a+b+c+d+e+f)^40", &["a", "b", "c", "d", "e", "f"]).contains("terms"));
        assert!(inexact("(2 + sqrt(2) + sqrt(3))^9000", &[]).contains("bits"));
        let many = (2..60)
            .map(|k| format!("sqrt({k})"))
            .collect::<Vec<_>>()
            .join(" + ");
        assert!(inexact(&format!("1/({many})"), &[]).contains("radicals"));
        let huge = format!("sqrt({}1)", "7".repeat(100));
        assert!(inexact(&huge, &[]).contains("too large"));
        let square = format!("sqrt({}^2)", "7".repeat(100));
        assert_eq!(value(&square, &[]), value(&"7".repeat(100), &[]));
        let long_sum = vec!["m"; 10_000].join("+");
        assert_eq!(value(&long_sum, &["m"]), q(10_000, 1) * s("m"));
        let deep = format!("{}m{}", "sqrt(".repeat(150), ")".repeat(150));
        inexact(&deep, &["m"]);
        let deep = format!("{}m{}", "(1 + ".repeat(150), ")".repeat(150));
        assert_eq!(value(&deep, &["m"]), s("m") + q(150, 1));
        // At the nesting limit (199 levels), on a test thread's stack.
        let deep = format!("{}4{}", "sqrt(".repeat(199), ")".repeat(199));
        assert!(inexact(&deep, &[]).contains("not of 'sqrt(sqrt(4))'"));
        let deep = format!("{}theta{}", "-sin(".repeat(99), ")".repeat(99));
        assert!(inexact(&deep, &["theta"]).contains("bare declared angle"));
        let deep = format!("{}1{}", "2^".repeat(199), "");
        assert!(inexact(&deep, &[]).contains("bits"));
        assert!(syntax(&"2^".repeat(300), &[]).contains("nested"));
        for text in [
            "2^2^2^2^2",
            "7^(2^40)",
            "(1/3)^(1/12345678901)",
            "0.5^(-0.5)",
            "1^(1/3)",
        ] {
            let _ = symbolic(text, &[]);
        }
    }

    /// `symbolic(x.to_text())` with the names of x gives x back.
    fn round_trip(x: &RatFun) -> Result<(), String> {
        let text = x.to_text();
        match symbolic(&text, &symbol_names(x)) {
            Ok(y) if y == *x => Ok(()),
            Ok(y) => Err(format!("{text} read back as {y}")),
            Err(e) => Err(format!("{text}: {e}")),
        }
    }

    #[test]
    fn to_text_reads_back() {
        let (m, jz, y1, a) = (s("m"), s("Jz"), s("y1"), s("a"));
        let (c, sn) = RatFun::angle("theta");
        let values = [
            q(0, 1),
            q(-7, 3),
            sqrt(12),
            -sqrt(6) / q(5, 1),
            q(1, 1) / &m + y1.clone() * &y1 / &jz,
            (q(3, 1) * s("k1") * &m + q(2, 1)) / (a.clone() * &a * &m + &jz),
            y1.clone() / (q(2, 1) * &m * (a.clone() * &a * &m + &jz).pow(2)),
            q(-1, 2) * sqrt(2) * y1.pow(2) + q(3, 1) * &m * s("k1") - q(2, 1),
            c.clone() * &c - sn.clone() * q(2, 1) * &m,
            (sn.clone() + sqrt(3) * &c) / (c.clone() + q(2, 1)),
            RatFun::cos_deg(15).unwrap() * s("omega0") - s("_x1").pow(3),
            (m.clone() - &jz).pow(3) / (m.clone() + &jz).pow(2) / &y1,
        ];
        for x in &values {
            round_trip(x).unwrap();
        }
    }

    /// A random small value: a polynomial over a polynomial in m, Jz, k1, √2, √3, cos θ, sin θ,
    /// plus a second such fraction.
    fn ratfun_strategy() -> impl proptest::strategy::Strategy<Value = RatFun> {
        use proptest::prelude::*;
        let term = (
            -6i64..=6,
            1i64..=4,
            proptest::collection::vec((0usize..7, 1u32..=3), 0..3),
        );
        let poly = proptest::collection::vec(term, 1..4).prop_map(|terms| {
            let atoms = [
                s("m"),
                s("Jz"),
                s("k1"),
                sqrt(2),
                sqrt(3),
                RatFun::angle("theta").0,
                RatFun::angle("theta").1,
            ];
            let mut p = q(0, 1);
            for (n, d, factors) in terms {
                let mut t = q(n, d);
                for (i, e) in factors {
                    t *= atoms[i].pow(e);
                }
                p += t;
            }
            p
        });
        (poly.clone(), poly.clone(), poly.clone(), poly).prop_map(|(a, b, c, d)| {
            let first = if b.is_zero() { a } else { a / b };
            if d.is_zero() { first } else { first + c / d }
        })
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { cases: 96, ..Default::default() })]

        /// Round trip of `to_text` through the grammar.
        #[test]
        fn random_values_read_back(x in ratfun_strategy()) {
            if let Err(e) = round_trip(&x) {
                proptest::prop_assert!(false, "{}", e);
            }
        }

        /// No input made of the grammar's pieces panics, in any evaluator.
        #[test]
        fn garbage_never_panics(tokens in proptest::collection::vec(proptest::sample::select(vec![
            "m", "theta", "sqrt(", "cos(", "sin(", "tan(", "pi", "deg", "(", ")", "+", "-", "*",
            "/", "^", "0", "1", "2", "15", "0.5", "1e400", "1e-9999", "inf", " ", "x", "_",
        ]), 0..14)) {
            let text: String = tokens.concat();
            let declared = names(&["m", "theta"]);
            let _ = symbolic(&text, &declared);
            let _ = number::parse_number_with(&text, &declared);
            let _ = crate::mechanics::surface::Surface::parse(&text);
        }
    }

    #[test]
    fn names_of_a_value() {
        let (c, _) = RatFun::angle("phi");
        let x = s("m") * sqrt(2) + c / s("Jz") + s("phi");
        assert_eq!(symbol_names(&x), ["Jz", "m", "phi"]);
    }
}
