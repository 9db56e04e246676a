//! A readable factored form of a polynomial: content, monomial, and the factors that content
//! extraction with respect to one symbol at a time reveals.
//!
//! For p with a symbol x, write p = Σ_e c_e(other symbols)·x^e. If the leading coefficient
//! c_d (or the trailing one) divides every c_e exactly, then p = c_d · (p / c_d) with p / c_d
//! monic in x, and both parts are split again. This finds the factors a hand derivation shows
//! — (k₁ − k₂), (l + b), ω in a compatibility condition such as eq. (100)–(102) — but it is
//! no complete multivariate factorization: an irreducible-looking factor may still split
//! (e.g. a quadratic in x with non-constant roots in the other symbols). Every returned
//! factorization is exact: the product of the factors equals the polynomial.

use std::collections::BTreeMap;

use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use super::poly::{Monomial, Poly};
use super::ratfun::RatFun;
use super::symbols;

/// p = constant · Π f_i^{e_i}: each f_i non-constant with coprime integer coefficients and a
/// positive leading coefficient, distinct; monomial factors (single symbols) first.
#[derive(Clone, Debug, PartialEq)]
pub struct Factored {
    /// The rational constant in front (0 for the zero polynomial).
    pub constant: BigRational,
    /// The factors with their multiplicities.
    pub factors: Vec<(Poly, u32)>,
}

impl Factored {
    /// The product, expanded (equals the polynomial it came from).
    pub fn expand(&self) -> Poly {
        let mut p = Poly::constant(self.constant.clone());
        for (f, e) in &self.factors {
            p = &p * &f.pow(*e);
        }
        p
    }

    /// Plain text: `-2*m*(b + l)^2*(k1 - k2)`.
    pub fn to_text(&self) -> String {
        self.render(false)
    }

    /// LaTeX: `-2 m \left(b + l\right)^{2} \left(k_{1} - k_{2}\right)`.
    pub fn to_latex(&self) -> String {
        self.render(true)
    }

    fn render(&self, latex: bool) -> String {
        if self.factors.is_empty() {
            return Poly::constant(self.constant.clone()).to_text();
        }
        let mut items: Vec<String> = Vec::new();
        let c = &self.constant;
        let sign = if c.is_negative() { "-" } else { "" };
        if !c.abs().is_one() {
            let t = crate::number::format_rational(&c.abs());
            items.push(if latex && !c.denom().is_one() {
                format!("\\frac{{{}}}{{{}}}", c.numer().abs(), c.denom())
            } else {
                t
            });
        }
        for (f, e) in &self.factors {
            let body = if latex { f.to_latex() } else { f.to_text() };
            let base = match (f.len() > 1, latex) {
                (false, _) => body,
                (true, false) => format!("({body})"),
                (true, true) => format!("\\left({body}\\right)"),
            };
            items.push(match (e, latex) {
                (1, _) => base,
                (e, false) => format!("{base}^{e}"),
                (e, true) => format!("{base}^{{{e}}}"),
            });
        }
        let sep = if latex { " " } else { "*" };
        format!("{sign}{}", items.join(sep))
    }
}

/// The readable form of a rational function: numerator and denominator factored (see the
/// [module docs](self)), common factors cancelled, `num/den` with the constant in front of
/// the numerator. Exact (the factors multiply back to the value), so it reads back equal.
pub fn readable(x: &RatFun, latex: bool) -> String {
    let (num, den) = &*readable_parts(x);
    render_quotient(num, den, latex)
}

/// The factored numerator and denominator [`readable`] prints, remembered per thread for the
/// last [`MEMO`] values: a report asks for the text and the LaTeX of each value, and factoring
/// is most of the cost of either.
fn readable_parts(x: &RatFun) -> std::rc::Rc<(Factored, Factored)> {
    use std::cell::RefCell;
    use std::rc::Rc;
    type Memo = Vec<(RatFun, Rc<(Factored, Factored)>)>;
    thread_local!(static LAST: RefCell<Memo> = const { RefCell::new(Vec::new()) });
    if let Some(hit) = LAST.with(|m| {
        m.borrow()
            .iter()
            .find(|(y, _)| y.same_repr(x))
            .map(|(_, parts)| Rc::clone(parts))
    }) {
        return hit;
    }
    let parts = Rc::new(factor_quotient(x));
    LAST.with(|m| {
        let mut m = m.borrow_mut();
        if m.len() == MEMO {
            m.remove(0);
        }
        m.push((x.clone(), Rc::clone(&parts)));
    });
    parts
}

/// How many values [`readable_parts`] remembers.
const MEMO: usize = 8;

/// Numerator and denominator factored, common factors cancelled, the constant in front of the
/// numerator (its denominator below the line when there is a denominator).
fn factor_quotient(x: &RatFun) -> (Factored, Factored) {
    let mut num = factor(x.numer());
    let mut den = Factored {
        constant: BigRational::one(),
        factors: Vec::new(),
    };
    for (f, e) in x.denom_factors() {
        let g = factor(f);
        den.constant *= pow(&g.constant, *e);
        for (h, k) in g.factors {
            match den.factors.iter_mut().find(|(d, _)| *d == h) {
                Some((_, j)) => *j += k * e,
                None => den.factors.push((h, k * e)),
            }
        }
    }
    // A denominator factor may hide inside a numerator factor the heuristic left whole.
    for (d, j) in den.factors.iter_mut() {
        let mut extra = 0;
        for (n, i) in num.factors.iter_mut() {
            while *j > extra && *i == 1 && n.len() > 1 && *n != *d {
                match n.div_exact(d) {
                    Some(q) => {
                        *n = q;
                        extra += 1;
                    }
                    None => break,
                }
            }
        }
        *j -= extra;
    }
    // The quotients may have become constants or changed sign conventions: normalise.
    let mut renorm = Factored {
        constant: num.constant.clone(),
        factors: Vec::new(),
    };
    for (n, i) in std::mem::take(&mut num.factors) {
        let g = factor(&n);
        renorm.constant *= pow(&g.constant, i);
        for (h, k) in g.factors {
            match renorm.factors.iter_mut().find(|(f, _)| *f == h) {
                Some((_, e)) => *e += k * i,
                None => renorm.factors.push((h, k * i)),
            }
        }
    }
    num = renorm;
    // Cancel common factors.
    for (d, j) in den.factors.iter_mut() {
        if let Some((_, i)) = num.factors.iter_mut().find(|(n, _)| n == d) {
            let c = (*i).min(*j);
            *i -= c;
            *j -= c;
        }
    }
    num.factors.retain(|(_, e)| *e > 0);
    den.factors.retain(|(_, e)| *e > 0);
    for f in [&mut num, &mut den] {
        f.factors
            .sort_by_key(|(p, _)| (p.len() > 1, p.len(), p.to_text()));
    }
    num.constant /= &den.constant;
    den.constant = BigRational::one();
    // The constant's denominator goes below the line.
    let c = num.constant.clone();
    if !den.factors.is_empty() && !c.denom().is_one() {
        num.constant = BigRational::from_integer(c.numer().clone());
        den.constant = BigRational::from_integer(c.denom().clone());
    }
    (num, den)
}

/// `num/den` as [`readable`] prints it.
fn render_quotient(num: &Factored, den: &Factored, latex: bool) -> String {
    // A lone polynomial factor keeps its own signs: `vx - w*y1`, not `-(w*y1 - vx)`.
    let lone = match num.factors.as_slice() {
        [(f, 1)] if num.constant.abs().is_one() && f.len() > 1 => Some(f.scale(&num.constant)),
        _ => None,
    };
    let n = match (&lone, latex) {
        (Some(p), false) if den.factors.is_empty() => p.to_text(),
        (Some(p), false) => format!("({})", p.to_text()),
        (Some(p), true) => p.to_latex(),
        (None, false) => num.to_text(),
        (None, true) => num.to_latex(),
    };
    if den.factors.is_empty() {
        return n;
    }
    let d = match den.factors.as_slice() {
        // A lone factor needs no parentheses under a fraction bar.
        [(f, 1)] if latex && den.constant.is_one() => f.to_latex(),
        _ if latex => den.to_latex(),
        _ => den.to_text(),
    };
    if latex {
        return format!("\\frac{{{n}}}{{{d}}}");
    }
    let wrap = |t: String, f: &Factored| {
        let atomic = f.factors.len() + usize::from(!f.constant.abs().is_one()) <= 1;
        if atomic { t } else { format!("({t})") }
    };
    // `a*(b + c)/(d*e)` reads left to right: only the denominator needs parentheses.
    format!("{n}/{}", wrap(d, den))
}

fn pow(q: &BigRational, e: u32) -> BigRational {
    let mut r = BigRational::one();
    for _ in 0..e {
        r *= q;
    }
    r
}

/// The factored form of `p` (see the [module docs](self)).
pub fn factor(p: &Poly) -> Factored {
    let (constant, prim) = p.primitive();
    if prim.is_zero() || prim.total_degree() == 0 {
        return Factored {
            constant: if prim.is_zero() {
                BigRational::zero()
            } else {
                p.leading_coefficient()
            },
            factors: Vec::new(),
        };
    }
    let mut factors: Vec<(Poly, u32)> = Vec::new();
    let mono = prim.monomial_gcd();
    let table = symbols::snapshot();
    // Radicals in the monomial content form one factor (√2·√3 shows as √6), first.
    let mut root = Poly::one();
    for &(v, e) in mono.vars() {
        if table.is_radical(v) {
            root = &root * &Poly::var(v);
        } else {
            factors.push((Poly::var(v), e));
        }
    }
    factors.sort_by_key(|(f, _)| f.to_text());
    if !root.is_one() {
        factors.insert(0, (root, 1));
    }
    let rest = prim
        .div_monomial(&mono)
        .expect("the monomial content divides every term");
    let mut found = Vec::new();
    split(rest, &mut found);
    let mut constant = constant;
    let mut polys: Vec<(Poly, u32)> = Vec::new();
    for f in found {
        let (c, f) = f.primitive();
        constant *= c;
        // Shown with a positive leading term.
        let f = if f.display_sign() < 0 {
            constant = -constant;
            -f
        } else {
            f
        };
        if f.total_degree() == 0 {
            continue;
        }
        match polys.iter_mut().find(|(g, _)| *g == f) {
            Some((_, e)) => *e += 1,
            None => polys.push((f, 1)),
        }
    }
    polys.sort_by_key(|(f, _)| (f.len(), f.to_text()));
    factors.extend(polys);
    Factored { constant, factors }
}

/// Split `p` (no monomial content) into factors by content extraction, appending them.
fn split(p: Poly, out: &mut Vec<Poly>) {
    if p.total_degree() == 0 {
        out.push(p);
        return;
    }
    let table = symbols::snapshot();
    for x in p.symbol_ids() {
        if table.relation(x).is_some() {
            continue; // sin θ, radicals: coefficients are only defined modulo the relation
        }
        let coeffs = coefficients_in(&p, x);
        if coeffs.len() < 2 {
            continue;
        }
        let lead = coeffs
            .values()
            .next_back()
            .expect("two or more coefficients");
        let trail = coeffs.values().next().expect("two or more coefficients");
        // A perfect power c·(x + t)^d, t = c_{d−1} / (d·c) (the binomial theorem).
        let d = *coeffs.keys().next_back().expect("two or more coefficients");
        if d >= 2
            && let Some(c) = lead.constant_value()
            && let Some(below) = coeffs.get(&(d - 1))
        {
            let t = below.scale(&(c * BigRational::from_integer(d.into())).recip());
            let g = &Poly::var(x) + &t;
            if let Some(q) = p.div_exact(&g) {
                out.push(g);
                split(q, out);
                return;
            }
        }
        for d in [lead, trail] {
            if d.total_degree() == 0 {
                continue;
            }
            if let Some(q) = p.div_exact(d) {
                let d = d.clone();
                split(d, out);
                split(q, out);
                return;
            }
        }
    }
    out.push(p);
}

/// p as Σ_e c_e x^e: the map e ↦ c_e (the symbol x removed from each term).
fn coefficients_in(p: &Poly, x: u32) -> BTreeMap<u32, Poly> {
    let mut groups: BTreeMap<u32, Vec<(Monomial, BigRational)>> = BTreeMap::new();
    for (m, c) in p.terms() {
        let e = m.exponent(x);
        let rest = m
            .div(&Monomial::var(x, e))
            .expect("x^e divides a monomial with exponent e");
        groups.entry(e).or_default().push((rest, c.clone()));
    }
    // Dividing the terms of one group by the same x^e keeps them distinct and in order
    // (the monomial order is multiplicative), so each group is a polynomial as it stands.
    groups
        .into_iter()
        .map(|(e, terms)| (e, Poly::from_sorted_terms(terms)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn s(name: &str) -> Poly {
        Poly::symbol(name)
    }
    fn n(k: i64) -> Poly {
        Poly::from_integer(k)
    }

    #[test]
    fn compatibility_condition_of_a_singular_bar() {
        // -2*omega*(l + b)^2*(k1 - k2)*m: the shape of eq. (100)–(101) for the allowed twist.
        let (k1, k2, l, b, w, m) = (s("k1"), s("k2"), s("l"), s("b"), s("omega"), s("m"));
        let lb = &l + &b;
        let p = &(&(&n(-2) * &w) * &(&lb * &lb)) * &(&(&k1 - &k2) * &m);
        let f = factor(&p);
        assert_eq!(f.expand(), p);
        assert_eq!(f.constant, BigRational::from_integer((-2).into()));
        let texts: Vec<String> = f.factors.iter().map(|(g, e)| format!("{g}^{e}")).collect();
        assert!(texts.contains(&"k1 - k2^1".to_string()), "{texts:?}");
        assert!(texts.contains(&"b + l^2".to_string()), "{texts:?}");
        assert!(texts.contains(&"m^1".to_string()), "{texts:?}");
        assert!(texts.contains(&"omega^1".to_string()), "{texts:?}");
        assert_eq!(f.to_text(), "-2*m*omega*(b + l)^2*(k1 - k2)");
    }

    #[test]
    fn irreducible_and_constant_inputs() {
        let (x, y) = (s("x"), s("y"));
        let p = &(&x * &x) + &(&y * &y);
        let f = factor(&p);
        assert_eq!(f.factors, vec![(p.clone(), 1)]);
        assert_eq!(factor(&n(6)).to_text(), "6");
        assert_eq!(factor(&Poly::zero()).to_text(), "0");
        // Rational content goes in front.
        let half = Poly::constant(BigRational::new(1.into(), 2.into()));
        let f = factor(&(&half * &(&x + &y)));
        assert_eq!(f.to_text(), "1/2*(x + y)");
        assert_eq!(f.to_latex(), "\\frac{1}{2} \\left(x + y\\right)");
    }

    #[test]
    fn products_of_binomials_expand_back() {
        let (a, b, c) = (s("a"), s("b"), s("c"));
        let p = &(&(&a - &b) * &(&b + &c)) * &(&(&a - &b) * &(&a + &n(3)));
        let f = factor(&p);
        assert_eq!(f.expand(), p);
        assert!(
            f.factors
                .iter()
                .any(|(g, e)| (*g == &a - &b || *g == &b - &a) && *e == 2),
            "{f:?}"
        );
    }

    /// The memo of [`readable_parts`] changes nothing: every value of the posed solves, read
    /// in an order that evicts entries (more values than [`MEMO`] between repeats), prints as
    /// its fresh factoring does, in text and LaTeX.
    #[test]
    fn remembered_readable_forms_equal_fresh_ones() {
        let values = super::super::radical::tests::posed_values();
        assert!(values.len() > 4 * MEMO);
        for round in 0..2 {
            for v in &values {
                let (num, den) = factor_quotient(v);
                for latex in [round == 0, round == 1] {
                    assert_eq!(
                        readable(v, latex),
                        render_quotient(&num, &den, latex),
                        "{v}"
                    );
                }
            }
        }
        // A symbolic value and a radical one alternating through the memo.
        let (m, jz) = (RatFun::symbol("m"), RatFun::symbol("Jz"));
        let x = (RatFun::from_integer(1) / &m) * &jz + RatFun::cos_deg(30).unwrap();
        for _ in 0..3 {
            for v in [&x, &values[0]] {
                let (num, den) = factor_quotient(v);
                assert_eq!(readable(v, false), render_quotient(&num, &den, false));
            }
        }
    }
}
