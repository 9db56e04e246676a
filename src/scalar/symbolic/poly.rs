//! Multivariate polynomials with exact rational coefficients, reduced modulo the side
//! relations of their symbols.
//!
//! **Representation.** A symbol is a `u32` id in the process-wide table of symbols (name,
//! kind, relation); a monomial is the sorted list of `(id, exponent)` pairs with positive
//! exponents; a polynomial is its list of `(monomial, coefficient)` terms, sorted by
//! a fixed monomial order (graded, then lexicographic in the ids) with the leading term first
//! and no zero coefficient. Two polynomials are equal iff their term lists are equal.
//!
//! **Normal form.** A symbol may carry a relation x² = p (p in symbols interned before x):
//! √n as r² = n, sin θ as s² = 1 − c². Every product is reduced by replacing x^k (k ≥ 2) by
//! x^(k mod 2)·p^(k div 2) until no related symbol has exponent ≥ 2. The relations' leading
//! monomials (x², for the lexicographic order with each related symbol above the symbols of
//! its p) are pure powers of distinct symbols, hence pairwise coprime; by Buchberger's first
//! criterion the relations are then a Gröbner basis of the ideal they generate, so the
//! remainder — the polynomial with every related exponent below 2 — is unique: two
//! polynomials are equal modulo the relations iff their reduced forms are identical. The
//! storage order plays no part in this; it only fixes the order of terms.

use std::cmp::Ordering;
use std::collections::btree_map::Entry;
use std::collections::{BTreeMap, HashMap};
use std::fmt;
use std::ops::{Add, Mul, Neg, Sub};

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use super::symbols::{self, Key, Table};

/// A monomial: sorted `(symbol id, exponent)` pairs (exponents ≥ 1) and the total degree.
#[derive(Clone, Debug, PartialEq, Eq, Hash, Default)]
pub(crate) struct Monomial {
    deg: u32,
    vars: Vec<(u32, u32)>,
}

impl Monomial {
    /// The monomial 1.
    pub fn one() -> Self {
        Monomial::default()
    }

    /// x_id^exp.
    pub fn var(id: u32, exp: u32) -> Self {
        if exp == 0 {
            return Monomial::one();
        }
        Monomial {
            deg: exp,
            vars: vec![(id, exp)],
        }
    }

    /// Whether this is the monomial 1.
    pub fn is_one(&self) -> bool {
        self.vars.is_empty()
    }

    /// The `(id, exponent)` pairs.
    pub fn vars(&self) -> &[(u32, u32)] {
        &self.vars
    }

    /// The total degree.
    pub fn degree(&self) -> u32 {
        self.deg
    }

    /// The exponent of symbol `id`.
    pub fn exponent(&self, id: u32) -> u32 {
        self.vars
            .binary_search_by_key(&id, |&(v, _)| v)
            .map_or(0, |i| self.vars[i].1)
    }

    /// self · other (merge of the sorted lists).
    pub fn mul(&self, other: &Monomial) -> Monomial {
        if other.is_one() {
            return self.clone();
        }
        if self.is_one() {
            return other.clone();
        }
        let mut vars = Vec::with_capacity(self.vars.len() + other.vars.len());
        let (mut i, mut j) = (0, 0);
        while i < self.vars.len() && j < other.vars.len() {
            let (a, b) = (self.vars[i], other.vars[j]);
            match a.0.cmp(&b.0) {
                Ordering::Less => {
                    vars.push(a);
                    i += 1;
                }
                Ordering::Greater => {
                    vars.push(b);
                    j += 1;
                }
                Ordering::Equal => {
                    vars.push((a.0, a.1 + b.1));
                    i += 1;
                    j += 1;
                }
            }
        }
        vars.extend_from_slice(&self.vars[i..]);
        vars.extend_from_slice(&other.vars[j..]);
        Monomial {
            deg: self.deg + other.deg,
            vars,
        }
    }

    /// self / other when other divides self.
    pub fn div(&self, other: &Monomial) -> Option<Monomial> {
        if other.is_one() {
            return Some(self.clone());
        }
        if other.deg > self.deg {
            return None;
        }
        let mut vars = Vec::with_capacity(self.vars.len());
        let mut j = 0;
        for &(v, e) in &self.vars {
            if j < other.vars.len() && other.vars[j].0 == v {
                let f = other.vars[j].1;
                match e.cmp(&f) {
                    Ordering::Less => return None,
                    Ordering::Equal => {}
                    Ordering::Greater => vars.push((v, e - f)),
                }
                j += 1;
            } else if j < other.vars.len() && other.vars[j].0 < v {
                return None;
            } else {
                vars.push((v, e));
            }
        }
        if j < other.vars.len() {
            return None;
        }
        Some(Monomial {
            deg: self.deg - other.deg,
            vars,
        })
    }

    /// The greatest common divisor (componentwise minimum of exponents).
    pub fn gcd(&self, other: &Monomial) -> Monomial {
        let mut vars = Vec::new();
        let (mut i, mut j) = (0, 0);
        while i < self.vars.len() && j < other.vars.len() {
            let (a, b) = (self.vars[i], other.vars[j]);
            match a.0.cmp(&b.0) {
                Ordering::Less => i += 1,
                Ordering::Greater => j += 1,
                Ordering::Equal => {
                    vars.push((a.0, a.1.min(b.1)));
                    i += 1;
                    j += 1;
                }
            }
        }
        Monomial {
            deg: vars.iter().map(|&(_, e)| e).sum(),
            vars,
        }
    }

    /// The same monomial with the exponent of `id` set to `exp`.
    fn with_exponent(&self, id: u32, exp: u32) -> Monomial {
        let mut vars: Vec<(u32, u32)> = self
            .vars
            .iter()
            .copied()
            .filter(|&(v, _)| v != id)
            .collect();
        if exp > 0 {
            let pos = vars.partition_point(|&(v, _)| v < id);
            vars.insert(pos, (id, exp));
        }
        Monomial {
            deg: vars.iter().map(|&(_, e)| e).sum(),
            vars,
        }
    }
}

impl Ord for Monomial {
    /// Graded lexicographic: total degree first, then exponent vectors compared with the
    /// lowest id most significant. A monomial order (multiplicative, a well-order).
    fn cmp(&self, other: &Self) -> Ordering {
        match self.deg.cmp(&other.deg) {
            Ordering::Equal => {}
            o => return o,
        }
        for (a, b) in self.vars.iter().zip(&other.vars) {
            if a.0 != b.0 {
                // The lower id is present in one and absent (exponent 0) in the other.
                return if a.0 < b.0 {
                    Ordering::Greater
                } else {
                    Ordering::Less
                };
            }
            match a.1.cmp(&b.1) {
                Ordering::Equal => {}
                o => return o,
            }
        }
        self.vars.len().cmp(&other.vars.len())
    }
}

impl PartialOrd for Monomial {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

type Term = (Monomial, BigRational);

/// A multivariate polynomial with `BigRational` coefficients in named symbols, kept in the
/// canonical normal form described in the [module docs](self): terms sorted by a fixed
/// monomial order, no zero coefficient, every related symbol (radical, sine) of exponent < 2.
#[derive(Clone, PartialEq, Eq, Hash, Default)]
pub struct Poly {
    terms: Vec<Term>,
}

/// gcd(a, b) ≥ 0 of two integers: a word gcd when either fits a word, Lehmer's method on big
/// ones ([`crate::scalar::rational`]), rather than num-integer's binary gcd, which shifts the
/// whole numbers bit by bit.
pub(crate) fn int_gcd(a: &BigInt, b: &BigInt) -> BigInt {
    if a.is_zero() {
        return b.abs();
    }
    if b.is_zero() {
        return a.abs();
    }
    crate::scalar::rational::big_gcd(a, b)
}

/// a·b by Henrici's product over the exact rationals' gcds (a word gcd when either part fits a
/// word, Lehmer's method beyond: [`crate::scalar::rational`]): the same lowest terms as
/// `BigRational`'s product, whose gcds are num-integer's binary ones.
fn q_mul(a: &BigRational, b: &BigRational) -> BigRational {
    let (n, d) = crate::scalar::rational::big_mul(a.numer(), a.denom(), b.numer(), b.denom());
    BigRational::new_raw(n, d)
}

/// a + b by Henrici's sum, as [`q_mul`].
fn q_add(a: &BigRational, b: &BigRational) -> BigRational {
    let (n, d) = crate::scalar::rational::big_add(a.numer(), a.denom(), b.numer(), b.denom());
    BigRational::new_raw(n, d)
}

impl Poly {
    /// The zero polynomial.
    pub fn zero() -> Self {
        Poly { terms: Vec::new() }
    }

    /// The polynomial 1.
    pub fn one() -> Self {
        Poly::constant(BigRational::one())
    }

    /// A constant polynomial.
    pub fn constant(q: BigRational) -> Self {
        if q.is_zero() {
            Poly::zero()
        } else {
            Poly {
                terms: vec![(Monomial::one(), q)],
            }
        }
    }

    /// A small integer constant.
    pub fn from_integer(n: i64) -> Self {
        Poly::constant(BigRational::from_integer(BigInt::from(n)))
    }

    /// The free symbol called `name` (created on first use; any name is accepted and kept
    /// apart from radicals and angles, even one that prints like them).
    pub fn symbol(name: &str) -> Self {
        Poly::var(symbols::intern(Key::Free(name.to_owned()), None))
    }

    /// The polynomial with these terms: distinct reduced monomials, nonzero coefficients,
    /// already in the monomial order (leading first).
    pub(crate) fn from_sorted_terms(terms: Vec<Term>) -> Self {
        debug_assert!(terms.windows(2).all(|w| w[0].0 > w[1].0));
        Poly { terms }
    }

    /// The symbol with id `id`.
    pub(crate) fn var(id: u32) -> Self {
        Poly {
            terms: vec![(Monomial::var(id, 1), BigRational::one())],
        }
    }

    fn from_map(map: HashMap<Monomial, BigRational>) -> Self {
        let mut terms: Vec<Term> = map.into_iter().filter(|(_, c)| !c.is_zero()).collect();
        terms.sort_unstable_by(|a, b| b.0.cmp(&a.0));
        Poly { terms }
    }

    /// The terms, leading first.
    pub(crate) fn terms(&self) -> &[Term] {
        &self.terms
    }

    /// Whether this is the zero polynomial.
    pub fn is_zero(&self) -> bool {
        self.terms.is_empty()
    }

    /// Whether this is the polynomial 1.
    pub fn is_one(&self) -> bool {
        self.terms.len() == 1 && self.terms[0].0.is_one() && self.terms[0].1.is_one()
    }

    /// The number of terms.
    pub fn len(&self) -> usize {
        self.terms.len()
    }

    /// Whether there are no terms (the zero polynomial; same as [`Poly::is_zero`]).
    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }

    /// The value when the polynomial has no symbol at all (radicals count as symbols here).
    pub fn constant_value(&self) -> Option<BigRational> {
        match self.terms.as_slice() {
            [] => Some(BigRational::zero()),
            [(m, c)] if m.is_one() => Some(c.clone()),
            _ => None,
        }
    }

    /// The total degree (0 for constants and for the zero polynomial).
    pub fn total_degree(&self) -> u32 {
        self.terms.first().map_or(0, |(m, _)| m.degree())
    }

    /// The leading coefficient (0 for the zero polynomial).
    pub fn leading_coefficient(&self) -> BigRational {
        self.terms
            .first()
            .map_or_else(BigRational::zero, |(_, c)| c.clone())
    }

    /// The content: gcd of the coefficients' numerators over the lcm of their denominators
    /// (positive; 0 for the zero polynomial). `self / content` has coprime integer
    /// coefficients.
    pub fn content(&self) -> BigRational {
        let mut g = BigInt::zero();
        let mut l = BigInt::one();
        for (_, c) in &self.terms {
            g = int_gcd(&g, c.numer());
            let d = c.denom();
            let gd = int_gcd(&l, d);
            l = &l / &gd * d;
        }
        if g.is_zero() {
            BigRational::zero()
        } else {
            BigRational::new(g, l)
        }
    }

    /// (c, p) with self = c·p, p with coprime integer coefficients and a positive leading
    /// coefficient (c = 0, p = 0 for the zero polynomial).
    pub fn primitive(&self) -> (BigRational, Poly) {
        let mut c = self.content();
        if c.is_zero() {
            return (c, Poly::zero());
        }
        if self.leading_coefficient().is_negative() {
            c = -c;
        }
        if c.is_one() {
            return (c, self.clone());
        }
        let inv = c.recip();
        (c, self.scale(&inv))
    }

    /// The largest monomial dividing every term, as a polynomial with coefficient 1 (1 for the
    /// zero polynomial).
    pub fn monomial_content(&self) -> Poly {
        Poly {
            terms: vec![(self.monomial_gcd(), BigRational::one())],
        }
    }

    /// The largest monomial dividing every term.
    pub(crate) fn monomial_gcd(&self) -> Monomial {
        let mut it = self.terms.iter();
        let Some((first, _)) = it.next() else {
            return Monomial::one();
        };
        let mut g = first.clone();
        for (m, _) in it {
            if g.is_one() {
                break;
            }
            g = g.gcd(m);
        }
        g
    }

    /// self / m for a monomial m dividing every term (exponents only decrease, so the result
    /// stays reduced and sorted).
    pub(crate) fn div_monomial(&self, m: &Monomial) -> Option<Poly> {
        if m.is_one() {
            return Some(self.clone());
        }
        let mut terms = Vec::with_capacity(self.terms.len());
        for (t, c) in &self.terms {
            terms.push((t.div(m)?, c.clone()));
        }
        Some(Poly { terms })
    }

    /// ∂self/∂x_id: each term c·x^e·m ↦ (c·e)·x^(e−1)·m, every other symbol a constant. The
    /// result is reduced (exponents only decrease) and re-sorted (the order of the lowered
    /// monomials may change). A derivation of the quotient ring whenever x_id carries no
    /// relation and no relation names it (a free symbol): it maps each relation x² − p to 0.
    pub(crate) fn derivative(&self, id: u32) -> Poly {
        let x = Monomial::var(id, 1);
        let mut map = HashMap::with_capacity(self.terms.len());
        for (m, c) in &self.terms {
            let e = m.exponent(id);
            if let (true, Some(lowered)) = (e > 0, m.div(&x)) {
                map.insert(lowered, c * BigRational::from_integer(BigInt::from(e)));
            }
        }
        Poly::from_map(map)
    }

    /// The conjugate under r ↦ −r (for a symbol r of exponent ≤ 1): the terms with r
    /// negated. For self = A + B·r it is A − B·r.
    pub(crate) fn conjugate(&self, r: u32) -> Poly {
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(m, c)| {
                    (
                        m.clone(),
                        if m.exponent(r) % 2 == 1 {
                            -c
                        } else {
                            c.clone()
                        },
                    )
                })
                .collect(),
        }
    }

    /// c · self.
    pub fn scale(&self, c: &BigRational) -> Poly {
        if c.is_zero() {
            return Poly::zero();
        }
        if c.is_one() {
            return self.clone();
        }
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(m, a)| (m.clone(), q_mul(a, c)))
                .collect(),
        }
    }

    /// Exact division by a constant: `None` when `c` = 0.
    pub fn div_constant(&self, c: &BigRational) -> Option<Poly> {
        if c.is_zero() {
            None
        } else {
            Some(self.scale(&c.recip()))
        }
    }

    /// self · (c·m) in the free polynomial ring (no reduction; the order is multiplicative,
    /// so the terms stay sorted).
    fn mul_term_free(&self, m: &Monomial, c: &BigRational) -> Poly {
        Poly {
            terms: self
                .terms
                .iter()
                .map(|(t, a)| (t.mul(m), q_mul(a, c)))
                .collect(),
        }
    }

    /// The product in the free polynomial ring (no reduction).
    fn mul_free(&self, other: &Poly) -> Poly {
        let mut map = HashMap::with_capacity(self.len() * other.len());
        for (a, ca) in &self.terms {
            for (b, cb) in &other.terms {
                accumulate(&mut map, a.mul(b), q_mul(ca, cb));
            }
        }
        Poly::from_map(map)
    }

    /// The reduced form modulo the side relations (see the module docs).
    pub(crate) fn reduced(self) -> Poly {
        let table = symbols::snapshot();
        let needs = self.terms.iter().any(|(m, _)| needs_reduction(&table, m));
        if !needs {
            return self;
        }
        let mut map = HashMap::with_capacity(self.terms.len());
        for (m, c) in self.terms {
            reduce_into(&table, m, c, &mut map);
        }
        Poly::from_map(map)
    }

    /// self^k (reduced).
    pub fn pow(&self, k: u32) -> Poly {
        let mut result = Poly::one();
        let mut base = self.clone();
        let mut k = k;
        while k > 0 {
            if k & 1 == 1 {
                result = &result * &base;
            }
            k >>= 1;
            if k > 0 {
                base = &base * &base;
            }
        }
        result
    }

    /// The exact quotient self / d when d divides self in the polynomial ring over the
    /// symbols (the division algorithm leaves no remainder), reduced; `None` when it does not
    /// or when the search exceeds a work budget. Sound (a returned q satisfies self = q·d),
    /// and complete for polynomials without related symbols; with radicals or angles some
    /// divisions that hold only modulo the relations are not found.
    pub fn div_exact(&self, d: &Poly) -> Option<Poly> {
        let (ld, lcd) = d.terms.first()?;
        if self.is_zero() {
            return Some(Poly::zero());
        }
        if ld.is_one() {
            return self.div_constant(lcd);
        }
        if d.len() == 1 {
            return self.div_monomial(ld)?.div_constant(lcd);
        }
        // Quick rejections: leading and trailing terms (the order is multiplicative), degree.
        let (lm, _) = self.terms.first()?;
        lm.div(ld)?;
        let (tm, _) = self.terms.last()?;
        let (td, _) = d.terms.last()?;
        tm.div(td)?;
        // The remainder in an ordered map: each step removes its leading term and subtracts
        // c·m·(d − LT(d)), |d| updates instead of a pass over the whole remainder.
        let mut r: BTreeMap<Monomial, BigRational> = self.terms.iter().cloned().collect();
        let mut q = Vec::new();
        let budget = 4 * self.len() + 64;
        while let Some((lm, lc)) = r.pop_last() {
            if q.len() >= budget {
                return None;
            }
            let m = lm.div(ld)?;
            let c = lc / lcd;
            for (t, a) in &d.terms[1..] {
                match r.entry(t.mul(&m)) {
                    Entry::Occupied(mut e) => {
                        *e.get_mut() -= &c * a;
                        if e.get().is_zero() {
                            e.remove();
                        }
                    }
                    Entry::Vacant(e) => {
                        e.insert(-(&c * a));
                    }
                }
            }
            q.push((m, c));
        }
        // The quotient's terms came out in strictly decreasing order.
        Some(Poly { terms: q }.reduced())
    }

    /// The symbol ids occurring, sorted.
    pub(crate) fn symbol_ids(&self) -> Vec<u32> {
        let mut ids: Vec<u32> = self
            .terms
            .iter()
            .flat_map(|(m, _)| m.vars().iter().map(|&(v, _)| v))
            .collect();
        ids.sort_unstable();
        ids.dedup();
        ids
    }

    /// The names of the symbols occurring (radicals as `sqrt(p)`, angles as `cos(θ)`,
    /// `sin(θ)`), sorted.
    pub fn symbols(&self) -> Vec<String> {
        let table = symbols::snapshot();
        let mut names: Vec<String> = self
            .symbol_ids()
            .into_iter()
            .map(|id| table.name(id))
            .collect();
        names.sort();
        names
    }

    /// Whether every symbol occurring is a radical: the polynomial is a real constant.
    pub fn is_constant(&self) -> bool {
        let table = symbols::snapshot();
        self.terms
            .iter()
            .all(|(m, _)| m.vars().iter().all(|&(v, _)| table.is_radical(v)))
    }

    /// The value at a rational point: `values` gives free symbols by name and angle symbols as
    /// `cos(θ)` / `sin(θ)` (a point with cos² + sin² ≠ 1 gives the value of this canonical
    /// representative, not of the class). `None` when a symbol has no value or a radical
    /// occurs (its value is irrational).
    pub fn eval(&self, values: &HashMap<String, BigRational>) -> Option<BigRational> {
        // In integers over one common denominator D = L·Π d_v^{k_v} (L: lcm of the
        // coefficients' denominators, k_v: the largest exponent of v, x_v = n_v/d_v), so the
        // sum needs no gcd until the end.
        let table = symbols::snapshot();
        let mut vars: HashMap<u32, (BigInt, BigInt, u32)> = HashMap::new();
        let mut l = BigInt::one();
        for (m, c) in &self.terms {
            let g = int_gcd(&l, c.denom());
            l = &l / &g * c.denom();
            for &(v, e) in m.vars() {
                if let Some(entry) = vars.get_mut(&v) {
                    entry.2 = entry.2.max(e);
                    continue;
                }
                if table.is_radical(v) {
                    return None;
                }
                let x = values.get(&table.name(v))?;
                vars.insert(v, (x.numer().clone(), x.denom().clone(), e));
            }
        }
        let mut powers: HashMap<(u32, u32, bool), BigInt> = HashMap::new();
        let mut power = |v: u32, e: u32, numer: bool, base: &BigInt| -> BigInt {
            powers
                .entry((v, e, numer))
                .or_insert_with(|| base.pow(e))
                .clone()
        };
        let mut den = l.clone();
        for (&v, (_, d, k)) in &vars {
            den *= power(v, *k, false, d);
        }
        let mut sum = BigInt::zero();
        for (m, c) in &self.terms {
            let mut t = c.numer() * (&l / c.denom());
            let mut present: Vec<u32> = Vec::with_capacity(m.vars().len());
            for &(v, e) in m.vars() {
                let (n, d, k) = vars.get(&v)?;
                t *= power(v, e, true, n);
                t *= power(v, k - e, false, d);
                present.push(v);
            }
            for (&v, (_, d, k)) in &vars {
                if !present.contains(&v) {
                    t *= power(v, *k, false, d);
                }
            }
            sum += t;
        }
        Some(BigRational::new(sum, den))
    }

    /// Plain text, e.g. `3*m*k1 - 1/2*sqrt(2)*y1^2 + 2`: terms by decreasing degree in the
    /// free symbols, then by name; radicals first within a term.
    pub fn to_text(&self) -> String {
        self.render(false)
    }

    /// LaTeX, e.g. `3 k_{1} m - \frac{1}{2} \sqrt{2} y_{1}^{2} + 2`.
    pub fn to_latex(&self) -> String {
        self.render(true)
    }

    /// The sign of the first coefficient in display order (0 for the zero polynomial):
    /// display normalises signs with it, so output does not depend on symbol ids.
    pub(crate) fn display_sign(&self) -> i8 {
        let table = symbols::snapshot();
        let first = self
            .terms
            .iter()
            .map(|(m, c)| DisplayTerm::new(&table, m, c))
            .min_by(DisplayTerm::order);
        match first {
            Some(t) if t.coeff.is_negative() => -1,
            Some(_) => 1,
            None => 0,
        }
    }

    fn render(&self, latex: bool) -> String {
        if self.is_zero() {
            return "0".to_owned();
        }
        let table = symbols::snapshot();
        let mut rows: Vec<DisplayTerm> = self
            .terms
            .iter()
            .map(|(m, c)| DisplayTerm::new(&table, m, c))
            .collect();
        rows.sort_by(DisplayTerm::order);
        let mut out = String::new();
        for (i, row) in rows.iter().enumerate() {
            let negative = row.coeff.is_negative();
            match (i, negative) {
                (0, true) => out.push('-'),
                (0, false) => {}
                (_, true) => out.push_str(" - "),
                (_, false) => out.push_str(" + "),
            }
            out.push_str(&row.render(latex));
        }
        out
    }
}

/// q^e for a rational q.
fn pow_q(q: &BigRational, e: u32) -> BigRational {
    let mut r = BigRational::one();
    for _ in 0..e {
        r *= q;
    }
    r
}

fn accumulate(map: &mut HashMap<Monomial, BigRational>, m: Monomial, c: BigRational) {
    match map.get_mut(&m) {
        Some(a) => *a = q_add(a, &c),
        None => {
            map.insert(m, c);
        }
    }
}

fn needs_reduction(table: &Table, m: &Monomial) -> bool {
    m.vars()
        .iter()
        .any(|&(v, e)| e >= 2 && table.relation(v).is_some())
}

/// Add c·m, reduced, into `map`: x^k → x^(k mod 2) · p^(k div 2) for the first related x
/// with k ≥ 2, recursively (p only involves symbols interned before x, so this terminates).
fn reduce_into(
    table: &Table,
    m: Monomial,
    c: BigRational,
    map: &mut HashMap<Monomial, BigRational>,
) {
    let hit = m
        .vars()
        .iter()
        .find(|&&(v, e)| e >= 2 && table.relation(v).is_some())
        .copied();
    let Some((v, e)) = hit else {
        accumulate(map, m, c);
        return;
    };
    let Some(p) = table.relation(v) else {
        accumulate(map, m, c);
        return;
    };
    let rest = m.with_exponent(v, e % 2);
    let k = e / 2;
    if let Some(q) = p.constant_value() {
        reduce_into(table, rest, q_mul(&c, &pow_q(&q, k)), map);
        return;
    }
    let mut pk = p.clone();
    for _ in 1..k {
        pk = pk.mul_free(p);
    }
    for (t, a) in pk.terms {
        reduce_into(table, rest.mul(&t), q_mul(&c, &a), map);
    }
}

/// A term prepared for display: names resolved, sorted.
struct DisplayTerm {
    free_degree: u32,
    /// (name, latex, exponent), sorted by name.
    free: Vec<(String, String, u32)>,
    /// (prime, latex), ascending.
    radicals: Vec<(BigInt, String)>,
    coeff: BigRational,
}

impl DisplayTerm {
    fn new(table: &Table, m: &Monomial, c: &BigRational) -> Self {
        let mut free = Vec::new();
        let mut radicals = Vec::new();
        for &(v, e) in m.vars() {
            match (table.radicand(v), table.info(v)) {
                (Some(p), Some(info)) => radicals.push((p.clone(), info.latex())),
                (_, Some(info)) => free.push((info.name(), info.latex(), e)),
                _ => free.push((format!("?{v}"), format!("?{v}"), e)),
            }
        }
        free.sort();
        radicals.sort();
        DisplayTerm {
            free_degree: free.iter().map(|f| f.2).sum(),
            free,
            radicals,
            coeff: c.clone(),
        }
    }

    /// Higher free degree first; then lexicographic by name (earlier names more
    /// significant, higher exponents first); then by radicals.
    fn order(a: &Self, b: &Self) -> Ordering {
        b.free_degree
            .cmp(&a.free_degree)
            .then_with(|| {
                for (x, y) in a.free.iter().zip(&b.free) {
                    if x.0 != y.0 {
                        return x.0.cmp(&y.0);
                    }
                    if x.2 != y.2 {
                        return y.2.cmp(&x.2);
                    }
                }
                b.free.len().cmp(&a.free.len())
            })
            .then_with(|| {
                let pa: Vec<&BigInt> = a.radicals.iter().map(|r| &r.0).collect();
                let pb: Vec<&BigInt> = b.radicals.iter().map(|r| &r.0).collect();
                pa.cmp(&pb)
            })
    }

    /// |coefficient| and factors.
    fn render(&self, latex: bool) -> String {
        let mut factors: Vec<String> = Vec::new();
        // √p·√q·… shown as one root √(pq…) (it reads back as the same product of primes).
        match self.radicals.as_slice() {
            [] => {}
            [(_, l)] if latex => factors.push(l.clone()),
            rs => {
                let n: BigInt = rs.iter().map(|r| &r.0).product();
                factors.push(if latex {
                    format!("\\sqrt{{{n}}}")
                } else {
                    format!("sqrt({n})")
                });
            }
        }
        for (name, l, e) in &self.free {
            factors.push(match (latex, *e) {
                (false, 1) => name.clone(),
                (false, e) => format!("{name}^{e}"),
                (true, 1) => l.clone(),
                (true, e) => format!("{l}^{{{e}}}"),
            });
        }
        let c = self.coeff.abs();
        let coeff = if latex {
            if c.denom().is_one() {
                c.numer().to_string()
            } else {
                format!("\\frac{{{}}}{{{}}}", c.numer(), c.denom())
            }
        } else if c.denom().is_one() {
            c.numer().to_string()
        } else {
            format!("{}/{}", c.numer(), c.denom())
        };
        let sep = if latex { " " } else { "*" };
        if factors.is_empty() {
            coeff
        } else if c.is_one() {
            factors.join(sep)
        } else {
            format!("{coeff}{sep}{}", factors.join(sep))
        }
    }
}

impl fmt::Display for Poly {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_text())
    }
}

impl fmt::Debug for Poly {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Poly({})", self.to_text())
    }
}

impl Add<&Poly> for &Poly {
    type Output = Poly;
    fn add(self, other: &Poly) -> Poly {
        merge(&self.terms, &other.terms, false)
    }
}

impl Sub<&Poly> for &Poly {
    type Output = Poly;
    fn sub(self, other: &Poly) -> Poly {
        merge(&self.terms, &other.terms, true)
    }
}

/// a ± b by merging the sorted term lists (a sum of reduced polynomials is reduced).
fn merge(a: &[Term], b: &[Term], negate_b: bool) -> Poly {
    let mut terms = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    let sign = |c: &BigRational| if negate_b { -c } else { c.clone() };
    while i < a.len() && j < b.len() {
        match a[i].0.cmp(&b[j].0) {
            Ordering::Greater => {
                terms.push(a[i].clone());
                i += 1;
            }
            Ordering::Less => {
                terms.push((b[j].0.clone(), sign(&b[j].1)));
                j += 1;
            }
            Ordering::Equal => {
                let c = if negate_b {
                    q_add(&a[i].1, &-&b[j].1)
                } else {
                    q_add(&a[i].1, &b[j].1)
                };
                if !c.is_zero() {
                    terms.push((a[i].0.clone(), c));
                }
                i += 1;
                j += 1;
            }
        }
    }
    terms.extend_from_slice(&a[i..]);
    terms.extend(b[j..].iter().map(|(m, c)| (m.clone(), sign(c))));
    Poly { terms }
}

impl Mul<&Poly> for &Poly {
    type Output = Poly;
    fn mul(self, other: &Poly) -> Poly {
        if self.is_zero() || other.is_zero() {
            return Poly::zero();
        }
        if let Some(c) = other.constant_value() {
            return self.scale(&c);
        }
        if let Some(c) = self.constant_value() {
            return other.scale(&c);
        }
        if other.len() == 1 {
            let (m, c) = &other.terms[0];
            return self.mul_term_free(m, c).reduced();
        }
        if self.len() == 1 {
            let (m, c) = &self.terms[0];
            return other.mul_term_free(m, c).reduced();
        }
        self.mul_free(other).reduced()
    }
}

impl Neg for &Poly {
    type Output = Poly;
    fn neg(self) -> Poly {
        Poly {
            terms: self.terms.iter().map(|(m, c)| (m.clone(), -c)).collect(),
        }
    }
}

impl Neg for Poly {
    type Output = Poly;
    fn neg(mut self) -> Poly {
        for (_, c) in &mut self.terms {
            *c = -std::mem::take(c);
        }
        self
    }
}

macro_rules! forward_poly_op {
    ($tr:ident, $f:ident) => {
        impl $tr<Poly> for Poly {
            type Output = Poly;
            fn $f(self, other: Poly) -> Poly {
                (&self).$f(&other)
            }
        }
        impl $tr<&Poly> for Poly {
            type Output = Poly;
            fn $f(self, other: &Poly) -> Poly {
                (&self).$f(other)
            }
        }
        impl $tr<Poly> for &Poly {
            type Output = Poly;
            fn $f(self, other: Poly) -> Poly {
                self.$f(&other)
            }
        }
    };
}

forward_poly_op!(Add, add);
forward_poly_op!(Sub, sub);
forward_poly_op!(Mul, mul);

#[cfg(test)]
mod tests {
    use super::*;

    fn x() -> Poly {
        Poly::symbol("x")
    }
    fn y() -> Poly {
        Poly::symbol("y")
    }
    fn z() -> Poly {
        Poly::symbol("z")
    }
    fn n(k: i64) -> Poly {
        Poly::from_integer(k)
    }
    fn q(a: i64, b: i64) -> BigRational {
        BigRational::new(a.into(), b.into())
    }

    /// A few "random-ish" polynomials (fixed, varied in degree, sign and coefficients).
    fn samples() -> Vec<Poly> {
        vec![
            Poly::zero(),
            n(1),
            n(-3),
            x(),
            &x() + &y(),
            &(&x() * &x()) - &(&y() * &n(2)) + Poly::constant(q(1, 3)),
            &(&x() * &y() * &z()) * &n(5) - &z().pow(3),
            &(&x() - &n(1)).pow(3) + &(&y() * &z()),
            Poly::constant(q(-7, 4)) * &(&y().pow(2) - &(&z() * &x())),
        ]
    }

    #[test]
    fn ring_axioms_hold_on_samples() {
        let s = samples();
        for a in &s {
            assert_eq!(a + &Poly::zero(), a.clone());
            assert_eq!(a * &Poly::one(), a.clone());
            assert!((a - a).is_zero());
            assert_eq!(-(-a.clone()), a.clone());
            for b in &s {
                assert_eq!(a + b, b + a);
                assert_eq!(a * b, b * a);
                for c in &s {
                    assert_eq!(&(a + b) + c, a + &(b + c));
                    assert_eq!(&(a * b) * c, a * &(b * c));
                    assert_eq!(a * &(b + c), &(a * b) + &(a * c));
                }
            }
        }
    }

    #[test]
    fn binomial_identities() {
        let (x, y) = (x(), y());
        assert_eq!(
            (&x + &y).pow(2),
            &(&(&x * &x) + &(&x * &y).scale(&q(2, 1))) + &(&y * &y)
        );
        assert_eq!(&(&x - &y) * &(&x + &y), &(&x * &x) - &(&y * &y));
    }

    #[test]
    fn content_monomials_degree_and_display() {
        let p = &(&x().pow(2) * &y()).scale(&q(6, 5)) + &(&x() * &y().pow(3)).scale(&q(-9, 10));
        assert_eq!(p.content(), q(3, 10));
        assert_eq!(p.monomial_content(), &x() * &y());
        assert_eq!(p.total_degree(), 4);
        let (c, prim) = p.primitive();
        assert_eq!(c.abs(), q(3, 10));
        assert_eq!(prim.scale(&c), p);
        assert!(prim.leading_coefficient().is_positive());
        assert_eq!(p.to_text(), "-9/10*x*y^3 + 6/5*x^2*y");
        assert_eq!((-p.clone()).to_text(), "9/10*x*y^3 - 6/5*x^2*y");
        assert_eq!(
            p.to_latex(),
            "-\\frac{9}{10} x y^{3} + \\frac{6}{5} x^{2} y"
        );
        assert_eq!(p.div_constant(&q(0, 1)), None);
        assert_eq!(
            p.div_constant(&q(3, 10)).map(|d| d.content()),
            Some(q(1, 1))
        );
    }

    #[test]
    fn exact_division() {
        let (x, y) = (x(), y());
        let a = &(&x * &x) - &(&y * &y);
        assert_eq!(a.div_exact(&(&x - &y)), Some(&x + &y));
        assert_eq!(a.div_exact(&(&x + &n(1))), None);
        assert_eq!((&x + &n(1)).div_exact(&a), None);
        let cube = (&x + &y + n(2)).pow(3);
        assert_eq!(
            cube.div_exact(&(&x + &y + n(2))),
            Some((&x + &y + n(2)).pow(2))
        );
    }

    #[test]
    fn evaluation() {
        let p = &(&x() * &y()).scale(&q(1, 2)) - &z();
        let mut v = HashMap::new();
        v.insert("x".to_owned(), q(3, 1));
        v.insert("y".to_owned(), q(1, 3));
        assert_eq!(p.eval(&v), None);
        v.insert("z".to_owned(), q(-1, 2));
        assert_eq!(p.eval(&v), Some(q(1, 1)));
    }

    /// int_gcd (word and Lehmer gcds) equals num-integer's binary gcd, on words, 128-bit and
    /// larger arguments, signs and zeros.
    #[test]
    fn integer_gcd_equals_num_integers() {
        use num_integer::Integer;
        let mut state = 0x1129_u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            state
        };
        for k in 0..400u32 {
            let common = BigInt::from(next() >> (k % 64));
            let mut big = |bits: u32| {
                let mut x = BigInt::from(next());
                while x.bits() < u64::from(bits) {
                    x = (x << 64u32) + next();
                }
                x
            };
            let a = big(k % 5 * 60) * &common * if k % 3 == 0 { -1 } else { 1 };
            let b = big(k % 7 * 40) * &common;
            for (x, y) in [
                (&a, &b),
                (&b, &a),
                (&a, &BigInt::zero()),
                (&BigInt::zero(), &b),
            ] {
                assert_eq!(int_gcd(x, y), x.gcd(y), "gcd({x}, {y})");
            }
        }
    }

    /// The coefficients' Henrici products and sums equal `BigRational`'s, in lowest terms
    /// (the same fields, not only the same values), on words and on big parts.
    #[test]
    fn coefficient_arithmetic_equals_big_rationals() {
        let mut state = 0x2911_u64;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            state
        };
        let mut values = Vec::new();
        for k in 0..60u32 {
            let shift = k % 4 * 50;
            let n = (BigInt::from(next() >> 1) << shift) - BigInt::from(next());
            let d = (BigInt::from(next() >> (k % 60)) << (shift / 2)) + 1;
            values.push(BigRational::new(n, d));
        }
        values.push(q(3, 7));
        values.push(q(-3, 7));
        values.push(q(1, 1));
        for a in &values {
            for b in &values {
                let (p, s) = (q_mul(a, b), q_add(a, b));
                let (ep, es) = (a * b, a + b);
                assert_eq!((p.numer(), p.denom()), (ep.numer(), ep.denom()));
                assert_eq!((s.numer(), s.denom()), (es.numer(), es.denom()));
            }
        }
    }
}
