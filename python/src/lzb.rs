//! The LZB multiple-impact law (`solve(scene, law="lzb")` or a scene with `[solve] law =
//! "lzb"`): an [`LzbSolution`] read from the library's [`LzbReport`]
//! (`inertance::scene::lzb::run_lzb`, what `inertance solve` prints). Contacts are numbered
//! from 0 here (indices into the arrays); the JSON of `to_json()` numbers them from 1, as the
//! command line does.

use std::sync::Arc;

use numpy::{PyArray1, PyArray2};
use pyo3::exceptions::{PyKeyError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use inertance::impact::unilateral::Law;
use inertance::scene::lzb::{LzbReport, run_lzb};
use inertance::scene::pipeline::RunError;

use crate::{Scene, errors, plain};

/// Solve `scene` under the LZB law (GIL released), `tolerance` overriding the scene's.
pub fn solve(py: Python<'_>, scene: &Scene, tolerance: Option<f64>) -> PyResult<LzbSolution> {
    let mut s = scene.scene.clone();
    if s.law != Law::Lzb {
        s.set_law(Law::Lzb, "law=\"lzb\"")
            .map_err(|e| errors::run_error(py, &RunError::Scene(e)))?;
    }
    s.tolerance = tolerance.or(s.tolerance);
    let report = py
        .allow_threads(|| run_lzb(&s))
        .map_err(|e| errors::run_error(py, &e))?;
    Ok(LzbSolution {
        report: Arc::new(report),
    })
}

/// Refuse the arguments of `solve` that the LZB law does not take.
pub fn refuse(exact: bool, model: bool, outputs: bool) -> PyResult<()> {
    let refused = if exact {
        "exact=True: the LZB law is integrated numerically (adaptive Runge–Kutta in f64), so \
         its result is never exact: drop exact="
    } else if model {
        "model=: the LZB law has no Newton or Poisson model (its restitution is each contact's \
         energetic coefficient, `k_energetic` or `k`): drop model="
    } else if outputs {
        "outputs=: the LZB law's outputs are reported whole: drop outputs="
    } else {
        return Ok(());
    };
    Err(PyValueError::new_err(refused))
}

/// The outcome of an impact under the LZB law (Liu, Zhao & Brogliato 2008): per contact
/// (index i from 0) its law, impulse, velocity after, works and largest potential energy; each
/// body's twist after impact; ΔE_c; the events; and the impulse history, one sample per
/// accepted step of the integration.
#[pyclass(frozen, module = "inertance")]
pub struct LzbSolution {
    report: Arc<LzbReport>,
}

fn array<'py>(py: Python<'py>, v: &[f64]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v)
}

#[pymethods]
impl LzbSolution {
    /// The scene's name.
    #[getter]
    fn scene(&self) -> String {
        self.report.name.clone()
    }

    /// `"lzb"`.
    #[getter]
    fn law(&self) -> &'static str {
        "lzb"
    }

    /// K_i per contact.
    #[getter]
    fn stiffness<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let v: Vec<f64> = self.report.laws.iter().map(|l| l.stiffness).collect();
        array(py, &v)
    }

    /// η_i per contact (1 linear, 1.5 Hertz).
    #[getter]
    fn exponent<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let v: Vec<f64> = self.report.laws.iter().map(|l| l.exponent).collect();
        array(py, &v)
    }

    /// e_i per contact: Stronge's energetic coefficient of restitution.
    #[getter]
    fn restitution<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let v: Vec<f64> = self.report.laws.iter().map(|l| l.restitution).collect();
        array(py, &v)
    }

    /// v_i⁰ per contact (m/s, positive approaching).
    #[getter]
    fn velocities_before<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, &self.report.before)
    }

    /// P_i per contact, along the unit normal (N s).
    #[getter]
    fn impulses<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, &self.report.impulses)
    }

    /// v_i after impact per contact (m/s, positive approaching).
    #[getter]
    fn velocities_after<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, &self.report.after)
    }

    /// The largest potential energy each contact held (J).
    #[getter]
    fn max_energies<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, &self.report.max_energy)
    }

    /// W_c,i: the energy each contact stored over its compression phases (J).
    #[getter]
    fn work_compression<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, &self.report.work_compression)
    }

    /// W_r,i: the energy each contact gave back over its expansion phases (J).
    #[getter]
    fn work_expansion<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, &self.report.work_expansion)
    }

    /// W_c,i − W_r,i: the energy dissipated at each contact (J).
    #[getter]
    fn dissipation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let r = &self.report;
        let v: Vec<f64> = (0..r.impulses.len())
            .map(|i| r.work_compression[i] - r.work_expansion[i])
            .collect();
        array(py, &v)
    }

    /// Each contact's tangential impulse τ (N s; empty for a frictionless contact, one entry in
    /// a plane, two in space).
    #[getter]
    fn tangential_impulses(&self) -> Vec<Vec<f64>> {
        self.report.tangential.clone()
    }

    /// The energy friction dissipated at each contact, W_f (J).
    #[getter]
    fn friction_dissipation<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        array(py, &self.report.friction_dissipation)
    }

    /// The bodies' names, in the order of `velocities` (`["body"]` for one body).
    #[getter]
    fn bodies(&self) -> Vec<String> {
        self.report.twists.iter().map(|t| t.0.clone()).collect()
    }

    /// v_C after impact, one row per body (m/s).
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<Vec<f64>> = self.report.twists.iter().map(|t| t.2.to_vec()).collect();
        Ok(PyArray2::from_vec2(py, &rows)?)
    }

    /// ω after impact, one row per body (rad/s).
    #[getter]
    fn angular_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let rows: Vec<Vec<f64>> = self.report.twists.iter().map(|t| t.1.to_vec()).collect();
        Ok(PyArray2::from_vec2(py, &rows)?)
    }

    /// v_C after impact of the body named `body` (or at index `body`).
    fn velocity<'py>(
        &self,
        py: Python<'py>,
        body: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let b = self.body(body)?;
        Ok(array(py, &self.report.twists[b].2))
    }

    /// ω after impact of the body named `body` (or at index `body`).
    fn angular_velocity<'py>(
        &self,
        py: Python<'py>,
        body: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let b = self.body(body)?;
        Ok(array(py, &self.report.twists[b].1))
    }

    /// ΔE_c = T⁰ − T (J).
    #[getter]
    fn kinetic_energy_loss(&self) -> f64 {
        self.report.kinetic_energy_loss
    }

    /// ΔE_c − Σ_i (W_c,i − W_r,i): zero but for the integration's error (J).
    #[getter]
    fn energy_residual(&self) -> f64 {
        self.report.energy_residual
    }

    /// The events, in order: dicts `{"tau", "contact" (from 0), "kind"}`.
    #[getter]
    fn events<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        let list = PyList::empty(py);
        for e in &self.report.events {
            let d = PyDict::new(py);
            d.set_item("tau", e.tau)?;
            d.set_item("contact", e.contact)?;
            d.set_item("kind", e.kind.name())?;
            list.append(d)?;
        }
        Ok(list)
    }

    /// The contacts (from 0) in the order they came to rest.
    #[getter]
    fn ending_order(&self) -> Vec<usize> {
        self.report.ending_order.clone()
    }

    /// The impulses' estimated error (N s).
    #[getter]
    fn error_estimate(&self) -> f64 {
        self.report.error_estimate
    }

    /// The relative tolerance the steps were held to.
    #[getter]
    fn tolerance(&self) -> f64 {
        self.report.tolerance
    }

    /// `{"accepted_steps", "rejected_steps", "events"}`.
    #[getter]
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("accepted_steps", self.report.stats.accepted)?;
        d.set_item("rejected_steps", self.report.stats.rejected)?;
        d.set_item("events", self.report.stats.events)?;
        Ok(d)
    }

    /// The impulse history, one entry per sample: `tau` (S,), `primary` (S,, the primary
    /// contact from 0), `impulses`, `velocities`, `energies` (S × N: P_i, v_i, E_i).
    #[getter]
    fn history<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = &self.report.samples;
        let d = PyDict::new(py);
        let tau: Vec<f64> = s.iter().map(|x| x.tau).collect();
        let primary: Vec<i64> = s.iter().map(|x| x.primary as i64).collect();
        d.set_item("tau", array(py, &tau))?;
        d.set_item("primary", PyArray1::from_vec(py, primary))?;
        let n = self.report.impulses.len();
        let rows = |f: fn(&inertance::impact::multiple::Sample) -> &Vec<f64>| {
            let m: Vec<Vec<f64>> = s.iter().map(|x| f(x).clone()).collect();
            if m.is_empty() {
                PyArray2::from_vec2(py, &[vec![0.0; n]; 0])
            } else {
                PyArray2::from_vec2(py, &m)
            }
        };
        d.set_item("impulses", rows(|x| &x.impulses)?)?;
        d.set_item("velocities", rows(|x| &x.velocities)?)?;
        d.set_item("energies", rows(|x| &x.energies)?)?;
        Ok(d)
    }

    /// The JSON report of `inertance solve --json` (contacts numbered from 1), as a dict.
    fn to_json<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        plain(py, &self.report.to_json())
    }

    fn __repr__(&self) -> String {
        format!(
            "LzbSolution(scene={:?}, impulses={:?})",
            self.report.name, self.report.impulses
        )
    }
}

impl LzbSolution {
    /// A body by name or index.
    fn body(&self, body: &Bound<'_, PyAny>) -> PyResult<usize> {
        let names = &self.report.twists;
        if let Ok(i) = body.extract::<usize>() {
            return if i < names.len() {
                Ok(i)
            } else {
                Err(PyKeyError::new_err(format!(
                    "body {i}: there are {} bodies",
                    names.len()
                )))
            };
        }
        let name: String = body.extract()?;
        names.iter().position(|t| t.0 == name).ok_or_else(|| {
            PyKeyError::new_err(format!(
                "body {name:?}: not one of {:?}",
                names.iter().map(|t| &t.0).collect::<Vec<_>>()
            ))
        })
    }
}
