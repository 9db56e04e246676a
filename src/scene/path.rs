//! Key paths (`body.mass`, `contact[1].k`, `body.velocity[0]`) and overriding the value one
//! names in a scene document, as derivations' `set` lines and sweeps do.

use toml_edit::{DocumentMut, Item, TableLike, Value};

use super::model::params::in_unit_of;

/// Override one value of a scene document: `path` like `body.mass`, `contact[1].k`,
/// `body.velocity[0]`; `value` is TOML text (`0.5`, `"1/3"`, `[1, 0, 0]`). Used by
/// derivations (`set` lines) and parameter sweeps.
///
/// A 3×3 `inertia` is addressed by the keys [`crate::scene::Scene::numbers`] lists: its
/// diagonal entry J_kk as `body.inertia[k]`, an entry off the diagonal as
/// `body.inertia[i][k]`, which sets its mirror `[k][i]` too (the tensor stays symmetric).
///
/// A parameter (`params.NAME`) keeps its unit: a bare number given to a parameter written in
/// degrees is a number of degrees ([`in_unit_of`]), whichever entry point sets it.
pub fn set_value(doc: &mut DocumentMut, path: &str, value: &str) -> Result<(), String> {
    let mut new: Value = value
        .trim()
        .parse::<Value>()
        .map_err(|e| format!("`{value}` is not a TOML value: {}", e.to_string().trim()))?;
    if let Some(name) = path.strip_prefix("params.") {
        let params = doc.get("params").and_then(Item::as_table_like);
        let text_of = |name: &str| {
            params
                .and_then(|t| t.get(name))
                .and_then(Item::as_value)
                .and_then(number_text)
        };
        if let (Some(old), Some(text)) = (text_of(name), number_text(&new))
            && let Some(with_unit) =
                in_unit_of(&old, &text, &text_of).map_err(|e| format!("`{path}`: {e}"))?
        {
            new = Value::from(with_unit);
        }
    }
    let segments: Vec<&str> = path.split('.').collect();
    let mut table: &mut dyn TableLike = doc.as_table_mut();
    for (depth, seg) in segments.iter().enumerate() {
        if depth + 1 == segments.len()
            && let Some((name, i, k)) = tensor_index(seg)
        {
            return set_tensor_entry(table, name, i, k, new, path);
        }
        let (name, index) =
            split_index(seg).ok_or_else(|| format!("bad key `{seg}` in `{path}`"))?;
        if depth + 1 == segments.len() {
            match index {
                None => {
                    table.insert(name, Item::Value(new));
                    if name == "k" {
                        table.remove("k_newton");
                        table.remove("k_poisson");
                    } else if name == "k_newton" || name == "k_poisson" {
                        split_k(table);
                    }
                }
                Some(i) if name == "inertia" && tensor_row(table, i) => {
                    return set_tensor_entry(table, name, i, i, new, path);
                }
                Some(i) => {
                    let slot = table
                        .get_mut(name)
                        .and_then(Item::as_array_mut)
                        .and_then(|a| a.get_mut(i))
                        .ok_or_else(|| format!("`{path}`: there is no {name}[{i}]"))?;
                    *slot = new;
                }
            }
            return Ok(());
        }
        let child = table
            .get_mut(name)
            .ok_or_else(|| format!("`{path}`: no key `{name}`"))?;
        table = match (child, index) {
            (Item::Table(t), None) => t,
            (Item::Value(Value::InlineTable(t)), None) => t,
            (Item::ArrayOfTables(arr), Some(i)) => arr
                .get_mut(i)
                .ok_or_else(|| format!("`{path}`: there is no {name}[{i}]"))?,
            _ => return Err(format!("`{path}`: `{seg}` is not a table")),
        };
    }
    Err(format!("`{path}`: nothing to set"))
}

/// `inertia[i][k]` → ("inertia", i, k), for an entry of a 3×3 tensor.
fn tensor_index(seg: &str) -> Option<(&str, usize, usize)> {
    let (head, k) = seg.strip_suffix(']')?.rsplit_once('[')?;
    let (name, Some(i)) = split_index(head)? else {
        return None;
    };
    Some((name, i, k.parse().ok()?))
}

/// Whether `inertia[i]` of the table is a row of a 3×3 tensor (not a principal moment).
fn tensor_row(table: &dyn TableLike, i: usize) -> bool {
    table
        .get("inertia")
        .and_then(Item::as_array)
        .and_then(|a| a.get(i))
        .is_some_and(Value::is_array)
}

/// Set the tensor entry `name[i][k]` and its mirror `name[k][i]`.
fn set_tensor_entry(
    table: &mut dyn TableLike,
    name: &str,
    i: usize,
    k: usize,
    new: Value,
    path: &str,
) -> Result<(), String> {
    let rows = table
        .get_mut(name)
        .and_then(Item::as_array_mut)
        .ok_or_else(|| format!("`{path}`: there is no {name}[{i}][{k}]"))?;
    for (r, c) in [(i, k), (k, i)] {
        let slot = rows
            .get_mut(r)
            .and_then(Value::as_array_mut)
            .and_then(|row| row.get_mut(c))
            .ok_or_else(|| format!("`{path}`: there is no {name}[{r}][{c}]"))?;
        *slot = new.clone();
    }
    Ok(())
}

/// The expression a TOML number or string holds, as written.
fn number_text(v: &Value) -> Option<String> {
    match v {
        Value::String(s) => Some(s.value().clone()),
        Value::Integer(i) => Some(i.display_repr().into_owned()),
        Value::Float(f) => Some(f.display_repr().into_owned()),
        _ => None,
    }
}

/// When `k` is replaced by one of `k_newton`/`k_poisson`, keep the other at the old `k`.
fn split_k(table: &mut dyn TableLike) {
    if let Some(k) = table.remove("k") {
        for key in ["k_newton", "k_poisson"] {
            if table.get(key).is_none() {
                table.insert(key, k.clone());
            }
        }
    }
}

/// `contact[1]` → ("contact", Some(1)); `mass` → ("mass", None).
fn split_index(seg: &str) -> Option<(&str, Option<usize>)> {
    match seg.find('[') {
        None => Some((seg, None)),
        Some(open) => {
            let close = seg.strip_suffix(']')?;
            let idx = close[open + 1..].parse().ok()?;
            Some((&seg[..open], Some(idx)))
        }
    }
}

/// Set the parameter `name` of a scene document to the expression `value` (`--param
/// theta="10 deg"`); the parameter must exist in `[params]`.
pub fn set_param(doc: &mut DocumentMut, name: &str, value: &str) -> Result<(), String> {
    let params = doc.get("params").and_then(Item::as_table_like);
    let known: Vec<String> = params
        .map(|t| t.iter().map(|(k, _)| k.to_string()).collect())
        .unwrap_or_default();
    if !known.iter().any(|k| k == name) {
        return Err(format!(
            "--param {name}: no such parameter; the scene's [params] has: {}",
            if known.is_empty() {
                "none".to_string()
            } else {
                known.join(", ")
            }
        ));
    }
    set_value(
        doc,
        &format!("params.{name}"),
        &Value::from(value.trim()).to_string(),
    )
}

/// Set `[solve] axes` of a scene document (`"world"` or `"body"`), creating `[solve]` if need be.
pub fn set_axes(doc: &mut DocumentMut, axes: &str) {
    if doc.get("solve").and_then(Item::as_table_like).is_none() {
        doc.insert("solve", toml_edit::table());
    }
    if let Some(t) = doc.get_mut("solve").and_then(Item::as_table_like_mut) {
        t.insert("axes", toml_edit::value(axes));
    }
}
