//! Numbers as written in scene files, read exactly.
//!
//! A scene number is a TOML literal (`0.1`, `1_000.5`, `-3e-2`, `0x10`) or a string holding a
//! fraction or expression (`"1/3"`, `"2/sqrt(5)"`, `"cos(30 deg)"`). Exact mode needs the value the
//! author meant, so `0.1` is exactly 1/10 and never the nearest binary float; expressions that
//! are not rational (`sqrt(5)`) carry the reason instead, and f64 mode still gets a value.
//!
//! The grammar is the crate's one expression grammar, parsed by [`crate::number::expr`]; this module
//! evaluates its tree. [`parse_number`] accepts no names besides the grammar's own;
//! [`parse_number_with`] also accepts declared symbols, and a number that names one has no
//! value here (its exact form is [`crate::scalar::symbolic::symbolic`]'s business).
//!
//! Evaluation tracks, besides rationals, rational multiples of pi, so that angles such as
//! `30 deg` or `pi/6` give exact sines and cosines where those are rational (Niven's theorem).
//! Limitation: other irrational values are not tracked symbolically, so cancellations such as
//! `sqrt(2)*sqrt(2)` are reported as irrational even though the result is 2.

use std::f64::consts::PI;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

pub mod expr;
mod rational;
pub(crate) mod tangent;
pub(crate) mod template;

use expr::{Func, Kind, Lit, MAX_DECIMAL_EXPONENT, Node, Op, Wording};

pub(crate) use rational::exact_root;
pub use rational::{canonical_surd, format_rational, format_surd, rational_to_f64, surd_to_f64};

/// A number as written in a scene: its text, its exact rational value when it has one, and its f64 value.
#[derive(Clone, Debug, PartialEq)]
pub struct Number {
    /// The text as given (outer whitespace trimmed), kept for messages and reports.
    pub text: String,
    /// Ok(q) when the expression is rational; Err(reason) says why not, e.g. "sqrt(5) is irrational".
    pub exact: Result<BigRational, String>,
    /// Best f64 value: the correctly rounded exact value when rational, else the f64 evaluation;
    /// NaN when the number names a symbol.
    pub approx: f64,
    /// The declared symbols the text names, sorted and without duplicates (see
    /// [`parse_number_with`]); empty for an ordinary number.
    pub symbols: Vec<String>,
    /// The derivative of the value with respect to the one parameter a sensitivity run
    /// seeds (forward mode, a dual-number run: [`crate::scalar::dual`],
    /// [`crate::scene::seed`]); 0 otherwise. An f64: a dual run over an exact type converts it
    /// exactly (`BigRational::from_float`), so a derivative seeded here is exact only as that
    /// f64 (1 for the number itself; a parameter's derivative d x/dθ rounded once).
    pub tangent: f64,
    /// The text as written, when named parameters were substituted into [`Number::text`]
    /// (`sin(theta)` for `sin((3 deg))`); `None` otherwise. Combining numbers into new ones
    /// (a pose, a shape's moments) starts from it, so that their derivatives follow.
    pub source: Option<String>,
}

/// Why a text could not be read as a finite number.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum NumberError {
    /// The text is not a number or expression of the accepted grammar.
    #[error("cannot read '{text}' as a number: {reason}")]
    Syntax {
        /// The text that was read.
        text: String,
        /// What was unexpected and where (1-based character position).
        reason: String,
    },
    /// The text is well formed but its value is not a finite real number.
    #[error("'{text}' is not finite ({reason})")]
    NotFinite {
        /// The text that was read.
        text: String,
        /// nan, inf, division by zero, root of a negative number or overflow of f64.
        reason: String,
    },
    /// The text is well formed and finite but has no exact symbolic value (only from
    /// [`crate::scalar::symbolic::symbolic`]), e.g. `cos(20 deg)` or `sqrt(m)`.
    #[error("'{text}' has no exact symbolic value: {reason}")]
    Inexact {
        /// The text that was read.
        text: String,
        /// Which sub-expression, and why.
        reason: String,
    },
}

/// Exact values wider than this many bits (numerator or denominator) are given up on:
/// no scene needs them, and the gcd behind every rational operation is quadratic in the size.
pub(crate) const MAX_EXACT_BITS: u64 = 16_384;
/// Names the expression grammar knows, listed in the error for an unknown name.
const KNOWN_NAMES: &str = "pi, deg, sqrt, sin, cos, tan";
/// Syntax messages of numbers.
const WORDING: Wording = Wording {
    input: "input",
    operand: "a number, 'pi', a function or '('",
};

/// Parse a number or expression.
///
/// Accepts TOML numeric literals too (underscores between digits, leading '+', exponent,
/// `0x..`, `0o..`, `0b..` integers) and the expression grammar of [`crate::number::expr`]
/// (`+ - * / ^ ( )`, `pi`, `X deg`, `sqrt sin cos tan`), without names. Rejects nan/inf
/// (NotFinite). Syntax errors take precedence over value errors, so the author sees typos first.
///
/// # Errors
/// [`NumberError::Syntax`] for text outside the grammar, an unknown name or nesting deeper
/// than 200 levels; [`NumberError::NotFinite`] for nan/inf, division by zero, even roots of
/// negative numbers, tan at a pole, and values without an exact rational value that overflow
/// f64 (an exact rational beyond f64's range is a number: its `approx` is ±∞).
pub fn parse_number(text: &str) -> Result<Number, NumberError> {
    parse_number_with(text, &[])
}

/// [`parse_number`], with the names in `symbols` allowed as symbols.
///
/// A number that names one of them has no value: `exact` is `Err("m*g/2 names the symbols
/// g, m")`, `approx` is NaN and `symbols` lists them; its rational parts are still checked
/// (`m/0` is NotFinite). Whether it has an exact symbolic form is left to
/// [`crate::scalar::symbolic::symbolic`]. A name neither known nor declared is the usual syntax error,
/// whose message also lists the declared symbols.
///
/// # Errors
/// As [`parse_number`].
pub fn parse_number_with(text: &str, symbols: &[String]) -> Result<Number, NumberError> {
    let src = text.trim();
    if let Some(n) = plain_decimal(src) {
        return Ok(n);
    }
    let root = parse_checked(src, symbols)?;
    evaluate(src, &root)
}

/// The number a plain decimal `[-]digits[.digits]` of at most 18 digits writes, nonzero — most
/// of a large scene's numbers — read without the expression parser: m / 10^k exactly (reduced),
/// and its f64 by Rust's correctly rounded parser, which is the correctly rounded value of
/// that rational, as the general path gives it (tested to be the same [`Number`]). `None` for
/// anything else, which the general path reads.
fn plain_decimal(src: &str) -> Option<Number> {
    let digits = src.strip_prefix('-').unwrap_or(src);
    let (int, frac) = digits.split_once('.').unwrap_or((digits, ""));
    let ok = |d: &str| d.bytes().all(|b| b.is_ascii_digit());
    if int.is_empty() || (digits.contains('.') && frac.is_empty()) || !ok(int) || !ok(frac) {
        return None;
    }
    if int.len() + frac.len() > 18 {
        return None;
    }
    let mut m: i64 = 0;
    for b in int.bytes().chain(frac.bytes()) {
        m = m * 10 + i64::from(b - b'0');
    }
    if m == 0 {
        return None; // ±0: the general path decides the sign of zero
    }
    if src.starts_with('-') {
        m = -m;
    }
    // Reduced in machine words (|m| < 10^18, 10^k ≤ 10^17): num's BigInt gcd costs more
    // than the rest of the read.
    let (mut a, mut b) = (m.unsigned_abs(), 10u64.pow(frac.len() as u32));
    let den = b;
    while b != 0 {
        (a, b) = (b, a % b);
    }
    let exact = BigRational::new_raw(BigInt::from(m / a as i64), BigInt::from(den / a));
    Some(Number {
        text: src.to_string(),
        approx: src.parse::<f64>().ok()?,
        exact: Ok(exact),
        symbols: Vec::new(),
        tangent: 0.0,
        source: None,
    })
}

/// Parse `src` (trimmed) and check that every name in it is declared in `symbols`: the syntax
/// half of [`parse_number_with`], shared with [`crate::scalar::symbolic::symbolic`].
pub(crate) fn parse_checked(src: &str, symbols: &[String]) -> Result<Node, NumberError> {
    parse_checked_measured(src, symbols).map(|(root, _)| root)
}

/// [`parse_checked`], with the deepest nesting the parse reached ([`expr::parse_measured`]).
fn parse_checked_measured(src: &str, symbols: &[String]) -> Result<(Node, usize), NumberError> {
    let syntax = |reason: String| NumberError::Syntax {
        text: src.to_string(),
        reason,
    };
    let (root, deepest) = expr::parse_measured(src, &WORDING).map_err(syntax)?;
    let undeclared = root.names().into_iter().find(|n| match &n.kind {
        Kind::Name(name) => !symbols.iter().any(|s| s.as_str() == &**name),
        _ => false,
    });
    if let Some(node) = undeclared {
        let mut declared: Vec<&str> = symbols
            .iter()
            .map(String::as_str)
            .filter(|s| expr::is_symbol_name(s))
            .collect();
        declared.sort_unstable();
        declared.dedup();
        let known = if declared.is_empty() {
            KNOWN_NAMES.to_string()
        } else {
            format!("{KNOWN_NAMES}; declared symbols: {}", declared.join(", "))
        };
        return Err(syntax(expr::unknown_name(src, node, &known)));
    }
    Ok((root, deepest))
}

/// The number written by `node`, a sub-tree of `src` whose names all count as declared
/// symbols; the number's text (and that of its errors) is the node's span.
pub(crate) fn evaluate(src: &str, node: &Node) -> Result<Number, NumberError> {
    let text = src.get(node.start..node.end).unwrap_or(src);
    let value = Eval {
        src,
        whole: text,
        at: template::At::Same,
    }
    .eval(node)?;
    number_of(text, value, symbol_names(node))
}

/// The number of `text` whose value is `value` and which names `symbols` (sorted, without
/// duplicates): the last step of [`evaluate`].
fn number_of(text: &str, value: Value, symbols: Vec<String>) -> Result<Number, NumberError> {
    if matches!(value.ex, Exact::Sym) {
        let s = if symbols.len() == 1 { "" } else { "s" };
        return Ok(Number {
            text: text.to_string(),
            exact: Err(format!("{text} names the symbol{s} {}", symbols.join(", "))),
            approx: f64::NAN,
            symbols,
            tangent: 0.0,
            source: None,
        });
    }
    // An exact rational whose f64 overflows is still a number (exact mode reads it; f64 mode
    // scales the scene or names it out of range); without an exact value it is refused.
    if !value.f.is_finite() && !matches!(value.ex, Exact::Rat(_)) {
        return Err(NumberError::NotFinite {
            text: text.to_string(),
            reason: if value.f.is_nan() {
                "the value is not a number".to_string()
            } else {
                "the value overflows f64".to_string()
            },
        });
    }
    let exact = match value.ex {
        Exact::Rat(q) => Ok(q),
        Exact::Pi(_) => Err(format!(
            "{text} is irrational (a non-zero rational multiple of pi)"
        )),
        Exact::No(reason) => Err(reason),
        Exact::Sym => Err(String::new()), // handled above
    };
    Ok(Number {
        text: text.to_string(),
        exact,
        approx: value.f,
        symbols,
        tangent: 0.0,
        source: None,
    })
}

/// The names in `node`, sorted, without duplicates.
fn symbol_names(node: &Node) -> Vec<String> {
    let mut names: Vec<String> = node
        .names()
        .into_iter()
        .filter_map(|n| match &n.kind {
            Kind::Name(name) => Some(name.to_string()),
            _ => None,
        })
        .collect();
    names.sort_unstable();
    names.dedup();
    names
}

/// Exact decimal literal -> rational: "0.1" -> 1/10, "-3e-2" -> -3/100, "1_000.5" -> 2001/2.
///
/// Also accepts a leading sign and TOML `0x`/`0o`/`0b` integers, so any TOML integer or float
/// text can be passed. None for anything else, including nan/inf and exponents beyond ±5000.
pub fn parse_decimal(text: &str) -> Option<BigRational> {
    let s = text.trim();
    let (negative, body) = match s.as_bytes().first() {
        Some(b'-') => (true, &s[1..]),
        Some(b'+') => (false, &s[1..]),
        _ => (false, s),
    };
    if !body.starts_with(|c: char| c.is_ascii_digit() || c == '.') {
        return None;
    }
    let (lit, end) = expr::scan_literal(body, 0).ok()?;
    if end != body.len() {
        return None;
    }
    let q = lit.exact?;
    Some(if negative { -q } else { q })
}

// ---------------------------------------------------------------------------------------------
// Evaluation: exact and f64 side by side.

/// The exact side of a value.
#[derive(Debug, Clone)]
enum Exact {
    Rat(BigRational),
    /// q*pi with q != 0: an angle in radians, so that trigonometry stays exact.
    Pi(BigRational),
    /// No exact value; the reason names the innermost culprit.
    No(String),
    /// Names a declared symbol: no value at all (the f64 side is NaN).
    Sym,
}

#[derive(Clone, Debug)]
struct Value {
    ex: Exact,
    f: f64,
}

struct Eval<'a> {
    /// The source, for quoting sub-expressions.
    src: &'a str,
    /// The text of the number evaluated (the text of its errors).
    whole: &'a str,
    /// Where the nodes' byte ranges lie in `src`: there, or in a text read again with its
    /// parameters' values in place ([`template`]).
    at: template::At<'a>,
}

fn bits(q: &BigRational) -> u64 {
    q.numer().bits().max(q.denom().bits())
}

fn int(n: i64) -> BigRational {
    BigRational::from_integer(BigInt::from(n))
}

fn odd(n: &BigInt) -> bool {
    n.magnitude().bit(0)
}

impl Eval<'_> {
    fn text(&self, start: usize, end: usize) -> &str {
        let (start, end) = self.at.range(start, end);
        self.src.get(start..end).unwrap_or(self.src)
    }

    fn not_finite(&self, reason: String) -> NumberError {
        NumberError::NotFinite {
            text: self.whole.to_string(),
            reason,
        }
    }

    /// Combine the exact and f64 results of one operation on `text`: the exact value, when
    /// there is one, also provides the (correctly rounded) f64; without one, the f64 must be finite.
    fn value(&self, ex: Exact, f: f64, text: &str) -> Result<Value, NumberError> {
        let (f, ex) = match ex {
            Exact::Pi(q) if q.is_zero() => (0.0, Exact::Rat(q)),
            Exact::Rat(q) => (rational_to_f64(&q), Exact::Rat(q)),
            Exact::Pi(q) => (rational_to_f64(&q) * PI, Exact::Pi(q)),
            Exact::Sym => return Ok(Value { ex: Exact::Sym, f }),
            no => (f, no),
        };
        let ex = match ex {
            Exact::Rat(ref q) | Exact::Pi(ref q) if bits(q) > MAX_EXACT_BITS => Exact::No(format!(
                "'{text}' exceeds {MAX_EXACT_BITS} bits of exact precision"
            )),
            ex => ex,
        };
        match ex {
            Exact::No(_) if f.is_nan() => Err(self.not_finite(format!("'{text}' is not a number"))),
            Exact::No(_) if f.is_infinite() => {
                Err(self.not_finite(format!("'{text}' overflows f64")))
            }
            ex => Ok(Value { ex, f }),
        }
    }

    /// Evaluate children first, then combine in a separate (non-recursive) function. Written with
    /// `and_then` rather than `?` because every nesting level pays for this frame, and in debug
    /// builds each `?` adds temporaries.
    fn eval(&self, node: &Node) -> Result<Value, NumberError> {
        if let Some(known) = self.at.known(node) {
            return Ok(known.clone());
        }
        let text = self.text(node.start, node.end);
        match &node.kind {
            Kind::Lit(lit) => self.literal(lit, text),
            Kind::Pi => self.value(Exact::Pi(BigRational::one()), PI, text),
            Kind::NonFinite => Err(self.not_finite_name(text)),
            Kind::Name(_) => match self.at.expansion(node) {
                Some(expansion) => self.expanded(expansion),
                None => self.value(Exact::Sym, f64::NAN, text),
            },
            Kind::Neg(inner) => self.eval(inner).and_then(|v| self.negate(v, text)),
            Kind::Chain(first, rest) => self.chain(node.start, first, rest),
            Kind::Pow(base, exp) => self
                .eval(base)
                .and_then(|b| self.eval(exp).and_then(|e| self.power(b, e, text))),
            Kind::Deg(inner) => self.eval(inner).and_then(|v| self.degrees(v, text)),
            Kind::Call(Func::Sqrt, arg) => self.eval(arg).and_then(|v| self.sqrt(v, text)),
            Kind::Call(func, arg) => self.eval(arg).and_then(|v| self.trig(*func, v, text)),
        }
    }

    fn chain(&self, start: usize, first: &Node, rest: &[(Op, Node)]) -> Result<Value, NumberError> {
        rest.iter().fold(self.eval(first), |acc, (op, rhs)| {
            // Quote the chain up to this operand, e.g. "2*3/0".
            acc.and_then(|a| {
                self.eval(rhs)
                    .and_then(|b| self.binary(*op, a, b, self.text(start, rhs.end)))
            })
        })
    }

    #[cold]
    fn not_finite_name(&self, text: &str) -> NumberError {
        self.not_finite(format!("'{text}' is not a finite number"))
    }

    fn literal(&self, lit: &Lit, text: &str) -> Result<Value, NumberError> {
        let ex = match &lit.exact {
            Some(q) => Exact::Rat(q.clone()),
            None => Exact::No(format!(
                "'{text}' is out of the exact range (decimal exponent beyond ±{MAX_DECIMAL_EXPONENT})"
            )),
        };
        self.value(ex, lit.approx, text)
    }

    fn negate(&self, v: Value, text: &str) -> Result<Value, NumberError> {
        let ex = match v.ex {
            Exact::Rat(q) => Exact::Rat(-q),
            Exact::Pi(q) => Exact::Pi(-q),
            no => no,
        };
        self.value(ex, -v.f, text)
    }

    fn power(&self, b: Value, e: Value, text: &str) -> Result<Value, NumberError> {
        let irrational = || Exact::No(format!("{text} is irrational"));
        let mut f = b.f.powf(e.f);
        // A negative base to p/q with odd q is real: (-8)^(1/3) = -2.
        if let (true, Exact::Rat(r)) = (b.f < 0.0 && f.is_nan(), &e.ex)
            && odd(r.denom())
        {
            f = (-b.f).powf(e.f) * if odd(r.numer()) { -1.0 } else { 1.0 };
        }
        let ex = match (&b.ex, &e.ex) {
            (Exact::Sym, _) | (_, Exact::Sym) => Exact::Sym,
            (Exact::No(r), _) | (_, Exact::No(r)) => Exact::No(r.clone()),
            (_, Exact::Pi(_)) => irrational(),
            (Exact::Pi(_), Exact::Rat(n)) if n.is_zero() => Exact::Rat(int(1)),
            (Exact::Pi(q), Exact::Rat(n)) if n.is_one() => Exact::Pi(q.clone()),
            (Exact::Pi(_), Exact::Rat(_)) => irrational(),
            (Exact::Rat(b), Exact::Rat(e)) => self.rational_power(b, e, text)?,
        };
        self.value(ex, f, text)
    }

    fn degrees(&self, v: Value, text: &str) -> Result<Value, NumberError> {
        let ex = match v.ex {
            Exact::Rat(q) => Exact::Pi(q / int(180)),
            Exact::Pi(_) => Exact::No(format!("{text} is irrational")),
            no => no,
        };
        self.value(ex, v.f.to_radians(), text)
    }

    fn sqrt(&self, v: Value, text: &str) -> Result<Value, NumberError> {
        let negative = match &v.ex {
            Exact::Rat(q) | Exact::Pi(q) => q.is_negative(),
            Exact::No(_) => v.f < 0.0,
            Exact::Sym => false,
        };
        if negative {
            return Err(self.not_finite(format!("square root of a negative number in '{text}'")));
        }
        let ex = match v.ex {
            Exact::Rat(q) => match (exact_root(q.numer(), 2), exact_root(q.denom(), 2)) {
                (Some(n), Some(d)) => Exact::Rat(BigRational::new(n, d)),
                _ => Exact::No(format!("{text} is irrational")),
            },
            Exact::Pi(_) => Exact::No(format!("{text} is irrational")),
            no => no,
        };
        self.value(ex, v.f.sqrt(), text)
    }

    fn trig(&self, func: Func, v: Value, text: &str) -> Result<Value, NumberError> {
        let irrational = || Exact::No(format!("{text} is irrational"));
        let x = match &v.ex {
            Exact::Pi(q) => reduced_radians(q),
            _ => v.f,
        };
        let f = match func {
            Func::Sin => x.sin(),
            Func::Cos => x.cos(),
            _ => x.tan(),
        };
        let ex = match v.ex {
            Exact::Rat(q) if q.is_zero() => Exact::Rat(int(i64::from(func == Func::Cos))),
            // Lindemann: sin/cos/tan of a non-zero rational (radian) is transcendental.
            Exact::Rat(_) => irrational(),
            Exact::Pi(q) => match trig_at_degrees(func, whole_degrees(&q)) {
                Trig::Rational(r) => Exact::Rat(r),
                Trig::Irrational => irrational(),
                Trig::Pole => return Err(self.not_finite(format!("'{text}' is infinite"))),
            },
            no => no,
        };
        self.value(ex, f, text)
    }

    fn binary(&self, op: Op, a: Value, b: Value, text: &str) -> Result<Value, NumberError> {
        use Exact::{No, Pi, Rat, Sym};
        let irrational = || No(format!("{text} is irrational"));
        let f = match op {
            Op::Add => a.f + b.f,
            Op::Sub => a.f - b.f,
            Op::Mul => a.f * b.f,
            Op::Div => a.f / b.f,
        };
        if op == Op::Div && matches!(&b.ex, Rat(q) if q.is_zero()) {
            return Err(self.not_finite(format!("division by zero in '{text}'")));
        }
        let ex = match (op, a.ex, b.ex) {
            (_, Sym, _) | (_, _, Sym) => Sym,
            (_, No(r), _) | (_, _, No(r)) => No(r),
            (Op::Add, Rat(x), Rat(y)) => Rat(x + y),
            (Op::Sub, Rat(x), Rat(y)) => Rat(x - y),
            (Op::Mul, Rat(x), Rat(y)) => Rat(x * y),
            (Op::Div, Rat(x), Rat(y)) => Rat(x / y),
            // Sums of angles stay angles; adding a non-zero rational to one does not.
            (Op::Add, Pi(x), Pi(y)) => Pi(x + y),
            (Op::Sub, Pi(x), Pi(y)) => Pi(x - y),
            (Op::Add | Op::Sub, Pi(x), Rat(y)) if y.is_zero() => Pi(x),
            (Op::Add, Rat(x), Pi(y)) if x.is_zero() => Pi(y),
            (Op::Sub, Rat(x), Pi(y)) if x.is_zero() => Pi(-y),
            (Op::Mul, Rat(x), Pi(y)) | (Op::Mul, Pi(y), Rat(x)) => Pi(x * y),
            (Op::Div, Pi(x), Rat(y)) => Pi(x / y),
            (Op::Div, Pi(x), Pi(y)) => Rat(x / y),
            (Op::Div, Rat(x), Pi(_)) if x.is_zero() => Rat(x),
            _ => irrational(),
        };
        self.value(ex, f, text)
    }

    /// b^e for rationals: exact when e is an integer, or e = p/q and b is a perfect q-th power.
    fn rational_power(
        &self,
        b: &BigRational,
        e: &BigRational,
        text: &str,
    ) -> Result<Exact, NumberError> {
        let irrational = || Exact::No(format!("{text} is irrational"));
        if b.is_negative() && !odd(e.denom()) {
            return Err(self.not_finite(format!(
                "a negative number has no real root of even order in '{text}'"
            )));
        }
        let base = if e.denom().is_one() || b.is_zero() || b.abs().is_one() {
            b.clone() // 0 and ±1 are their own roots (the sign is fine: the root order is odd)
        } else {
            let Some(q) = e.denom().to_u32() else {
                return Ok(irrational()); // |b| != 1 is no perfect power of such high order
            };
            match (exact_root(&b.numer().abs(), q), exact_root(b.denom(), q)) {
                (Some(n), Some(d)) => {
                    let r = BigRational::new(n, d);
                    if b.is_negative() { -r } else { r }
                }
                _ => return Ok(irrational()),
            }
        };
        let n = e.numer();
        if base.is_zero() {
            return match n.sign() {
                num_bigint::Sign::Minus => {
                    Err(self.not_finite(format!("zero to a negative power in '{text}'")))
                }
                num_bigint::Sign::NoSign => Ok(Exact::Rat(int(1))),
                num_bigint::Sign::Plus => Ok(Exact::Rat(base)),
            };
        }
        if base.abs().is_one() {
            return Ok(Exact::Rat(if base.is_negative() && odd(n) {
                base
            } else {
                int(1)
            }));
        }
        // Refuse before computing: the result has about |n| * bits(base) bits.
        let small = n
            .magnitude()
            .to_u32()
            .filter(|&k| u64::from(k) * bits(&base) <= MAX_EXACT_BITS);
        let Some(k) = small else {
            return Ok(Exact::No(format!(
                "'{text}' exceeds {MAX_EXACT_BITS} bits of exact precision"
            )));
        };
        let (num, den) = (base.numer().pow(k), base.denom().pow(k));
        Ok(Exact::Rat(if n.is_negative() {
            BigRational::new(den, num)
        } else {
            BigRational::new(num, den)
        }))
    }
}

/// f64 radians of q*pi after exact reduction of q into (-1, 1], so large angles lose no accuracy.
fn reduced_radians(q: &BigRational) -> f64 {
    // Parts of a word (an angle in degrees as written, over 180): the same reduction in
    // machine integers, the remainder then rounded once as `rational_to_f64` rounds it.
    if let (Some(n), Some(d)) = (q.numer().to_i64(), q.denom().to_i64())
        && d > 0
    {
        let (n, d) = (i128::from(n), i128::from(d));
        let mut r = n - n.div_euclid(2 * d) * 2 * d;
        if r > d {
            r -= 2 * d;
        }
        return rational_to_f64(&BigRational::new_raw(BigInt::from(r), BigInt::from(d))) * PI;
    }
    reduced_radians_big(q)
}

/// [`reduced_radians`] in big rationals.
fn reduced_radians_big(q: &BigRational) -> f64 {
    let two = int(2);
    let mut r = q - (q / &two).floor() * &two;
    if r > BigRational::one() {
        r -= two;
    }
    rational_to_f64(&r) * PI
}

enum Trig {
    Rational(BigRational),
    Irrational,
    Pole,
}

/// The angle q·π in whole degrees, in [0, 360): `None` when q·180 is no integer.
fn whole_degrees(q: &BigRational) -> Option<i64> {
    // Parts of a word (an angle swept in degrees): q is reduced, so q·180 is an integer iff
    // q's denominator divides 180·numerator — the same answer as the big rationals' below,
    // without their gcds (a sweep over an angle takes a sine or cosine of it dozens of times
    // a point).
    if let (Some(n), Some(d)) = (q.numer().to_i64(), q.denom().to_i64())
        && d > 0
    {
        let degrees = i128::from(n) * 180;
        let d = i128::from(d);
        return (degrees % d == 0).then(|| (degrees / d).rem_euclid(360) as i64);
    }
    whole_degrees_big(q)
}

/// [`whole_degrees`] in big rationals.
fn whole_degrees_big(q: &BigRational) -> Option<i64> {
    let degrees = q * int(180);
    // Only whole degrees are listed, and a whole number of turns keeps a fraction one.
    if !degrees.is_integer() {
        return None;
    }
    let full = int(360);
    let d = &degrees - (&degrees / &full).floor() * &full;
    d.is_integer().then(|| d.to_integer().to_i64()).flatten()
}

/// sin/cos/tan at a whole number of degrees in [0, 360) ([`whole_degrees`]; `None`: not a
/// whole number). By Niven's theorem their only rational values at rational degrees are 0,
/// ±1/2, ±1 (sin, cos) and 0, ±1 (tan), taken at the angles listed here.
fn trig_at_degrees(func: Func, degrees: Option<i64>) -> Trig {
    let Some(d) = degrees else {
        return Trig::Irrational;
    };
    let half = || BigRational::new(BigInt::from(1), BigInt::from(2));
    let value = match (func, d) {
        (Func::Sin, 0 | 180) | (Func::Cos, 90 | 270) | (Func::Tan, 0 | 180) => int(0),
        (Func::Sin, 90) | (Func::Cos, 0) | (Func::Tan, 45 | 225) => int(1),
        (Func::Sin, 270) | (Func::Cos, 180) | (Func::Tan, 135 | 315) => int(-1),
        (Func::Sin, 30 | 150) | (Func::Cos, 60 | 300) => half(),
        (Func::Sin, 210 | 330) | (Func::Cos, 120 | 240) => -half(),
        (Func::Tan, 90 | 270) => return Trig::Pole,
        _ => return Trig::Irrational,
    };
    Trig::Rational(value)
}

#[cfg(test)]
mod tests {
    /// An angle's whole degrees read in machine words are those read in big rationals.
    #[test]
    fn whole_degrees_in_words_are_those_in_big_rationals() {
        let mut seed = 0xdeb_u64;
        let mut next = |k: i64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 33) as i64) % k
        };
        let mut cases: Vec<(i64, i64)> = vec![(0, 1), (1, 1), (-1, 1), (1, 6), (-7, 4), (2, 1)];
        for _ in 0..20_000 {
            let d = [1, 2, 3, 4, 5, 6, 9, 12, 36, 60, 180, 7, 11, 1000, 2875][next(15) as usize];
            cases.push((next(4001) - 2000, d));
        }
        cases.push((i64::MAX, 1));
        cases.push((i64::MIN + 1, 180));
        cases.push((i64::MAX, i64::MAX - 1));
        for (n, d) in cases {
            let q = BigRational::new(BigInt::from(n), BigInt::from(d));
            assert_eq!(whole_degrees(&q), whole_degrees_big(&q), "{n}/{d}");
        }
    }

    /// The plain-decimal shortcut gives the very number the expression parser does.
    #[test]
    fn plain_decimals_read_as_the_general_path_reads_them() {
        let mut seed = 0x5eed_u64;
        let mut next = |k: u64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) % k
        };
        let mut texts: Vec<String> = ["1", "-2", "0.5", "-0.25", "12.000", "007.10", "-0.000001"]
            .map(String::from)
            .to_vec();
        for _ in 0..4000 {
            let int: String = (0..1 + next(9))
                .map(|_| char::from(b'0' + next(10) as u8))
                .collect();
            let frac: String = (0..next(10))
                .map(|_| char::from(b'0' + next(10) as u8))
                .collect();
            let sign = if next(2) == 0 { "-" } else { "" };
            texts.push(match frac.is_empty() {
                true => format!("{sign}{int}"),
                false => format!("{sign}{int}.{frac}"),
            });
        }
        let mut fast = 0;
        for t in &texts {
            let general = evaluate(t, &parse_checked(t, &[]).unwrap()).unwrap();
            if let Some(n) = plain_decimal(t) {
                fast += 1;
                assert_eq!(n, general, "{t}");
                assert_eq!(n.approx.to_bits(), general.approx.to_bits(), "{t}");
                let (q, r) = (n.exact.as_ref().unwrap(), general.exact.as_ref().unwrap());
                assert_eq!(
                    (q.numer(), q.denom()),
                    (r.numer(), r.denom()),
                    "{t}: in lowest terms"
                );
            }
        }
        assert!(fast > 3000, "the shortcut took {fast} of {}", texts.len());
        for t in [
            "1e3",
            "1.",
            ".5",
            "1/3",
            "0",
            "-0.0",
            "1234567890123456789",
            "+1",
            "1_0",
        ] {
            assert!(plain_decimal(t).is_none(), "{t}");
        }
    }

    use super::*;

    fn q(n: i64, d: i64) -> BigRational {
        BigRational::new(BigInt::from(n), BigInt::from(d))
    }

    fn exact(text: &str) -> BigRational {
        match parse_number(text) {
            Ok(Number { exact: Ok(v), .. }) => v,
            other => panic!("{text}: expected an exact value, got {other:?}"),
        }
    }

    fn inexact(text: &str) -> (String, f64) {
        match parse_number(text) {
            Ok(Number {
                exact: Err(reason),
                approx,
                ..
            }) => (reason, approx),
            other => panic!("{text}: expected an inexact value, got {other:?}"),
        }
    }

    fn ulps(a: f64, b: f64) -> u64 {
        (a.to_bits() as i64 - b.to_bits() as i64).unsigned_abs()
    }

    fn is_syntax(text: &str) -> String {
        match parse_number(text) {
            Err(NumberError::Syntax { reason, .. }) => reason,
            other => panic!("{text}: expected a syntax error, got {other:?}"),
        }
    }

    fn is_not_finite(text: &str) -> String {
        match parse_number(text) {
            Err(NumberError::NotFinite { reason, .. }) => reason,
            other => panic!("{text}: expected NotFinite, got {other:?}"),
        }
    }

    #[test]
    fn literals_are_exact() {
        assert_eq!(exact("0.1"), q(1, 10));
        assert_eq!(parse_number("0.1").map(|n| n.approx), Ok(0.1));
        assert_eq!(exact("1/3"), q(1, 3));
        assert_eq!(exact("-3e-2"), q(-3, 100));
        assert_eq!(exact("1_000.5"), q(2001, 2));
        assert_eq!(exact("+7"), q(7, 1));
        assert_eq!(exact("0x10"), q(16, 1));
        assert_eq!(exact("0o17"), q(15, 1));
        assert_eq!(exact("0b1_01"), q(5, 1));
        assert_eq!(exact(".5"), q(1, 2));
        assert_eq!(exact("5."), q(5, 1));
        assert_eq!(exact("2.5E+4"), q(25000, 1));
        assert_eq!(exact("1e-3"), q(1, 1000));
        assert_eq!(exact("0e99999999"), q(0, 1));
        assert_eq!(exact(" 0.75*4^2 "), q(12, 1));
    }

    #[test]
    fn parse_decimal_cases() {
        assert_eq!(parse_decimal("0.1"), Some(q(1, 10)));
        assert_eq!(parse_decimal("-3e-2"), Some(q(-3, 100)));
        assert_eq!(parse_decimal("1_000.5"), Some(q(2001, 2)));
        assert_eq!(parse_decimal("+0x1F"), Some(q(31, 1)));
        for bad in [
            "", "-", "1_", "_1", "1__0", "1.2.3", "1e", "nan", "inf", "1/3", "0x", "1e99999",
        ] {
            assert_eq!(parse_decimal(bad), None, "{bad}");
        }
    }

    #[test]
    fn powers() {
        assert_eq!(exact("2^-2"), q(1, 4));
        assert_eq!(exact("-2^2"), q(-4, 1));
        assert_eq!(exact("2^3^2"), q(512, 1));
        assert_eq!(exact("(9/4)^(1/2)"), q(3, 2));
        assert_eq!(exact("(-8)^(1/3)"), q(-2, 1));
        assert_eq!(exact("(-8)^(-2/3)"), q(1, 4));
        assert_eq!(exact("0^0"), q(1, 1));
        assert_eq!(exact("0^(1/2)"), q(0, 1));
        assert_eq!(exact("(-1)^(1/3)"), q(-1, 1));
        assert_eq!(exact("(-1)^(2/3)"), q(1, 1));
        is_not_finite("(-1)^(1/2)");
        is_not_finite("0^(-1/2)");
        assert_eq!(exact("(-1)^12345678901234567890"), q(1, 1));
        let (reason, approx) = inexact("2^(1/2)");
        assert_eq!(reason, "2^(1/2) is irrational");
        assert_eq!(approx, 2f64.sqrt());
        assert_eq!(inexact("(-2)^(1/3)").1, -(2f64.cbrt()));
        is_not_finite("0^-1");
        is_not_finite("(-4)^(1/2)");
        is_not_finite("2^100000"); // too big to be exact, and inf in f64
        assert!(inexact("(1/2)^100000").0.contains("bits"));
    }

    #[test]
    fn roots() {
        assert_eq!(exact("sqrt(9/4)"), q(3, 2));
        assert_eq!(exact("6*sqrt(3/27)"), q(2, 1));
        let (reason, approx) = inexact("sqrt(5)");
        assert!(reason.contains("sqrt(5)"), "{reason}");
        assert_eq!(approx, 5f64.sqrt());
        let (reason, approx) = inexact("2/sqrt(5)");
        assert_eq!(reason, "sqrt(5) is irrational");
        assert!(ulps(approx, 2.0 / 5f64.sqrt()) <= 1);
        assert!(is_not_finite("sqrt(-1)").contains("sqrt(-1)"));
        is_not_finite("sqrt(0 - sqrt(2))");
        // The documented limitation: invisible cancellations are not found.
        assert!(inexact("sqrt(2)*sqrt(2)").0.contains("sqrt(2)"));
    }

    #[test]
    fn angles_reduce_in_words_as_in_big_rationals() {
        let big = BigRational::new(BigInt::from(10).pow(30) + 7, BigInt::from(3));
        let mut qs = vec![big.clone(), -big];
        for n in [
            -721,
            -360,
            -181,
            -180,
            -1,
            0,
            1,
            179,
            180,
            181,
            359,
            360,
            10059,
            i64::MAX,
        ] {
            for d in [1, 2, 7, 180, 1_800_000, i64::MAX] {
                qs.push(BigRational::new(n.into(), d.into()));
            }
        }
        for q in qs {
            assert_eq!(
                reduced_radians(&q).to_bits(),
                reduced_radians_big(&q).to_bits(),
                "{q}"
            );
        }
    }

    #[test]
    fn angles() {
        assert_eq!(exact("cos(60 deg)"), q(1, 2));
        assert_eq!(exact("sin(30 deg)"), q(1, 2));
        assert_eq!(exact("sin(-30deg)"), q(-1, 2));
        assert_eq!(exact("cos(720 deg + 120 deg)"), q(-1, 2));
        assert_eq!(exact("tan(135 deg)"), q(-1, 1));
        assert_eq!(exact("sin(pi/6)"), q(1, 2));
        assert_eq!(exact("cos(pi)"), q(-1, 1));
        assert_eq!(exact("sin(0)"), q(0, 1));
        assert_eq!(exact("cos(0)"), q(1, 1));
        assert_eq!(exact("pi/pi"), q(1, 1));
        assert_eq!(exact("0 deg"), q(0, 1));
        let (reason, approx) = inexact("cos(30 deg)");
        assert_eq!(reason, "cos(30 deg) is irrational");
        assert!(ulps(approx, 3f64.sqrt() / 2.0) <= 1, "{approx}");
        assert!(inexact("sin(1)").0.contains("sin(1)"));
        assert!(inexact("pi").0.contains("pi"));
        assert_eq!(inexact("30 deg").1, 30f64.to_radians());
        assert!(inexact("pi + 1").0.contains("pi + 1"));
        is_not_finite("tan(90 deg)");
        is_not_finite("tan(pi/2)");
    }

    #[test]
    fn not_finite() {
        assert!(is_not_finite("1/0").contains("division by zero in '1/0'"));
        assert!(is_not_finite("2*3/(1-1)").contains("2*3/(1-1)"));
        for text in ["nan", "inf", "-inf", "+inf", "NaN"] {
            is_not_finite(text);
        }
        // Beyond f64 but exact: a number (exact mode reads it; f64 mode scales or refuses it).
        for text in ["1e400", "-1e400", "10^400", "1/(1e-400)"] {
            let n = parse_number(text).unwrap();
            assert!(n.exact.is_ok() && n.approx.is_infinite(), "{text}");
        }
        // Beyond f64 and without an exact value: not finite.
        assert!(is_not_finite("sqrt(2)*1e400").contains("overflows"));
        // Intermediate overflow is fine when the exact value is finite.
        assert_eq!(exact("10^400/10^399"), q(10, 1));
        assert_eq!(parse_number("1e-400").map(|n| n.approx), Ok(0.0));
    }

    #[test]
    fn syntax_errors() {
        assert!(is_syntax("3 +").contains("end of input"));
        assert!(is_syntax("").contains("empty"));
        assert!(is_syntax("   ").contains("empty"));
        let foo = is_syntax("foo");
        assert!(
            foo.contains("'foo'") && foo.contains("sqrt") && foo.contains("pi"),
            "{foo}"
        );
        assert!(is_syntax("1 2").contains("position 3"));
        assert!(is_syntax("(1").contains("')'"));
        assert!(is_syntax("1)").contains("position 2"));
        for text in [
            "1_",
            "1__0",
            "_1",
            "1._5",
            "1.2.3",
            "1e",
            "1e+",
            "0x",
            "0xg",
            "0b12",
            "sqrt 4",
            "sqrt()",
            "deg",
            "3pi",
            "2 ** 3",
            "1 $ 2",
            "π",
            "\"1/3\"",
            "--",
            "1 deg deg",
            "nan +",
        ] {
            is_syntax(text);
        }
    }

    #[test]
    fn no_panics_on_odd_inputs() {
        let deep_ok = format!("{}1{}", "(".repeat(150), ")".repeat(150));
        assert_eq!(exact(&deep_ok), q(1, 1));
        let deep = format!("{}1{}", "(".repeat(100_000), ")".repeat(100_000));
        assert!(is_syntax(&deep).contains("nested"));
        is_syntax(&"-".repeat(100_000));
        is_syntax(&"2^".repeat(100_000));
        is_syntax(&"sqrt(".repeat(10_000));
        let long_sum = vec!["1"; 100_000].join("+");
        assert_eq!(exact(&long_sum), q(100_000, 1));
        let long_literal = format!("0.{}1", "0".repeat(3_000));
        assert!(parse_number(&long_literal).is_ok());
        let huge_exponent = format!("1e{}", "9".repeat(100));
        is_not_finite(&huge_exponent);
        assert_eq!(
            parse_number(&format!("1e-{}", "9".repeat(100))).map(|n| n.approx),
            Ok(0.0)
        );
        let (reason, approx) = inexact("(1/2)^(3^20) + 1");
        assert!(reason.contains("bits"), "{reason}");
        assert_eq!(approx, 1.0);
        is_not_finite("2^(3^20) * 0"); // no exact value, and inf in f64
        for text in [
            "2^2^2^2^2",
            "(1/3)^(1/12345678901)",
            "7^(2^40)",
            "0.5^(-0.5)",
            "é",
            "1 é",
        ] {
            let _ = parse_number(text);
        }
    }

    fn with(text: &str, symbols: &[&str]) -> Result<Number, NumberError> {
        let symbols: Vec<String> = symbols.iter().map(|s| s.to_string()).collect();
        parse_number_with(text, &symbols)
    }

    #[test]
    fn declared_symbols() {
        let n = with(" m*g/2 ", &["m", "g", "k1"]).unwrap();
        assert_eq!(n.text, "m*g/2");
        assert_eq!(n.exact, Err("m*g/2 names the symbols g, m".to_string()));
        assert!(n.approx.is_nan());
        assert_eq!(n.symbols, ["g", "m"]);
        let n = with("cos(theta)*sqrt(k1) + theta", &["theta", "k1"]).unwrap();
        assert_eq!(
            n.exact,
            Err("cos(theta)*sqrt(k1) + theta names the symbols k1, theta".to_string())
        );
        assert_eq!(n.symbols, ["k1", "theta"]);
        assert_eq!(
            with("-m deg", &["m"]).unwrap().exact,
            Err("-m deg names the symbol m".to_string())
        );
        // Ordinary numbers are unaffected by declarations.
        let n = with("1/3", &["m"]).unwrap();
        assert_eq!((n.exact, n.symbols), (Ok(q(1, 3)), Vec::new()));
        assert_eq!(parse_number("0.1").unwrap().symbols, Vec::<String>::new());
        // The rational parts are still checked.
        for text in [
            "m/0",
            "m + 1/0",
            "m*inf",
            "sqrt(-1)*m",
            "m^(0^-1)",
            "m*1e99999",
        ] {
            assert!(
                matches!(with(text, &["m"]), Err(NumberError::NotFinite { .. })),
                "{text}"
            );
        }
        // Undeclared names: the usual syntax error, which also lists the declared symbols.
        let reason = |text: &str, symbols: &[&str]| match with(text, symbols) {
            Err(NumberError::Syntax { reason, .. }) => reason,
            other => panic!("{text}: expected a syntax error, got {other:?}"),
        };
        assert_eq!(
            reason("2*m", &[]),
            "unknown name 'm' at position 3 (known names: pi, deg, sqrt, sin, cos, tan)"
        );
        assert_eq!(reason("2*m", &[]), is_syntax("2*m"));
        assert_eq!(
            reason("m + w", &["m", "k1", "m", "not a name"]),
            "unknown name 'w' at position 5 (known names: pi, deg, sqrt, sin, cos, tan; \
             declared symbols: k1, m)"
        );
        // Syntax errors come first.
        assert!(reason("m +", &["m"]).contains("end of input"));
        assert!(reason("1/0 + w", &["m"]).contains("unknown name 'w'"));
        // Reserved names stay what they are even when declared.
        assert_eq!(with("pi/pi", &["pi"]).unwrap().exact, Ok(q(1, 1)));
    }

    #[test]
    fn formatting() {
        assert_eq!(format_rational(&q(-6, 8)), "-3/4");
        assert_eq!(format_rational(&q(5, 1)), "5");
        assert_eq!(format_surd(&q(1, 1), &q(17, 1)), "sqrt(17)");
        assert_eq!(format_surd(&q(-1, 1), &q(17, 1)), "-sqrt(17)");
        assert_eq!(format_surd(&q(3, 17), &q(17, 1)), "3/17*sqrt(17)");
        assert_eq!(format_surd(&q(1, 1), &q(12, 1)), "2*sqrt(3)");
        assert_eq!(format_surd(&q(-1, 1), &q(12, 1)), "-2*sqrt(3)");
        assert_eq!(format_surd(&q(1, 1), &q(1, 2)), "1/2*sqrt(2)");
        assert_eq!(format_surd(&q(2, 1), &q(9, 4)), "3");
        assert_eq!(format_surd(&q(0, 1), &q(5, 1)), "0");
        assert_eq!(format_surd(&q(5, 1), &q(0, 1)), "0");
        assert_eq!(canonical_surd(&q(0, 1), &q(5, 1)), (q(0, 1), q(1, 1)));
        assert_eq!(canonical_surd(&q(6, 1), &q(3, 31)), (q(6, 31), q(93, 1)));
        // A square of a prime above the trial-division bound is still found.
        let p = BigInt::from(1_000_003);
        let r = BigRational::from_integer(&p * &p * 7);
        assert_eq!(
            canonical_surd(&q(1, 1), &r),
            (BigRational::from_integer(p), q(7, 1))
        );
    }

    #[test]
    fn conversions() {
        let big = BigInt::from(10).pow(400);
        assert_eq!(
            rational_to_f64(&BigRational::new(&big + 1, big.clone())),
            1.0
        );
        assert_eq!(
            rational_to_f64(&BigRational::new(big.clone(), &big * 3)),
            1.0 / 3.0
        );
        assert_eq!(rational_to_f64(&q(1, 3)), 1.0 / 3.0);
        assert_eq!(rational_to_f64(&q(-7, 2)), -3.5);
        assert_eq!(
            rational_to_f64(&BigRational::from_integer(big.clone())),
            f64::INFINITY
        );
        assert_eq!(
            rational_to_f64(&BigRational::new(BigInt::from(1), big)),
            0.0
        );
        // Ties to even, and subnormals.
        let two = BigInt::from(2);
        let tie = BigRational::from_integer(two.pow(53) + 1);
        assert_eq!(rational_to_f64(&tie), 2f64.powi(53));
        let tiny = BigRational::new(BigInt::from(3), two.pow(1075));
        assert_eq!(rational_to_f64(&tiny), f64::from_bits(2));
        let max = BigRational::from_integer(
            BigInt::from(f64::MAX.to_bits() & ((1 << 52) - 1) | 1 << 52) * two.pow(971),
        );
        assert_eq!(rational_to_f64(&max), f64::MAX);
        for (n, d) in [(1, 10), (2, 3), (123456789, 1000), (-5, 7), (1, 1 << 40)] {
            assert_eq!(rational_to_f64(&q(n, d)), n as f64 / d as f64);
        }
        assert!(ulps(surd_to_f64(&q(3, 1), &q(2, 1)), 3.0 * 2f64.sqrt()) <= 1);
        assert!(ulps(surd_to_f64(&q(3, 17), &q(17, 1)), 3.0 / 17f64.sqrt()) <= 1);
        let huge = BigRational::from_integer(BigInt::from(10).pow(600));
        assert_eq!(surd_to_f64(&q(1, 1), &huge), 1e300);
        assert_eq!(surd_to_f64(&q(0, 1), &q(-1, 1)), 0.0);
        assert!(surd_to_f64(&q(1, 1), &q(-1, 1)).is_nan());
    }
}
