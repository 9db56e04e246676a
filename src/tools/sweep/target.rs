//! Where a varied value goes: a key path of the scene document, or a named parameter
//! (`--vary theta=0:30:31`, in degrees when the parameter is written in degrees) — and how a
//! document is seeded to differentiate by it.

use num_rational::BigRational;
use toml_edit::DocumentMut;

use super::text::{text, toml_text};
use crate::scene::model::params::written_in_degrees;
use crate::scene::{Scene, set_value};

/// Where a varied value is written: a key path of the document, or a parameter of `[params]`
/// (its value in degrees when the parameter is written in degrees).
#[derive(Clone, Debug)]
pub(super) struct Target {
    /// The document path (`contact[1].k`, `params.theta`).
    pub(super) path: String,
    /// Whether the value is in degrees (a parameter written `"… deg"`).
    pub(super) degrees: bool,
    /// Whether it is a parameter.
    pub(super) param: bool,
}

impl Target {
    /// The target of the varied path `path` in the scene `base`: a name of `[params]` (bare or
    /// as `params.NAME`), or a key path.
    pub(super) fn of(path: &str, base: &Scene) -> Target {
        let name = path.strip_prefix("params.").unwrap_or(path);
        match base.params.iter().find(|p| p.name == name) {
            Some(p) => Target {
                path: format!("params.{name}"),
                degrees: written_in_degrees(&p.text, &|n| {
                    base.params
                        .iter()
                        .find(|q| q.name == n)
                        .map(|q| q.text.clone())
                }),
                param: true,
            },
            None => Target {
                path: path.to_string(),
                degrees: false,
                param: false,
            },
        }
    }

    /// Whether `path` (this target's spelling) can be varied in `base`: a parameter, any
    /// number of a modelled scene's document (its written numbers are not the solver's; the
    /// re-reading checks them), or one of `keys` (`contact[i].k` for its two coefficients).
    pub(super) fn known(&self, path: &str, base: &Scene, keys: &[String]) -> bool {
        self.param
            || base.axes.is_some()
            || base.system.is_some()
            || keys.iter().any(|k| {
                k == path
                    || path
                        .strip_suffix(".k")
                        .is_some_and(|c| *k == format!("{c}.k_newton"))
            })
    }

    /// The names that can be varied in `base`, for messages: its parameters, then its numbers.
    pub(super) fn keys(base: &Scene) -> Vec<String> {
        let mut keys: Vec<String> = base.params.iter().map(|p| p.name.clone()).collect();
        keys.extend(base.numbers().map(|(k, _)| k));
        keys
    }

    /// The TOML text of the value q at this target (a parameter in degrees takes it as degrees:
    /// [`set_value`] gives it the unit, as for every entry point).
    pub(super) fn text(&self, q: &BigRational) -> String {
        toml_text(q)
    }

    /// `doc` with this target set to q.
    pub(super) fn set(&self, doc: &mut DocumentMut, q: &BigRational) -> Result<(), String> {
        set_value(doc, &self.path, &self.text(q))
    }

    /// `doc` seeded to differentiate by this target at q: a parameter `__seed` = q first in
    /// `[params]`, and the target written as an expression of it — so every number computed
    /// from it (a shape's moments, a pose, other parameters) carries its derivative, per unit
    /// of the swept value (per degree for a parameter in degrees).
    pub(super) fn seed(&self, doc: &DocumentMut, q: &BigRational) -> Result<DocumentMut, String> {
        let mut d = doc.clone();
        let mut params = toml_edit::Table::new();
        params.insert(SEED, toml_edit::value(text(q)));
        if let Some(old) = d.get("params").and_then(toml_edit::Item::as_table_like) {
            for (k, v) in old.iter() {
                params.insert(k, v.clone());
            }
        }
        d.insert("params", toml_edit::Item::Table(params));
        let expr = if self.degrees {
            format!("{SEED} deg")
        } else {
            SEED.to_string()
        };
        set_value(
            &mut d,
            &self.path,
            &toml_edit::Value::from(expr).to_string(),
        )?;
        Ok(d)
    }
}

/// The parameter a seeded document differentiates by.
pub(super) const SEED: &str = "__seed";
