//! The library's errors as Python exceptions, in one place.
//!
//! `InertanceError` is the base. `SceneError` (bad input: file, key, value, message — the
//! CLI's exit status 2) carries the library's [`SceneError`] fields as attributes;
//! `SolveError` (no answer: Δ = 0 under the simultaneous law, §8 of the paper, or a jammed
//! body under the unilateral law — exit status 3) carries `kind` (`"singular"`, `"jammed"`, …);
//! `SweepError` a bad varied input or a point where the scene is invalid; `FormatError` a
//! malformed derivation (`check`).

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

use inertance::SolveError as LibSolveError;
use inertance::impact::unilateral::UnilateralError;
use inertance::scene::SceneError as LibSceneError;
use inertance::scene::pipeline::RunError;
use inertance::tools::check::FormatError as LibFormatError;
use inertance::tools::sweep::SweepError as LibSweepError;

create_exception!(
    inertance,
    InertanceError,
    PyException,
    "Base of inertance's errors."
);
create_exception!(
    inertance,
    SceneError,
    InertanceError,
    "An unreadable or invalid scene: `.file`, `.key` (e.g. `contact[1].k`), `.value` (as written, or None) and `.message`."
);
create_exception!(
    inertance,
    SolveError,
    InertanceError,
    "The collision has no answer: `.kind` is \"singular\" (Δ = det G = 0, §8; see analyze or law=\"unilateral\") or \"jammed\" (no admissible impulses under the unilateral law)."
);
create_exception!(
    inertance,
    SweepError,
    InertanceError,
    "A bad varied input (`.key`) or a point where the scene is invalid (`.point`, `.key`, `.value`)."
);
create_exception!(
    inertance,
    FormatError,
    InertanceError,
    "A malformed derivation file: `.file`, `.line`, `.message`."
);

/// An exception of type `E` with `message` and the attributes `attrs`.
fn raise<E: pyo3::PyTypeInfo>(
    py: Python<'_>,
    message: String,
    attrs: &[(&str, PyObject)],
) -> PyErr {
    let err = PyErr::new::<E, _>(message);
    let value = err.value(py);
    for (k, v) in attrs {
        // Setting an attribute on a fresh exception instance cannot fail.
        let _ = value.setattr(*k, v);
    }
    err
}

/// A scene error with its file, key, value and message.
pub fn scene_error(py: Python<'_>, e: &LibSceneError) -> PyErr {
    raise::<SceneError>(
        py,
        e.to_string(),
        &[
            (
                "file",
                e.file
                    .clone()
                    .into_pyobject(py)
                    .unwrap()
                    .into_any()
                    .unbind(),
            ),
            (
                "key",
                e.key.clone().into_pyobject(py).unwrap().into_any().unbind(),
            ),
            ("value", e.value.clone().into_pyobject(py).unwrap().unbind()),
            (
                "message",
                e.message
                    .clone()
                    .into_pyobject(py)
                    .unwrap()
                    .into_any()
                    .unbind(),
            ),
        ],
    )
}

/// A solve that failed: bad input, or no answer.
pub fn run_error(py: Python<'_>, e: &RunError) -> PyErr {
    let (message, kind) = match e {
        RunError::Scene(s) => return scene_error(py, s),
        RunError::Solve(s) => (
            s.to_string(),
            match s {
                LibSolveError::Singular { .. } => "singular",
                LibSolveError::Tangent(_) => "frame",
                LibSolveError::NotSemidefinite(_) => "not-semidefinite",
            },
        ),
        RunError::Unilateral(u) => (
            u.to_string(),
            match u {
                UnilateralError::Jammed { .. } => "jammed",
                _ => "pivots",
            },
        ),
        // A friction verdict (no consistent modes, …) or a spatial scene asked for exactly.
        RunError::Friction(f) => (f.to_string(), f.status().unwrap_or("friction")),
        RunError::Lzb(l) => (l.to_string(), "lzb"),
    };
    raise::<SolveError>(
        py,
        message,
        &[("kind", kind.into_pyobject(py).unwrap().into_any().unbind())],
    )
}

/// A sweep or batch that failed.
pub fn sweep_error(py: Python<'_>, e: &LibSweepError) -> PyErr {
    let s = |x: &str| x.into_pyobject(py).unwrap().into_any().unbind();
    match e {
        LibSweepError::Scene(s) => scene_error(py, s),
        LibSweepError::Vary { spec, .. } => {
            raise::<SweepError>(py, e.to_string(), &[("key", s(spec))])
        }
        LibSweepError::Point { point, at, message } => {
            let (key, value) = at.split_once(" = ").unwrap_or((at, ""));
            raise::<SweepError>(
                py,
                e.to_string(),
                &[
                    (
                        "point",
                        point.into_pyobject(py).unwrap().into_any().unbind(),
                    ),
                    ("key", s(key)),
                    ("value", s(value)),
                    ("message", s(message)),
                ],
            )
        }
        _ => raise::<SweepError>(py, e.to_string(), &[]),
    }
}

/// A malformed derivation.
pub fn format_error(py: Python<'_>, e: &LibFormatError) -> PyErr {
    raise::<FormatError>(
        py,
        e.to_string(),
        &[
            (
                "file",
                e.file
                    .clone()
                    .into_pyobject(py)
                    .unwrap()
                    .into_any()
                    .unbind(),
            ),
            (
                "line",
                e.line.into_pyobject(py).unwrap().into_any().unbind(),
            ),
            (
                "message",
                e.message
                    .clone()
                    .into_pyobject(py)
                    .unwrap()
                    .into_any()
                    .unbind(),
            ),
        ],
    )
}

/// Register the exception types.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("InertanceError", py.get_type::<InertanceError>())?;
    m.add("SceneError", py.get_type::<SceneError>())?;
    m.add("SolveError", py.get_type::<SolveError>())?;
    m.add("SweepError", py.get_type::<SweepError>())?;
    m.add("FormatError", py.get_type::<FormatError>())?;
    Ok(())
}
