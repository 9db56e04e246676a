//! A text read again and again with other values of the parameters it names, parsed once.
//!
//! A scene's parameters are substituted into its texts as parenthesised values
//! (`cos(theta)` is read as `cos(((47/2) deg))`, [`crate::scene`]'s `params`), and a sweep over
//! a parameter reads the same texts back at every point with only that value changed. Parsing
//! each substituted text anew (lexing it, reading every literal such as `1/120` into a reduced
//! big rational) was most of a point's cost. A [`Template`] is the text as written, parsed once;
//! [`Template::read`] evaluates its tree as the tree of the substituted text, which it is: a
//! name is an atom, and so is the parenthesised value put in its place, so the substituted
//! text parses into the template's tree with each substituted name replaced by the value's
//! tree ([`Expansion`]) and every byte range moved by the lengths substituted before it. The
//! evaluator reads its sub-texts (the reasons and errors it writes) through that move, from
//! the substituted text itself, so the number — text, exact value or reason, f64 — is the very
//! one the parse of the substituted text gives, and so is every error.
//!
//! Two things are kept, both only when they evaluate without error (a failure is evaluated
//! again where it stands and says what it says there, quoting the whole text):
//! * the value of each largest sub-tree of the template that names nothing (`1/120`,
//!   `sqrt(2)/2`): its text is the same in every substituted text, and so is its value;
//! * the value of each parameter's parenthesised value, read once per value.
//!
//! One case is left to the ordinary parse: a substituted text nested deeper than the parser
//! allows ([`MAX_DEPTH`]) is a syntax error there, so when the template's depth and a
//! value's could add up beyond it, [`Template::read`] declines.

use super::expr::{Kind, MAX_DEPTH, Node};
use super::{
    Eval, Number, NumberError, Value, number_of, parse_checked_measured, plain_decimal,
    symbol_names,
};

/// A name in a text, by its byte range: (start, end, name).
pub(crate) type NameSpan = (usize, usize, Box<str>);

/// A text with names, parsed once to be read with values in place of its names.
#[derive(Debug)]
pub(crate) struct Template {
    root: Node,
    /// The deepest nesting of its parse.
    deepest: usize,
    /// Its names, in source order.
    names: Vec<NameSpan>,
    /// (start, end, value) of each largest sub-tree that names nothing and evaluates, in
    /// source order.
    known: Vec<(usize, usize, Value)>,
}

/// A parameter's value as it replaces the parameter's name: `(value)`, parsed and evaluated.
#[derive(Debug)]
pub(crate) struct Expansion {
    /// `(value)`.
    text: String,
    root: Node,
    deepest: usize,
    /// Its value, when it evaluates.
    value: Option<Value>,
    /// The names in it (declared symbols), sorted, without duplicates.
    names: Vec<String>,
}

/// A name of a template replaced by a value: its byte range in the template and the value.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sub<'a> {
    /// Start of the name.
    pub(crate) start: usize,
    /// End of the name.
    pub(crate) end: usize,
    /// What replaces it.
    pub(crate) expansion: &'a Expansion,
}

/// A template read with names replaced.
pub(super) struct Reading<'a> {
    template: &'a Template,
    /// In source order.
    subs: &'a [Sub<'a>],
}

/// Where the byte ranges of the nodes an [`Eval`] walks lie in the text it quotes.
#[derive(Clone, Copy)]
pub(super) enum At<'a> {
    /// In that text: an ordinary parse.
    Same,
    /// That far into it: an expansion's nodes, at the place of its name.
    Shifted(usize),
    /// A template's nodes; the text is the template's with its names replaced.
    Template(&'a Reading<'a>),
}

impl Template {
    /// Parse `src` (trimmed), checking that it names only `allowed` names, as
    /// [`super::parse_checked`] does (and failing as it does).
    pub(crate) fn parse(src: &str, allowed: &[String]) -> Result<Template, NumberError> {
        let (root, deepest) = parse_checked_measured(src, allowed)?;
        let names = root
            .names()
            .into_iter()
            .filter_map(|n| match &n.kind {
                Kind::Name(name) => Some((n.start, n.end, name.clone())),
                _ => None,
            })
            .collect();
        let mut known = Vec::new();
        keep_known(src, &root, &mut known);
        Ok(Template {
            root,
            deepest,
            names,
            known,
        })
    }

    /// Its names with their byte ranges, in source order.
    pub(crate) fn names(&self) -> &[NameSpan] {
        &self.names
    }

    /// The number `text` writes, `text` being this template's source with each name of `subs`
    /// (in source order) replaced by its expansion: the number, or error, that
    /// [`super::parse_number_with`] reads from `text` given the declared symbols the
    /// template's other names and the expansions' names are. `None` when the two depths could
    /// add up beyond the parser's limit: then parse `text`.
    pub(crate) fn read(&self, text: &str, subs: &[Sub<'_>]) -> Option<Result<Number, NumberError>> {
        let deepest = subs.iter().map(|s| s.expansion.deepest).max().unwrap_or(0);
        if self.deepest + deepest > MAX_DEPTH {
            return None;
        }
        if subs.is_empty()
            && let Some(n) = plain_decimal(text)
        {
            return Some(Ok(n));
        }
        let reading = Reading {
            template: self,
            subs,
        };
        let at = At::Template(&reading);
        let (start, end) = at.range(self.root.start, self.root.end);
        let whole = text.get(start..end).unwrap_or(text);
        let value = Eval {
            src: text,
            whole,
            at,
        }
        .eval(&self.root);
        Some(value.and_then(|v| number_of(whole, v, self.symbols(subs))))
    }

    /// The names of the substituted text: the template's not replaced and the expansions'.
    fn symbols(&self, subs: &[Sub<'_>]) -> Vec<String> {
        let mut names: Vec<String> = self
            .names
            .iter()
            .filter(|(start, _, _)| !subs.iter().any(|s| s.start == *start))
            .map(|(_, _, name)| name.to_string())
            .chain(subs.iter().flat_map(|s| s.expansion.names.iter().cloned()))
            .collect();
        names.sort_unstable();
        names.dedup();
        names
    }

    /// The value kept for `node`, if it is one of the sub-trees kept.
    fn known(&self, node: &Node) -> Option<&Value> {
        let i = self
            .known
            .binary_search_by_key(&node.start, |(start, _, _)| *start)
            .ok()?;
        let (_, end, value) = &self.known[i];
        (*end == node.end).then_some(value)
    }
}

/// Keep the value of each largest sub-tree of `node` that names nothing and evaluates.
fn keep_known(src: &str, node: &Node, out: &mut Vec<(usize, usize, Value)>) {
    if !node.has_name {
        let eval = Eval {
            src,
            whole: src,
            at: At::Same,
        };
        if let Ok(value) = eval.eval(node) {
            out.push((node.start, node.end, value));
        }
        return;
    }
    match &node.kind {
        Kind::Lit(_) | Kind::Pi | Kind::NonFinite | Kind::Name(_) => {}
        Kind::Neg(e) | Kind::Deg(e) | Kind::Call(_, e) => keep_known(src, e, out),
        Kind::Chain(first, rest) => {
            keep_known(src, first, out);
            for (_, e) in rest {
                keep_known(src, e, out);
            }
        }
        Kind::Pow(base, exp) => {
            keep_known(src, base, out);
            keep_known(src, exp, out);
        }
    }
}

impl Expansion {
    /// `(value)`, where `value` is a parameter's value as substituted (naming only `symbols`);
    /// `None` if it does not parse so (then the texts naming it are parsed as they are).
    pub(crate) fn new(value: &str, symbols: &[String]) -> Option<Expansion> {
        let text = format!("({value})");
        let (root, deepest) = parse_checked_measured(&text, symbols).ok()?;
        let value = Eval {
            src: &text,
            whole: &text,
            at: At::Same,
        }
        .eval(&root)
        .ok();
        let names = symbol_names(&root);
        Some(Expansion {
            text,
            root,
            deepest,
            value,
            names,
        })
    }
}

impl Reading<'_> {
    /// Where the template's byte `offset` lies in the substituted text.
    fn offset(&self, offset: usize) -> usize {
        let mut at = offset;
        for s in self.subs.iter().take_while(|s| s.end <= offset) {
            // The names before `offset` are disjoint and lie before it: no underflow.
            at = at + s.expansion.text.len() - (s.end - s.start);
        }
        at
    }
}

impl At<'_> {
    /// The byte range `start..end` of a node, in the text quoted.
    pub(super) fn range(&self, start: usize, end: usize) -> (usize, usize) {
        match self {
            At::Same => (start, end),
            At::Shifted(by) => (start + by, end + by),
            At::Template(r) => (r.offset(start), r.offset(end)),
        }
    }

    /// The value kept for a template's `node`, when there is one.
    pub(super) fn known(&self, node: &Node) -> Option<&Value> {
        match self {
            At::Template(r) if !node.has_name => r.template.known(node),
            _ => None,
        }
    }

    /// The expansion that replaces a template's name `node`, and where it stands in the text.
    pub(super) fn expansion(&self, node: &Node) -> Option<(&Expansion, usize)> {
        let At::Template(r) = self else {
            return None;
        };
        let s = r.subs.iter().find(|s| s.start == node.start)?;
        Some((s.expansion, r.offset(s.start)))
    }
}

impl Eval<'_> {
    /// The value of an expansion standing at byte `at` of the text: kept, or evaluated there.
    pub(super) fn expanded(
        &self,
        (expansion, at): (&Expansion, usize),
    ) -> Result<Value, NumberError> {
        match &expansion.value {
            Some(value) => Ok(value.clone()),
            None => Eval {
                src: self.src,
                whole: self.whole,
                at: At::Shifted(at),
            }
            .eval(&expansion.root),
        }
    }
}
