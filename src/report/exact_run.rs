//! What `inertance simulate --exact` reports: each impact of the exact run with its time, plane
//! and normal velocities as exact values (radicals) and their f64 values, the accumulation time
//! when there is one, and how the run ended; or the same as JSON.

use serde_json::{Value as Json, json};

use super::json_f64;
use crate::scalar::Scalar;
use crate::simulate::exact::{ExactEnd, ExactError, ExactRun, ExactSphere};

fn both<T: Scalar>(x: &T) -> String {
    let approx = x.to_f64();
    match x.exact_text() {
        Some(t) if t != format!("{approx}") => format!("{t} = {}", super::simulation::sig(approx)),
        _ => super::simulation::sig(approx),
    }
}

/// The exact run as a table.
pub fn exact_text<T: Scalar>(
    name: &str,
    sphere: &ExactSphere<T>,
    run: &ExactRun<T>,
    error: Option<&ExactError>,
) -> String {
    let mut out = format!("{name} — simulated exactly (a frictionless sphere among planes)\n");
    for (i, r) in run.impacts.iter().enumerate() {
        out += &format!(
            "  {:>3}  t = {}\n       on {}: ġ⁻ = {}, ġ⁺ = {}\n",
            i + 1,
            both(&r.t),
            sphere.planes[r.plane].name,
            both(&r.before),
            both(&r.after)
        );
    }
    if let Some(t) = &run.zeno {
        out += &format!(
            "the impacts accumulate at t∞ = {} (one plane, k = {})\n",
            both(t),
            both(&sphere.planes[0].k)
        );
    }
    let ended = match &run.end {
        ExactEnd::Duration => "the duration".to_string(),
        ExactEnd::Impacts => "the impact budget".to_string(),
        ExactEnd::Zeno { .. } => "the accumulation of impacts, at rest on the plane".to_string(),
        ExactEnd::Rest => "rest on a plane".to_string(),
        ExactEnd::Escapes => "no plane ahead: the ball flies on".to_string(),
        ExactEnd::Stopped => format!(
            "an error ({})",
            error.map_or_else(String::new, ToString::to_string)
        ),
    };
    out += &format!(
        "ended at {ended}, t = {}: {} impact{}\n",
        both(&run.t_end),
        run.impacts.len(),
        if run.impacts.len() == 1 { "" } else { "s" }
    );
    out
}

/// The exact run for programs: each value as its exact text and its f64.
pub fn exact_json<T: Scalar>(name: &str, sphere: &ExactSphere<T>, run: &ExactRun<T>) -> Json {
    let value = |x: &T| json!({"exact": x.exact_text(), "f64": json_f64(x.to_f64())});
    json!({
        "name": name,
        "exact": true,
        "impacts": run.impacts.iter().map(|r| json!({
            "t": value(&r.t),
            "plane": sphere.planes[r.plane].name,
            "before": value(&r.before),
            "after": value(&r.after),
            "x": r.x.iter().map(value).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "zeno": run.zeno.as_ref().map(value),
        "end": match run.end {
            ExactEnd::Duration => "duration",
            ExactEnd::Impacts => "impacts",
            ExactEnd::Zeno { .. } => "zeno",
            ExactEnd::Rest => "rest",
            ExactEnd::Escapes => "escapes",
            ExactEnd::Stopped => "stopped",
        },
        "t_end": value(&run.t_end),
    })
}
