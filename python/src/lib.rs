//! `inertance._inertance`: the Python bindings, a thin layer over the Rust library.
//!
//! Each function converts its arguments ((`convert.rs`)), calls the library
//! (`inertance::scene::pipeline::run`, `inertance::tools::{analyze, check, derive, sweep}`),
//! and converts the result back; errors become exceptions in `errors.rs`. Long work (exact and
//! symbolic solves, `check`, `derive`, `sweep`, batches) runs with the GIL released.

mod convert;
mod errors;
mod lzb;
mod simulate;
mod system;

use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use serde_json::Value as Json;
use toml_edit::DocumentMut;

use inertance::impact::outputs::Outputs;
use inertance::report::Report;
use inertance::scalar::Exact;
use inertance::scalar::symbolic::RatFun;
use inertance::scene::pipeline::{Prepared, RunError, prepare_scaled, run, run_prepared_scaled};
use inertance::scene::{Scene as LibScene, parse_document, set_value};
use inertance::tools::{
    analyze as lib_analyze, check as lib_check, derive as lib_derive, sweep as lib_sweep,
};

use convert::{Mode, json_to_py};

/// A validated scene (guide/scenes.md), read once and reused across calls.
#[pyclass(frozen, module = "inertance")]
struct Scene {
    scene: LibScene,
    doc: DocumentMut,
    text: String,
    /// The file it was read from, when unchanged since.
    path: Option<PathBuf>,
    symbols: Vec<String>,
    /// The problem in f64, prepared once in the units the CLI solves it in (None when the
    /// scene has symbols or is invalid in f64: a solve then reports why).
    f64: Option<Prepared<f64>>,
}

impl Scene {
    fn new(
        py: Python<'_>,
        text: String,
        file: &str,
        path: Option<PathBuf>,
        symbols: Vec<String>,
    ) -> PyResult<Scene> {
        let doc = parse_document(&text, file).map_err(|e| errors::scene_error(py, &e))?;
        let scene = LibScene::from_document_with(&doc, file, &symbols)
            .map_err(|e| errors::scene_error(py, &e))?;
        let f64 = prepare_scaled::<f64>(&scene).ok();
        Ok(Scene {
            scene,
            doc,
            text,
            path,
            symbols,
            f64,
        })
    }
}

#[pymethods]
impl Scene {
    /// Read a scene from TOML text; `file` names it in messages.
    #[staticmethod]
    #[pyo3(signature = (text, *, symbols = None, file = "<string>"))]
    fn from_toml(
        py: Python<'_>,
        text: String,
        symbols: Option<Vec<String>>,
        file: &str,
    ) -> PyResult<Scene> {
        Scene::new(py, text, file, None, symbols.unwrap_or_default())
    }

    /// Read a scene file.
    #[staticmethod]
    #[pyo3(signature = (path, *, symbols = None))]
    fn load(py: Python<'_>, path: PathBuf, symbols: Option<Vec<String>>) -> PyResult<Scene> {
        let file = path.display().to_string();
        let text = std::fs::read_to_string(&path).map_err(|e| {
            errors::scene_error(
                py,
                &inertance::scene::SceneError {
                    file: file.clone(),
                    key: String::new(),
                    value: None,
                    message: format!("cannot read the file: {e}"),
                },
            )
        })?;
        Scene::new(py, text, &file, Some(path), symbols.unwrap_or_default())
    }

    /// Build a scene from Python values: a dict with the keys of a scene file (`body`,
    /// `contact` as a list of dicts, `solve`, …); numbers may be int, float, `Fraction`,
    /// numpy values or strings such as `"2/sqrt(5)"`, and are kept exact.
    #[staticmethod]
    #[pyo3(signature = (values, *, symbols = None))]
    fn from_dict(
        py: Python<'_>,
        values: &Bound<'_, PyDict>,
        symbols: Option<Vec<String>>,
    ) -> PyResult<Scene> {
        let text = convert::dict_to_toml(values)?;
        Scene::new(py, text, "<dict>", None, symbols.unwrap_or_default())
    }

    /// A copy with some numbers replaced, by key path: `{"contact[1].k": 0.5}`.
    fn with_values(&self, py: Python<'_>, values: &Bound<'_, PyDict>) -> PyResult<Scene> {
        let mut doc = self.doc.clone();
        for (k, v) in values.iter() {
            let key: String = k.extract()?;
            let text = convert::number_text(&v)?;
            let toml = if text.parse::<toml_edit::Value>().is_ok_and(|t| !t.is_str()) {
                text
            } else {
                toml_edit::Value::from(text).to_string()
            };
            set_value(&mut doc, &key, &toml).map_err(|message| {
                errors::scene_error(
                    py,
                    &inertance::scene::SceneError {
                        file: self.scene.file.clone(),
                        key: key.clone(),
                        value: Some(v.to_string()),
                        message,
                    },
                )
            })?;
        }
        Scene::new(
            py,
            doc.to_string(),
            &self.scene.file,
            None,
            self.symbols.clone(),
        )
    }

    /// The scene's `name`.
    #[getter]
    fn name(&self) -> &str {
        &self.scene.name
    }

    /// Where it came from, for messages.
    #[getter]
    fn file(&self) -> &str {
        &self.scene.file
    }

    /// The TOML text.
    #[getter]
    fn toml(&self) -> &str {
        &self.text
    }

    /// The symbols its values may name (derive).
    #[getter]
    fn symbols(&self) -> Vec<String> {
        self.symbols.clone()
    }

    /// Notes on likely slips (`note: …` lines, as the CLI prints them on stderr): angles in
    /// radians beside degrees, a density that suggests millimetres or grams. The scene is
    /// solved as written.
    #[getter]
    fn notes(&self) -> Vec<String> {
        self.scene.notes()
    }

    /// Number of contacts N.
    #[getter]
    fn contacts(&self) -> usize {
        self.scene.contacts.len()
    }

    /// Whether the scene is a system of several bodies (`[[body]]` tables): `solve` then
    /// gives a `SystemSolution`.
    #[getter]
    fn is_system(&self) -> bool {
        self.scene.system.is_some()
    }

    /// A system's bodies' names, in order; `None` for a one-body scene.
    #[getter]
    fn bodies(&self) -> Option<Vec<String>> {
        self.scene
            .system
            .as_ref()
            .map(|s| s.bodies.iter().map(|b| b.name.clone()).collect())
    }

    /// A system's number of `[[joint]]` tables; `None` for a one-body scene (its joints to
    /// the ground are `[constraints]`).
    #[getter]
    fn joints(&self) -> Option<usize> {
        self.scene.system.as_ref().map(|s| s.joints.len())
    }

    /// Every number by key path, as written.
    fn numbers(&self) -> Vec<(String, String)> {
        self.scene
            .numbers()
            .map(|(k, n)| (k, n.text.clone()))
            .collect()
    }

    fn __repr__(&self) -> String {
        match &self.scene.system {
            Some(s) => format!(
                "Scene({:?}, {} bodies, {} contacts, {} joints)",
                self.scene.name,
                s.bodies.len(),
                self.scene.contacts.len(),
                s.joints.len()
            ),
            None => format!(
                "Scene({:?}, {} contacts)",
                self.scene.name,
                self.scene.contacts.len()
            ),
        }
    }
}

/// The result of `solve`: the JSON report's keys as attributes (guide/solving.md, "JSON report").
#[pyclass(frozen, module = "inertance")]
struct Solution {
    report: Arc<Report>,
    mode: Mode,
    json: OnceLock<Json>,
}

impl Solution {
    fn json(&self) -> &Json {
        self.json.get_or_init(|| self.report.to_json())
    }

    fn key<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        match self.json().get(key) {
            Some(v) => json_to_py(py, v, self.mode, &[]),
            None => Ok(py.None().into_bound(py)),
        }
    }

    fn model(&self, name: &str) -> Option<ModelSolution> {
        let index = self
            .report
            .models
            .iter()
            .position(|m| m.model.name() == name)?;
        Some(ModelSolution {
            report: Arc::clone(&self.report),
            index,
            mode: self.mode,
            json: OnceLock::new(),
        })
    }
}

#[pymethods]
impl Solution {
    /// `"f64"` or `"exact"`.
    #[getter]
    fn scalar(&self) -> &str {
        self.report.scalar
    }
    /// The effects simulated, e.g. `["newton", "poisson"]`.
    #[getter]
    fn effects(&self) -> Vec<String> {
        self.report.effects.clone()
    }
    /// G = [g_ij,xx] (eq. 12).
    #[getter]
    fn inertance<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match convert::direct_matrix(py, &self.report.inertance, self.mode)? {
            Some(m) => Ok(m),
            None => self.key(py, "inertance"),
        }
    }
    /// [g_ij,yx] (eq. 127).
    #[getter]
    fn inertance_yx<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match convert::direct_matrix(py, &self.report.inertance_yx, self.mode)? {
            Some(m) => Ok(m),
            None => self.key(py, "inertance_yx"),
        }
    }
    /// [g_ij,zx] (eq. 128).
    #[getter]
    fn inertance_zx<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match convert::direct_matrix(py, &self.report.inertance_zx, self.mode)? {
            Some(m) => Ok(m),
            None => self.key(py, "inertance_zx"),
        }
    }
    /// Δ = det G.
    #[getter]
    fn det<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match convert::direct_value(py, &self.report.det, self.mode)? {
            Some(v) => Ok(v),
            None => self.key(py, "det"),
        }
    }
    /// Per contact: unit axes `x`, `y`, `z` and how the tangent was chosen (eq. 2–4, §12).
    #[getter]
    fn frames<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "frames")
    }
    /// Constrained scenes: `free` (D), `blocked` (U), `blocked_derived`, `reduced_mass` (eq. 83).
    #[getter]
    fn constraints<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "constraints")
    }
    /// Surface scenes: `f` and its `gradient` (§12).
    #[getter]
    fn surface<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "surface")
    }
    /// Scenes with friction (`mu`, `[solve] restitution`, §14): per law, the frictional
    /// readout — the `"friction"` object of the JSON report (impulses, modes, events,
    /// verdicts, or `error` and `status` for a law without an answer); `None` otherwise.
    #[getter]
    fn friction<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "friction")
    }
    /// One result per model solved, by name.
    #[getter]
    fn models(&self) -> Vec<(String, ModelSolution)> {
        self.report
            .models
            .iter()
            .filter_map(|m| {
                self.model(m.model.name())
                    .map(|s| (m.model.name().to_string(), s))
            })
            .collect()
    }
    /// The models (and frictional laws) without an answer while others have one, by name:
    /// `{"newton": {"error": "no admissible impulses: …", "status": "jammed"}}` (the CLI
    /// exits 4 then). Empty when every model answered.
    #[getter]
    fn failures<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        let failures = self
            .report
            .model_failures
            .iter()
            .map(|(m, e, s)| (m.name(), e, s))
            .chain(
                self.report
                    .friction_failures
                    .iter()
                    .map(|(l, e, s)| (l.name(), e, s)),
            );
        for (name, error, status) in failures {
            let d = PyDict::new(py);
            d.set_item("error", error)?;
            d.set_item("status", *status)?;
            out.set_item(name, d)?;
        }
        Ok(out)
    }
    /// Newton's law (eq. 14–20), if solved.
    #[getter]
    fn newton(&self) -> Option<ModelSolution> {
        self.model("newton")
    }
    /// Poisson's law (eq. 21–23), if solved.
    #[getter]
    fn poisson(&self) -> Option<ModelSolution> {
        self.model("poisson")
    }
    /// The report as the CLI's `--json` prints it (exact values as strings).
    fn to_json<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        plain(py, self.json())
    }
    fn __repr__(&self) -> String {
        let names: Vec<&str> = self.report.models.iter().map(|m| m.model.name()).collect();
        format!(
            "Solution({:?}, {}, models={names:?})",
            self.report.scene, self.report.scalar
        )
    }
}

/// JSON as plain Python values (dicts, lists, str, float, int, bool, None).
fn plain<'py>(py: Python<'py>, j: &Json) -> PyResult<Bound<'py, PyAny>> {
    let json = py.import("json")?;
    json.getattr("loads")?.call1((j.to_string(),))
}

/// One restitution model's results: the keys of `"models"."newton"` / `"poisson"`.
#[pyclass(frozen, module = "inertance")]
struct ModelSolution {
    report: Arc<Report>,
    index: usize,
    mode: Mode,
    json: OnceLock<Json>,
}

impl ModelSolution {
    fn report(&self) -> &inertance::report::ModelReport {
        &self.report.models[self.index]
    }

    /// Whether the solve computed `x` (`[solve] outputs`, `outputs=`): an output not asked
    /// for reads as `None`, never as the zero its empty slot would give.
    fn asked(&self, x: Outputs) -> bool {
        self.report.outputs.contains(x)
    }

    /// A key of this model's JSON, converted (`None` when absent).
    fn key<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        match self.json().get(key) {
            Some(v) => json_to_py(py, v, self.mode, &[]),
            None => Ok(py.None().into_bound(py)),
        }
    }

    /// This model's part of the report's JSON.
    fn json(&self) -> &Json {
        self.json.get_or_init(|| {
            let name = self.report().model.name();
            self.report.to_json()["models"][name].take()
        })
    }
}

macro_rules! model_keys {
    ($($(#[$doc:meta])* $name:ident),* $(,)?) => {
        #[pymethods]
        impl ModelSolution {
            $(
                $(#[$doc])*
                #[getter]
                fn $name<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                    self.key(py, stringify!($name))
                }
            )*
            /// This model's part of the CLI's JSON.
            fn to_json<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
                plain(py, self.json())
            }
            fn __repr__(&self) -> String {
                format!("ModelSolution({})", self.json())
            }
        }
    };
}

/// The numbers read straight from the report (no JSON built).
#[pymethods]
impl ModelSolution {
    /// P_i, N s (eq. 20, 23).
    #[getter]
    fn impulses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        if !self.asked(Outputs::IMPULSES) {
            return Ok(py.None().into_bound(py));
        }
        convert::values(py, &self.report().impulses, self.mode)
    }
    /// v_C after impact (eq. 24).
    #[getter]
    fn velocity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        if !self.asked(Outputs::TWIST) {
            return Ok(py.None().into_bound(py));
        }
        convert::values(py, &self.report().velocity, self.mode)
    }
    /// ω after impact (eq. 24).
    #[getter]
    fn angular_velocity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        if !self.asked(Outputs::TWIST) {
            return Ok(py.None().into_bound(py));
        }
        convert::values(py, &self.report().angular_velocity, self.mode)
    }
    /// E_p, the energy of lost velocities (eq. 28).
    #[getter]
    fn lost_velocity_energy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        if !self.asked(Outputs::ENERGIES) {
            return Ok(py.None().into_bound(py));
        }
        convert::value(py, &self.report().lost_velocity_energy, self.mode)
    }
    /// ΔE_c, the loss of kinetic energy (eq. 32).
    #[getter]
    fn kinetic_energy_loss<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        if !self.asked(Outputs::ENERGIES) {
            return Ok(py.None().into_bound(py));
        }
        convert::value(py, &self.report().kinetic_energy_loss, self.mode)
    }
    /// P̂_i = P_i / |n_i|: the impulse as a multiple of the normal as written.
    #[getter]
    fn impulses_per_normal<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        if !self.asked(Outputs::IMPULSES) {
            return Ok(py.None().into_bound(py));
        }
        match convert::direct_values(py, &self.report().impulse_multiples, self.mode)? {
            Some(v) => Ok(v),
            None => self.key(py, "impulses_per_normal"),
        }
    }
    /// P_i^c, Poisson only (eq. 22); `None` for Newton.
    #[getter]
    fn compression_impulses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        if !self.asked(Outputs::IMPULSES) {
            return Ok(py.None().into_bound(py));
        }
        let direct = match &self.report().compression_impulses {
            Some(c) => convert::direct_values(py, c, self.mode)?,
            None => None,
        };
        match direct {
            Some(v) => Ok(v),
            None => self.key(py, "compression_impulses"),
        }
    }
}

model_keys!(
    /// Per contact: velocity before and after in its frame, angles (eq. 8, 25–27).
    contacts,
    /// {q}, constrained bodies (eq. 90–93), in the basis of the blocked screws.
    constraint_impulses,
    /// U q as `force` (N s) and `moment` about C (N m s), constrained bodies.
    constraint_wrench,
    /// Per joint: `kind`, `about`, `point` (from C), `force`, `moment` about that point.
    joint_reactions,
    /// `"simultaneous"` or `"unilateral"`.
    law,
    /// False when the simultaneous answer is not physical.
    admissible,
    /// The reasons: dicts with `reason`, `contact`, `message`.
    inadmissible,
    /// Unilateral law: per contact, whether it takes an impulse.
    active,
    /// Unilateral law: whether the impulses are unique.
    impulses_unique,
    /// Unilateral law: False when Poisson's outcome is not decided.
    outcome_decided,
    /// Then: `twist_min`, `twist_max` over the compression impulses' vertices.
    outcome_range,
);

/// Solve in f64, exactly (rationals, or exact radicals when the scene has them) — as
/// `inertance solve` (`tolerance` as `--tolerance`).
fn run_scene(
    py: Python<'_>,
    scene: &Scene,
    models: Option<Vec<inertance::Model>>,
    law: Option<inertance::impact::unilateral::Law>,
    outputs: Option<Outputs>,
    tolerance: Option<f64>,
    exact: bool,
) -> Result<Report, RunError> {
    let changed;
    let law_changes = law.is_some_and(|l| l != scene.scene.law);
    let outputs_change = outputs.is_some_and(|o| o != scene.scene.outputs);
    let s = if law_changes || outputs_change || tolerance.is_some() {
        let mut c = scene.scene.clone();
        c.law = law.unwrap_or(c.law);
        c.outputs = outputs.unwrap_or(c.outputs);
        c.tolerance = tolerance.or(c.tolerance);
        changed = c;
        &changed
    } else {
        &scene.scene
    };
    let models = models.as_deref();
    if !exact {
        return match &scene.f64 {
            Some(p) => run_prepared_scaled(s, p, models),
            None => run::<f64>(s, models),
        }
        .map(|r| r.report);
    }
    py.allow_threads(|| {
        if s.is_rational() {
            run::<Exact>(s, models)
        } else {
            run::<RatFun>(s, models)
        }
    })
    .map(|r| r.report)
}

/// A `Solution`, or a `SystemSolution` for a scene of several bodies.
#[pyfunction]
#[pyo3(signature = (scene, model = None, law = None, exact = false, outputs = None, tolerance = None))]
fn solve(
    py: Python<'_>,
    scene: &Scene,
    model: Option<&Bound<'_, PyAny>>,
    law: Option<&str>,
    exact: bool,
    outputs: Option<&Bound<'_, PyAny>>,
    tolerance: Option<f64>,
) -> PyResult<PyObject> {
    let models = convert::models(model)?;
    let law = convert::law(law)?;
    let outputs = convert::outputs(outputs)?;
    let tolerance = convert::tolerance(tolerance)?;
    if law.unwrap_or(scene.scene.law) == inertance::impact::unilateral::Law::Lzb {
        lzb::refuse(exact, models.is_some(), outputs.is_some())?;
        return Ok(lzb::solve(py, scene, tolerance)?
            .into_pyobject(py)?
            .into_any()
            .unbind());
    }
    if scene.scene.system.is_some() {
        if outputs.is_some() {
            return Err(PyValueError::new_err(
                "outputs=: a system of bodies is solved and reported whole (as by `inertance \
                 solve`); outputs= selects the outputs of a one-body solve",
            ));
        }
        let solved = system::run(py, scene, models, law, tolerance, exact)
            .map_err(|e| errors::run_error(py, &e))?;
        return Ok(system::SystemSolution::new(solved, exact)
            .into_pyobject(py)?
            .into_any()
            .unbind());
    }
    let report = run_scene(py, scene, models, law, outputs, tolerance, exact)
        .map_err(|e| errors::run_error(py, &e))?;
    Ok(Solution {
        report: Arc::new(report),
        mode: if exact { Mode::Exact } else { Mode::F64 },
        json: OnceLock::new(),
    }
    .into_pyobject(py)?
    .into_any()
    .unbind())
}

#[pyfunction]
#[pyo3(signature = (scene, model = None, exact = false))]
fn analyze<'py>(
    py: Python<'py>,
    scene: &Scene,
    model: Option<&Bound<'_, PyAny>>,
    exact: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let models = convert::models(model)?;
    let s = &scene.scene;
    let report = py
        .allow_threads(|| {
            let m = models.as_deref();
            if exact && !s.is_rational() {
                lib_analyze::analyze_scene::<RatFun>(s, m)
            } else if exact {
                lib_analyze::analyze_scene::<Exact>(s, m)
            } else {
                lib_analyze::analyze_scene::<f64>(s, m)
            }
        })
        .map_err(|e| errors::run_error(py, &e))?;
    json_to_py(
        py,
        &report.to_json(),
        if exact { Mode::Exact } else { Mode::F64 },
        &[],
    )
}

#[pyfunction]
#[pyo3(signature = (directory = PathBuf::from("derivations")))]
fn check<'py>(py: Python<'py>, directory: PathBuf) -> PyResult<(bool, Bound<'py, PyList>, String)> {
    let results = py
        .allow_threads(|| lib_check::check_dir(&directory))
        .map_err(|e| errors::format_error(py, &e))?;
    let (text, passed) = lib_check::render(&results);
    let lines = PyList::empty(py);
    for f in &results {
        for l in &f.lines {
            let d = PyDict::new(py);
            d.set_item("file", f.path.display().to_string())?;
            d.set_item("case", &l.case)?;
            d.set_item("quantity", &l.quantity)?;
            d.set_item("printed", &l.printed)?;
            d.set_item("computed", &l.computed)?;
            d.set_item("identity", l.identity)?;
            let (verdict, reason) = match &l.verdict {
                lib_check::Verdict::Reproduced => ("reproduced", None),
                lib_check::Verdict::KnownErratum(r) => ("erratum", Some(r)),
                lib_check::Verdict::Fail(r) => ("fail", Some(r)),
            };
            d.set_item("verdict", verdict)?;
            d.set_item("reason", reason)?;
            lines.append(d)?;
        }
    }
    Ok((passed, lines, text))
}

#[pyfunction]
#[pyo3(signature = (scene, model = None))]
fn derive<'py>(
    py: Python<'py>,
    scene: &Scene,
    model: Option<&Bound<'_, PyAny>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>, String, String)> {
    let models = convert::models(model)?;
    // No symbols named: the scene's [params], as `inertance derive` takes them.
    let defaulted;
    let (s, symbols) = match scene.symbols.is_empty() {
        false => (&scene.scene, scene.symbols.clone()),
        true => {
            let symbols = lib_derive::default_symbols(&scene.doc, &[]);
            if symbols.is_empty() {
                return Err(errors::scene_error(
                    py,
                    &inertance::scene::SceneError {
                        file: scene.scene.file.clone(),
                        key: "params".into(),
                        value: None,
                        message: "derive needs symbols: give symbols=[…] (the names the scene's \
                                  values use as symbols), or declare [params], which derive takes \
                                  as symbols"
                            .into(),
                    },
                ));
            }
            defaulted = LibScene::from_document_with(&scene.doc, &scene.scene.file, &symbols)
                .map_err(|e| errors::scene_error(py, &e))?;
            (&defaulted, symbols)
        }
    };
    let d = py
        .allow_threads(|| lib_derive::derive(s, &symbols, models.as_deref()))
        .map_err(|e| errors::run_error(py, &e))?;
    let json = d.to_json();
    Ok((
        json_to_py(py, &json, Mode::Symbolic, &symbols)?,
        plain(py, &json)?,
        d.to_text(false),
        d.to_text(true),
    ))
}

/// A sweep's CSV columns by name. `shard = (i, n)` solves shard i of n only, the contiguous
/// block of global points `inertance sweep --shard i/n` solves (its `point` column global);
/// an empty shard (n greater than the grid's points) checks the sweep, solving nothing but the
/// corners the check solves, and gives the header's columns, empty.
#[pyfunction]
#[pyo3(signature = (scene, vary, exact = false, law = None, threads = None, shard = None))]
#[allow(clippy::too_many_arguments)]
fn sweep<'py>(
    py: Python<'py>,
    scene: &Scene,
    vary: Vec<(String, Bound<'py, PyAny>, Bound<'py, PyAny>, usize)>,
    exact: bool,
    law: Option<&str>,
    threads: Option<usize>,
    shard: Option<(usize, usize)>,
) -> PyResult<Bound<'py, PyDict>> {
    let law = convert::law(law)?;
    let shard = shard.map(|(index, count)| lib_sweep::Shard { index, count });
    let vary = vary
        .iter()
        .map(|(path, a, b, n)| {
            let spec = format!(
                "{path}={}:{}:{n}",
                convert::number_text(a)?,
                convert::number_text(b)?
            );
            lib_sweep::Vary::parse(&spec).map_err(|e| errors::sweep_error(py, &e))
        })
        .collect::<PyResult<Vec<_>>>()?;
    // One directory per call: calls on one scene from several threads (a thread pool's
    // tasks) must not share it.
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let dir = std::env::temp_dir().join(format!(
        "inertance-sweep-{}-{}",
        std::process::id(),
        CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
    ));
    std::fs::create_dir_all(&dir)?;
    let scene_file = match &scene.path {
        Some(p) => p.clone(),
        None => {
            let p = dir.join("scene.toml");
            std::fs::write(&p, &scene.text)?;
            p
        }
    };
    let opts = lib_sweep::SweepOptions {
        scene: scene_file,
        vary,
        exact,
        out: dir.join("sweep.csv"),
        threads: pool_threads(threads),
        law,
        shard,
        ..Default::default()
    };
    let done =
        py.allow_threads(|| lib_sweep::sweep(&opts).map(|_| std::fs::read_to_string(&opts.out)));
    let _ = std::fs::remove_dir_all(&dir);
    let csv = done.map_err(|e| errors::sweep_error(py, &e))??;
    convert::csv_columns(py, &csv)
}

/// The process that first ran a sweep or batch on rayon's global pool (their threads).
static GLOBAL_POOL_PID: OnceLock<u32> = OnceLock::new();

/// The threads of a parallel call: `threads` when given; in a process forked from one whose
/// global pool had started (the worker of a `fork` process pool, Linux's default before Python
/// 3.14), a pool of its own with a thread per core — the global pool's threads did not survive
/// the fork, and a call waiting on them would wait forever; otherwise `None`, the global pool.
fn pool_threads(threads: Option<usize>) -> Option<usize> {
    if threads.is_some_and(|n| n > 0) {
        return threads;
    }
    let pid = std::process::id();
    if *GLOBAL_POOL_PID.get_or_init(|| pid) == pid {
        return None;
    }
    Some(std::thread::available_parallelism().map_or(1, |n| n.get()))
}

/// A batch's arrays by model (and `status`). `offset`: the index of the first point in a
/// larger batch this one is a chunk of, so that an error names the point by its index there.
#[pyfunction]
#[pyo3(signature = (scene, vary, law = None, offset = 0))]
fn solve_batch<'py>(
    py: Python<'py>,
    scene: &Scene,
    vary: Vec<(String, Vec<f64>)>,
    law: Option<&str>,
    offset: usize,
) -> PyResult<Bound<'py, PyDict>> {
    let law = convert::law(law)?;
    let vary: Vec<lib_sweep::Varied> = vary
        .into_iter()
        .map(|(path, values)| lib_sweep::Varied { path, values })
        .collect();
    let (doc, file) = (&scene.doc, &scene.scene.file);
    let pool = pool_threads(None)
        .map(|n| rayon::ThreadPoolBuilder::new().num_threads(n).build())
        .transpose()
        .map_err(|e| {
            pyo3::exceptions::PyRuntimeError::new_err(format!(
                "cannot start the worker threads: {e}"
            ))
        })?;
    let b = py
        .allow_threads(|| match &pool {
            Some(pool) => pool.install(|| lib_sweep::solve_batch(doc, file, &vary, law)),
            None => lib_sweep::solve_batch(doc, file, &vary, law),
        })
        .map_err(|e| match e {
            lib_sweep::SweepError::Point { point, at, message } => lib_sweep::SweepError::Point {
                point: point + offset,
                at,
                message,
            },
            e => e,
        })
        .map_err(|e| errors::sweep_error(py, &e))?;
    let out = PyDict::new(py);
    let w = b.outputs.len();
    let friction = b.outputs.last().is_some_and(|o| o == "Ef");
    // Columns: P_1 … P_N, six per body (v_C then ω; one body's unnamed), E_p, ΔE_c (, E_f).
    let bodies = b.bodies.len();
    let n = w - 2 - 6 * bodies.max(1) - usize::from(friction);
    let e = w - 2 - usize::from(friction);
    for (m, values) in b.models.iter().zip(&b.values) {
        let d = PyDict::new(py);
        d.set_item("impulses", convert::columns(py, values, w, 0..n)?)?;
        if bodies == 0 {
            d.set_item("velocity", convert::columns(py, values, w, n..n + 3)?)?;
            d.set_item(
                "angular_velocity",
                convert::columns(py, values, w, n + 3..n + 6)?,
            )?;
        } else {
            let per_body = PyDict::new(py);
            for (k, name) in b.bodies.iter().enumerate() {
                let at = n + 6 * k;
                let body = PyDict::new(py);
                body.set_item("velocity", convert::columns(py, values, w, at..at + 3)?)?;
                body.set_item(
                    "angular_velocity",
                    convert::columns(py, values, w, at + 3..at + 6)?,
                )?;
                per_body.set_item(name, body)?;
            }
            d.set_item("bodies", per_body)?;
        }
        d.set_item("lost_velocity_energy", convert::column(py, values, w, e))?;
        d.set_item("kinetic_energy_loss", convert::column(py, values, w, e + 1))?;
        if friction {
            d.set_item(
                "friction_dissipation",
                convert::column(py, values, w, e + 2),
            )?;
        }
        out.set_item(m.name(), d)?;
    }
    out.set_item("status", b.status)?;
    Ok(out)
}

#[pymodule]
fn _inertance(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", inertance::VERSION)?;
    m.add_class::<Scene>()?;
    m.add_class::<Solution>()?;
    m.add_class::<ModelSolution>()?;
    m.add_class::<system::SystemSolution>()?;
    m.add_class::<system::SystemModelSolution>()?;
    m.add_class::<lzb::LzbSolution>()?;
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(analyze, m)?)?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    m.add_function(wrap_pyfunction!(derive, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(solve_batch, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::simulate, m)?)?;
    errors::register(m)?;
    Ok(())
}
