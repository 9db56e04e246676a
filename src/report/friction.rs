//! The readout of a frictional impact ([`crate::impact::friction`]): per contact the normal
//! impulse (N s), the tangential impulse vector the obstacle applies (body axes), the contact
//! point's velocity after impact and its mode history; the twist after, E_p, ΔE_c, the energy
//! dissipated by friction, the events, the verdicts and the path.

use crate::impact::friction::{Frictional, ModeLabel, Restitution};
use crate::mechanics::contact::Surd;
use crate::mechanics::screw::{Vec3, norm2};
use crate::report::Value;
use crate::report::trajectory::{TrajectoryPoint, trajectory};
use crate::scalar::Scalar;

/// One contact of a frictional readout.
#[derive(Clone, Debug, PartialEq)]
pub struct FrictionContact {
    /// P_i, the normal impulse.
    pub normal_impulse: Value,
    /// P_i^c, the normal impulse at the end of compression.
    pub compression_impulse: Value,
    /// The tangential impulse the obstacle applies to the body, body axes.
    pub tangential_impulse: [Value; 3],
    /// v_ix after impact (positive: still approaching).
    pub normal_velocity: Value,
    /// The contact point's velocity after impact, body axes.
    pub velocity: [Value; 3],
    /// The modes the contact went through (`stick`, `slide+`, `slide-`, `slide`, `free`).
    pub history: Vec<ModeLabel>,
    /// Whether it sticks at the end of the impact.
    pub sticks: bool,
}

/// The readout of one frictional law.
#[derive(Clone, Debug, PartialEq)]
pub struct FrictionReport {
    /// The restitution law.
    pub law: Restitution,
    /// `"planar, exact events"` or `"spatial, adaptive RK5(4)"`.
    pub method: &'static str,
    /// Per contact.
    pub contacts: Vec<FrictionContact>,
    /// ω after impact.
    pub angular_velocity: [Value; 3],
    /// v_C after impact.
    pub velocity: [Value; 3],
    /// E_p.
    pub lost_velocity_energy: Value,
    /// ΔE_c.
    pub kinetic_energy_loss: Value,
    /// The energy dissipated by friction.
    pub friction_dissipation: Value,
    /// The values of s where the modes change or a contact stops (phase ends aside from the
    /// last are included), in order.
    pub events: Vec<Value>,
    /// The parameter s at the end.
    pub end: Value,
    /// The verdicts, as sentences.
    pub verdicts: Vec<String>,
    /// Their short names (`tensile-rate`, …), in the same order.
    pub verdict_names: Vec<&'static str>,
    /// The estimated error of impulses (N s), for the spatial integration.
    pub error_estimate: Option<f64>,
    /// The relative tolerance the spatial integration was run to.
    pub tolerance: Option<f64>,
    /// The path ([`super::trajectory`]).
    pub trajectory: Vec<TrajectoryPoint>,
}

fn vector<T: Scalar>(v: &Vec3<T>) -> [Value; 3] {
    [Value::of(&v[0]), Value::of(&v[1]), Value::of(&v[2])]
}

impl FrictionReport {
    /// Read out `f`.
    pub fn new<T: Scalar>(f: &Frictional<T>) -> Self {
        let b = &f.blocks;
        let contacts = (0..b.contacts())
            .map(|i| {
                let off = b.offset[i];
                let axis = &b.axes[off];
                let n2 = norm2(&axis.top());
                let (_, tangential) = f.impulse_vectors(i);
                let point_velocity = f.velocity.bottom() + f.velocity.top().cross(&b.points[i]);
                let history = f.history(i);
                FrictionContact {
                    normal_impulse: Value::surd(&Surd::times_norm(f.normal_hat(i), &n2)),
                    compression_impulse: f
                        .compression
                        .get(i)
                        .map(|p| Value::surd(&Surd::times_norm(p, &n2)))
                        .unwrap_or_else(|| Value::float(0.0)),
                    tangential_impulse: vector(&tangential),
                    normal_velocity: Value::surd(&Surd::over_norm(&f.after[off], &n2)),
                    velocity: vector(&point_velocity),
                    sticks: history.last() == Some(&ModeLabel::Stick),
                    history,
                }
            })
            .collect();
        let mut events = Vec::new();
        for s in f.segments.iter().take(f.segments.len().saturating_sub(1)) {
            events.push(Value::of(&s.to));
        }
        FrictionReport {
            law: f.law,
            method: if f.error_estimate.is_some() {
                "spatial, adaptive RK5(4)"
            } else {
                "planar, exact events"
            },
            contacts,
            angular_velocity: vector(&f.velocity.top()),
            velocity: vector(&f.velocity.bottom()),
            lost_velocity_energy: Value::of(&f.lost_velocity_energy),
            kinetic_energy_loss: Value::of(&f.kinetic_energy_loss),
            friction_dissipation: Value::of(&f.friction_dissipation),
            events,
            end: Value::of(&f.end),
            verdicts: f.verdicts.iter().map(|v| v.to_string()).collect(),
            verdict_names: f.verdicts.iter().map(|v| v.name()).collect(),
            error_estimate: f.error_estimate,
            tolerance: f.tolerance,
            trajectory: trajectory(f),
        }
    }
}
