//! The expression grammar of the crate: one lexer and one parser, producing a syntax tree that
//! every evaluator shares.
//!
//! ```text
//! expr    := term (('+' | '-') term)*          flat chains, left-associative
//! term    := product ('deg' (('*' | '/') unary)*)?
//! product := unary (('*' | '/') unary)*
//! unary   := ('-' | '+') unary | power
//! power   := atom ('^' unary)?                 right-associative: 2^3^2 = 2^9
//! atom    := literal | 'pi' | name | func '(' expr ')' | '(' expr ')'
//! func    := 'sqrt' | 'sin' | 'cos' | 'tan'
//! ```
//!
//! **`deg` is a unit, and binds loosest of the products**: it multiplies the whole product or
//! quotient before it by π/180, so `80/3 deg` is (80/3)·π/180 — as a reader means it, never
//! 80/(3 deg) — `-45 deg` is −π/4, `2*15 deg` is π/6 and `2^3 deg` is 8°. A product may go on
//! after it (`30 deg / 2` is 15°); since `deg` is a factor, where it stands in a product does not
//! change the value. It takes one unit per product (`30 deg * 2 deg` is refused, with the fix:
//! parentheses) and binds tighter than `+` and `-`: `30 deg + 1` is π/6 + 1 (radians). Table of
//! precedence, loosest first: `+ -`; `deg`; `* /`; unary `- +`; `^`; calls and parentheses.
//!
//! Literals are TOML numbers (`0.1`, `1_000.5`, `-3e-2`, `0x10`, `0o17`, `0b101`), read
//! exactly. `nan`, `inf` and `infinity` (any case) are names that are never finite. Any other
//! name (an ASCII letter or `_`, then letters, digits or `_`: `m`, `Jz`, `k1`, `omega0`) is a
//! [`Kind::Name`] for the evaluator to resolve. The evaluators:
//!
//! * [`crate::number::parse_number`]: exact rationals (tracking rational multiples of pi) and
//!   f64; no names, or with [`crate::number::parse_number_with`] declared symbols, which leave
//!   the number without a value.
//! * [`crate::scalar::symbolic::symbolic`]: exact values in [`crate::scalar::symbolic::RatFun`]: declared names are symbols,
//!   `sqrt` of rational constants is an exact radical, sin/cos/tan take multiples of 15° or a
//!   bare declared angle.
//! * [`crate::mechanics::surface::Surface::parse`]: f(x, y, z); the names x, y, z are its variables.
//!
//! Nesting deeper than [`MAX_DEPTH`] is a syntax error, so no input overflows the stack; every
//! node carries its byte range, to quote sub-expressions in messages; syntax errors give
//! 1-based character positions.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Zero;

use super::rational::rational_to_f64;

/// Deeper nesting (signs, parentheses, powers, calls) is refused so that no input can overflow
/// the stack.
pub const MAX_DEPTH: usize = 200;
/// Decimal exponents beyond this are not read exactly ([`Lit::exact`] is `None`).
pub const MAX_DECIMAL_EXPONENT: i64 = 5_000;
/// The names the grammar reserves (besides `nan`, `inf`, `infinity` in any case).
pub const RESERVED_NAMES: [&str; 6] = ["pi", "deg", "sqrt", "sin", "cos", "tan"];

/// A numeric literal: its exact value (`None` when its decimal exponent is beyond
/// ±[`MAX_DECIMAL_EXPONENT`]) and its correctly rounded f64 value.
#[derive(Debug, Clone, PartialEq)]
pub struct Lit {
    /// The exact value.
    pub exact: Option<BigRational>,
    /// The f64 value (saturating to ±inf or 0 for huge exponents).
    pub approx: f64,
}

/// A function of the grammar.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Func {
    /// `sqrt`.
    Sqrt,
    /// `sin` (radians).
    Sin,
    /// `cos` (radians).
    Cos,
    /// `tan` (radians).
    Tan,
}

impl Func {
    /// The name as written.
    pub fn name(self) -> &'static str {
        match self {
            Func::Sqrt => "sqrt",
            Func::Sin => "sin",
            Func::Cos => "cos",
            Func::Tan => "tan",
        }
    }
}

/// A binary operator of a chain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    /// `+`.
    Add,
    /// `-`.
    Sub,
    /// `*`.
    Mul,
    /// `/`.
    Div,
}

/// What a [`Node`] is.
#[derive(Debug)]
pub enum Kind {
    /// A numeric literal.
    Lit(Box<Lit>),
    /// `pi`.
    Pi,
    /// `nan`, `inf` or `infinity` (any case): well formed, never finite.
    NonFinite,
    /// Any other name, e.g. `m`, `theta`, `x`.
    Name(Box<str>),
    /// `-e`.
    Neg(Box<Node>),
    /// `first (op rhs)*`, the ops all from `+ -` or all from `* /`, left-associative.
    Chain(Box<Node>, Vec<(Op, Node)>),
    /// `base ^ exponent`.
    Pow(Box<Node>, Box<Node>),
    /// `e deg`.
    Deg(Box<Node>),
    /// `func(e)`.
    Call(Func, Box<Node>),
}

/// A node of the syntax tree.
#[derive(Debug)]
pub struct Node {
    /// Start of its byte range in the source (for a parenthesised node, the '(').
    pub start: usize,
    /// End of its byte range in the source.
    pub end: usize,
    /// Whether a [`Kind::Name`] occurs in it.
    pub has_name: bool,
    /// What it is.
    pub kind: Kind,
}

impl Node {
    /// The [`Kind::Name`] nodes in it, in source order.
    pub fn names(&self) -> Vec<&Node> {
        let mut out = Vec::new();
        self.collect_names(&mut out);
        out
    }

    fn collect_names<'a>(&'a self, out: &mut Vec<&'a Node>) {
        if !self.has_name {
            return;
        }
        match &self.kind {
            Kind::Name(_) => out.push(self),
            Kind::Lit(_) | Kind::Pi | Kind::NonFinite => {}
            Kind::Neg(e) | Kind::Deg(e) | Kind::Call(_, e) => e.collect_names(out),
            Kind::Chain(first, rest) => {
                first.collect_names(out);
                for (_, e) in rest {
                    e.collect_names(out);
                }
            }
            Kind::Pow(base, exp) => {
                base.collect_names(out);
                exp.collect_names(out);
            }
        }
    }
}

/// How syntax messages call the input and what may start an operand, e.g. "input" and
/// "a number, 'pi', a function or '('".
#[derive(Debug, Clone, Copy)]
pub struct Wording {
    /// The input as a whole: "unexpected end of {input}", "empty {input}".
    pub input: &'static str,
    /// What an operand may be: "unexpected ')' at position 3, expected {operand}".
    pub operand: &'static str,
}

/// Parse `src` (positions in messages count from its first character; outer whitespace is
/// allowed).
///
/// # Errors
/// The reason, with its 1-based character position: an empty input, a malformed literal, an
/// unexpected character or token, a missing ')', nesting deeper than [`MAX_DEPTH`].
pub fn parse(src: &str, wording: &Wording) -> Result<Node, String> {
    parse_measured(src, wording).map(|(root, _)| root)
}

/// [`parse`], with the deepest nesting the parse reached (at most [`MAX_DEPTH`]): a text read
/// again with a parenthesised text in place of a name nests at most the two depths added.
pub(crate) fn parse_measured(src: &str, wording: &Wording) -> Result<(Node, usize), String> {
    if src.trim().is_empty() {
        return Err(format!("empty {}", wording.input));
    }
    let toks = lex(src)?;
    let mut parser = Parser {
        src,
        toks,
        pos: 0,
        depth: 0,
        deepest: 0,
        wording,
    };
    let root = parser.expr()?;
    if parser.peek().kind != TokKind::End {
        return Err(parser.unexpected(&format!("an operator or the end of the {}", wording.input)));
    }
    Ok((root, parser.deepest))
}

/// The message for a name an evaluator does not know: "unknown name 'w' at position 1
/// (known names: {known})".
pub fn unknown_name(src: &str, node: &Node, known: &str) -> String {
    let name = match &node.kind {
        Kind::Name(name) => name,
        _ => src.get(node.start..node.end).unwrap_or_default(),
    };
    format!(
        "unknown name '{name}' at position {} (known names: {known})",
        char_pos(src, node.start)
    )
}

/// Whether `name` can be declared as a symbol: a name of the grammar (an ASCII letter or `_`,
/// then letters, digits or `_`) that it does not reserve (pi, deg, sqrt, sin, cos, tan, nan,
/// inf, infinity).
pub fn is_symbol_name(name: &str) -> bool {
    let mut bytes = name.bytes();
    bytes
        .next()
        .is_some_and(|b| b.is_ascii_alphabetic() || b == b'_')
        && bytes.all(|b| b.is_ascii_alphanumeric() || b == b'_')
        && !RESERVED_NAMES.contains(&name)
        && !is_non_finite_name(name)
}

fn is_non_finite_name(name: &str) -> bool {
    ["nan", "inf", "infinity"]
        .iter()
        .any(|n| n.eq_ignore_ascii_case(name))
}

/// 1-based character position of a byte offset, for messages.
pub fn char_pos(src: &str, byte: usize) -> usize {
    src.get(..byte).map_or(byte, |s| s.chars().count()) + 1
}

// ---------------------------------------------------------------------------------------------
// Lexer

#[derive(Debug, Clone, PartialEq)]
enum TokKind {
    Num(Box<Lit>),
    Ident,
    Sym(u8),
    End,
}

#[derive(Debug, Clone)]
struct Tok {
    kind: TokKind,
    start: usize,
    end: usize,
}

fn lex(src: &str) -> Result<Vec<Tok>, String> {
    let bytes = src.as_bytes();
    let mut toks = Vec::new();
    let mut i = 0;
    while let Some(c) = src.get(i..).and_then(|rest| rest.chars().next()) {
        let start = i;
        let digit_at = |j: usize| bytes.get(j).is_some_and(u8::is_ascii_digit);
        let kind = if c.is_whitespace() {
            i += c.len_utf8();
            continue;
        } else if c.is_ascii_digit() || (c == '.' && digit_at(i + 1)) {
            let (lit, end) = scan_literal(src, i).map_err(|(reason, at)| {
                format!(
                    "malformed number at position {}: {reason} at position {}",
                    char_pos(src, start),
                    char_pos(src, at)
                )
            })?;
            if let Some(&b) = bytes.get(end).filter(|b| matches!(b, b'.' | b'_')) {
                return Err(format!(
                    "unexpected '{}' after a number at position {}",
                    b as char,
                    char_pos(src, end)
                ));
            }
            i = end;
            TokKind::Num(Box::new(lit))
        } else if c.is_ascii_alphabetic() || c == '_' {
            i += 1;
            while bytes
                .get(i)
                .is_some_and(|b| b.is_ascii_alphanumeric() || *b == b'_')
            {
                i += 1;
            }
            TokKind::Ident
        } else if "+-*/^()".contains(c) {
            i += 1;
            TokKind::Sym(c as u8)
        } else {
            return Err(format!(
                "unexpected character '{c}' at position {}",
                char_pos(src, i)
            ));
        };
        toks.push(Tok {
            kind,
            start,
            end: i,
        });
    }
    toks.push(Tok {
        kind: TokKind::End,
        start: src.len(),
        end: src.len(),
    });
    Ok(toks)
}

/// A run of digits of `radix` with TOML underscores (only between two digits), from byte `i`.
/// Returns the digits without underscores and the end offset; errors carry a byte offset.
fn digit_run(s: &str, mut i: usize, radix: u32) -> Result<(String, usize), (String, usize)> {
    let bytes = s.as_bytes();
    let is_digit = |j: usize| bytes.get(j).is_some_and(|&b| (b as char).is_digit(radix));
    let mut digits = String::new();
    while let Some(&b) = bytes.get(i) {
        if (b as char).is_digit(radix) {
            digits.push(b as char);
        } else if b == b'_' {
            if !(i > 0 && is_digit(i - 1) && is_digit(i + 1)) {
                return Err(("'_' must stand between two digits".to_string(), i));
            }
        } else {
            break;
        }
        i += 1;
    }
    Ok((digits, i))
}

/// Scan one unsigned numeric literal starting at byte `i` of `s`; returns it and its end offset
/// (errors carry the reason and a byte offset).
pub(crate) fn scan_literal(s: &str, i: usize) -> Result<(Lit, usize), (String, usize)> {
    let bytes = s.as_bytes();
    let radix = match (bytes.get(i), bytes.get(i + 1)) {
        (Some(b'0'), Some(b'x')) => Some(16),
        (Some(b'0'), Some(b'o')) => Some(8),
        (Some(b'0'), Some(b'b')) => Some(2),
        _ => None,
    };
    if let Some(radix) = radix {
        let (digits, end) = digit_run(s, i + 2, radix)?;
        if digits.is_empty() || bytes.get(end).is_some_and(u8::is_ascii_alphanumeric) {
            return Err((format!("malformed base-{radix} integer"), i));
        }
        let n = BigInt::parse_bytes(digits.as_bytes(), radix)
            .ok_or_else(|| (format!("malformed base-{radix} integer"), i))?;
        let q = BigRational::from_integer(n);
        let approx = rational_to_f64(&q);
        return Ok((
            Lit {
                exact: Some(q),
                approx,
            },
            end,
        ));
    }

    let (int, mut end) = digit_run(s, i, 10)?;
    let mut frac = String::new();
    if bytes.get(end) == Some(&b'.') {
        (frac, end) = digit_run(s, end + 1, 10)?;
    }
    if int.is_empty() && frac.is_empty() {
        return Err(("expected digits".to_string(), i));
    }
    let mut exp_text = String::from("0");
    let mut exp_negative = false;
    if matches!(bytes.get(end), Some(b'e' | b'E')) {
        let mut j = end + 1;
        if let Some(&sign @ (b'+' | b'-')) = bytes.get(j) {
            exp_negative = sign == b'-';
            j += 1;
        }
        let (digits, e) = digit_run(s, j, 10)?;
        if digits.is_empty() {
            return Err(("the exponent needs digits".to_string(), j));
        }
        (exp_text, end) = (digits, e);
    }

    let mantissa = format!("{int}{frac}");
    // The f64 parser rounds correctly and saturates huge exponents, so it serves as fallback.
    let approx_text = format!(
        "{}.{}e{}{}",
        if int.is_empty() { "0" } else { &int },
        if frac.is_empty() { "0" } else { &frac },
        if exp_negative { "-" } else { "" },
        exp_text
    );
    let approx = approx_text.parse::<f64>().unwrap_or(f64::NAN);
    let exact = if mantissa.bytes().all(|b| b == b'0') {
        Some(BigRational::zero())
    } else {
        exp_text
            .parse::<i64>()
            .ok()
            .map(|e| if exp_negative { -e } else { e })
            .and_then(|e| e.checked_sub(frac.len() as i64))
            .filter(|e| e.abs() <= MAX_DECIMAL_EXPONENT)
            .and_then(|e| {
                let m = BigInt::parse_bytes(mantissa.as_bytes(), 10)?;
                let p = BigInt::from(10u32).pow(e.unsigned_abs() as u32);
                Some(if e >= 0 {
                    BigRational::from_integer(m * p)
                } else {
                    BigRational::new(m, p)
                })
            })
    };
    Ok((Lit { exact, approx }, end))
}

// ---------------------------------------------------------------------------------------------
// Parser: builds a tree whose depth is bounded by MAX_DEPTH (sums and products are flat lists,
// so long chains like 1+1+...+1 do not deepen it).

struct Parser<'a> {
    src: &'a str,
    toks: Vec<Tok>,
    pos: usize,
    depth: usize,
    /// The largest `depth` reached.
    deepest: usize,
    wording: &'a Wording,
}

impl Parser<'_> {
    fn peek(&self) -> &Tok {
        // `lex` always ends the list with End, and `pos` never passes it.
        &self.toks[self.pos.min(self.toks.len() - 1)]
    }

    /// Consume the current token (End stays put) and return its byte range.
    fn advance(&mut self) -> (usize, usize) {
        let tok = self.peek();
        let span = (tok.start, tok.end);
        if tok.kind != TokKind::End {
            self.pos += 1;
        }
        span
    }

    fn sym(&self) -> Option<u8> {
        match self.peek().kind {
            TokKind::Sym(c) => Some(c),
            _ => None,
        }
    }

    fn ident(&self) -> Option<&str> {
        let tok = self.peek();
        (tok.kind == TokKind::Ident)
            .then(|| self.src.get(tok.start..tok.end))
            .flatten()
    }

    fn unexpected(&self, expected: &str) -> String {
        let tok = self.peek();
        match tok.kind {
            TokKind::End => format!(
                "unexpected end of {}, expected {expected}",
                self.wording.input
            ),
            _ => format!(
                "unexpected '{}' at position {}, expected {expected}",
                self.src.get(tok.start..tok.end).unwrap_or_default(),
                char_pos(self.src, tok.start)
            ),
        }
    }

    /// expr := term (('+' | '-') term)*
    fn expr(&mut self) -> Result<Node, String> {
        self.chain(&[(b'+', Op::Add), (b'-', Op::Sub)], Self::term)
    }

    /// term := product ('deg' (('*' | '/') unary)*)?
    ///
    /// `deg` applies to the whole product before it: `80/3 deg` = (80/3) deg. The product may
    /// go on after it, with that degree value as its first factor.
    fn term(&mut self) -> Result<Node, String> {
        const MUL_DIV: [(u8, Op); 2] = [(b'*', Op::Mul), (b'/', Op::Div)];
        let product = self.chain(&MUL_DIV, Self::unary)?;
        if self.ident() != Some("deg") {
            return Ok(product);
        }
        let end = self.advance().1;
        let degrees = Node {
            start: product.start,
            end,
            has_name: product.has_name,
            kind: Kind::Deg(Box::new(product)),
        };
        let mut rest = Vec::new();
        while let Some(op) = self
            .sym()
            .and_then(|c| MUL_DIV.iter().find(|(s, _)| *s == c).map(|(_, op)| *op))
        {
            self.advance();
            rest.push((op, self.unary()?));
        }
        if self.sym() == Some(b'^') {
            return Err(format!(
                "'^' after 'deg' at position {}: 'deg' applies to the whole product before it; \
                 to raise an angle to a power, put it in parentheses, e.g. (30 deg)^2",
                char_pos(self.src, self.peek().start)
            ));
        }
        if self.ident() == Some("deg") {
            return Err(format!(
                "a second 'deg' in one product at position {}: 'deg' applies to the whole \
                 product before it; put each angle in parentheses, e.g. (30 deg)*(2 deg)",
                char_pos(self.src, self.peek().start)
            ));
        }
        Ok(match rest.last() {
            None => degrees,
            Some((_, last)) => Node {
                start: degrees.start,
                end: last.end,
                has_name: degrees.has_name || rest.iter().any(|(_, n)| n.has_name),
                kind: Kind::Chain(Box::new(degrees), rest),
            },
        })
    }

    /// Left-associative chain of `operand`s joined by `ops`, kept flat.
    ///
    /// The recursive parser functions use `and_then`/`map` instead of `?`: every nesting level
    /// pays for their frames, and in debug builds each `?` adds temporaries.
    fn chain(
        &mut self,
        ops: &[(u8, Op)],
        operand: fn(&mut Self) -> Result<Node, String>,
    ) -> Result<Node, String> {
        operand(self).and_then(|first| {
            let mut rest = Vec::new();
            while let Some(op) = self
                .sym()
                .and_then(|c| ops.iter().find(|(s, _)| *s == c).map(|(_, op)| *op))
            {
                self.advance();
                rest.push((op, operand(self)?));
            }
            Ok(match rest.last() {
                None => first,
                Some((_, last)) => Node {
                    start: first.start,
                    end: last.end,
                    has_name: first.has_name || rest.iter().any(|(_, n)| n.has_name),
                    kind: Kind::Chain(Box::new(first), rest),
                },
            })
        })
    }

    /// unary := ('-' | '+') unary | power. Every level of nesting passes here, so depth is
    /// counted here.
    fn unary(&mut self) -> Result<Node, String> {
        if self.depth >= MAX_DEPTH {
            return Err(self.too_deep());
        }
        self.depth += 1;
        self.deepest = self.deepest.max(self.depth);
        let node = match self.sym() {
            Some(sign @ (b'-' | b'+')) => {
                let start = self.advance().0;
                self.unary().map(|inner| Node {
                    start,
                    end: inner.end,
                    has_name: inner.has_name,
                    kind: if sign == b'-' {
                        Kind::Neg(Box::new(inner))
                    } else {
                        inner.kind
                    },
                })
            }
            _ => self.power(),
        };
        self.depth -= 1;
        node
    }

    #[cold]
    fn too_deep(&self) -> String {
        format!(
            "nested more than {MAX_DEPTH} levels deep at position {}",
            char_pos(self.src, self.peek().start)
        )
    }

    /// power := atom ('^' unary)?  (right-associative through unary)
    fn power(&mut self) -> Result<Node, String> {
        self.atom().and_then(|base| {
            if self.sym() != Some(b'^') {
                return Ok(base);
            }
            self.advance();
            self.unary().map(|exp| Node {
                start: base.start,
                end: exp.end,
                has_name: base.has_name || exp.has_name,
                kind: Kind::Pow(Box::new(base), Box::new(exp)),
            })
        })
    }

    /// atom := leaf | func '(' expr ')' | '(' expr ')'
    ///
    /// Only the recursive cases live here; the leaves are parsed by `leaf`.
    fn atom(&mut self) -> Result<Node, String> {
        let start = self.peek().start;
        let func = if self.sym() == Some(b'(') {
            self.advance();
            None
        } else {
            match self.function() {
                Ok(Some(func)) => Some(func),
                Ok(None) => return self.leaf(),
                Err(e) => return Err(e),
            }
        };
        self.expr().and_then(|inner| {
            self.close().map(|end| match func {
                None => Node {
                    start,
                    end,
                    ..inner
                },
                Some(func) => Node {
                    start,
                    end,
                    has_name: inner.has_name,
                    kind: Kind::Call(func, Box::new(inner)),
                },
            })
        })
    }

    /// A function name followed by '(' (both consumed), or None when the next token is no
    /// function.
    fn function(&mut self) -> Result<Option<Func>, String> {
        let func = match self.ident() {
            Some("sqrt") => Func::Sqrt,
            Some("sin") => Func::Sin,
            Some("cos") => Func::Cos,
            Some("tan") => Func::Tan,
            _ => return Ok(None),
        };
        self.advance();
        if self.sym() != Some(b'(') {
            return Err(self.unexpected(&format!("'(' after '{}'", func.name())));
        }
        self.advance();
        Ok(Some(func))
    }

    /// A number, 'pi', a nan/inf name or any other name.
    fn leaf(&mut self) -> Result<Node, String> {
        let tok = self.peek();
        let (start, end) = (tok.start, tok.end);
        let kind = match &tok.kind {
            TokKind::Num(lit) => Kind::Lit(lit.clone()),
            TokKind::Ident => match self.src.get(start..end).unwrap_or_default() {
                "pi" => Kind::Pi,
                "deg" => return Err(self.unexpected(self.wording.operand)),
                name if is_non_finite_name(name) => Kind::NonFinite,
                name => Kind::Name(name.into()),
            },
            _ => return Err(self.unexpected(self.wording.operand)),
        };
        self.advance();
        Ok(Node {
            start,
            end,
            has_name: matches!(kind, Kind::Name(_)),
            kind,
        })
    }

    /// Consume ')' and return its end offset.
    fn close(&mut self) -> Result<usize, String> {
        if self.sym() != Some(b')') {
            return Err(self.unexpected("')'"));
        }
        Ok(self.advance().1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const WORDING: Wording = Wording {
        input: "input",
        operand: "an operand",
    };

    fn tree(src: &str) -> Node {
        match parse(src, &WORDING) {
            Ok(node) => node,
            Err(e) => panic!("{src}: {e}"),
        }
    }

    fn error(src: &str) -> String {
        match parse(src, &WORDING) {
            Err(e) => e,
            Ok(node) => panic!("{src}: expected an error, got {node:?}"),
        }
    }

    /// The tree in prefix form, to check its shape.
    fn shape(src: &str, n: &Node) -> String {
        let text = &src[n.start..n.end];
        match &n.kind {
            Kind::Lit(_) | Kind::Pi | Kind::NonFinite => text.to_string(),
            Kind::Name(name) => format!("${name}"),
            Kind::Neg(e) => format!("(neg {})", shape(src, e)),
            Kind::Deg(e) => format!("(deg {})", shape(src, e)),
            Kind::Call(f, e) => format!("({} {})", f.name(), shape(src, e)),
            Kind::Pow(b, e) => format!("(^ {} {})", shape(src, b), shape(src, e)),
            Kind::Chain(first, rest) => {
                let mut s = format!("(chain {}", shape(src, first));
                for (op, e) in rest {
                    let op = match op {
                        Op::Add => "+",
                        Op::Sub => "-",
                        Op::Mul => "*",
                        Op::Div => "/",
                    };
                    s += &format!(" {op} {}", shape(src, e));
                }
                s + ")"
            }
        }
    }

    fn parsed(src: &str) -> String {
        shape(src, &tree(src))
    }

    #[test]
    fn shapes() {
        assert_eq!(parsed("1 + 2*3 - 4"), "(chain 1 + (chain 2 * 3) - 4)");
        assert_eq!(parsed("-2^2"), "(neg (^ 2 2))");
        assert_eq!(parsed("2^3^2"), "(^ 2 (^ 3 2))");
        assert_eq!(parsed("2^-1"), "(^ 2 (neg 1))");
        assert_eq!(parsed("+7"), "+7"); // the sign stays in the span
        assert_eq!(parsed("cos(30 deg)"), "(cos (deg 30))");
        assert_eq!(parsed("-45 deg"), "(deg (neg 45))");
        // `deg` takes the whole product or quotient before it (issue 28: `80/3 deg` was read
        // as 80/(3 deg)).
        assert_eq!(parsed("80/3 deg"), "(deg (chain 80 / 3))");
        assert_eq!(parsed("-80/3 deg"), "(deg (chain (neg 80) / 3))");
        assert_eq!(parsed("2*theta deg"), "(deg (chain 2 * $theta))");
        assert_eq!(parsed("2^3 deg"), "(deg (^ 2 3))");
        assert_eq!(parsed("30 deg / 2"), "(chain (deg 30) / 2)");
        assert_eq!(
            parsed("1/2 deg * 3/4"),
            "(chain (deg (chain 1 / 2)) * 3 / 4)"
        );
        assert_eq!(parsed("30 deg + 1/2"), "(chain (deg 30) + (chain 1 / 2))");
        assert_eq!(
            parsed("90 deg - 1/3 deg"),
            "(chain (deg 90) - (deg (chain 1 / 3)))"
        );
        assert_eq!(parsed("cos(80/3 deg)"), "(cos (deg (chain 80 / 3)))");
        assert_eq!(parsed("2^(30 deg)"), "(^ 2 (deg 30))");
        assert_eq!(parsed("sqrt(2)/pi"), "(chain (sqrt 2) / pi)");
        assert_eq!(parsed("NaN + inf"), "(chain NaN + inf)");
        assert_eq!(
            parsed("m*Jz/k1 + omega0 - _a1"),
            "(chain (chain $m * $Jz / $k1) + $omega0 - $_a1)"
        );
        assert_eq!(
            parsed("(3*k1*m + 2)/(a^2*m + Jz)"),
            "(chain (chain (chain 3 * $k1 * $m) + 2) / (chain (chain (^ $a 2) * $m) + $Jz))"
        );
        assert_eq!(
            parsed("-1/2*sqrt(2)*cos(theta)^2"),
            "(chain (neg 1) / 2 * (sqrt 2) * (^ (cos $theta) 2))"
        );
    }

    #[test]
    fn spans_and_names() {
        let src = " (m + 1) * sin(theta)";
        let root = tree(src);
        assert_eq!(&src[root.start..root.end], "(m + 1) * sin(theta)");
        let Kind::Chain(first, rest) = &root.kind else {
            panic!("{root:?}");
        };
        assert_eq!(&src[first.start..first.end], "(m + 1)");
        assert!(matches!(first.kind, Kind::Chain(..)));
        assert_eq!(&src[rest[0].1.start..rest[0].1.end], "sin(theta)");
        let names: Vec<(&str, usize)> = root
            .names()
            .iter()
            .map(|n| (&src[n.start..n.end], n.start))
            .collect();
        assert_eq!(names, [("m", 2), ("theta", 15)]);
        assert!(root.has_name);
        assert!(!tree("1 + sqrt(2)*pi").has_name);
        let bad = &tree("1 + w")
            .names()
            .first()
            .map(|n| unknown_name("1 + w", n, "pi"));
        assert_eq!(
            bad.as_deref(),
            Some("unknown name 'w' at position 5 (known names: pi)")
        );
    }

    #[test]
    fn syntax_errors() {
        assert_eq!(error("  "), "empty input");
        assert_eq!(error("3 +"), "unexpected end of input, expected an operand");
        assert_eq!(
            error("1 2"),
            "unexpected '2' at position 3, expected an operator or the end of the input"
        );
        assert_eq!(
            error("1_"),
            "malformed number at position 1: '_' must stand between two digits at position 2"
        );
        assert_eq!(error("é + x"), "unexpected character 'é' at position 1");
        assert_eq!(error("x + é"), "unexpected character 'é' at position 5");
        assert!(error("deg").contains("'deg' at position 1"));
        assert!(error("1/deg").contains("'deg' at position 3"));
        assert_eq!(
            error("30 deg * 2 deg"),
            "a second 'deg' in one product at position 12: 'deg' applies to the whole product \
             before it; put each angle in parentheses, e.g. (30 deg)*(2 deg)"
        );
        assert!(error("30 deg^2").contains("e.g. (30 deg)^2"));
        assert!(error("30 deg deg").contains("a second 'deg'"));
        assert!(error("sqrt 4").contains("'(' after 'sqrt'"));
        assert!(error("(1").contains("')'"));
        assert!(error("1.5.").contains("'.' after a number"));
        let deep = format!("{}1{}", "(".repeat(100_000), ")".repeat(100_000));
        assert!(error(&deep).contains("nested more than 200"));
    }

    #[test]
    fn declarable_names() {
        for ok in ["m", "Jz", "k1", "omega0", "theta", "_", "_a", "x"] {
            assert!(is_symbol_name(ok), "{ok}");
        }
        for bad in [
            "", "1a", "a-b", "a b", "pi", "deg", "sqrt", "sin", "cos", "tan", "nan", "Inf",
            "INFINITY", "é", "a.b",
        ] {
            assert!(!is_symbol_name(bad), "{bad}");
        }
    }

    #[test]
    fn garbage_never_panics() {
        // Every string over a small alphabet up to length 4, plus some longer mixes.
        let alphabet: Vec<char> = "1.e_x(+-*/^)d é0b".chars().collect();
        let mut inputs = vec![String::new()];
        for _ in 0..4 {
            let mut next = Vec::new();
            for s in &inputs {
                for c in &alphabet {
                    next.push(format!("{s}{c}"));
                }
            }
            for s in &next {
                let _ = parse(s, &WORDING);
            }
            inputs = next;
        }
        for s in [
            "0x",
            "0b2",
            "0o_1",
            "1e+",
            ".e1",
            "1._",
            "sin(",
            "cos)",
            "(((",
            "^^^",
            "2^^2",
            "deg deg",
            "x deg deg",
            "1 +- 2",
            "--1",
        ] {
            let _ = parse(s, &WORDING);
        }
    }
}
