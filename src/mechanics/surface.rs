//! Body surfaces given as an implicit equation f(x, y, z) = 0, with their symbolic gradient.
//!
//! The paper's §12–13 algorithm takes the body's surface as f(x, y, z) = 0 in the central
//! principal axes Cxyz: a contact then needs only its point A_i, and its outward normal is
//! ∇f(A_i) (eq. 103–104), normalised in eq. 105–107. This module parses f, differentiates it
//! symbolically once, and evaluates f and ∇f in any [`Scalar`]: exactly in rationals (so the
//! gradient at a rational point is exact), in floats otherwise. Normalising (eq. 105–107) needs
//! a square root and is left to the caller, as everywhere in the crate.
//!
//! Grammar: the crate's one expression grammar, parsed by [`crate::number::expr`] (`+ - * / ^ ( )`,
//! TOML literals, `pi`, `X deg`, `sqrt sin cos tan`); its names `x`, `y`, `z` are the variables,
//! any other name is an error. Functions and `deg` apply to constants only; `^` with a base in
//! x, y, z needs a constant integer exponent of magnitude at most 1000 (negative allowed).
//! Every sub-tree free of x, y, z is evaluated as a scene number (as [`parse_number`] would
//! read its text), so it is exact or irrational exactly as a scene number would be.
//! Limitation: constants in separate operands are not combined symbolically, so in `x + pi - pi`
//! the two `pi` stay irrational and exact evaluation refuses them.
//!
//! [`parse_number`]: crate::number::parse_number

use std::fmt;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::number::expr::{self, Kind, Node, Op, Wording, char_pos};
use crate::number::{self, format_rational};
use crate::scalar::Scalar;
/// Largest magnitude of an integer exponent on an expression in x, y, z.
const MAX_EXPONENT: i64 = 1000;
/// Largest size (in tree nodes copied) of one partial derivative; beyond it the expression is
/// refused rather than differentiated (a product of n factors has a derivative of about n² nodes).
const MAX_DERIVATIVE_NODES: usize = 200_000;
/// Exact powers whose result would be wider than this many bits are refused at evaluation,
/// so that nested powers such as `((x^2+1)^2+1)^2…` cannot exhaust time or memory.
const MAX_EXACT_BITS: u64 = 1 << 16;
/// Quoted sub-expressions longer than this are shortened in messages.
const MAX_QUOTE_CHARS: usize = 60;
/// Names the grammar knows, listed in the error for an unknown name.
const KNOWN_NAMES: &str = "x, y, z, pi, deg, sqrt, sin, cos, tan";
/// The variables, by index.
const VARIABLES: [&str; 3] = ["x", "y", "z"];
/// Syntax messages of surfaces.
const WORDING: Wording = Wording {
    input: "expression",
    operand: "a number, x, y, z, 'pi', a function or '('",
};

/// An implicit surface f(x, y, z) = 0 with its symbolic gradient.
///
/// The gradient ∇f = [∂f/∂x, ∂f/∂y, ∂f/∂z] is the (unnormalised) outward normal of eq. 103–104
/// when f grows outwards (f < 0 inside the body).
#[derive(Clone, Debug)]
pub struct Surface {
    /// The source text, trimmed.
    text: String,
    /// f.
    f: Expr,
    /// ∂f/∂x, ∂f/∂y, ∂f/∂z.
    gradient: [Expr; 3],
}

/// Why a surface could not be read or evaluated: what went wrong, and where (1-based character
/// position in the expression, or the point of evaluation).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{message}")]
pub struct SurfaceError {
    /// The full message.
    pub message: String,
}

impl SurfaceError {
    fn new(message: String) -> Self {
        SurfaceError { message }
    }
}

impl Surface {
    /// Parse f(x, y, z) and differentiate it symbolically.
    ///
    /// # Errors
    /// Text outside the grammar, unknown names, nesting deeper than 200 levels, functions, `deg`
    /// or exponents applied to x, y, z, a non-integer exponent on an expression in x, y, z,
    /// constants that are not finite (`1/0`, `sqrt(-1)`), an expression free of x, y and z, and
    /// derivatives too large to build. The message says what and at which character position.
    pub fn parse(text: &str) -> Result<Surface, SurfaceError> {
        Surface::parse_with(text, &[])
    }

    /// As [`Surface::parse`], with names in `symbols` allowed as symbolic constants
    /// (`x^2 + y^2 + z^2 - R^2` with R declared): such a surface evaluates only in the
    /// symbolic scalar (`inertance derive`).
    pub fn parse_with(text: &str, symbols: &[String]) -> Result<Surface, SurfaceError> {
        let trimmed = text.trim();
        let fail = |reason: String| {
            SurfaceError::new(format!(
                "cannot read surface '{}': {reason}",
                quote(trimmed)
            ))
        };
        let root = expr::parse(text, &WORDING).map_err(fail)?;
        let declared = |n: &Node| match &n.kind {
            Kind::Name(name) => symbols.iter().any(|s| s.as_str() == &**name),
            _ => false,
        };
        let unknown = root
            .names()
            .into_iter()
            .find(|n| variable(n).is_none() && !declared(n));
        if let Some(node) = unknown {
            return Err(fail(expr::unknown_name(text, node, KNOWN_NAMES)));
        }
        // Every name is now a variable or a declared symbol.
        if !has_variable(&root) {
            return Err(fail(
                "the expression does not contain x, y or z".to_string(),
            ));
        }
        let f = Builder { src: text }.build(&root).map_err(fail)?;
        Surface::with_gradient(trimmed.to_string(), f).map_err(fail)
    }

    /// f and its symbolic gradient.
    fn with_gradient(text: String, f: Expr) -> Result<Surface, String> {
        let mut gradient = [zero(), zero(), zero()];
        for (var, slot) in gradient.iter_mut().enumerate() {
            let mut deriver = Deriver {
                var,
                budget: MAX_DERIVATIVE_NODES,
            };
            *slot = deriver.derive(&f).map_err(|()| {
                format!(
                    "∂f/∂{} has more than {MAX_DERIVATIVE_NODES} nodes; simplify the expression",
                    VARIABLES[var]
                )
            })?;
        }
        Ok(Surface { text, f, gradient })
    }

    /// The surface in a length unit of 2^b: f′(x′, y′, z′) = f(2^b x′, 2^b y′, 2^b z′), so that
    /// f′(p/2^b) = f(p) exactly and ∇f′ = 2^b ∇f (the same direction). The powers of two are
    /// folded into the rational coefficients wherever a product or a power allows
    /// (`x^2/10^600` becomes `2^(2b)/10^600 · x^2`, exactly), so that a surface whose
    /// coefficients f64 cannot hold in metres is evaluated in a unit where it can. Its text
    /// stays as written.
    ///
    /// # Errors
    /// When a derivative of f′ exceeds the size limit of [`Surface::parse`].
    pub fn scaled(&self, b: i64) -> Result<Surface, SurfaceError> {
        let two = BigRational::from_integer(BigInt::from(2));
        let factor = if b >= 0 {
            num_traits::pow(two, b.unsigned_abs() as usize)
        } else {
            num_traits::pow(two, b.unsigned_abs() as usize).recip()
        };
        Surface::with_gradient(self.text.clone(), rescaled(&self.f, &factor))
            .map_err(SurfaceError::new)
    }

    /// The source text.
    pub fn text(&self) -> &str {
        &self.text
    }

    /// f at p, in T.
    ///
    /// # Errors
    /// When a constant of the expression has no value in T (an irrational constant in exact
    /// mode: the message names it, e.g. "sqrt(3)"), on division by zero at p, and when a float
    /// result is not finite.
    pub fn value<T: Scalar>(&self, p: &[T; 3]) -> Result<T, SurfaceError> {
        evaluate(&self.f, p).map_err(|reason| self.eval_error("f", p, reason))
    }

    /// ∇f at p (eq. 103–104), in T; the same errors as [`Surface::value`].
    ///
    /// Constants that differentiation removes do not matter: the gradient of
    /// `x^2 + y^2 - sqrt(2)` is exact at rational points although f itself is not.
    pub fn gradient<T: Scalar>(&self, p: &[T; 3]) -> Result<[T; 3], SurfaceError> {
        let [gx, gy, gz] = &self.gradient;
        let one = |var: usize, e: &Expr| {
            evaluate(e, p)
                .map_err(|reason| self.eval_error(&format!("∂f/∂{}", VARIABLES[var]), p, reason))
        };
        Ok([one(0, gx)?, one(1, gy)?, one(2, gz)?])
    }

    /// The partial derivatives as readable text in the input grammar, e.g.
    /// `["2*x", "1/2*y", "2/9*z"]` for `x^2/1 + y^2/4 + z^2/9 - 1` (for reports and docs).
    pub fn gradient_text(&self) -> [String; 3] {
        let [gx, gy, gz] = &self.gradient;
        [gx.to_string(), gy.to_string(), gz.to_string()]
    }

    fn eval_error<T: Scalar>(&self, what: &str, p: &[T; 3], reason: String) -> SurfaceError {
        SurfaceError::new(format!(
            "cannot evaluate {what} of surface '{}' at (x, y, z) = ({}, {}, {}) in {}: {reason}",
            quote(&self.text),
            scalar_text(&p[0]),
            scalar_text(&p[1]),
            scalar_text(&p[2]),
            T::NAME
        ))
    }
}

/// A text for messages, shortened when long.
fn quote(s: &str) -> String {
    if s.chars().count() <= MAX_QUOTE_CHARS {
        s.to_string()
    } else {
        let head: String = s.chars().take(MAX_QUOTE_CHARS - 1).collect();
        format!("{head}…")
    }
}

fn scalar_text<T: Scalar>(v: &T) -> String {
    match v.to_rational() {
        Some(q) => format_rational(&q),
        None => v.to_f64().to_string(),
    }
}

// ---------------------------------------------------------------------------------------------
// Expressions: the symbolic form of f and its derivatives, kept trivially simplified by the
// constructors `sum`, `product` and `power` (rational constants folded, 0 and 1 removed).

/// A constant without a rational value, e.g. `sqrt(2)`: its text, its f64 value, and why it is
/// not rational.
#[derive(Clone, Debug)]
struct Irrational {
    text: String,
    approx: f64,
    reason: String,
    /// Declared symbols it names (then it has a value only in the symbolic scalar).
    symbols: Vec<String>,
}

#[derive(Clone, Debug)]
enum Expr {
    Rational(BigRational),
    Irrational(Box<Irrational>),
    Var(usize),
    /// Σ terms; at most one rational term, and then it is the last.
    Sum(Vec<Expr>),
    /// coefficient × Π factors; no factor is rational or a product, the coefficient is not 0.
    Product(BigRational, Vec<Expr>),
    /// base^n with n ∉ {0, 1}; a negative n is a division.
    Pow(Box<Expr>, i64),
}

fn zero() -> Expr {
    Expr::Rational(BigRational::zero())
}

fn rational(n: i64) -> BigRational {
    BigRational::from_integer(BigInt::from(n))
}

impl Expr {
    fn is_zero(&self) -> bool {
        matches!(self, Expr::Rational(q) if q.is_zero())
    }

    /// Number of nodes, the unit of the derivative budget.
    fn size(&self) -> usize {
        match self {
            Expr::Rational(_) | Expr::Irrational(_) | Expr::Var(_) => 1,
            Expr::Sum(terms) | Expr::Product(_, terms) => {
                1 + terms.iter().map(Expr::size).sum::<usize>()
            }
            Expr::Pow(base, _) => 1 + base.size(),
        }
    }
}

/// Σ terms, flattened, with the rational terms folded into one (placed last).
fn sum(terms: Vec<Expr>) -> Expr {
    let mut constant = BigRational::zero();
    let mut out = Vec::with_capacity(terms.len());
    let mut add = |t: Expr, out: &mut Vec<Expr>| match t {
        Expr::Rational(q) => constant += q,
        t => out.push(t),
    };
    for t in terms {
        match t {
            Expr::Sum(inner) => inner.into_iter().for_each(|u| add(u, &mut out)),
            t => add(t, &mut out),
        }
    }
    if !constant.is_zero() {
        out.push(Expr::Rational(constant));
    }
    match out.len() {
        0 => zero(),
        1 => out.pop().unwrap_or_else(zero),
        _ => Expr::Sum(out),
    }
}

/// coefficient × Π factors, flattened, with the rational factors folded into the coefficient.
fn product(coefficient: BigRational, factors: Vec<Expr>) -> Expr {
    let mut c = coefficient;
    let mut out = Vec::with_capacity(factors.len());
    for f in factors {
        match f {
            Expr::Rational(q) => c *= q,
            Expr::Product(k, inner) => {
                c *= k;
                out.extend(inner);
            }
            f => out.push(f),
        }
    }
    if c.is_zero() || out.is_empty() {
        return Expr::Rational(c);
    }
    if c.is_one() && out.len() == 1 {
        return out.pop().unwrap_or_else(zero);
    }
    Expr::Product(c, out)
}

/// base^n, folded when n is 0 or 1 or the base is a rational (except 0 to a negative power,
/// kept so that evaluation reports the division by zero).
fn power(base: Expr, n: i64) -> Expr {
    match (base, n) {
        (_, 0) => Expr::Rational(BigRational::one()),
        (base, 1) => base,
        (Expr::Rational(q), n) if !(q.is_zero() && n < 0) && i32::try_from(n).is_ok() => {
            Expr::Rational(q.pow(n as i32))
        }
        (base, n) => Expr::Pow(Box::new(base), n),
    }
}

/// e with every variable v replaced by `factor`·v, the factor folded through products and
/// integer powers into the rational coefficients ((c·v)^n = c^n·v^n).
fn rescaled(e: &Expr, factor: &BigRational) -> Expr {
    match e {
        Expr::Rational(_) | Expr::Irrational(_) => e.clone(),
        Expr::Var(_) => product(factor.clone(), vec![e.clone()]),
        Expr::Sum(terms) => sum(terms.iter().map(|t| rescaled(t, factor)).collect()),
        Expr::Product(c, factors) => product(
            c.clone(),
            factors.iter().map(|f| rescaled(f, factor)).collect(),
        ),
        Expr::Pow(base, n) => match (rescaled(base, factor), i32::try_from(*n)) {
            (Expr::Product(c, factors), Ok(k)) => product(
                c.pow(k),
                vec![power(product(BigRational::one(), factors), *n)],
            ),
            (b, _) => power(b, *n),
        },
    }
}

/// Whether x, y or z occurs in the sub-tree.
fn has_variable(node: &Node) -> bool {
    node.has_name && node.names().into_iter().any(|n| variable(n).is_some())
}

/// The index of the variable a name node stands for.
fn variable(node: &Node) -> Option<usize> {
    match &node.kind {
        Kind::Name(name) => VARIABLES.iter().position(|v| **v == **name),
        _ => None,
    }
}

/// Turns the syntax tree (every name in it a variable) into an [`Expr`], evaluating
/// sub-trees free of x, y, z as scene numbers.
struct Builder<'a> {
    src: &'a str,
}

impl Builder<'_> {
    fn text(&self, start: usize, end: usize) -> &str {
        self.src.get(start..end).unwrap_or_default()
    }

    fn at(&self, node: &Node) -> String {
        format!(
            "'{}' at position {}",
            quote(self.text(node.start, node.end)),
            char_pos(self.src, node.start)
        )
    }

    /// A sub-tree free of x, y, z.
    fn constant(&self, node: &Node) -> Result<Expr, String> {
        match number::evaluate(self.src, node) {
            Ok(n) => Ok(match n.exact {
                Ok(q) => Expr::Rational(q),
                Err(reason) => Expr::Irrational(Box::new(Irrational {
                    text: n.text,
                    approx: n.approx,
                    reason,
                    symbols: n.symbols,
                })),
            }),
            Err(e) => Err(format!(
                "the constant at position {} has no value: {e}",
                char_pos(self.src, node.start)
            )),
        }
    }

    fn build(&self, node: &Node) -> Result<Expr, String> {
        if !has_variable(node) {
            return self.constant(node);
        }
        match &node.kind {
            Kind::Lit(_) | Kind::Pi | Kind::NonFinite => self.constant(node),
            Kind::Name(_) => variable(node)
                .map(Expr::Var)
                .ok_or_else(|| expr::unknown_name(self.src, node, KNOWN_NAMES)),
            Kind::Neg(inner) => self.build(inner).map(|e| product(rational(-1), vec![e])),
            Kind::Chain(first, rest) => self.chain(node.start, first, rest),
            Kind::Pow(base, exp) => {
                if has_variable(exp) {
                    return Err(format!(
                        "an exponent in x, y, z is not supported: {}",
                        self.at(node)
                    ));
                }
                let n = self.integer_exponent(node, exp)?;
                self.build(base).map(|b| power(b, n))
            }
            Kind::Deg(_) => Err(format!(
                "'deg' of an expression in x, y, z is not supported: {}",
                self.at(node)
            )),
            Kind::Call(func, _) => Err(format!(
                "{} of an expression in x, y, z is not supported: {}",
                func.name(),
                self.at(node)
            )),
        }
    }

    fn chain(&self, start: usize, first: &Node, rest: &[(Op, Node)]) -> Result<Expr, String> {
        let additive = rest
            .first()
            .is_some_and(|(op, _)| matches!(op, Op::Add | Op::Sub));
        let mut items = Vec::with_capacity(rest.len() + 1);
        items.push(self.build(first)?);
        for (op, rhs) in rest {
            let item = match op {
                Op::Sub => product(rational(-1), vec![self.build(rhs)?]),
                Op::Div if !has_variable(rhs) => match self.constant(rhs)? {
                    Expr::Rational(q) if q.is_zero() => {
                        return Err(format!(
                            "division by zero in '{}' at position {}",
                            quote(self.text(start, rhs.end)),
                            char_pos(self.src, rhs.start)
                        ));
                    }
                    Expr::Rational(q) => Expr::Rational(q.recip()),
                    c => Expr::Pow(Box::new(c), -1),
                },
                Op::Div => power(self.build(rhs)?, -1),
                Op::Add | Op::Mul => self.build(rhs)?,
            };
            items.push(item);
        }
        Ok(if additive {
            sum(items)
        } else {
            product(BigRational::one(), items)
        })
    }

    fn integer_exponent(&self, node: &Node, exp: &Node) -> Result<i64, String> {
        let n = match self.constant(exp)? {
            Expr::Rational(q) if q.is_integer() => q.to_integer().to_i64(),
            _ => None,
        };
        n.filter(|n| n.abs() <= MAX_EXPONENT).ok_or_else(|| {
            format!(
                "the exponent of an expression in x, y, z must be an integer constant of \
                 magnitude at most {MAX_EXPONENT}, not '{}': {}",
                quote(self.text(exp.start, exp.end)),
                self.at(node)
            )
        })
    }
}

/// Symbolic ∂/∂(variable `var`), charging every copied node to `budget`.
struct Deriver {
    var: usize,
    budget: usize,
}

impl Deriver {
    fn copy(&mut self, e: &Expr) -> Result<Expr, ()> {
        self.budget = self.budget.checked_sub(e.size()).ok_or(())?;
        Ok(e.clone())
    }

    fn derive(&mut self, e: &Expr) -> Result<Expr, ()> {
        match e {
            Expr::Rational(_) | Expr::Irrational(_) => Ok(zero()),
            Expr::Var(j) => Ok(Expr::Rational(rational(i64::from(*j == self.var)))),
            Expr::Sum(terms) => {
                let mut out = Vec::with_capacity(terms.len());
                for t in terms {
                    out.push(self.derive(t)?);
                }
                Ok(sum(out))
            }
            // Product rule: Σ_i c · f_1 ⋯ f_i' ⋯ f_n.
            Expr::Product(c, factors) => {
                let mut terms = Vec::new();
                for (i, fi) in factors.iter().enumerate() {
                    let di = self.derive(fi)?;
                    if di.is_zero() {
                        continue;
                    }
                    let mut fs = Vec::with_capacity(factors.len());
                    for f in &factors[..i] {
                        fs.push(self.copy(f)?);
                    }
                    fs.push(di);
                    for f in &factors[i + 1..] {
                        fs.push(self.copy(f)?);
                    }
                    terms.push(product(c.clone(), fs));
                }
                Ok(sum(terms))
            }
            // (g^n)' = n g^(n-1) g'.
            Expr::Pow(base, n) => {
                let db = self.derive(base)?;
                if db.is_zero() {
                    return Ok(zero());
                }
                let b = self.copy(base)?;
                Ok(product(rational(*n), vec![power(b, n - 1), db]))
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Evaluation in any scalar type.

fn evaluate<T: Scalar>(e: &Expr, p: &[T; 3]) -> Result<T, String> {
    let v = eval(e, p)?;
    if !T::IS_EXACT && !v.to_f64().is_finite() {
        return Err(format!("the result {} is not finite", v.to_f64()));
    }
    Ok(v)
}

fn eval<T: Scalar>(e: &Expr, p: &[T; 3]) -> Result<T, String> {
    match e {
        Expr::Rational(q) => Ok(T::from_rational(q)),
        Expr::Irrational(c) => T::from_number(&crate::number::Number {
            text: c.text.clone(),
            exact: Err(c.reason.clone()),
            approx: c.approx,
            symbols: c.symbols.clone(),
            tangent: 0.0,
            source: None,
        })
        .map_err(|_| {
            format!(
                "the constant '{}' has no exact value ({}); use a floating-point scalar",
                quote(&c.text),
                c.reason
            )
        }),
        Expr::Var(i) => Ok(p[*i].clone()),
        Expr::Sum(terms) => {
            let mut acc = T::zero();
            for t in terms {
                acc += eval(t, p)?;
            }
            Ok(acc)
        }
        Expr::Product(c, factors) => {
            let mut acc = T::from_rational(c);
            for f in factors {
                acc *= eval(f, p)?;
            }
            Ok(acc)
        }
        Expr::Pow(base, n) => {
            let b = eval(base, p)?;
            let k = n.unsigned_abs();
            if let Some(q) = b.to_rational()
                && q.numer().bits().max(q.denom().bits()).saturating_mul(k) > MAX_EXACT_BITS
            {
                return Err(format!(
                    "'{}'^{n} exceeds {MAX_EXACT_BITS} bits of exact precision",
                    quote(&base.to_string())
                ));
            }
            let r = powu(b, k);
            if *n >= 0 {
                Ok(r)
            } else if r.is_zero() {
                Err(format!(
                    "division by zero: '{}' is 0",
                    quote(&base.to_string())
                ))
            } else {
                Ok(T::one() / r)
            }
        }
    }
}

/// b^k by repeated squaring.
fn powu<T: Scalar>(mut b: T, mut k: u64) -> T {
    let mut r = T::one();
    while k > 0 {
        if k & 1 == 1 {
            r *= &b;
        }
        k >>= 1;
        if k > 0 {
            b = b.clone() * &b;
        }
    }
    r
}

// ---------------------------------------------------------------------------------------------
// Display, in the input grammar (so that the text parses back to the same function).

impl fmt::Display for Expr {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Expr::Sum(terms) => {
                for (k, t) in terms.iter().enumerate() {
                    match (k, t) {
                        (0, t) => write_term(f, t)?,
                        (_, Expr::Rational(q)) if q.is_negative() => {
                            write!(f, " - {}", format_rational(&-q))?;
                        }
                        (_, Expr::Product(c, fs)) if c.is_negative() => {
                            f.write_str(" - ")?;
                            write_product(f, &-c, fs)?;
                        }
                        (_, t) => {
                            f.write_str(" + ")?;
                            write_term(f, t)?;
                        }
                    }
                }
                Ok(())
            }
            t => write_term(f, t),
        }
    }
}

/// An operand of `+` or `-`.
fn write_term(f: &mut fmt::Formatter<'_>, e: &Expr) -> fmt::Result {
    match e {
        Expr::Rational(q) => f.write_str(&format_rational(q)),
        Expr::Product(c, fs) => write_product(f, c, fs),
        Expr::Pow(_, n) if *n < 0 => write_product(f, &BigRational::one(), std::slice::from_ref(e)),
        e => write_factor(f, e),
    }
}

/// An operand of `*` or `/`.
fn write_factor(f: &mut fmt::Formatter<'_>, e: &Expr) -> fmt::Result {
    match e {
        Expr::Var(i) => f.write_str(VARIABLES[*i]),
        Expr::Rational(q) if !q.is_negative() && q.is_integer() => f.write_str(&format_rational(q)),
        Expr::Irrational(c) if is_atomic(&c.text) => f.write_str(&c.text),
        Expr::Pow(base, n) if *n > 0 => write_power(f, base, n.unsigned_abs()),
        e => write!(f, "({e})"),
    }
}

/// base^k for k ≥ 1.
fn write_power(f: &mut fmt::Formatter<'_>, base: &Expr, k: u64) -> fmt::Result {
    match base {
        Expr::Pow(..) => write!(f, "({base})")?,
        base => write_factor(f, base)?,
    }
    if k != 1 {
        write!(f, "^{k}")?;
    }
    Ok(())
}

/// c·Π factors, with the negative powers written as divisions: "-2*x*y^2*z/(z^2 + 1)^2".
fn write_product(f: &mut fmt::Formatter<'_>, c: &BigRational, factors: &[Expr]) -> fmt::Result {
    let is_den = |e: &Expr| matches!(e, Expr::Pow(_, n) if *n < 0);
    let mut numerator = factors.iter().filter(|e| !is_den(e)).peekable();
    if numerator.peek().is_none() {
        f.write_str(&format_rational(c))?;
    } else if (-c).is_one() {
        f.write_str("-")?;
    } else if !c.is_one() {
        write!(f, "{}*", format_rational(c))?;
    }
    for (k, e) in numerator.enumerate() {
        if k > 0 {
            f.write_str("*")?;
        }
        write_factor(f, e)?;
    }
    for e in factors {
        if let Expr::Pow(base, n) = e
            && *n < 0
        {
            f.write_str("/")?;
            write_power(f, base, n.unsigned_abs())?;
        }
    }
    Ok(())
}

/// Whether a constant's text can stand as a factor without parentheses: a name or number,
/// optionally followed by one parenthesised argument, e.g. `pi`, `sqrt(2)`, `cos(30 deg)`.
fn is_atomic(text: &str) -> bool {
    let head = text.trim_start_matches(|c: char| c.is_ascii_alphanumeric() || c == '_' || c == '.');
    if head.is_empty() {
        return !text.is_empty();
    }
    if !(head.starts_with('(') && head.ends_with(')')) || head.len() == text.len() {
        return false;
    }
    // The first '(' must close at the very end.
    let mut depth = 0usize;
    for (i, c) in head.char_indices() {
        match c {
            '(' => depth += 1,
            ')' => {
                depth = depth.saturating_sub(1);
                if depth == 0 {
                    return i + 1 == head.len();
                }
            }
            _ => {}
        }
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::parse_number;
    use crate::scalar::Exact;

    fn q(n: i64, d: i64) -> Exact {
        Exact::new(BigInt::from(n), BigInt::from(d))
    }

    fn surface(text: &str) -> Surface {
        match Surface::parse(text) {
            Ok(s) => s,
            Err(e) => panic!("{text}: {e}"),
        }
    }

    fn error(text: &str) -> String {
        match Surface::parse(text) {
            Err(e) => e.message,
            Ok(s) => panic!("{text}: expected an error, got {s:?}"),
        }
    }

    fn point(p: [(i64, i64); 3]) -> [Exact; 3] {
        p.map(|(n, d)| q(n, d))
    }

    fn point_f64(p: [(i64, i64); 3]) -> [f64; 3] {
        p.map(|(n, d)| n as f64 / d as f64)
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-15 * b.abs().max(1.0)
    }

    #[test]
    fn ellipsoid_exact_and_f64() {
        let s = surface("x^2/1 + y^2/4 + z^2/9 - 1");
        assert_eq!(s.text(), "x^2/1 + y^2/4 + z^2/9 - 1");
        let p = point([(3, 5), (8, 5), (0, 1)]);
        assert_eq!(s.value(&p), Ok(q(0, 1)));
        assert_eq!(s.gradient(&p), Ok([q(6, 5), q(4, 5), q(0, 1)]));
        let pf = point_f64([(3, 5), (8, 5), (0, 1)]);
        let v = s.value(&pf).unwrap();
        assert!(v.abs() <= 1e-15, "{v}");
        let g = s.gradient(&pf).unwrap();
        for (a, b) in g.iter().zip([1.2, 0.8, 0.0]) {
            assert!(close(*a, b), "{g:?}");
        }
        // Another exact point, off the surface, with all three components.
        let p = point([(1, 2), (1, 1), (3, 2)]);
        assert_eq!(s.value(&p), Ok(q(1, 4) + q(1, 4) + q(1, 4) - q(1, 1)));
        assert_eq!(s.gradient(&p), Ok([q(1, 1), q(1, 2), q(1, 3)]));
        assert_eq!(s.gradient_text(), ["2*x", "1/2*y", "2/9*z"]);
    }

    #[test]
    fn sphere() {
        let s = surface("x^2 + y^2 + z^2 - 1/4");
        let p = point([(1, 2), (0, 1), (0, 1)]);
        assert_eq!(s.value(&p), Ok(q(0, 1)));
        assert_eq!(s.gradient(&p), Ok([q(1, 1), q(0, 1), q(0, 1)]));
        let p = point([(3, 10), (2, 5), (0, 1)]);
        assert_eq!(s.value(&p), Ok(q(0, 1)));
        assert_eq!(s.gradient(&p), Ok([q(3, 5), q(4, 5), q(0, 1)]));
        assert_eq!(s.gradient_text(), ["2*x", "2*y", "2*z"]);
        let g = s.gradient(&[0.3f32, 0.4, 0.0]).unwrap();
        assert_eq!(g, [0.6f32, 0.8, 0.0]);
    }

    #[test]
    fn product_and_quotient_rules() {
        // f = x y²/(1+z²) − 3; at (2, 3, 1/2): 1+z² = 5/4,
        // f = 18·4/5 − 3 = 57/5, f_x = y²/(1+z²) = 36/5, f_y = 2xy/(1+z²) = 48/5,
        // f_z = −2xy²z/(1+z²)² = −18·16/25 = −288/25.
        let s = surface("x*y^2/(1+z^2) - 3");
        let p = point([(2, 1), (3, 1), (1, 2)]);
        assert_eq!(s.value(&p), Ok(q(57, 5)));
        assert_eq!(s.gradient(&p), Ok([q(36, 5), q(48, 5), q(-288, 25)]));
        assert_eq!(
            s.gradient_text(),
            ["y^2/(z^2 + 1)", "2*x*y/(z^2 + 1)", "-2*x*y^2*z/(z^2 + 1)^2"]
        );
        let g = s.gradient(&point_f64([(2, 1), (3, 1), (1, 2)])).unwrap();
        for (a, b) in g.iter().zip([7.2, 9.6, -11.52]) {
            assert!(close(*a, b), "{g:?}");
        }
        // Quotient of two variable expressions, and unary minus: f = −x/(y − z).
        // At (1, 3, 1): f = −1/2, f_x = −1/2, f_y = x/(y−z)² = 1/4, f_z = −1/4.
        let s = surface("-x/(y - z)");
        let p = point([(1, 1), (3, 1), (1, 1)]);
        assert_eq!(s.value(&p), Ok(q(-1, 2)));
        assert_eq!(s.gradient(&p), Ok([q(-1, 2), q(1, 4), q(-1, 4)]));
    }

    #[test]
    fn negative_integer_exponent() {
        let s = surface("x^-2 + y - 2");
        let p = point([(1, 1), (1, 1), (0, 1)]);
        assert_eq!(s.value(&p), Ok(q(0, 1)));
        assert_eq!(s.gradient(&p), Ok([q(-2, 1), q(1, 1), q(0, 1)]));
        assert_eq!(s.gradient_text(), ["-2/x^3", "1", "0"]);
        // Constant integer exponents may be written as expressions.
        let s = surface("x^(4/2) + y^sqrt(9) + z^(-(1))");
        let p = point([(3, 1), (2, 1), (2, 1)]);
        assert_eq!(s.value(&p), Ok(q(9 + 8, 1) + q(1, 2)));
        assert_eq!(s.gradient(&p), Ok([q(6, 1), q(12, 1), q(-1, 4)]));
        assert_eq!(s.gradient_text(), ["2*x", "3*y^2", "-1/z^2"]);
    }

    #[test]
    fn irrational_constants() {
        let s = surface("x^2 + y^2 - sqrt(2)");
        let v = s.value(&[1.0f64, 0.5, 0.0]).unwrap();
        assert!(close(v, 1.25 - 2f64.sqrt()), "{v}");
        let e = s.value(&point([(1, 1), (1, 2), (0, 1)])).unwrap_err();
        assert!(e.message.contains("sqrt(2)"), "{e}");
        assert!(e.message.contains("irrational"), "{e}");
        // Differentiation removes the constant, so the gradient stays exact.
        let p = point([(1, 1), (1, 2), (0, 1)]);
        assert_eq!(s.gradient(&p), Ok([q(2, 1), q(1, 1), q(0, 1)]));
        // An irrational factor survives differentiation and is refused in exact mode.
        let s = surface("cos(30 deg)*x^2 + pi*y - z/sqrt(3)");
        assert_eq!(s.gradient_text(), ["2*cos(30 deg)*x", "pi", "-1/sqrt(3)"]);
        let g = s.gradient(&[2.0f64, 0.0, 0.0]).unwrap();
        assert!(close(g[0], 2.0 * 3f64.sqrt()), "{g:?}");
        assert!(close(g[1], std::f64::consts::PI), "{g:?}");
        assert!(close(g[2], -1.0 / 3f64.sqrt()), "{g:?}");
        let e = s.gradient(&point([(1, 1), (0, 1), (0, 1)])).unwrap_err();
        assert!(e.message.contains("cos(30 deg)"), "{e}");
        // Rational constants written as expressions stay exact.
        let s = surface("sin(30 deg)*x + cos(pi)*y + sqrt(9/4)*z");
        let p = point([(1, 1), (1, 1), (1, 1)]);
        assert_eq!(s.value(&p), Ok(q(1, 1)));
        assert_eq!(s.gradient(&p), Ok([q(1, 2), q(-1, 1), q(3, 2)]));
    }

    #[test]
    fn errors_name_the_culprit() {
        let e = error("sqrt(x)");
        assert!(
            e.contains("sqrt of an expression in x, y, z is not supported"),
            "{e}"
        );
        assert!(e.contains("'sqrt(x)' at position 1"), "{e}");
        assert!(error("1 + cos(2*y)").contains("'cos(2*y)' at position 5"));
        assert!(error("x deg").contains("'deg'"));
        let e = error("x^y");
        assert!(
            e.contains("exponent in x, y, z") && e.contains("'x^y'"),
            "{e}"
        );
        assert!(error("2^z + x").contains("'2^z'"));
        let e = error("x^(1/2)");
        assert!(e.contains("integer") && e.contains("'(1/2)'"), "{e}");
        assert!(error("x^pi").contains("integer"));
        assert!(error("x^1001").contains("1000"));
        let e = error("w + 1");
        assert!(e.contains("unknown name 'w' at position 1"), "{e}");
        assert!(error("x + X").contains("unknown name 'X' at position 5"));
        assert!(error("x +").contains("unexpected end of expression"));
        assert!(error("x y").contains("'y' at position 3"));
        assert!(error("(x").contains("')'"));
        assert!(error("x)").contains("position 2"));
        assert!(error("2x").contains("position 2"));
        assert!(error("x + 1__0").contains("position 5"));
        assert!(error("x $ 1").contains("'$' at position 3"));
        assert!(error("x/0").contains("division by zero in 'x/0'"));
        assert!(error("x + 1/0").contains("position 5"));
        assert!(error("x + sqrt(-1)").contains("not finite"));
        assert!(error("x*inf").contains("not finite"));
        assert!(error("1 + 2").contains("does not contain x, y or z"));
        assert!(error("   ").contains("empty"));
        assert!(error("sqrt x").contains("'(' after 'sqrt'"));
        // Nesting: a bomb is refused, not a stack overflow.
        let bomb = format!("{}x{}", "(".repeat(1000), ")".repeat(1000));
        assert!(error(&bomb).contains("nested more than 200"));
        error(&"-".repeat(100_000));
        error(&format!("{}x", "sqrt(".repeat(10_000)));
        error(&"x^".repeat(100_000));
        // Derivatives too large to build are refused.
        let long_product = vec!["x"; 2000].join("*");
        assert!(error(&long_product).contains("nodes"));
    }

    #[test]
    fn deep_but_allowed_nesting() {
        let deep = format!("{}x{}", "(".repeat(190), ")".repeat(190));
        let s = surface(&deep);
        assert_eq!(s.gradient_text(), ["1", "0", "0"]);
        // g_{k+1} = x*(g_k) + 1, 150 levels: derivative built and evaluated without overflow.
        let mut text = "x".to_string();
        for _ in 0..150 {
            text = format!("x*({text}) + 1");
        }
        let s = surface(&text);
        let p = point([(1, 1), (0, 1), (0, 1)]);
        // At x = 1: g_k = k + 1 (g_0 = x = 1), g_k' = g_{k-1} + g_{k-1}' → g_150' = Σ = 1 + Σ_{k=1}^{150} k.
        assert_eq!(s.value(&p), Ok(q(151, 1)));
        assert_eq!(
            s.gradient(&p).map(|g| g[0].clone()),
            Ok(q(1 + 150 * 151 / 2, 1))
        );
        // Nested powers: refused in exact arithmetic rather than computed for ever; inf in f64.
        let mut text = "x".to_string();
        for _ in 0..40 {
            text = format!("({text})^2 + 1");
        }
        let s = surface(&text);
        let e = s.value(&point([(2, 1), (0, 1), (0, 1)])).unwrap_err();
        assert!(e.message.contains("bits"), "{e}");
        assert!(s.gradient(&[2.0f64, 0.0, 0.0]).is_err());
        // The same shape, shallow: at x = 0 the levels are 1, 2, 5, 26, 677.
        let s = surface("((((x^2 + 1)^2 + 1)^2 + 1)^2 + 1)^2 + 1");
        assert_eq!(s.value(&point([(0, 1), (0, 1), (0, 1)])), Ok(q(677, 1)));
        let long_sum = vec!["x"; 100_000].join("+");
        let s = surface(&long_sum);
        assert_eq!(s.gradient_text(), ["100000", "0", "0"]);
    }

    #[test]
    fn nesting_at_the_limit_fits_the_stack() {
        // Parse, differentiate, evaluate and print at close to 200 levels (debug build, test thread).
        let mut shapes = Vec::new();
        let (mut a, mut b, mut c) = ("x".to_string(), "y".to_string(), "z".to_string());
        for k in 0..195 {
            a = format!("x*({a}) + 1");
            c = format!("1/({c} + 1)");
            if k < 95 {
                // Two levels each: the sign and the parenthesis.
                b = format!("-({b})^2");
            }
        }
        shapes.extend([a, b, c]);
        for text in &shapes {
            let s = surface(text);
            let p = point([(1, 1), (1, 1), (1, 1)]);
            assert!(s.value(&p).is_ok(), "{}", quote(text));
            assert!(s.gradient(&p).is_ok(), "{}", quote(text));
            assert!(s.gradient_text().iter().all(|t| !t.is_empty()));
        }
    }

    #[test]
    fn division_by_zero_at_a_point() {
        let s = surface("1/x + y");
        let e = s.value(&point([(0, 1), (1, 1), (0, 1)])).unwrap_err();
        assert!(e.message.contains("division by zero"), "{e}");
        assert!(e.message.contains("(x, y, z) = (0, 1, 0)"), "{e}");
        assert!(s.gradient(&[0.0f64, 1.0, 0.0]).is_err());
        assert_eq!(s.gradient_text(), ["-1/x^2", "1", "0"]);
        let s = surface("x/(y - z)");
        assert!(s.value(&[1.0f64, 2.0, 2.0]).is_err());
        assert_eq!(s.value(&[1.0f64, 2.0, 1.5]), Ok(2.0));
    }

    #[test]
    fn gradient_text_parses_back() {
        for text in [
            "x^2/1 + y^2/4 + z^2/9 - 1",
            "x*y^2/(1+z^2) - 3",
            "-(x - 2*y)^3 + x/(y*z) - 1/2*z^-2",
            "(x + y)^2*(y - z)^-1 - pi*x*z",
            "x*sqrt(2)/3 - y/(-z+1) + 0*x + 1*y",
        ] {
            let s = surface(text);
            let p = [0.7f64, -1.3, 0.45];
            let g = s.gradient(&p).unwrap();
            for (k, t) in s.gradient_text().iter().enumerate() {
                // A constant derivative has no x, y, z: compare it as a number.
                let back = match Surface::parse(t) {
                    Ok(b) => b.value(&p).unwrap(),
                    Err(_) => parse_number(t).unwrap().approx,
                };
                assert!(
                    (back - g[k]).abs() <= 1e-12 * g[k].abs().max(1.0),
                    "{text}: ∂{k} = {t}: {back} vs {}",
                    g[k]
                );
            }
        }
    }

    #[test]
    fn atomic_constant_texts() {
        assert!(is_atomic("pi"));
        assert!(is_atomic("sqrt(2)"));
        assert!(is_atomic("cos(30 deg)"));
        assert!(!is_atomic("sqrt(2)*sqrt(3)"));
        assert!(!is_atomic("(1)+(2)"));
        assert!(!is_atomic("-sqrt(2)"));
        assert!(!is_atomic("30 deg"));
        assert!(!is_atomic(""));
    }
}
