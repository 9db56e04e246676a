//! `inertance.simulate`: a sequence of impacts (`inertance simulate`) from Python — the run's
//! log as `simulate --json` has it, and its samples as numpy arrays.

use numpy::{PyArray1, PyArray2, PyArray3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use inertance::report::simulation;
use inertance::scene::AnySimulation;
use inertance::simulate::run::{Sample, simulate_history};
use inertance::simulate::system::simulate_system;

use crate::errors;

/// Run the scene `text` (read as the file `file`), or the file `file` when `text` is `None`,
/// under `law` when given: a dict with
/// `"log"` (the JSON report of `inertance simulate --json`, as text: the caller parses it, so
/// that the numbers are the command's) and `"samples"`
/// (numpy arrays, one row per sample). One body: `t` (N,), `x`, `v`, `omega` (N, 3), `q`
/// (N, 4: w, i, j, k, body → world), `kinetic`, `potential` (N,), `closed` (N,). A system:
/// `t`, `x`, `v` and `omega` (N, B, 3), `q` (N, B, 4; a sphere's held), `kinetic`,
/// `potential`, `closed`, and `"bodies"`, the members' names in that order.
#[pyfunction]
#[pyo3(signature = (text, file, law = None))]
pub fn simulate<'py>(
    py: Python<'py>,
    text: Option<&str>,
    file: &str,
    law: Option<&str>,
) -> PyResult<Bound<'py, PyDict>> {
    let scene = match text {
        Some(text) => AnySimulation::parse(text, file),
        None => AnySimulation::load(std::path::Path::new(file)),
    }
    .map_err(|e| errors::scene_error(py, &e))?;
    let chosen = |l: inertance::simulate::Law| -> PyResult<inertance::simulate::Law> {
        match law {
            None => Ok(l),
            Some(name) => l.chosen(name).map_err(|m| {
                pyo3::exceptions::PyValueError::new_err(format!("{file}: law = {name:?}: {m}"))
            }),
        }
    };
    let out = PyDict::new(py);
    match scene {
        AnySimulation::Body(mut s) => {
            s.setup.law = chosen(s.setup.law)?;
            let sim = py.allow_threads(|| simulate_history(&s.setup));
            let log = simulation::to_json(&s.name, &s.setup, &sim);
            out.set_item("log", log.to_string())?;
            out.set_item("samples", body_samples(py, &sim.samples)?)?;
        }
        AnySimulation::System(mut s) => {
            s.setup.law = chosen(s.setup.law)?;
            let sim = py.allow_threads(|| simulate_system(&s.setup));
            let log = inertance::report::simulation_system::to_json(&s.name, &s.setup, &sim);
            out.set_item("log", log.to_string())?;
            let d = PyDict::new(py);
            let n = sim.samples.len();
            let b = s.setup.members.len();
            let per = |f: &dyn Fn(
                &inertance::simulate::system::SystemSample,
            ) -> &Vec<inertance::simulate::body::V3>|
             -> Vec<Vec<Vec<f64>>> {
                sim.samples
                    .iter()
                    .map(|smp| f(smp).iter().map(|v| vec![v.x, v.y, v.z]).collect())
                    .collect()
            };
            d.set_item(
                "t",
                PyArray1::from_iter(py, sim.samples.iter().map(|s| s.t)),
            )?;
            if n > 0 {
                d.set_item("x", PyArray3::from_vec3(py, &per(&|s| &s.state.x))?)?;
                d.set_item("v", PyArray3::from_vec3(py, &per(&|s| &s.state.v))?)?;
                d.set_item("omega", PyArray3::from_vec3(py, &per(&|s| &s.state.w))?)?;
                let q: Vec<Vec<Vec<f64>>> = sim
                    .samples
                    .iter()
                    .map(|smp| {
                        smp.state
                            .q
                            .iter()
                            .map(|q| {
                                let q = q.quaternion();
                                vec![q.w, q.i, q.j, q.k]
                            })
                            .collect()
                    })
                    .collect();
                d.set_item("q", PyArray3::from_vec3(py, &q)?)?;
            } else {
                d.set_item("x", PyArray3::<f64>::zeros(py, [0, b, 3], false))?;
                d.set_item("v", PyArray3::<f64>::zeros(py, [0, b, 3], false))?;
                d.set_item("omega", PyArray3::<f64>::zeros(py, [0, b, 3], false))?;
                d.set_item("q", PyArray3::<f64>::zeros(py, [0, b, 4], false))?;
            }
            d.set_item(
                "kinetic",
                PyArray1::from_iter(py, sim.samples.iter().map(|s| s.kinetic)),
            )?;
            d.set_item(
                "potential",
                PyArray1::from_iter(py, sim.samples.iter().map(|s| s.potential)),
            )?;
            d.set_item(
                "closed",
                PyArray1::from_iter(py, sim.samples.iter().map(|s| s.closed as i64)),
            )?;
            out.set_item("samples", d)?;
            let names: Vec<String> = s.setup.members.iter().map(|s| s.name.clone()).collect();
            out.set_item("bodies", names)?;
        }
    }
    Ok(out)
}

/// One body's samples as arrays.
fn body_samples<'py>(py: Python<'py>, samples: &[Sample]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let rows = |f: &dyn Fn(&Sample) -> Vec<f64>, width: usize| -> PyResult<Bound<'py, PyAny>> {
        if samples.is_empty() {
            return Ok(PyArray2::<f64>::zeros(py, [0, width], false).into_any());
        }
        let v: Vec<Vec<f64>> = samples.iter().map(f).collect();
        Ok(PyArray2::from_vec2(py, &v)?.into_any())
    };
    d.set_item("t", PyArray1::from_iter(py, samples.iter().map(|s| s.t)))?;
    d.set_item(
        "x",
        rows(&|s| vec![s.state.x.x, s.state.x.y, s.state.x.z], 3)?,
    )?;
    d.set_item(
        "q",
        rows(
            &|s| {
                let q = s.state.q.quaternion();
                vec![q.w, q.i, q.j, q.k]
            },
            4,
        )?,
    )?;
    d.set_item(
        "v",
        rows(&|s| vec![s.state.v.x, s.state.v.y, s.state.v.z], 3)?,
    )?;
    d.set_item(
        "omega",
        rows(&|s| vec![s.state.w.x, s.state.w.y, s.state.w.z], 3)?,
    )?;
    d.set_item(
        "kinetic",
        PyArray1::from_iter(py, samples.iter().map(|s| s.kinetic)),
    )?;
    d.set_item(
        "potential",
        PyArray1::from_iter(py, samples.iter().map(|s| s.potential)),
    )?;
    d.set_item(
        "closed",
        PyArray1::from_iter(py, samples.iter().map(|s| s.closed as i64)),
    )?;
    Ok(d)
}
