//! Named parameters: `[params] theta = "3 deg"`, `L = 2`, usable in every expression of the
//! scene.
//!
//! A parameter is read in order (it may use the parameters above it) and is substituted into
//! each expression that names it, so a number keeps one self-contained text that every scalar
//! reads: `sin(theta)` becomes `sin((3 deg))`, exact where the value is. A parameter that
//! `inertance derive --symbols` declares stays a symbol instead. For a sensitivity run one
//! parameter is *seeded*: every number that depends on it carries its derivative with respect
//! to it in [`Number::tangent`] ([`crate::number::tangent`]).

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;
use std::sync::Arc;

use crate::number::expr::{self, Kind, Node};
use crate::number::tangent::derivative;
use crate::number::template::{Expansion, NameSpan, Sub, Template};
use crate::number::{Number, NumberError, parse_checked, parse_number_with};

/// One parameter as read.
#[derive(Clone, Debug, PartialEq)]
pub struct ParamSpec {
    /// Its name.
    pub name: String,
    /// Its value as written (`"3 deg"`), for sweeps that keep its unit.
    pub text: String,
    /// Its value; a declared symbol's has none.
    pub value: Number,
}

/// The parameters of a scene, with the symbols values may name and the seeded parameter.
#[derive(Clone, Debug, Default)]
pub(crate) struct Params {
    list: Vec<Param>,
    symbols: Vec<String>,
    seed: Option<String>,
}

#[derive(Clone, Debug)]
struct Param {
    spec: ParamSpec,
    /// The value as a self-contained text (names only symbols): what replaces the name.
    expanded: String,
    /// Whether it is a declared symbol (then it is not substituted).
    symbol: bool,
    /// `(expanded)` parsed and evaluated once, for the texts read back that name it
    /// ([`Params::number`]); `None` for a symbol (or, never seen, a value that does not parse).
    expansion: Option<Arc<Expansion>>,
}

/// The [`Kind::Name`] nodes of `root`, in source order.
fn name_spans(root: &Node) -> Vec<NameSpan> {
    root.names()
        .into_iter()
        .filter_map(|n| match &n.kind {
            Kind::Name(name) => Some((n.start, n.end, name.clone())),
            _ => None,
        })
        .collect()
}

/// The texts [`Params::template`] remembers per thread at most (it forgets them all at once).
const TEMPLATES_KEPT: usize = 4096;

/// [`Params::template`]'s memory: (text, names allowed) → the text parsed.
type TemplateMemo = HashMap<(String, String), Rc<Template>>;

thread_local! {
    static TEMPLATES: RefCell<TemplateMemo> = RefCell::new(HashMap::new());
}

/// Names a parameter may not take: the grammar's own and a surface's variables.
const TAKEN: [&str; 3] = ["x", "y", "z"];

impl Params {
    /// No parameters yet; values may name `symbols`; `seed` is the parameter whose derivative
    /// numbers carry.
    pub(crate) fn new(symbols: &[String], seed: Option<&str>) -> Params {
        Params {
            list: Vec::new(),
            symbols: symbols.to_vec(),
            seed: seed.map(str::to_string),
        }
    }

    /// The parameters read so far.
    pub(crate) fn specs(&self) -> Vec<ParamSpec> {
        self.list.iter().map(|p| p.spec.clone()).collect()
    }

    /// Why `name` cannot be a parameter, if it cannot.
    pub(crate) fn refuse_name(&self, name: &str) -> Option<String> {
        if !expr::is_symbol_name(name) {
            Some(
                "not a parameter name (a letter or '_', then letters, digits or '_'; not one of \
                 pi, deg, sqrt, sin, cos, tan)"
                    .into(),
            )
        } else if TAKEN.contains(&name) {
            Some("x, y and z are a surface's coordinates; give the parameter another name".into())
        } else if self.list.iter().any(|p| p.spec.name == name) {
            Some("defined twice".into())
        } else {
            None
        }
    }

    /// Read the parameter `name = text` (after the ones already read).
    pub(crate) fn push(&mut self, name: &str, text: &str) -> Result<(), NumberError> {
        let symbol = self.symbols.iter().any(|s| s == name);
        let (value, expanded) = if symbol {
            let mut n = parse_number_with(name, &self.symbols)?;
            n.tangent = 0.0;
            (n, name.to_string())
        } else {
            let mut n = self.number(text)?;
            if self.seed.as_deref() == Some(name) {
                n.tangent = 1.0;
            }
            let expanded = n.text.clone();
            (n, expanded)
        };
        let expansion = (!symbol)
            .then(|| Expansion::new(&expanded, &self.symbols).map(Arc::new))
            .flatten();
        self.list.push(Param {
            spec: ParamSpec {
                name: name.to_string(),
                text: text.trim().to_string(),
                value,
            },
            expanded,
            symbol,
            expansion,
        });
        Ok(())
    }

    /// The names an expression may use: symbols and parameters, plus `extra`.
    fn names(&self, extra: &[&str]) -> Vec<String> {
        let mut names = self.symbols.clone();
        names.extend(self.list.iter().map(|p| p.spec.name.clone()));
        names.extend(extra.iter().map(|s| s.to_string()));
        names
    }

    /// `src` with each parameter it names replaced by its value in parentheses.
    fn substitute(&self, src: &str, root: &Node) -> String {
        self.substitute_spans(src, &name_spans(root))
    }

    /// [`Params::substitute`], from the names' byte ranges in `src` (in source order).
    fn substitute_spans(&self, src: &str, names: &[NameSpan]) -> String {
        let mut out = src.to_string();
        // Right to left, so that earlier byte ranges stay valid.
        for (start, end, name) in names.iter().rev() {
            if let Some(p) = self
                .list
                .iter()
                .find(|p| *p.spec.name == **name && !p.symbol)
            {
                out.replace_range(*start..*end, &format!("({})", p.expanded));
            }
        }
        out
    }

    /// `src` parsed, checked against the names it may use ([`parse_checked`]). A sweep over a
    /// parameter reads back the same texts at every point (`(cos(theta))*(1/5) + …`, only
    /// θ's value differs), so the parse is remembered per thread, by the text and the names
    /// allowed, and [`Template::read`] evaluates it with the values in place — the number the
    /// substituted text parses into. Only successes are kept: a failure is parsed again and
    /// says the same.
    fn template(&self, src: &str) -> Result<Rc<Template>, NumberError> {
        let allowed = self.names(&[]);
        let key = (src.to_string(), allowed.join(" "));
        if let Some(hit) = TEMPLATES.with(|m| m.borrow().get(&key).cloned()) {
            return Ok(hit);
        }
        let template = Rc::new(Template::parse(src, &allowed)?);
        TEMPLATES.with(|m| {
            let mut m = m.borrow_mut();
            if m.len() >= TEMPLATES_KEPT {
                m.clear();
            }
            m.insert(key, template.clone());
        });
        Ok(template)
    }

    /// The number of `src` with the parameters' values in place, from its template.
    fn read_back(&self, src: &str) -> Result<Number, NumberError> {
        let template = self.template(src)?;
        let text = self.substitute_spans(src, template.names());
        let mut subs = Vec::new();
        for (start, end, name) in template.names() {
            let Some(p) = self
                .list
                .iter()
                .find(|p| *p.spec.name == **name && !p.symbol)
            else {
                continue;
            };
            match &p.expansion {
                Some(expansion) => subs.push(Sub {
                    start: *start,
                    end: *end,
                    expansion,
                }),
                None => return parse_number_with(&text, &self.symbols),
            }
        }
        match template.read(&text, &subs) {
            Some(n) => n,
            None => parse_number_with(&text, &self.symbols),
        }
    }

    /// The number written `text`, parameters substituted, with its tangent when a parameter
    /// is seeded.
    pub(crate) fn number(&self, text: &str) -> Result<Number, NumberError> {
        if self.list.is_empty() {
            return parse_number_with(text, &self.symbols);
        }
        let src = text.trim();
        if self.seed.is_none() {
            let mut n = self.read_back(src)?;
            if n.text != src {
                n.source = Some(src.to_string());
            }
            return Ok(n);
        }
        let root = parse_checked(src, &self.names(&[]))?;
        let mut n = parse_number_with(&self.substitute(src, &root), &self.symbols)?;
        if n.text != src {
            n.source = Some(src.to_string());
        }
        if root.has_name {
            let env = |name: &str| {
                let p = self.list.iter().find(|p| p.spec.name == name)?;
                (!p.symbol).then_some((p.spec.value.approx, p.spec.value.tangent))
            };
            n.tangent = derivative(src, &root, &env).map_or(0.0, |(_, d)| d);
        }
        Ok(n)
    }

    /// `text` (an expression that may also name `extra`, e.g. a surface's x, y, z) with the
    /// parameters substituted; `text` unchanged when it names none.
    pub(crate) fn expand(&self, text: &str, extra: &[&str]) -> Result<String, NumberError> {
        if self.list.is_empty() {
            return Ok(text.to_string());
        }
        let src = text.trim();
        let root = parse_checked(src, &self.names(extra))?;
        Ok(self.substitute(src, &root))
    }
}

/// How deep a parameter may refer to others when its unit is decided ([`written_in_degrees`]).
const UNIT_DEPTH: usize = 32;

/// Whether a parameter's value, as written, is an angle given in degrees: a `deg` stands outside
/// every function call in it (`"20 deg"`, `"-(80/3) deg"`, `"90 deg - alpha"`), or it names,
/// outside a call, a parameter that is (`"2*alpha"` with `alpha = "10 deg"`; `lookup` gives a
/// parameter's text by name). A number computed from an angle (`"cos(20 deg)"`) is not.
pub fn written_in_degrees(text: &str, lookup: &dyn Fn(&str) -> Option<String>) -> bool {
    degrees_at(text, lookup, UNIT_DEPTH)
}

fn degrees_at(text: &str, lookup: &dyn Fn(&str) -> Option<String>, depth: usize) -> bool {
    fn walk(n: &Node, lookup: &dyn Fn(&str) -> Option<String>, depth: usize) -> bool {
        match &n.kind {
            Kind::Deg(_) => true,
            Kind::Name(name) => lookup(name).is_some_and(|t| degrees_at(&t, lookup, depth - 1)),
            Kind::Neg(e) => walk(e, lookup, depth),
            Kind::Chain(first, rest) => {
                walk(first, lookup, depth) || rest.iter().any(|(_, e)| walk(e, lookup, depth))
            }
            Kind::Pow(base, _) => walk(base, lookup, depth),
            Kind::Lit(_) | Kind::Pi | Kind::NonFinite | Kind::Call(..) => false,
        }
    }
    depth > 0
        && expr::parse(
            text,
            &crate::number::expr::Wording {
                input: "value",
                operand: "a number",
            },
        )
        .is_ok_and(|root| walk(&root, lookup, depth))
}

/// The value `new` (an expression, as written by a user or a sweep) given to a parameter whose
/// value as written is `old`: one rule for every entry point (`--param`, `sweep --vary`,
/// Python's `Scene.with_values` and `solve_batch`). When the parameter is written in degrees
/// ([`written_in_degrees`]), a bare number is a number of degrees: `45` becomes `45 deg`, `80/3` `(80/3) deg` —
/// never 45 radians. A value that carries its own unit (`45 deg`) or names other parameters is
/// taken as written; one that mentions `pi` (radians) is refused with the fix. `Ok(None)`: take
/// `new` as written.
///
/// # Errors
/// The message for a value in radians given to a parameter in degrees.
pub fn in_unit_of(
    old: &str,
    new: &str,
    lookup: &dyn Fn(&str) -> Option<String>,
) -> Result<Option<String>, String> {
    if !written_in_degrees(old, lookup) {
        return Ok(None);
    }
    let wording = crate::number::expr::Wording {
        input: "value",
        operand: "a number",
    };
    let Ok(root) = expr::parse(new, &wording) else {
        // A syntax error is reported where the value is read, with its key.
        return Ok(None);
    };
    fn mentions(n: &Node, what: &dyn Fn(&Kind) -> bool) -> bool {
        what(&n.kind)
            || match &n.kind {
                Kind::Neg(e) | Kind::Deg(e) | Kind::Call(_, e) => mentions(e, what),
                Kind::Chain(first, rest) => {
                    mentions(first, what) || rest.iter().any(|(_, e)| mentions(e, what))
                }
                Kind::Pow(b, e) => mentions(b, what) || mentions(e, what),
                Kind::Lit(_) | Kind::Pi | Kind::NonFinite | Kind::Name(_) => false,
            }
    }
    if root.has_name || mentions(&root, &|k| matches!(k, Kind::Deg(_))) {
        return Ok(None);
    }
    if mentions(&root, &|k| matches!(k, Kind::Pi)) {
        return Err(format!(
            "`{}` is in radians, but this parameter is written in degrees (`{}`): give a number \
             of degrees (`45`) or the value with its unit (`45 deg`)",
            new.trim(),
            old.trim()
        ));
    }
    // A lone number takes the unit as is; anything longer is parenthesised, so that the unit
    // applies to all of it whatever the grammar's precedence.
    let lone = match &root.kind {
        Kind::Lit(_) => true,
        Kind::Neg(e) => matches!(e.kind, Kind::Lit(_)),
        _ => false,
    };
    Ok(Some(if lone {
        format!("{} deg", new.trim())
    } else {
        format!("({}) deg", new.trim())
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn none(_: &str) -> Option<String> {
        None
    }

    /// The number of `text` as a read without templates gives it: the text parsed for its
    /// names, then again with the parameters' values in place.
    fn two_parses(params: &Params, text: &str) -> Result<Number, NumberError> {
        parse_checked(text, &params.names(&[])).and_then(|root| {
            let mut n = parse_number_with(&params.substitute(text, &root), &params.symbols)?;
            if n.text != text.trim() {
                n.source = Some(text.trim().to_string());
            }
            Ok(n)
        })
    }

    /// `params.number(text)`, read twice (the second time from the remembered template), is
    /// [`two_parses`]'s number or error, to the bit.
    fn reads_as_two_parses(params: &Params, text: &str) -> bool {
        // Every field, the f64s to the bit (a symbol's NaN included).
        let bits = |n: Result<Number, NumberError>| {
            n.map(|n| {
                let (approx, tangent) = (n.approx.to_bits(), n.tangent.to_bits());
                (n.text, n.exact, approx, n.symbols, tangent, n.source)
            })
        };
        let expected = bits(two_parses(params, text));
        for _ in 0..2 {
            assert_eq!(bits(params.number(text)), expected, "{text}");
        }
        expected.is_ok()
    }

    /// A text read back from its template ([`Params::template`]) is the very number of the two
    /// parses it stands for, at each value of the parameters — the parse of a text and the
    /// values of its parts that name nothing are kept across values, never its number — and a
    /// failure says the same each time, quoting the same text.
    #[test]
    fn templates_read_the_number_the_two_parses_read() {
        let texts = [
            "((cos(theta))*(1/5)) + ((sin(theta))*(-1/20))",
            "((cos(theta)) + (1 - (cos(theta))))*(1/10)",
            "(((sin(theta))*(-1))*(1/120))*((sin(theta))*(-1))",
            "theta",
            "L*phi - theta/2",
            "0",
            "-1/3",
            "sqrt(2)/2",
            "cos(phi)^2",
            "  (1/120)*(theta*L) + sqrt(3)*phi - 1e-3 ",
            "2^L + theta^(1/3) - (-8)^(1/3)*cos(theta deg)",
            "1 + 2 + 3 + theta*L*phi/4 - 0x10*0.5e1",
            "sqrt(2)*sqrt(2) + tan(pi/4)*theta",
            "(theta)",
            "+theta",
            "-(phi)",
            "1/3",
            "0.25",
            "sqrt(5)",
        ];
        // Failures at every value, and failures at some: the error quotes the whole text with
        // the values in place.
        let failing = [
            "unknown + 1",
            "theta/(L - L)",
            "1 +",
            "cos(theta",
            "sqrt(theta - 1)",
            "tan(theta)",
            "1/(theta - 30 deg)",
            "tan(theta + 45 deg)",
            "(theta - 2/7)^(-1)",
            "1/0 + theta",
        ];
        let fails = |text: &str, theta: &str| match text {
            "sqrt(theta - 1)" => !["60 deg", "90 deg"].contains(&theta),
            "tan(theta)" => theta == "90 deg",
            "1/(theta - 30 deg)" => theta == "30 deg",
            "tan(theta + 45 deg)" => theta == "45 deg",
            "(theta - 2/7)^(-1)" => theta == "2/7",
            _ => failing.contains(&text),
        };
        for theta in [
            "30 deg",
            "(1187/25) deg",
            "0 deg",
            "2/7",
            "60 deg",
            "90 deg",
            "45 deg",
        ] {
            let mut params = Params::new(&[], None);
            params.push("theta", theta).unwrap();
            params.push("L", "0.4").unwrap();
            params.push("phi", "2*theta").unwrap();
            for text in texts.iter().chain(&failing) {
                let ok = reads_as_two_parses(&params, text);
                assert_eq!(ok, !fails(text, theta), "{text} at theta = {theta}");
            }
        }
    }

    /// Declared symbols, in a text or in a parameter's value, stay names of the number read
    /// from a template, as the parse of the substituted text keeps them.
    #[test]
    fn templates_keep_declared_symbols() {
        let mut params = Params::new(&["m".to_string(), "g".to_string()], None);
        params.push("m", "2").unwrap();
        params.push("theta", "20 deg").unwrap();
        params.push("h", "g*cos(theta)").unwrap();
        for text in ["h*theta", "m*h + 1/2", "g/0 + theta", "theta*(1/3)", "m"] {
            let ok = reads_as_two_parses(&params, text);
            assert_eq!(ok, text != "g/0 + theta", "{text}");
        }
    }

    /// Nesting: a template and a value that nest deeper together than the parser allows are
    /// refused as the parse of the substituted text refuses them; nearer the limit they read.
    #[test]
    fn templates_nest_as_the_substituted_text_does() {
        let nested = |depth: usize, inner: &str| {
            format!("{}{inner}{}", "(".repeat(depth), ")".repeat(depth))
        };
        for (outer, inner, reads) in [
            (90, 90, true),
            (150, 60, false),
            (196, 1, true),
            (198, 1, false),
        ] {
            let mut params = Params::new(&[], None);
            params.push("a", &nested(inner, "1/3")).unwrap();
            let text = nested(outer, "a*2");
            assert_eq!(
                reads_as_two_parses(&params, &text),
                reads,
                "{outer} + {inner}"
            );
        }
    }

    #[test]
    fn the_unit_of_a_parameter_is_read_from_its_tree() {
        for text in [
            "20 deg",
            "-20 deg",
            "(80/3) deg",
            "80/3 deg",
            "90 deg - 1",
            "2*(3 deg)",
        ] {
            assert!(written_in_degrees(text, &none), "{text}");
        }
        for text in [
            "20",
            "pi/9",
            "cos(20 deg)",
            "2*sin(30 deg)",
            "alpha",
            "1/deg",
        ] {
            assert!(!written_in_degrees(text, &none), "{text}");
        }
        let lookup = |n: &str| (n == "alpha").then(|| "10 deg".to_string());
        assert!(written_in_degrees("2*alpha", &lookup));
        assert!(!written_in_degrees("cos(alpha)", &lookup));
        // A parameter that names itself (refused when the scene is read) ends the walk.
        let me = |n: &str| (n == "a").then(|| "2*a".to_string());
        assert!(!written_in_degrees("a", &me));
    }

    #[test]
    fn a_bare_number_given_to_a_parameter_in_degrees_is_degrees() {
        let unit = |old: &str, new: &str| in_unit_of(old, new, &none);
        assert_eq!(unit("20 deg", "45"), Ok(Some("45 deg".into())));
        assert_eq!(unit("20 deg", " 80/3 "), Ok(Some("(80/3) deg".into())));
        assert_eq!(unit("20 deg", "-1.5e1"), Ok(Some("-1.5e1 deg".into())));
        assert_eq!(unit("20 deg", "2^3"), Ok(Some("(2^3) deg".into())));
        assert_eq!(unit("20 deg", "45 deg"), Ok(None));
        assert_eq!(unit("20 deg", "2*beta"), Ok(None));
        assert_eq!(unit("0.3", "45"), Ok(None));
        assert_eq!(unit("pi/9", "1"), Ok(None));
        assert!(
            unit("20 deg", "pi/4")
                .is_err_and(|e| e.contains("in radians") && e.contains("`45 deg`"))
        );
    }

    #[test]
    fn parameters_substitute_exactly_and_chain() {
        let mut p = Params::new(&[], None);
        p.push("theta", "30 deg").expect("reads");
        p.push("h", "2*sin(theta)").expect("reads");
        let n = p.number("h + 1").expect("reads");
        assert_eq!(n.text, "(2*sin((30 deg))) + 1");
        assert_eq!(n.source.as_deref(), Some("h + 1"));
        assert_eq!(
            n.exact,
            Ok(num_rational::BigRational::from_integer(2.into()))
        );
        assert_eq!(n.tangent, 0.0);
    }

    #[test]
    fn a_seeded_parameter_gives_derivatives_through_others() {
        let mut p = Params::new(&[], Some("L"));
        p.push("L", "3").expect("reads");
        p.push("A", "L^2").expect("reads");
        let n = p.number("2*A + L").expect("reads");
        assert_eq!(n.approx, 21.0);
        // d/dL (2L² + L) = 4L + 1 = 13.
        assert_eq!(n.tangent, 13.0);
    }

    #[test]
    fn a_declared_symbol_stays_a_symbol() {
        let mut p = Params::new(&["theta".to_string()], None);
        p.push("theta", "3 deg").expect("reads");
        let n = p.number("cos(theta)").expect("reads");
        assert_eq!(n.symbols, vec!["theta".to_string()]);
        assert_eq!(n.text, "cos(theta)");
    }

    #[test]
    fn names_that_cannot_be_parameters() {
        let p = Params::new(&[], None);
        assert!(p.refuse_name("x").is_some());
        assert!(p.refuse_name("sin").is_some());
        assert!(p.refuse_name("2a").is_some());
        assert!(p.refuse_name("theta").is_none());
    }
}
