//! The exact peer corpus: `benches/peers/corpus.txt`, random two-contact free-body scenes with
//! rational data, one scene a line — the scenes SymPy and inertance's exact paths are timed on
//! side by side (`benches/peers/compare.py`, the criterion bench `exact`, `inertance bench
//! --corpus`).
//!
//! A line holds 24 rationals (integers or `p/q`), separated by spaces:
//!
//! ```text
//! m  Jx Jy Jz  vCx vCy vCz  ωx ωy ωz  A1x A1y A1z n1x n1y n1z k1  A2x A2y A2z n2x n2y n2z k2
//! ```
//!
//! (mass, central principal moments, the twist before impact, then per contact its point, its
//! outward normal and its restitution coefficient, the same for Newton and Poisson). Lines
//! starting with `#` and blank lines are skipped.
//!
//! [`time`] measures a solve per scene over the whole corpus in the exact types — [`Exact`]
//! and plain `BigRational`, the arithmetic it replaced — and in f64, back to back in one run.

use std::time::Instant;

use num_rational::BigRational;

use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::scalar::{Exact, Scalar};
use crate::scene::{Scene, SceneError};

/// Numbers per corpus line.
const FIELDS: usize = 24;

/// The scenes of a corpus file's text, named `corpus-1`, `corpus-2`, … in order.
///
/// # Errors
/// A line without 24 fields, or one whose scene is refused (the message names the line).
pub fn parse(text: &str) -> Result<Vec<Scene>, String> {
    let mut scenes = Vec::new();
    for (line_no, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let x: Vec<&str> = line.split_whitespace().collect();
        if x.len() != FIELDS {
            return Err(format!(
                "corpus line {}: {} numbers, expected {FIELDS}",
                line_no + 1,
                x.len()
            ));
        }
        let name = format!("corpus-{}", scenes.len() + 1);
        let scene = Scene::parse(&scene_toml(&x), &name)
            .map_err(|e: SceneError| format!("corpus line {}: {e}", line_no + 1))?;
        scenes.push(scene);
    }
    Ok(scenes)
}

/// The scene of one line's fields in the public schema (every number a `"p/q"` string).
fn scene_toml(x: &[&str]) -> String {
    let v = |r: std::ops::Range<usize>| {
        let items: Vec<String> = x[r].iter().map(|s| format!("\"{s}\"")).collect();
        format!("[{}]", items.join(", "))
    };
    let mut t = format!(
        "[body]\nmass = \"{}\"\ninertia = {}\nvelocity = {}\nangular_velocity = {}\n",
        x[0],
        v(1..4),
        v(4..7),
        v(7..10)
    );
    for o in [10, 17] {
        t += &format!(
            "[[contact]]\npoint = {}\nnormal = {}\nk = \"{}\"\n",
            v(o..o + 3),
            v(o + 3..o + 6),
            x[o + 6]
        );
    }
    t
}

/// The time per scene of one solve — assemble + Newton + Poisson with every output, the solve
/// `inertance bench --scene` times — over the whole corpus, in ns, per type: `"exact"`
/// ([`Exact`]), `"bigrational"` (plain `BigRational`) and `"f64"`. Each is the median over
/// `passes` passes (after one untimed pass) of a pass's wall time divided by the scenes solved;
/// the problems are built beforehand. `None` for a type in which some scene is singular.
pub fn time(scenes: &[Scene], passes: usize) -> Vec<(&'static str, Option<f64>)> {
    vec![
        ("exact", time_in::<Exact>(scenes, passes)),
        ("bigrational", time_in::<BigRational>(scenes, passes)),
        ("f64", time_in::<f64>(scenes, passes)),
    ]
}

fn time_in<T: Scalar>(scenes: &[Scene], passes: usize) -> Option<f64> {
    let problems: Vec<Problem<T>> = scenes
        .iter()
        .map(|s| s.problem::<T>().ok())
        .collect::<Option<_>>()?;
    let mut impact = Impact::assemble(problems.first()?).ok()?;
    let (mut newton, mut poisson) = (Outcome::default(), Outcome::default());
    let mut pass = || -> Option<f64> {
        let start = Instant::now();
        for p in &problems {
            impact.reassemble(std::hint::black_box(p)).ok()?;
            impact.solve(Model::Newton, &mut newton).ok()?;
            impact.solve(Model::Poisson, &mut poisson).ok()?;
        }
        Some(start.elapsed().as_nanos() as f64 / problems.len() as f64)
    };
    pass()?;
    let mut times = (0..passes.max(1))
        .map(|_| pass())
        .collect::<Option<Vec<f64>>>()?;
    times.sort_by(f64::total_cmp);
    Some(times[times.len() / 2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_is_a_two_contact_scene() {
        let text = "# comment\n\n5/2 425/384 75/32 965/384 3/2 -3/2 -5/2 -1/4 3/4 3/4 \
                    -1/2 2 -1/4 4/9 -7/9 -4/9 3/5 1 -5/4 1 12/17 -9/17 8/17 3/5\n";
        let scenes = parse(text).unwrap();
        assert_eq!(scenes.len(), 1);
        assert_eq!(scenes[0].contacts.len(), 2);
        assert_eq!(scenes[0].text_of("body.mass").as_deref(), Some("5/2"));
    }

    #[test]
    fn every_type_is_timed() {
        let text = "5/2 425/384 75/32 965/384 3/2 -3/2 -5/2 -1/4 3/4 3/4 \
                    -1/2 2 -1/4 4/9 -7/9 -4/9 3/5 1 -5/4 1 12/17 -9/17 8/17 3/5\n";
        let t = time(&parse(text).unwrap(), 1);
        let names: Vec<_> = t.iter().map(|(n, _)| *n).collect();
        assert_eq!(names, ["exact", "bigrational", "f64"]);
        assert!(t.iter().all(|(_, ns)| ns.is_some_and(|x| x > 0.0)));
    }

    #[test]
    fn a_short_line_is_refused_with_its_number() {
        let e = parse("# c\n1 2 3\n").unwrap_err();
        assert!(e.contains("line 2") && e.contains("3 numbers"), "{e}");
    }
}
