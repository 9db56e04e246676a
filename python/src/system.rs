//! Systems of bodies (`[[body]]` tables): `solve` on such a scene gives a [`SystemSolution`],
//! read from the library's [`SystemReport`] (`inertance::scene::system_pipeline::run_system`,
//! the CLI's `solve` on the same scene). Per body its twist after impact about its own centre
//! of mass in world axes, per joint its reaction on its first body at its anchor, per contact
//! the impulse P_i (−P_i n_i on the first body, +P_i n_i on the second) and the relative
//! velocity in the contact's frame; the system's E_p (eq. 28) and ΔE_c (eq. 32) and, for a
//! free system, its momentum before and after. Values convert as for one body
//! (`convert.rs`): f64 as floats and numpy arrays, exactly as `Fraction`s (radicals strings).

use std::sync::{Arc, OnceLock};

use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::{PyIndexError, PyKeyError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyList, PyString};
use serde_json::Value as Json;

use inertance::impact::unilateral::Law;
use inertance::report::Value;
use inertance::report::system::{SystemModelReport, SystemReport};
use inertance::scalar::Exact;
use inertance::scalar::symbolic::RatFun;
use inertance::scene::pipeline::RunError;
use inertance::scene::system_pipeline::{SolvedSystem, run_system};

use crate::convert::{self, Mode, json_to_py};
use crate::{Scene, plain};

/// Solve the system scene `scene` as `inertance solve` does (`law` and `tolerance` override
/// the scene's); exact in rationals, or exact radicals when the scene has them.
pub fn run(
    py: Python<'_>,
    scene: &Scene,
    models: Option<Vec<inertance::Model>>,
    law: Option<Law>,
    tolerance: Option<f64>,
    exact: bool,
) -> Result<SolvedSystem, RunError> {
    let changed;
    let s = if law.is_some_and(|l| l != scene.scene.law) || tolerance.is_some() {
        let mut c = scene.scene.clone();
        c.law = law.unwrap_or(c.law);
        c.tolerance = tolerance.or(c.tolerance);
        changed = c;
        &changed
    } else {
        &scene.scene
    };
    let models = models.as_deref();
    if !exact {
        return run_system::<f64>(s, models);
    }
    py.allow_threads(|| {
        if s.is_rational() {
            run_system::<Exact>(s, models)
        } else {
            run_system::<RatFun>(s, models)
        }
    })
}

/// A vector of three values: a numpy array in f64, a list of exact values otherwise.
fn vector<'py>(py: Python<'py>, v: &[Value; 3], mode: Mode) -> PyResult<Bound<'py, PyAny>> {
    convert::values(py, v, mode)
}

/// Rows of three values: an (R, 3) numpy array in f64, a list of lists of exact values
/// otherwise.
fn rows<'py, 'a>(
    py: Python<'py>,
    rows: impl ExactSizeIterator<Item = &'a [Value; 3]>,
    mode: Mode,
) -> PyResult<Bound<'py, PyAny>> {
    let n = rows.len();
    if mode == Mode::F64 {
        let flat: Vec<f64> = rows.flat_map(|r| r.iter().map(|v| v.f64)).collect();
        return Ok(PyArray1::from_vec(py, flat).reshape([n, 3])?.into_any());
    }
    let list = PyList::empty(py);
    for r in rows {
        list.append(vector(py, r, mode)?)?;
    }
    Ok(list.into_any())
}

/// `{"linear": p, "angular": L about the origin}`.
fn momentum<'py>(
    py: Python<'py>,
    (p, l): &([Value; 3], [Value; 3]),
    mode: Mode,
) -> PyResult<Bound<'py, PyAny>> {
    let d = PyDict::new(py);
    d.set_item("linear", vector(py, p, mode)?)?;
    d.set_item("angular", vector(py, l, mode)?)?;
    Ok(d.into_any())
}

/// The bodies a contact or joint joins, by name (one name: an obstacle or the ground).
fn pair<'py>(
    py: Python<'py>,
    first: &str,
    second: &Option<String>,
) -> PyResult<Bound<'py, PyList>> {
    let names: Vec<&str> = std::iter::once(first).chain(second.as_deref()).collect();
    PyList::new(py, names)
}

/// The result of `solve` on a system scene: the system's JSON report as attributes
/// (guide/python.md, "Systems").
#[pyclass(frozen, module = "inertance")]
pub struct SystemSolution {
    solved: Arc<SolvedSystem>,
    mode: Mode,
    json: OnceLock<Json>,
}

impl SystemSolution {
    pub fn new(solved: SolvedSystem, exact: bool) -> SystemSolution {
        SystemSolution {
            solved: Arc::new(solved),
            mode: if exact { Mode::Exact } else { Mode::F64 },
            json: OnceLock::new(),
        }
    }

    fn report(&self) -> &SystemReport {
        &self.solved.report
    }

    fn model(&self, name: &str) -> Option<SystemModelSolution> {
        let index = self
            .report()
            .models
            .iter()
            .position(|m| m.model.name() == name)?;
        Some(SystemModelSolution {
            solved: Arc::clone(&self.solved),
            index,
            mode: self.mode,
            json: OnceLock::new(),
        })
    }
}

#[pymethods]
impl SystemSolution {
    /// The scene's name.
    #[getter]
    fn scene(&self) -> &str {
        &self.report().scene
    }
    /// `"f64"` or `"exact"`.
    #[getter]
    fn scalar(&self) -> &str {
        self.report().scalar
    }
    /// The effects simulated, e.g. `["joints", "newton", "poisson"]`.
    #[getter]
    fn effects(&self) -> Vec<String> {
        self.report().effects.clone()
    }
    /// The bodies' names, in the scene's order (the rows of `velocities`).
    #[getter]
    fn bodies(&self) -> Vec<String> {
        self.report().bodies.clone()
    }
    /// G = [g_ij,xx] (eq. 12) of the system, 1/kg.
    #[getter]
    fn inertance<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        match convert::direct_matrix(py, &self.report().inertance, self.mode)? {
            Some(m) => Ok(m),
            None => json_to_py(py, &self.to_json_value()["inertance"], self.mode, &[]),
        }
    }
    /// Δ = det G.
    #[getter]
    fn det<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::value(py, &self.report().det, self.mode)
    }
    /// Whether no obstacle and no joint to the ground acts on the system (its momentum is then
    /// conserved).
    #[getter]
    fn free(&self) -> bool {
        self.report().free
    }
    /// `{"linear": Σ m_b v_Cb, "angular": Σ (J_b ω_b + C_b × m_b v_Cb)}` before impact (about
    /// the world origin).
    #[getter]
    fn momentum_before<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        momentum(py, &self.report().momentum_before, self.mode)
    }
    /// Each body's kinetic energy before impact, J.
    #[getter]
    fn kinetic_energies_before<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::values(py, &self.report().kinetic_energy_before, self.mode)
    }
    /// Per contact: `bodies` (one name: against an obstacle), `normal` (out of the first body)
    /// and `velocity_before` (relative, in the contact's frame; v_x > 0 approaching).
    #[getter]
    fn contacts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let r = self.report();
        let list = PyList::empty(py);
        for (((a, b), (axes, _)), before) in r.pairs.iter().zip(&r.frames).zip(&r.contacts_before) {
            let d = PyDict::new(py);
            d.set_item("bodies", pair(py, a, b)?)?;
            d.set_item("normal", vector(py, &axes[0], self.mode)?)?;
            d.set_item(
                "velocity_before",
                vector(py, &before.components, self.mode)?,
            )?;
            list.append(d)?;
        }
        Ok(list)
    }
    /// Per joint: `kind` and `bodies` (one name: to the ground).
    #[getter]
    fn joints<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for (kind, a, b) in &self.report().joints {
            let d = PyDict::new(py);
            d.set_item("kind", *kind)?;
            d.set_item("bodies", pair(py, a, b)?)?;
            list.append(d)?;
        }
        Ok(list)
    }
    /// One result per model solved, by name.
    #[getter]
    fn models(&self) -> Vec<(String, SystemModelSolution)> {
        self.report()
            .models
            .iter()
            .filter_map(|m| {
                let name = m.model.name();
                self.model(name).map(|s| (name.to_string(), s))
            })
            .collect()
    }
    /// The models without an answer while others have one (the unilateral law's jams), by
    /// name: `{"newton": {"error": …, "status": "jammed"}}` (the CLI exits 4 then).
    #[getter]
    fn failures<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        for (model, error, status) in &self.report().model_failures {
            let d = PyDict::new(py);
            d.set_item("error", error)?;
            d.set_item("status", *status)?;
            out.set_item(model.name(), d)?;
        }
        Ok(out)
    }
    /// Newton's law (eq. 14–20), if solved.
    #[getter]
    fn newton(&self) -> Option<SystemModelSolution> {
        self.model("newton")
    }
    /// Poisson's law (eq. 21–23), if solved.
    #[getter]
    fn poisson(&self) -> Option<SystemModelSolution> {
        self.model("poisson")
    }
    /// The report as the CLI's `--json` prints it (exact values as strings).
    fn to_json<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        plain(py, self.to_json_value())
    }
    fn __repr__(&self) -> String {
        let r = self.report();
        let names: Vec<&str> = r.models.iter().map(|m| m.model.name()).collect();
        format!(
            "SystemSolution({:?}, {}, bodies={:?}, models={names:?})",
            r.scene, r.scalar, r.bodies
        )
    }
}

impl SystemSolution {
    fn to_json_value(&self) -> &Json {
        self.json.get_or_init(|| self.report().to_json())
    }
}

/// One restitution model's results for a system: the keys of the JSON report's
/// `models.<name>`, with each body's twist by name or index.
#[pyclass(frozen, module = "inertance")]
pub struct SystemModelSolution {
    solved: Arc<SolvedSystem>,
    index: usize,
    mode: Mode,
    json: OnceLock<Json>,
}

impl SystemModelSolution {
    fn report(&self) -> &SystemModelReport {
        &self.solved.report.models[self.index]
    }

    fn json(&self) -> &Json {
        self.json.get_or_init(|| {
            let name = self.report().model.name();
            self.solved.report.to_json()["models"][name].take()
        })
    }

    /// A key of this model's JSON, converted (`None` when absent).
    fn key<'py>(&self, py: Python<'py>, key: &str) -> PyResult<Bound<'py, PyAny>> {
        match self.json().get(key) {
            Some(v) => json_to_py(py, v, self.mode, &[]),
            None => Ok(py.None().into_bound(py)),
        }
    }

    /// The index of `body`: a name of the scene's bodies, or an index into them.
    fn body(&self, body: &Bound<'_, PyAny>) -> PyResult<usize> {
        let names = &self.solved.report.bodies;
        if body.is_instance_of::<PyString>() {
            let name: String = body.extract()?;
            return names.iter().position(|n| *n == name).ok_or_else(|| {
                PyKeyError::new_err(format!(
                    "no body named {name:?}; the bodies are {}",
                    names
                        .iter()
                        .map(|n| format!("{n:?}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ))
            });
        }
        if body.is_instance_of::<PyBool>() {
            return Err(PyTypeError::new_err(
                "a body is named by its name (str) or its index (int), not a bool",
            ));
        }
        let Ok(i) = body.extract::<i64>() else {
            return Err(PyTypeError::new_err(format!(
                "a body is named by its name (str) or its index (int), not {}",
                body.get_type().name()?
            )));
        };
        usize::try_from(i)
            .ok()
            .filter(|&i| i < names.len())
            .ok_or_else(|| {
                PyIndexError::new_err(format!(
                    "body {i}: the scene has {} bodies, indexed 0 to {}",
                    names.len(),
                    names.len() - 1
                ))
            })
    }
}

#[pymethods]
impl SystemModelSolution {
    /// P_i along each contact's normal as written, N s (eq. 20, 23): −P_i n_i on the contact's
    /// first body, +P_i n_i on its second.
    #[getter]
    fn impulses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::values(py, &self.report().impulses, self.mode)
    }
    /// P_i^c, Poisson only (eq. 22); `None` for Newton.
    #[getter]
    fn compression_impulses<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.report()
            .compression_impulses
            .as_ref()
            .map(|c| convert::values(py, c, self.mode))
            .transpose()
    }
    /// v_C of `body` (a name or an index) after impact, world axes, m/s.
    fn velocity<'py>(
        &self,
        py: Python<'py>,
        body: &Bound<'_, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let b = self.body(body)?;
        vector(py, &self.report().twists[b].1, self.mode)
    }
    /// ω of `body` (a name or an index) after impact, world axes, rad/s.
    fn angular_velocity<'py>(
        &self,
        py: Python<'py>,
        body: &Bound<'_, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let b = self.body(body)?;
        vector(py, &self.report().twists[b].0, self.mode)
    }
    /// Every body's v_C after impact: a (B, 3) numpy array in f64, B lists of three
    /// `Fraction`s exactly; rows in the order of `bodies`.
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        rows(py, self.report().twists.iter().map(|t| &t.1), self.mode)
    }
    /// Every body's ω after impact, as `velocities`.
    #[getter]
    fn angular_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        rows(py, self.report().twists.iter().map(|t| &t.0), self.mode)
    }
    /// Each body's kinetic energy after impact, J.
    #[getter]
    fn kinetic_energies<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::values(py, &self.report().kinetic_energy_after, self.mode)
    }
    /// E_p, the system's energy of lost velocities (eq. 28).
    #[getter]
    fn lost_velocity_energy<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::value(py, &self.report().lost_velocity_energy, self.mode)
    }
    /// ΔE_c, the system's loss of kinetic energy (eq. 32).
    #[getter]
    fn kinetic_energy_loss<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::value(py, &self.report().kinetic_energy_loss, self.mode)
    }
    /// Per joint: `kind`, `bodies` (one name: to the ground), and its reaction on its first
    /// body as `force` (N s) and `moment` (N m s) about its `anchor` (world; the origin for a
    /// joint without one). The second body takes the opposite.
    #[getter]
    fn joint_reactions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for ((kind, a, b), w) in self
            .solved
            .report
            .joints
            .iter()
            .zip(&self.report().joint_reactions)
        {
            let d = PyDict::new(py);
            d.set_item("kind", *kind)?;
            d.set_item("bodies", pair(py, a, b)?)?;
            d.set_item("anchor", vector(py, &w.point, self.mode)?)?;
            d.set_item("force", vector(py, &w.force, self.mode)?)?;
            d.set_item("moment", vector(py, &w.moment, self.mode)?)?;
            list.append(d)?;
        }
        Ok(list)
    }
    /// `{"linear", "angular"}` after impact, as `momentum_before`.
    #[getter]
    fn momentum_after<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        momentum(py, &self.report().momentum_after, self.mode)
    }
    /// Each contact's relative velocity after impact in its frame, (v_x, v_y, v_z) with x the
    /// normal (v_x > 0 approaching): an (N, 3) numpy array in f64, lists of `Fraction`s exactly.
    #[getter]
    fn contact_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        rows(
            py,
            self.report().contacts.iter().map(|c| &c.components),
            self.mode,
        )
    }
    /// Whether ΔE_c = −E_p + Σ P_i v_ix⁰ (eq. 34) held: exactly in exact mode, to rounding in
    /// f64 (the CLI warns when it does not).
    #[getter]
    fn energy_identity(&self) -> bool {
        self.solved.energy_identity[self.index]
    }
    /// Whether a free system's momentum after equals its momentum before (always true when
    /// the system is not free): exactly in exact mode, to rounding in f64.
    #[getter]
    fn momentum_conserved(&self) -> bool {
        self.solved.momentum_conserved[self.index]
    }
    /// `"simultaneous"` or `"unilateral"`.
    #[getter]
    fn law(&self) -> &'static str {
        self.report().law.name()
    }
    /// False when the answer is not physical (reasons in `inadmissible`).
    #[getter]
    fn admissible(&self) -> bool {
        self.report().inadmissible.is_empty()
    }
    /// Why the answer is not physical: dicts with `reason`, `message`.
    #[getter]
    fn inadmissible<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "inadmissible")
    }
    /// Unilateral law: per contact, whether it takes an impulse; `None` otherwise.
    #[getter]
    fn active<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "active")
    }
    /// Per contact: `velocity` after impact in its frame and its tangential angle `angle_deg`.
    #[getter]
    fn contacts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.key(py, "contacts")
    }
    /// This model's part of the CLI's JSON.
    fn to_json<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        plain(py, self.json())
    }
    fn __repr__(&self) -> String {
        format!("SystemModelSolution({})", self.json())
    }
}
