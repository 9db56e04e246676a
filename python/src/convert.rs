//! Every conversion between Python values and the library's, in one place.
//!
//! Out of the library: a report's JSON (the CLI's contract, guide/solving.md, "JSON report") becomes
//! Python values with the same keys — in f64 mode numbers become `float` and arrays of numbers
//! numpy arrays, a value beyond f64 (a JSON string `"1.2e600"`, Δ of a tiny mass) a
//! `decimal.Decimal`; in exact mode `"p/q"` becomes `fractions.Fraction` and an exact radical
//! (`"12/17*sqrt(17)"`) stays a string `sympy.sympify` reads; in symbolic mode (derive) every
//! expression becomes a SymPy expression when SymPy is installed. Into the library: a scene
//! given as Python values becomes a TOML document, numbers kept exact (`Fraction` → `"p/q"`);
//! model and law names become [`Model`] and [`Law`].

use inertance::impact::outputs::Outputs;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::sync::GILOnceCell;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use serde_json::Value as Json;
use toml_edit::{Array, ArrayOfTables, DocumentMut, Item, Table, Value};

use inertance::Model;
use inertance::impact::unilateral::Law;

/// How a report's values are given to Python.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mode {
    /// Numbers as float, arrays of numbers as numpy arrays.
    F64,
    /// `"p/q"` as `Fraction`, radicals as strings.
    Exact,
    /// Expressions as SymPy expressions (strings without SymPy).
    Symbolic,
}

/// Keys whose string values are names or prose, never numbers or expressions.
const TEXT_KEYS: &[&str] = &[
    "scene",
    "scalar",
    "effects",
    "tangent",
    "law",
    "reason",
    "message",
    "model",
    "symbols",
    "conditions",
    "det_locus",
    "classification",
    "verdicts",
    "f",
    "gradient",
    "name",
    "status",
    "kind",
    "about",
];

static FRACTION: GILOnceCell<Py<PyAny>> = GILOnceCell::new();

/// `fractions.Fraction`.
fn fraction(py: Python<'_>) -> PyResult<&Bound<'_, PyAny>> {
    FRACTION.import(py, "fractions", "Fraction")
}

static DECIMAL: GILOnceCell<Py<PyAny>> = GILOnceCell::new();

/// `decimal.Decimal`.
fn decimal(py: Python<'_>) -> PyResult<&Bound<'_, PyAny>> {
    DECIMAL.import(py, "decimal", "Decimal")
}

/// A float value beyond f64 as the JSON report writes it (`"1.2345678901234567e600"`: an
/// optional sign, a digit, optional decimals, an exponent): given to Python as a
/// `decimal.Decimal`, which holds it exactly.
fn is_wide_text(s: &str) -> bool {
    let s = s.strip_prefix('-').unwrap_or(s);
    let Some((m, e)) = s.split_once('e') else {
        return false;
    };
    let (head, tail) = m.split_once('.').unwrap_or((m, "0"));
    let e = e.strip_prefix('-').unwrap_or(e);
    head.len() == 1
        && [head, tail, e]
            .iter()
            .all(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit()))
}

/// `p/q` or `p` (an optional sign, digits, an optional `/digits`).
fn is_rational_text(s: &str) -> bool {
    let s = s.strip_prefix('-').unwrap_or(s);
    let (p, q) = s.split_once('/').unwrap_or((s, "1"));
    !p.is_empty()
        && !q.is_empty()
        && p.bytes().all(|b| b.is_ascii_digit())
        && q.bytes().all(|b| b.is_ascii_digit())
}

/// An exact text as Python: `Fraction` when rational, else the string itself.
pub fn exact_text<'py>(py: Python<'py>, s: &str) -> PyResult<Bound<'py, PyAny>> {
    if is_rational_text(s) {
        fraction(py)?.call1((s,))
    } else {
        Ok(PyString::new(py, s).into_any())
    }
}

/// A SymPy expression of `s` over `symbols` (declared names are always symbols, never SymPy's
/// constants such as `I` or `E`); the string itself when SymPy is missing or cannot read it.
fn sympy_expr<'py>(py: Python<'py>, s: &str, symbols: &[String]) -> PyResult<Bound<'py, PyAny>> {
    let Ok(sympy) = py.import("sympy") else {
        return Ok(PyString::new(py, s).into_any());
    };
    let locals = PyDict::new(py);
    for name in symbols {
        locals.set_item(name, sympy.getattr("Symbol")?.call1((name,))?)?;
    }
    let kwargs = PyDict::new(py);
    kwargs.set_item("locals", locals)?;
    match sympy.getattr("sympify")?.call((s,), Some(&kwargs)) {
        Ok(e) => Ok(e),
        Err(_) => Ok(PyString::new(py, s).into_any()),
    }
}

/// A JSON value as Python, by `mode`; `symbols` name the symbols of a derivation.
pub fn json_to_py<'py>(
    py: Python<'py>,
    j: &Json,
    mode: Mode,
    symbols: &[String],
) -> PyResult<Bound<'py, PyAny>> {
    convert(py, j, mode, symbols, false)
}

fn convert<'py>(
    py: Python<'py>,
    j: &Json,
    mode: Mode,
    symbols: &[String],
    text: bool,
) -> PyResult<Bound<'py, PyAny>> {
    Ok(match j {
        Json::Null => py.None().into_bound(py),
        Json::Bool(b) => PyBool::new(py, *b).to_owned().into_any(),
        Json::Number(n) => match n.as_i64() {
            Some(i) => i.into_pyobject(py)?.into_any(),
            None => PyFloat::new(py, n.as_f64().unwrap_or(f64::NAN)).into_any(),
        },
        Json::String(s) if text => PyString::new(py, s).into_any(),
        Json::String(s) => match mode {
            Mode::F64 if is_wide_text(s) => decimal(py)?.call1((s,))?,
            Mode::F64 => PyString::new(py, s).into_any(),
            Mode::Exact => exact_text(py, s)?,
            Mode::Symbolic => sympy_expr(py, s, symbols)?,
        },
        Json::Array(items) => {
            if mode == Mode::F64 && !text {
                if let Some(v) = numbers(items) {
                    return Ok(PyArray1::from_vec(py, v).into_any());
                }
                if let Some(rows) = matrix(items) {
                    return Ok(PyArray2::from_vec2(py, &rows)?.into_any());
                }
            }
            let list = PyList::empty(py);
            for x in items {
                list.append(convert(py, x, mode, symbols, text)?)?;
            }
            list.into_any()
        }
        Json::Object(map) => {
            let d = PyDict::new(py);
            for (k, v) in map {
                d.set_item(
                    k,
                    convert(
                        py,
                        v,
                        mode,
                        symbols,
                        text || TEXT_KEYS.contains(&k.as_str()),
                    )?,
                )?;
            }
            d.into_any()
        }
    })
}

/// A non-empty array of numbers (`null`, a float that is not finite, as NaN).
fn numbers(items: &[Json]) -> Option<Vec<f64>> {
    if items.is_empty() {
        return None;
    }
    items.iter().map(|x| x.as_f64()).collect()
}

/// A non-empty array of equally long non-empty arrays of numbers.
fn matrix(items: &[Json]) -> Option<Vec<Vec<f64>>> {
    let rows: Vec<Vec<f64>> = items
        .iter()
        .map(|r| r.as_array().and_then(|r| numbers(r)))
        .collect::<Option<_>>()?;
    (!rows.is_empty() && rows.iter().all(|r| r.len() == rows[0].len())).then_some(rows)
}

/// `None`, `"newton"`, `"poisson"`, `"both"` or a list of names as models (`None`: the scene's).
pub fn models(model: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Vec<Model>>> {
    let Some(m) = model else { return Ok(None) };
    if m.is_none() {
        return Ok(None);
    }
    let names: Vec<String> = if let Ok(s) = m.extract::<String>() {
        vec![s]
    } else {
        m.extract()?
    };
    let mut out = Vec::new();
    for n in names {
        match n.as_str() {
            "newton" => out.push(Model::Newton),
            "poisson" => out.push(Model::Poisson),
            "both" => out.extend(Model::ALL),
            _ => {
                return Err(PyValueError::new_err(format!(
                    "model {n:?}: expected \"newton\", \"poisson\" or \"both\""
                )));
            }
        }
    }
    Ok(Some(out))
}

/// `None`, `"simultaneous"` or `"unilateral"`.
pub fn law(law: Option<&str>) -> PyResult<Option<Law>> {
    match law {
        None => Ok(None),
        Some("simultaneous") => Ok(Some(Law::Simultaneous)),
        Some("unilateral") => Ok(Some(Law::Unilateral)),
        Some("lzb") => Ok(Some(Law::Lzb)),
        Some(other) => Err(PyValueError::new_err(format!(
            "law {other:?}: expected \"simultaneous\", \"unilateral\" or \"lzb\""
        ))),
    }
}

/// `tolerance=`: the relative tolerance of a spatial frictional integration, in (0, 1);
/// `None` keeps the scene's `[solve] tolerance`.
pub fn tolerance(tolerance: Option<f64>) -> PyResult<Option<f64>> {
    match tolerance {
        Some(x) if !inertance::scene::valid_tolerance(x) => Err(PyValueError::new_err(format!(
            "tolerance {x}: {}",
            inertance::scene::TOLERANCE_RULE
        ))),
        t => Ok(t),
    }
}

/// `outputs=`: a name or a list of names of [`Outputs::NAMED`] (or `"all"`); `None` keeps the
/// scene's `[solve] outputs`.
pub fn outputs(outputs: Option<&Bound<'_, PyAny>>) -> PyResult<Option<Outputs>> {
    let Some(o) = outputs else {
        return Ok(None);
    };
    let names: Vec<String> = match o.extract::<String>() {
        Ok(one) => vec![one],
        Err(_) => o
            .extract::<Vec<String>>()
            .map_err(|_| PyValueError::new_err("outputs: expected a name or a list of names"))?,
    };
    Outputs::parse(names.iter().map(String::as_str))
        .map(Some)
        .map_err(|e| PyValueError::new_err(format!("outputs: {e}")))
}

/// A number given from Python as the text a scene reads exactly: an int as itself, a float
/// as its shortest round-trip decimal, a `Fraction` as `"p/q"`, a string as written.
pub fn number_text(x: &Bound<'_, PyAny>) -> PyResult<String> {
    let py = x.py();
    if x.is_instance_of::<PyBool>() {
        return Err(PyValueError::new_err(format!(
            "{x}: a number is expected, not a bool"
        )));
    }
    if x.is_instance_of::<PyInt>() || x.is_instance_of::<PyString>() {
        return x.str()?.extract();
    }
    if x.is_instance(fraction(py)?)? {
        let (p, q): (Bound<'_, PyAny>, Bound<'_, PyAny>) =
            (x.getattr("numerator")?, x.getattr("denominator")?);
        return Ok(format!("{p}/{q}"));
    }
    // floats and numpy scalars
    let f: f64 = x.extract()?;
    Ok(format!("{f:?}"))
}

/// A Python value as a TOML value (inside an array or an inline table).
fn toml_value(x: &Bound<'_, PyAny>) -> PyResult<Value> {
    if x.is_instance_of::<PyBool>() {
        return Ok(Value::from(x.extract::<bool>()?));
    }
    if x.is_instance_of::<PyString>() {
        return Ok(Value::from(x.extract::<String>()?));
    }
    if x.is_instance_of::<PyInt>() {
        return Ok(Value::from(x.extract::<i64>()?));
    }
    if x.is_instance(fraction(x.py())?)? {
        return Ok(Value::from(number_text(x)?));
    }
    if let Some(items) = sequence(x)? {
        let mut a = Array::new();
        for item in items {
            a.push(toml_value(&item)?);
        }
        return Ok(Value::Array(a));
    }
    if let Ok(d) = x.downcast::<PyDict>() {
        let mut t = toml_edit::InlineTable::new();
        for (k, v) in d.iter() {
            t.insert(&k.extract::<String>()?, toml_value(&v)?);
        }
        return Ok(Value::InlineTable(t));
    }
    // floats and numpy scalars: the decimal, so that it reads back exactly as this f64.
    let text = number_text(x)?;
    text.parse::<Value>()
        .map_err(|e| PyValueError::new_err(format!("{x}: not a number a scene can hold ({e})")))
}

/// The items of a list, a tuple or a numpy array (via `tolist()`); `None` for anything else.
fn sequence<'py>(x: &Bound<'py, PyAny>) -> PyResult<Option<Vec<Bound<'py, PyAny>>>> {
    if x.is_instance_of::<PyList>() || x.is_instance_of::<PyTuple>() {
        return Ok(Some(x.try_iter()?.collect::<PyResult<_>>()?));
    }
    if x.hasattr("tolist")? && x.hasattr("ndim")? && x.getattr("ndim")?.extract::<usize>()? > 0 {
        let list = x.call_method0("tolist")?;
        return Ok(Some(list.try_iter()?.collect::<PyResult<_>>()?));
    }
    Ok(None)
}

/// A dict as a TOML table: nested dicts as tables, lists of dicts as arrays of tables
/// (`contact`, `constraints.joint`).
fn toml_table(d: &Bound<'_, PyDict>) -> PyResult<Table> {
    let mut t = Table::new();
    for (k, v) in d.iter() {
        let key: String = k.extract()?;
        if let Ok(sub) = v.downcast::<PyDict>() {
            t.insert(&key, Item::Table(toml_table(sub)?));
            continue;
        }
        if let Some(items) = sequence(&v)?
            && !items.is_empty()
            && items.iter().all(|i| i.is_instance_of::<PyDict>())
        {
            let mut a = ArrayOfTables::new();
            for i in items {
                a.push(toml_table(i.downcast::<PyDict>()?)?);
            }
            t.insert(&key, Item::ArrayOfTables(a));
            continue;
        }
        t.insert(&key, Item::Value(toml_value(&v)?));
    }
    Ok(t)
}

/// A scene given as a dict, as TOML text.
pub fn dict_to_toml(d: &Bound<'_, PyDict>) -> PyResult<String> {
    let mut doc = DocumentMut::new();
    for (k, v) in toml_table(d)?.iter() {
        doc.insert(k, v.clone());
    }
    Ok(doc.to_string())
}

/// A row-major points × width block as a 2-D numpy array of columns `cols`.
pub fn columns<'py>(
    py: Python<'py>,
    values: &[f64],
    width: usize,
    cols: std::ops::Range<usize>,
) -> PyResult<Bound<'py, PyAny>> {
    let points = values.len().checked_div(width).unwrap_or(0);
    let mut out = Vec::with_capacity(points * cols.len());
    for p in 0..points {
        out.extend_from_slice(&values[p * width + cols.start..p * width + cols.end]);
    }
    Ok(PyArray1::from_vec(py, out)
        .reshape([points, cols.len()])?
        .into_any())
}

/// One column of a row-major points × width block as a 1-D numpy array.
pub fn column<'py>(py: Python<'py>, values: &[f64], width: usize, col: usize) -> Bound<'py, PyAny> {
    let v: Vec<f64> = values
        .iter()
        .skip(col)
        .step_by(width.max(1))
        .copied()
        .collect();
    PyArray1::from_vec(py, v).into_any()
}

/// A sweep's CSV as columns by name: numbers as numpy arrays (an empty field as NaN, `point`
/// as integers), `status` (and an LZB sweep's `order`) as strings, the `_exact` columns as `Fraction`s (radicals as strings).
pub fn csv_columns<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyDict>> {
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    let header: Vec<String> = reader
        .headers()
        .map_err(|e| PyValueError::new_err(e.to_string()))?
        .iter()
        .map(str::to_string)
        .collect();
    let mut cells: Vec<Vec<String>> = vec![Vec::new(); header.len()];
    for row in reader.records() {
        let row = row.map_err(|e| PyValueError::new_err(e.to_string()))?;
        for (c, field) in cells.iter_mut().zip(row.iter()) {
            c.push(field.to_string());
        }
    }
    let out = PyDict::new(py);
    for (name, col) in header.iter().zip(cells) {
        if name == "status" || name == "order" {
            // `order`: an LZB sweep's contacts in the order they came to rest ("1 2").
            out.set_item(name, col)?;
        } else if name.ends_with("_exact") {
            let list = PyList::empty(py);
            for x in &col {
                list.append(if x.is_empty() {
                    py.None().into_bound(py)
                } else {
                    exact_text(py, x)?
                })?;
            }
            out.set_item(name, list)?;
        } else if name == "point" {
            let v: Vec<i64> = col.iter().map(|x| x.parse().unwrap_or(-1)).collect();
            out.set_item(name, PyArray1::from_vec(py, v))?;
        } else {
            let v: Vec<f64> = col.iter().map(|x| x.parse().unwrap_or(f64::NAN)).collect();
            out.set_item(name, PyArray1::from_vec(py, v))?;
        }
    }
    Ok(out)
}

/// One reported value: a float in f64 mode, else its exact text (`Fraction` or radical string).
pub fn value<'py>(
    py: Python<'py>,
    v: &inertance::report::Value,
    mode: Mode,
) -> PyResult<Bound<'py, PyAny>> {
    match (&v.exact, mode) {
        (Some(t), Mode::Exact | Mode::Symbolic) => exact_text(py, t),
        _ => Ok(PyFloat::new(py, v.f64).into_any()),
    }
}

/// Reported values: a numpy array in f64 mode, else a list of exact values.
pub fn values<'py>(
    py: Python<'py>,
    vs: &[inertance::report::Value],
    mode: Mode,
) -> PyResult<Bound<'py, PyAny>> {
    if mode == Mode::F64 {
        return Ok(PyArray1::from_vec(py, vs.iter().map(|v| v.f64).collect()).into_any());
    }
    let list = PyList::empty(py);
    for v in vs {
        list.append(value(py, v, mode)?)?;
    }
    Ok(list.into_any())
}

/// Reported values read straight from the report (no JSON built), exactly as the JSON path
/// (`json_to_py` of the report's JSON) would give them; `None` where that path behaves
/// differently (symbolic mode, an empty list or a non-finite f64 in f64 mode): the caller then
/// converts through the JSON.
pub fn direct_values<'py>(
    py: Python<'py>,
    vs: &[inertance::report::Value],
    mode: Mode,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    if mode == Mode::Symbolic
        || (mode == Mode::F64
            && (vs.is_empty() || vs.iter().any(|v| !v.f64.is_finite() || v.wide.is_some())))
    {
        return Ok(None);
    }
    values(py, vs, mode).map(Some)
}

/// One reported value straight from the report, as [`direct_values`].
pub fn direct_value<'py>(
    py: Python<'py>,
    v: &inertance::report::Value,
    mode: Mode,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    if mode == Mode::Symbolic || (mode == Mode::F64 && (!v.f64.is_finite() || v.wide.is_some())) {
        return Ok(None);
    }
    value(py, v, mode).map(Some)
}

/// A reported matrix (G, eq. 12) straight from the report, as [`direct_values`]: a 2-D numpy
/// array in f64 mode, lists of rows of exact values otherwise.
pub fn direct_matrix<'py>(
    py: Python<'py>,
    rows: &[Vec<inertance::report::Value>],
    mode: Mode,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    if mode == Mode::Symbolic {
        return Ok(None);
    }
    if mode == Mode::F64 {
        let ok = !rows.is_empty()
            && rows.iter().all(|r| {
                r.len() == rows[0].len()
                    && !r.is_empty()
                    && r.iter().all(|v| v.f64.is_finite() && v.wide.is_none())
            });
        if !ok {
            return Ok(None);
        }
        let m: Vec<Vec<f64>> = rows
            .iter()
            .map(|r| r.iter().map(|v| v.f64).collect())
            .collect();
        return Ok(Some(PyArray2::from_vec2(py, &m)?.into_any()));
    }
    let list = PyList::empty(py);
    for r in rows {
        list.append(values(py, r, mode)?)?;
    }
    Ok(Some(list.into_any()))
}
