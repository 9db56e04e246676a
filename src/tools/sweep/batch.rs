//! Batches: one scene solved in f64 at many points whose varied numbers are given as arrays
//! (not a grid), results returned as arrays instead of CSV rows — what a caller holding its
//! numbers in memory (the Python bindings' `solve_batch`) needs.
//!
//! Point p sets `vary[k].path` to `vary[k].values[p]` for every k (all arrays of one length),
//! read exactly as its shortest decimal (`0.1` is 1/10, as in a scene file), straight into the
//! scene where the number has a [`Slot`] and by re-reading the document otherwise. Unlike a
//! sweep's range, arbitrary values are not checked up front: a value that makes the scene
//! invalid (k = 1.5) fails the batch with [`SweepError::Point`] naming the point, the key and
//! the value. Points are solved in parallel (rayon).
//!
//! A scene of several bodies (`[[body]]` tables) is solved as `inertance sweep` solves it
//! ([`crate::scene::system_pipeline::run_system`] at each point, the document re-read): per
//! law the impulses, each body's v_C and ω by name ([`Batch::bodies`]), the system's E_p and
//! ΔE_c (and E_f), and the sweep's status per point.

use num_rational::BigRational;
use rayon::prelude::*;
use toml_edit::DocumentMut;

use super::SweepError;
use super::answer::{Answer, body_names};
use super::outputs::{law_values, output_names, point_status, status, sweep_laws};
use super::slot::Slot;
use super::target::Target;

use crate::impact::friction::Restitution;
use crate::impact::unilateral::Law;
use crate::number::parse_decimal;
use crate::scene::Scene;

/// One varied number: its key path (`contact[1].k`, `body.mass`, …) and its value per point.
#[derive(Clone, Debug, PartialEq)]
pub struct Varied {
    /// The key path, as in [`set_value`](crate::scene::set_value).
    pub path: String,
    /// One value per point.
    pub values: Vec<f64>,
}

/// The results of a batch, per model as the sweep's CSV columns (without the CSV).
#[derive(Clone, Debug, PartialEq)]
pub struct Batch {
    /// The laws solved, in the scene's order (its models; or, with friction, the laws it
    /// integrates).
    pub models: Vec<Restitution>,
    /// The output names per law: `P1 … PN`, `vCx vCy vCz`, `wx wy wz`, `Ep`, `dEc` (and `Ef`
    /// with friction). A system's bodies each give their six, named by body as the sweep's
    /// columns: `P1 … PN`, then per body in [`Batch::bodies`] order `BODY.vCx BODY.vCy BODY.vCz
    /// BODY.wx BODY.wy BODY.wz`, then `Ep`, `dEc` (the system's) and `Ef`.
    pub outputs: Vec<String>,
    /// A system's bodies by name, in the scene's order (empty for one body).
    pub bodies: Vec<String>,
    /// Points solved.
    pub points: usize,
    /// Per model, row-major points × outputs; NaN where the point has no answer
    /// (`singular`, `jammed`).
    pub values: Vec<Vec<f64>>,
    /// Per point: `ok`, `singular`, `jammed`, or the reasons a simultaneous answer is not
    /// physical joined by `+` (as the sweep's `status` column).
    pub status: Vec<String>,
}

/// Solve the scene `doc` (read from `file`) in f64 at every point of `vary`, under `law`
/// (the scene's own when `None`).
///
/// # Errors
/// [`SweepError::Scene`] for an invalid scene, [`SweepError::Vary`] for a path that names no
/// number of the scene or arrays of different lengths, [`SweepError::Point`] for a value that
/// makes the scene invalid.
pub fn solve_batch(
    doc: &DocumentMut,
    file: &str,
    vary: &[Varied],
    law: Option<Law>,
) -> Result<Batch, SweepError> {
    let mut base = Scene::from_document(doc, file)?;
    if let Some(law) = law {
        base.law = law;
    }
    let points = vary.first().map_or(0, |v| v.values.len());
    let keys = Target::keys(&base);
    let targets: Vec<Target> = vary.iter().map(|v| Target::of(&v.path, &base)).collect();
    for (v, t) in vary.iter().zip(&targets) {
        if !t.known(&v.path, &base, &keys) {
            return Err(SweepError::Vary {
                spec: v.path.clone(),
                reason: format!(
                    "no such number in the scene; its numbers are {}",
                    keys.join(", ")
                ),
            });
        }
        // A system's paths are checked against its document (every number of it can be
        // varied): a path it has no place for is refused up front, not at point 0.
        if base.system.is_some() {
            t.set(&mut doc.clone(), &BigRational::from_integer(0.into()))
                .map_err(|reason| SweepError::Vary {
                    spec: v.path.clone(),
                    reason,
                })?;
        }
        if v.values.len() != points {
            return Err(SweepError::Vary {
                spec: v.path.clone(),
                reason: format!(
                    "{} values, but `{}` has {points}: every varied number needs one value per point",
                    v.values.len(),
                    vary[0].path
                ),
            });
        }
    }
    // Values are not checked up front: a modelled scene re-reads the document for a number
    // with a condition (a coefficient), so that an invalid one is named by the reader as it
    // always was; its velocities have none (the values are finite f64).
    let velocities_only = vary.iter().all(|v| {
        matches!(
            Slot::find(&v.path, &base),
            Some(Slot::Velocity(_) | Slot::AngularVelocity(_))
        )
    });
    let slots = Slot::all(
        vary.iter().map(|v| v.path.as_str()),
        &base,
        (base.axes.is_some() && !velocities_only) || targets.iter().any(|t| t.param),
    );
    let (models, friction) = sweep_laws(&base, vary.iter().map(|v| v.path.as_str()));
    let bodies = body_names(&base);
    let outputs = output_names(base.contacts.len(), friction, &bodies);
    let width = outputs.len();
    let solved = (0..points)
        .into_par_iter()
        .map(|p| {
            let at = |message: String| SweepError::Point {
                point: p,
                at: vary
                    .iter()
                    .map(|v| format!("{} = {}", v.path, v.values[p]))
                    .collect::<Vec<_>>()
                    .join(", "),
                message,
            };
            let values = vary
                .iter()
                .map(|v| {
                    parse_decimal(&v.values[p].to_string())
                        .ok_or_else(|| at("not a finite number".into()))
                })
                .collect::<Result<Vec<BigRational>, _>>()?;
            let scene = match &slots {
                Some(slots) => {
                    let mut scene = base.clone();
                    for (slot, q) in slots.iter().zip(&values) {
                        slot.set(&mut scene, q);
                    }
                    scene
                }
                None => {
                    let mut d = doc.clone();
                    for (t, q) in targets.iter().zip(&values) {
                        t.set(&mut d, q).map_err(&at)?;
                    }
                    let mut scene =
                        Scene::from_document(&d, file).map_err(|e| at(e.to_string()))?;
                    scene.law = base.law;
                    scene
                }
            };
            match Answer::solve::<f64>(&scene) {
                Ok(answer) => {
                    let status = status(&answer);
                    Ok((Some(answer), status))
                }
                Err(e) => match point_status(&e) {
                    Some(status) => Ok((None, status.to_string())),
                    None => Err(at(e.to_string())),
                },
            }
        })
        .collect::<Result<Vec<_>, SweepError>>()?;
    let mut values = vec![Vec::with_capacity(points * width); models.len()];
    let mut statuses = Vec::with_capacity(points);
    for (report, s) in solved {
        for (m, column) in models.iter().zip(&mut values) {
            match report.as_ref().and_then(|r| law_values(r, *m, friction)) {
                Some(v) => column.extend(v),
                None => column.extend(std::iter::repeat_n(f64::NAN, width)),
            }
        }
        statuses.push(s);
    }
    Ok(Batch {
        models,
        outputs,
        bodies,
        points,
        values,
        status: statuses,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{parse_document, set_value};

    const BAR: &str = include_str!("../../../examples/planar-bar.toml");

    #[test]
    fn a_batch_equals_the_scenes_solved_one_by_one() {
        let doc = parse_document(BAR, "bar.toml").unwrap();
        let ks = vec![0.0, 0.2, 0.3, 0.75, 1.0];
        let b = solve_batch(
            &doc,
            "bar.toml",
            &[Varied {
                path: "contact[1].k".into(),
                values: ks.clone(),
            }],
            None,
        )
        .unwrap();
        assert_eq!(b.points, 5);
        assert_eq!(b.outputs[0], "P1");
        for (p, k) in ks.iter().enumerate() {
            let mut d = doc.clone();
            set_value(&mut d, "contact[1].k", &k.to_string()).unwrap();
            let scene = Scene::from_document(&d, "bar.toml").unwrap();
            let r = crate::scene::pipeline::run::<f64>(&scene, None)
                .unwrap()
                .report;
            let r = Answer::Body(r);
            for (m, column) in b.models.iter().zip(&b.values) {
                let expected = law_values(&r, *m, false).unwrap();
                let w = b.outputs.len();
                assert_eq!(column[p * w..(p + 1) * w], expected[..], "{m:?} at k = {k}");
            }
            assert_eq!(b.status[p], status(&r));
        }
    }

    /// A world-frame scene's velocities are set in the scene read once: the batch equals the
    /// document re-read at each point, bit for bit.
    #[test]
    fn a_world_frame_velocity_batch_equals_the_scenes_read_one_by_one() {
        let text = include_str!("../../../examples/tilted-box.toml");
        let doc = parse_document(text, "tilted.toml").unwrap();
        let vz = vec![-2.0, -1.0, -0.1, 0.3, -1e-300];
        let wy = vec![0.0, 1.5, -3.0, 0.1, 7.0];
        let vary = [
            Varied {
                path: "body.velocity[2]".into(),
                values: vz.clone(),
            },
            Varied {
                path: "body.angular_velocity[1]".into(),
                values: wy.clone(),
            },
        ];
        let b = solve_batch(&doc, "tilted.toml", &vary, None).unwrap();
        let w = b.outputs.len();
        for p in 0..vz.len() {
            let mut d = doc.clone();
            set_value(&mut d, "body.velocity[2]", &format!("{:?}", vz[p])).unwrap();
            set_value(&mut d, "body.angular_velocity[1]", &format!("{:?}", wy[p])).unwrap();
            let scene = Scene::from_document(&d, "tilted.toml").unwrap();
            match crate::scene::pipeline::run::<f64>(&scene, None) {
                Ok(r) => {
                    let r = Answer::Body(r.report);
                    for (m, column) in b.models.iter().zip(&b.values) {
                        let expected = law_values(&r, *m, false).unwrap();
                        let got = &column[p * w..(p + 1) * w];
                        let same = got
                            .iter()
                            .zip(&expected)
                            .all(|(a, e)| a.to_bits() == e.to_bits());
                        assert!(same, "{m:?} at point {p}: {got:?} vs {expected:?}");
                    }
                    assert_eq!(b.status[p], status(&r), "point {p}");
                }
                Err(e) => assert_eq!(Some(b.status[p].as_str()), point_status(&e), "point {p}"),
            }
        }
        assert!(b.status.iter().any(|s| s == "ok"));
    }

    #[test]
    fn a_normal_is_varied_through_the_document() {
        let doc = parse_document(BAR, "bar.toml").unwrap();
        let b = solve_batch(
            &doc,
            "bar.toml",
            &[Varied {
                path: "contact[0].normal[0]".into(),
                values: vec![1.0, 2.0],
            }],
            None,
        )
        .unwrap();
        // The physical outputs do not depend on the normal's length.
        let w = b.outputs.len();
        for column in &b.values {
            for (a, c) in column[..w].iter().zip(&column[w..]) {
                assert!((a - c).abs() <= 1e-12 * a.abs().max(1.0), "{a} vs {c}");
            }
        }
    }

    #[test]
    fn bad_batches_name_the_key_and_the_value() {
        let doc = parse_document(BAR, "bar.toml").unwrap();
        let vary = |path: &str, values: Vec<f64>| {
            vec![Varied {
                path: path.into(),
                values,
            }]
        };
        let e = solve_batch(
            &doc,
            "bar.toml",
            &vary("contact[1].k", vec![0.5, 1.5]),
            None,
        )
        .unwrap_err();
        assert!(
            matches!(&e, SweepError::Point { point: 1, at, .. } if at == "contact[1].k = 1.5"),
            "{e}"
        );
        let e = solve_batch(&doc, "bar.toml", &vary("contact[7].k", vec![0.5]), None).unwrap_err();
        assert!(matches!(e, SweepError::Vary { .. }), "{e}");
        let e =
            solve_batch(&doc, "bar.toml", &vary("body.mass", vec![f64::NAN]), None).unwrap_err();
        assert!(e.to_string().contains("body.mass = NaN"), "{e}");
        let two = [
            Varied {
                path: "body.mass".into(),
                values: vec![1.0, 2.0],
            },
            Varied {
                path: "contact[0].k".into(),
                values: vec![0.5],
            },
        ];
        let e = solve_batch(&doc, "bar.toml", &two, None).unwrap_err();
        assert!(e.to_string().contains("one value per point"), "{e}");
    }

    #[test]
    fn singular_and_jammed_points_have_a_status_and_no_numbers() {
        // Both contacts at one point, one normal: Δ = 0 for every k.
        let doc = parse_document(
            &BAR.replace("point = [0, 4, 0]", "point = [0, -2, 0]"),
            "bar.toml",
        )
        .unwrap();
        let b = solve_batch(
            &doc,
            "bar.toml",
            &[Varied {
                path: "contact[1].k".into(),
                values: vec![0.5],
            }],
            None,
        )
        .unwrap();
        assert_eq!(b.status, ["singular"]);
        assert!(b.values.iter().all(|c| c.iter().all(|x| x.is_nan())));
        let b = solve_batch(
            &doc,
            "bar.toml",
            &[Varied {
                path: "contact[1].k".into(),
                values: vec![0.3],
            }],
            Some(Law::Unilateral),
        )
        .unwrap();
        assert_eq!(b.status, ["ok"]);
    }
}
