//! The path of a frictional impact, to plot it or to check a sensitive case at a tighter
//! tolerance: per sample ([`crate::impact::friction::Sample`]) the parameter s, the phase and,
//! per contact, the normal impulse P_i (N s), the tangential impulse vector the obstacle applies
//! and the slip velocity of the contact point (the report's axes), and the mode. Rendered as
//! CSV or JSON for `inertance solve --trajectory FILE`.
//!
//! A planar scene's path is sampled at the ends of its segments (every rate is constant in
//! between, so Λ is linear there); a spatial one's at every accepted step. At an event two
//! samples share s: the first carries the modes of the segment that ends there, the second
//! those of the one that starts.

use serde_json::{Value as Json, json};

use crate::impact::friction::{Frictional, ModeLabel, Phase};
use crate::mechanics::contact::Surd;
use crate::mechanics::screw::{Vec3, norm2};
use crate::report::{FrictionReport, json_f64};
use crate::scalar::Scalar;

/// One contact at one sample.
#[derive(Clone, Debug, PartialEq)]
pub struct TrajectoryContact {
    /// P_i.
    pub normal_impulse: f64,
    /// The tangential impulse the obstacle has applied so far.
    pub tangential_impulse: [f64; 3],
    /// The contact point's tangential velocity (its slip).
    pub slip: [f64; 3],
    /// The mode.
    pub mode: ModeLabel,
}

/// One sample of the path.
#[derive(Clone, Debug, PartialEq)]
pub struct TrajectoryPoint {
    /// s.
    pub s: f64,
    /// The phase.
    pub phase: Phase,
    /// Per contact.
    pub contacts: Vec<TrajectoryContact>,
}

fn vector<T: Scalar>(v: &Vec3<T>) -> [f64; 3] {
    [v[0].to_f64(), v[1].to_f64(), v[2].to_f64()]
}

/// The path of `f`, in the units and axes of its problem.
pub fn trajectory<T: Scalar>(f: &Frictional<T>) -> Vec<TrajectoryPoint> {
    let b = &f.blocks;
    let mut change = Vec::new();
    f.samples
        .iter()
        .map(|sample| {
            let lambda = &sample.impulses;
            b.velocity_change(lambda, &mut change);
            let contacts = (0..b.contacts())
                .map(|i| {
                    let off = b.offset[i];
                    let n2 = norm2(&b.axes[off].top());
                    let mut tau = Vec3::<T>::zeros();
                    let mut slip = Vec3::<T>::zeros();
                    for q in off + 1..off + 1 + b.dims[i] {
                        let d = b.axes[q].top();
                        tau -= d.clone() * lambda[q].clone();
                        // v̂_q = d·v_A along the axis d: the component d v̂_q / |d|².
                        let along = b.v0[q].clone() + &change[q];
                        slip += d.clone() * (along / norm2(&d));
                    }
                    TrajectoryContact {
                        normal_impulse: Surd::times_norm(&lambda[off], &n2).to_f64(),
                        tangential_impulse: vector(&tau),
                        slip: vector(&slip),
                        mode: sample.modes[i],
                    }
                })
                .collect();
            TrajectoryPoint {
                s: sample.s.to_f64(),
                phase: sample.phase,
                contacts,
            }
        })
        .collect()
}

/// An f64 in a CSV cell: shortest round-trip digits, scientific when very small or large.
pub(super) fn cell(x: f64) -> String {
    if x == 0.0 || (1e-4..1e7).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// The paths of `reports` as CSV: one row per sample and law, the columns `law`, `s`,
/// `phase`, then per contact i (from 1) `P{i}`, `tau{i}_x`, `tau{i}_y`, `tau{i}_z`,
/// `slip{i}_x`, `slip{i}_y`, `slip{i}_z`, `mode{i}`.
pub fn to_csv(reports: &[FrictionReport]) -> String {
    let contacts = reports.first().map_or(0, |r| r.contacts.len());
    let mut out = String::from("law,s,phase");
    for i in 1..=contacts {
        out += &format!(",P{i},tau{i}_x,tau{i}_y,tau{i}_z,slip{i}_x,slip{i}_y,slip{i}_z,mode{i}");
    }
    out.push('\n');
    for r in reports {
        for p in &r.trajectory {
            out += &format!("{},{},{}", r.law, cell(p.s), p.phase);
            for c in &p.contacts {
                out += &format!(",{}", cell(c.normal_impulse));
                for x in c.tangential_impulse.iter().chain(&c.slip) {
                    out += &format!(",{}", cell(*x));
                }
                out += &format!(",{}", c.mode.name());
            }
            out.push('\n');
        }
    }
    out
}

/// The paths of `reports` as JSON: an object keyed by law, each an array of samples
/// `{"s", "phase", "contacts": [{"normal_impulse", "tangential_impulse", "slip", "mode"}]}`.
pub fn to_json(reports: &[FrictionReport]) -> Json {
    let mut out = serde_json::Map::new();
    for r in reports {
        let points: Vec<Json> = r
            .trajectory
            .iter()
            .map(|p| {
                json!({
                    "s": json_f64(p.s),
                    "phase": p.phase.to_string(),
                    "contacts": p.contacts.iter().map(|c| json!({
                        "normal_impulse": json_f64(c.normal_impulse),
                        "tangential_impulse": c.tangential_impulse.map(json_f64),
                        "slip": c.slip.map(json_f64),
                        "mode": c.mode.name(),
                    })).collect::<Vec<_>>(),
                })
            })
            .collect();
        out.insert(r.law.name().to_string(), Json::Array(points));
    }
    Json::Object(out)
}
