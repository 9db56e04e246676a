//! The process-wide symbol table: every symbol is a small integer id with a kind (free symbol,
//! square root of a prime, cosine or sine of a named angle) and, for the last two that carry
//! one, a side relation x² = p(other symbols).
//!
//! Ids are handed out in order of first use, behind a `RwLock` holding an `Arc` snapshot
//! (copy-on-write), so arithmetic takes one cheap read lock per operation and never blocks on
//! another thread's interning for long. Ids index the table; names are only needed for
//! display and evaluation, which sort by name so output does not depend on the order in which
//! threads happened to create symbols.

use std::collections::HashMap;
use std::sync::{Arc, OnceLock, RwLock};

use num_bigint::BigInt;

use super::poly::Poly;

/// What a symbol stands for. The kind is part of the key, so a free symbol can never be
/// confused with a radical or an angle that prints the same.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Key {
    /// A free symbol (m, Jz, k1, …), no relation.
    Free(String),
    /// √p for a prime p: relation r² = p.
    Radical(BigInt),
    /// cos θ of the angle named θ: no relation of its own.
    Cos(String),
    /// sin θ of the angle named θ: relation s² = 1 − c², c = cos θ.
    Sin(String),
}

/// One entry of the table.
#[derive(Clone, Debug)]
pub(crate) struct Info {
    /// What the symbol is.
    pub key: Key,
    /// x² = relation, when the symbol carries a side relation.
    pub relation: Option<Poly>,
}

impl Info {
    /// The plain-text name: `m`, `sqrt(2)`, `cos(theta)`.
    pub fn name(&self) -> String {
        match &self.key {
            Key::Free(n) => n.clone(),
            Key::Radical(p) => format!("sqrt({p})"),
            Key::Cos(n) => format!("cos({n})"),
            Key::Sin(n) => format!("sin({n})"),
        }
    }

    /// The LaTeX form: `J_{z}`, `\sqrt{2}`, `\cos\theta`.
    pub fn latex(&self) -> String {
        match &self.key {
            Key::Free(n) => latex_name(n),
            Key::Radical(p) => format!("\\sqrt{{{p}}}"),
            Key::Cos(n) => format!("\\cos {}", latex_name(n)),
            Key::Sin(n) => format!("\\sin {}", latex_name(n)),
        }
    }

    /// Whether the symbol is a radical (a constant, not a free symbol).
    pub fn is_radical(&self) -> bool {
        matches!(self.key, Key::Radical(_))
    }
}

/// The table itself.
#[derive(Clone, Default, Debug)]
pub(crate) struct Table {
    infos: Vec<Info>,
    index: HashMap<Key, u32>,
}

impl Table {
    /// The entry of symbol `id` (`None` only for an id from nowhere).
    pub fn info(&self, id: u32) -> Option<&Info> {
        self.infos.get(id as usize)
    }

    /// The relation x² = p of symbol `id`, if it has one.
    pub fn relation(&self, id: u32) -> Option<&Poly> {
        self.info(id).and_then(|i| i.relation.as_ref())
    }

    /// Whether symbol `id` is a radical √p.
    pub fn is_radical(&self, id: u32) -> bool {
        self.info(id).is_some_and(Info::is_radical)
    }

    /// The prime p of the radical `id`.
    pub fn radicand(&self, id: u32) -> Option<&BigInt> {
        match self.info(id).map(|i| &i.key) {
            Some(Key::Radical(p)) => Some(p),
            _ => None,
        }
    }

    /// The plain-text name of `id` (`?id` for an unknown id).
    pub fn name(&self, id: u32) -> String {
        self.info(id).map_or_else(|| format!("?{id}"), Info::name)
    }
}

fn table_lock() -> &'static RwLock<Arc<Table>> {
    static TABLE: OnceLock<RwLock<Arc<Table>>> = OnceLock::new();
    TABLE.get_or_init(|| RwLock::new(Arc::new(Table::default())))
}

/// A consistent snapshot of the table (symbols interned later are not in it; no value built
/// before the snapshot can refer to them).
pub(crate) fn snapshot() -> Arc<Table> {
    let lock = table_lock().read().unwrap_or_else(|e| e.into_inner());
    Arc::clone(&lock)
}

/// The id of `key`, interning it with `relation` if it is new. `relation` must only refer to
/// symbols interned before (so reduction terminates).
pub(crate) fn intern(key: Key, relation: Option<Poly>) -> u32 {
    if let Some(&id) = snapshot().index.get(&key) {
        return id;
    }
    let mut lock = table_lock().write().unwrap_or_else(|e| e.into_inner());
    if let Some(&id) = lock.index.get(&key) {
        return id;
    }
    let table = Arc::make_mut(&mut *lock);
    let id = u32::try_from(table.infos.len()).unwrap_or(u32::MAX);
    debug_assert!(id < u32::MAX, "symbol table overflow");
    table.index.insert(key.clone(), id);
    table.infos.push(Info { key, relation });
    id
}

/// A symbol name in LaTeX: a Greek name becomes its macro, a trailing part after the first
/// letter(s) becomes a subscript: `Jz` → `J_{z}`, `k1` → `k_{1}`, `omega0` → `\omega_{0}`.
fn latex_name(name: &str) -> String {
    const GREEK: [&str; 24] = [
        "alpha", "beta", "gamma", "delta", "epsilon", "zeta", "eta", "theta", "iota", "kappa",
        "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau", "upsilon", "phi", "chi", "psi",
        "omega", "Omega",
    ];
    for g in GREEK {
        if let Some(rest) = name.strip_prefix(g) {
            let rest = rest.trim_start_matches('_');
            return if rest.is_empty() {
                format!("\\{g}")
            } else {
                format!("\\{g}_{{{rest}}}")
            };
        }
    }
    let mut chars = name.chars();
    match chars.next() {
        Some(first) if first.is_alphabetic() => {
            let rest: String = chars.collect();
            let rest = rest.trim_start_matches('_');
            if rest.is_empty() {
                first.to_string()
            } else {
                format!("{first}_{{{rest}}}")
            }
        }
        _ => format!("\\mathrm{{{name}}}"),
    }
}
