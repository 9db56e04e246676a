//! The readout of a frictional impact of a system of bodies ([`crate::impact::friction`] on a
//! [`System`]): per contact the normal impulse, the tangential impulse on its first body (the
//! second takes the opposite), the relative velocity after impact and the mode history; per
//! body its twist and kinetic energy after; per joint its reaction; the energies, the
//! momentum after, the events and the verdicts. World axes, the paper's units, as
//! [`super::system`].

use serde_json::{Value as Json, json};

use super::{Value, WrenchReport, fmt_f64, json_f64};
use crate::impact::friction::{Frictional, ModeLabel, Restitution};
use crate::mechanics::contact::Surd;
use crate::mechanics::screw::{Vec3, norm2};
use crate::mechanics::system::{System, SystemScrew};
use crate::scalar::Scalar;

/// One contact of a system's frictional readout: the fields of one body's
/// ([`super::FrictionContact`]), read in the system's terms — P_i along the normal as
/// written (−P_i n_i on the first body, +P_i n_i on the second), the tangential impulse on the
/// first body and v_a(A) − v_b(A) after impact, both in world axes (the second body takes the
/// opposite impulse).
pub type SystemFrictionContact = super::FrictionContact;

/// One frictional law's readout of a system.
#[derive(Clone, Debug, PartialEq)]
pub struct SystemFrictionReport {
    /// The restitution law.
    pub law: Restitution,
    /// `"planar, exact events"` or `"spatial, adaptive RK5(4)"`.
    pub method: &'static str,
    /// Per contact.
    pub contacts: Vec<SystemFrictionContact>,
    /// Each body's (ω, v_C) after impact.
    pub twists: Vec<([Value; 3], [Value; 3])>,
    /// Each body's kinetic energy after impact.
    pub kinetic_energy_after: Vec<Value>,
    /// Each joint's reaction on its first body, at its anchor.
    pub joint_reactions: Vec<WrenchReport>,
    /// Linear momentum and angular momentum about the origin after impact.
    pub momentum_after: ([Value; 3], [Value; 3]),
    /// E_p, the system's.
    pub lost_velocity_energy: Value,
    /// ΔE_c, the system's.
    pub kinetic_energy_loss: Value,
    /// The energy dissipated by friction.
    pub friction_dissipation: Value,
    /// The values of s where the modes change or a contact stops, in order.
    pub events: Vec<Value>,
    /// The parameter s at the end.
    pub end: Value,
    /// The verdicts, as sentences.
    pub verdicts: Vec<String>,
    /// Their short names, in the same order.
    pub verdict_names: Vec<&'static str>,
    /// The estimated error of the impulses (N s), for the spatial integration.
    pub error_estimate: Option<f64>,
    /// The relative tolerance the spatial integration was run to.
    pub tolerance: Option<f64>,
}

fn triple<T: Scalar>(v: &Vec3<T>) -> [Value; 3] {
    [0, 1, 2].map(|k| Value::of(&v[k]))
}

impl SystemFrictionReport {
    /// Read out `f`, the frictional impact of `system`.
    pub fn new<T: Scalar>(system: &System<T>, f: &Frictional<T, SystemScrew<T>>) -> Self {
        let b = &f.blocks;
        let at = |i: usize, body: usize| {
            let v = &f.velocity.0[body];
            v.bottom() + v.top().cross(system.lever_arm(i, body))
        };
        let contacts = (0..b.contacts())
            .map(|i| {
                let off = b.offset[i];
                let n2 = norm2(&b.directions[off]);
                let (_, tangential) = f.impulse_vectors(i);
                let pair = system.pairs()[i];
                let mut relative = at(i, pair.first);
                if let Some(second) = pair.second {
                    relative -= at(i, second);
                }
                let history = f.history(i);
                SystemFrictionContact {
                    normal_impulse: Value::surd(&Surd::times_norm(f.normal_hat(i), &n2)),
                    compression_impulse: f
                        .compression
                        .get(i)
                        .map(|p| Value::surd(&Surd::times_norm(p, &n2)))
                        .unwrap_or_else(|| Value::float(0.0)),
                    tangential_impulse: triple(&tangential),
                    normal_velocity: Value::surd(&Surd::over_norm(&f.after[off], &n2)),
                    velocity: triple(&relative),
                    sticks: history.last() == Some(&ModeLabel::Stick),
                    history,
                }
            })
            .collect();
        let mut dv = f.velocity.clone();
        crate::mechanics::screw::Screws::add_scaled(&mut dv, &-T::one(), system.velocity());
        let lambda = system.joint_impulses(&dv, f.impulses.iter().zip(&b.axes));
        let (p, l) = system.momentum(&f.velocity);
        let events = f
            .segments
            .iter()
            .take(f.segments.len().saturating_sub(1))
            .map(|s| Value::of(&s.to))
            .collect();
        SystemFrictionReport {
            law: f.law,
            method: if f.error_estimate.is_some() {
                "spatial, adaptive RK5(4)"
            } else {
                "planar, exact events"
            },
            contacts,
            twists: f
                .velocity
                .0
                .iter()
                .map(|s| (triple(&s.top()), triple(&s.bottom())))
                .collect(),
            kinetic_energy_after: system
                .kinetic_energies(&f.velocity)
                .iter()
                .map(Value::of)
                .collect(),
            joint_reactions: system
                .joint_reactions(&lambda)
                .iter()
                .map(WrenchReport::of)
                .collect(),
            momentum_after: (triple(&p), triple(&l)),
            lost_velocity_energy: Value::of(&f.lost_velocity_energy),
            kinetic_energy_loss: Value::of(&f.kinetic_energy_loss),
            friction_dissipation: Value::of(&f.friction_dissipation),
            events,
            end: Value::of(&f.end),
            verdicts: f.verdicts.iter().map(|v| v.to_string()).collect(),
            verdict_names: f.verdicts.iter().map(|v| v.name()).collect(),
            error_estimate: f.error_estimate,
            tolerance: f.tolerance,
        }
    }

    /// The law's object under the system report's `friction` (keys in guide/systems.md).
    pub fn to_json(&self, bodies: &[String]) -> Json {
        let vec = |v: &[Value]| Json::Array(v.iter().map(Value::json).collect());
        json!({
            "method": self.method,
            "contacts": self.contacts.iter().map(|c| json!({
                "normal_impulse": c.normal_impulse.json(),
                "compression_impulse": c.compression_impulse.json(),
                "tangential_impulse": vec(&c.tangential_impulse),
                "normal_velocity_after": c.normal_velocity.json(),
                "velocity_after": vec(&c.velocity),
                "modes": c.history.iter().map(|m| m.name()).collect::<Vec<_>>(),
                "sticks": c.sticks,
            })).collect::<Vec<_>>(),
            "bodies": bodies.iter().zip(&self.twists).zip(&self.kinetic_energy_after)
                .map(|((name, (w, v)), t)| json!({
                    "name": name,
                    "angular_velocity": vec(w),
                    "velocity": vec(v),
                    "kinetic_energy": t.json(),
                }))
                .collect::<Vec<_>>(),
            "joint_reactions": self.joint_reactions.iter().map(|w| json!({
                "anchor": vec(&w.point),
                "force": vec(&w.force),
                "moment": vec(&w.moment),
            })).collect::<Vec<_>>(),
            "momentum_after": {
                "linear": vec(&self.momentum_after.0),
                "angular": vec(&self.momentum_after.1),
            },
            "lost_velocity_energy": self.lost_velocity_energy.json(),
            "kinetic_energy_loss": self.kinetic_energy_loss.json(),
            "friction_dissipation": self.friction_dissipation.json(),
            "events": vec(&self.events),
            "end": self.end.json(),
            "verdicts": self.verdicts,
            "error_estimate": self.error_estimate.map(json_f64),
            "tolerance": self.tolerance.map(json_f64),
        })
    }

    /// The law's readout as text: per contact the impulses, the relative velocity after and
    /// the modes; per body its twist; the energies, the events and the verdicts.
    pub fn to_text(&self, bodies: &[String], free: bool) -> String {
        let bracketed = |v: &[Value]| {
            format!(
                "[{}]",
                v.iter().map(Value::text).collect::<Vec<_>>().join(", ")
            )
        };
        let mut out = format!(
            "\nAfter impact, with friction — {} restitution ({}):\n",
            self.law, self.method
        );
        for (i, c) in self.contacts.iter().enumerate() {
            out += &format!(
                "  A{}: P = {} N s (compression {}), tangential impulse on the first body {} N s\n      \
                 relative velocity {} m/s (normal {}); modes {}{}\n",
                i + 1,
                c.normal_impulse.text(),
                c.compression_impulse.text(),
                bracketed(&c.tangential_impulse),
                bracketed(&c.velocity),
                c.normal_velocity.text(),
                c.history
                    .iter()
                    .map(|m| m.name())
                    .collect::<Vec<_>>()
                    .join(" → "),
                if c.sticks { " (sticks at the end)" } else { "" }
            );
        }
        for (name, (w, v)) in bodies.iter().zip(&self.twists) {
            out += &format!(
                "  {name}: ω = {} rad/s, v_C = {} m/s\n",
                bracketed(w),
                bracketed(v)
            );
        }
        for (j, r) in self.joint_reactions.iter().enumerate() {
            out += &format!(
                "  J{}: F = {} N s, M = {} N m s\n",
                j + 1,
                bracketed(&r.force),
                bracketed(&r.moment)
            );
        }
        out += &format!(
            "  E_p = {} J, ΔE_c = {} J, dissipated by friction {} J\n",
            self.lost_velocity_energy.text(),
            self.kinetic_energy_loss.text(),
            self.friction_dissipation.text()
        );
        if free {
            out += &format!(
                "  momentum after: linear {} N s, angular about O {} N m s\n",
                bracketed(&self.momentum_after.0),
                bracketed(&self.momentum_after.1)
            );
        }
        if !self.events.is_empty() {
            out += &format!(
                "  events at s = {} (end s = {})\n",
                self.events
                    .iter()
                    .map(Value::text)
                    .collect::<Vec<_>>()
                    .join(", "),
                self.end.text()
            );
        }
        if let Some(e) = self.error_estimate {
            out += &format!("  estimated error of the impulses: {} N s", fmt_f64(e));
            if let Some(t) = self.tolerance {
                out += &format!(" (relative tolerance {})", fmt_f64(t));
            }
            out.push('\n');
        }
        for v in &self.verdicts {
            out += &format!("  verdict: {v}\n");
        }
        out
    }
}
