//! The JSON report: its keys are a public contract (guide/solving.md, "JSON report"), so they change
//! only with that page.

use serde_json::{Map, Value as Json, json};

use super::{FrictionReport, ModelReport, PointVelocity, Report, Value, json_f64};
use crate::impact::outputs::Outputs;
use crate::mechanics::contact::TangentRule;

/// A matrix, row by row.
fn mat(m: &[Vec<Value>]) -> Json {
    Json::Array(
        m.iter()
            .map(|r| Json::Array(r.iter().map(Value::json).collect()))
            .collect(),
    )
}

/// A list of values.
fn vec(v: &[Value]) -> Json {
    Json::Array(v.iter().map(Value::json).collect())
}

/// How a frame's y axis was chosen, as named in the report.
fn tangent_rule(rule: &TangentRule) -> String {
    match rule {
        TangentRule::Given => "given".to_string(),
        TangentRule::Velocity => "velocity".to_string(),
        TangentRule::Fallback(k) => format!("fallback-{}", ["x", "y", "z"][*k]),
    }
}

impl Report {
    /// The JSON report (keys documented in guide/solving.md).
    pub fn to_json(&self) -> Json {
        let mut models = Map::new();
        for r in &self.models {
            models.insert(r.model.name().into(), self.model_json(r));
        }
        for (model, message, status) in &self.model_failures {
            models.insert(
                model.name().into(),
                json!({ "error": message, "status": status }),
            );
        }
        let mut top = json!({
            "scene": self.scene,
            "scalar": self.scalar,
            "effects": self.effects,
            "inertance": mat(&self.inertance),
            "inertance_yx": mat(&self.inertance_yx),
            "inertance_zx": mat(&self.inertance_zx),
            "det": self.det.json(),
            "frames": self.frames.iter().map(|(axes, rule)| json!({
                "x": vec(&axes[0]), "y": vec(&axes[1]), "z": vec(&axes[2]),
                "tangent": tangent_rule(rule),
            })).collect::<Vec<_>>(),
            "models": Json::Object(models),
        });
        if let Some(axes) = self.axes {
            top["axes"] = json!(axes);
        }
        if let (false, Some(obj)) = (self.outputs == Outputs::ALL, top.as_object_mut()) {
            // Only the outputs asked for: say which, and leave the tangential part out.
            obj.insert("outputs".into(), self.outputs.to_string().into());
            if !self.outputs.contains(Outputs::TANGENTIAL) {
                obj.remove("inertance_yx");
                obj.remove("inertance_zx");
                for f in obj["frames"].as_array_mut().into_iter().flatten() {
                    if let Some(f) = f.as_object_mut() {
                        f.remove("y");
                        f.remove("z");
                        f.remove("tangent");
                    }
                }
            }
        }
        if let (false, Some(obj)) = (self.friction.is_empty(), top.as_object_mut()) {
            let mut laws = Map::new();
            for f in &self.friction {
                laws.insert(f.law.name().into(), f.to_json());
            }
            for (law, message, status) in &self.friction_failures {
                laws.insert(
                    law.name().into(),
                    json!({ "error": message, "status": status }),
                );
            }
            obj.insert("friction".into(), Json::Object(laws));
        }
        if let (Some((f, grad)), Some(obj)) = (&self.surface, top.as_object_mut()) {
            obj.insert("surface".into(), json!({ "f": f, "gradient": grad }));
        }
        if let (Some(c), Some(obj)) = (&self.constraints, top.as_object_mut()) {
            obj.insert(
                "constraints".into(),
                json!({
                    "free": c.free.iter().map(|s| vec(s)).collect::<Vec<_>>(),
                    "blocked": c.blocked.iter().map(|s| vec(s)).collect::<Vec<_>>(),
                    "blocked_derived": c.blocked_derived,
                    "reduced_mass": mat(&c.reduced_mass),
                }),
            );
        }
        top
    }

    /// One model's object under `models`.
    fn model_json(&self, r: &ModelReport) -> Json {
        let mut o = Map::new();
        let asked = |x: Outputs| self.outputs.contains(x);
        if asked(Outputs::IMPULSES) {
            o.insert("impulses".into(), vec(&r.impulses));
            o.insert("impulses_per_normal".into(), vec(&r.impulse_multiples));
            if let Some(c) = &r.compression_impulses {
                o.insert("compression_impulses".into(), vec(c));
            }
        }
        if asked(Outputs::TWIST) {
            o.insert("velocity".into(), vec(&r.velocity));
            o.insert("angular_velocity".into(), vec(&r.angular_velocity));
        }
        let pairs = self.contacts_before.iter().zip(&r.contacts);
        if asked(Outputs::TANGENTIAL) {
            let contacts = pairs.map(|(b, a)| contact_json(b, a)).collect();
            o.insert("contacts".into(), Json::Array(contacts));
        } else if asked(Outputs::NORMAL_VELOCITIES) {
            let contacts = pairs.map(|(b, a)| {
                json!({
                    "normal_velocity_before": b.components[0].json(),
                    "normal_velocity_after": a.components[0].json(),
                })
            });
            o.insert("contacts".into(), Json::Array(contacts.collect()));
        }
        if asked(Outputs::ENERGIES) {
            o.insert("lost_velocity_energy".into(), r.lost_velocity_energy.json());
            o.insert("kinetic_energy_loss".into(), r.kinetic_energy_loss.json());
        }
        if let (Some(c), true) = (&self.constraints, asked(Outputs::CONSTRAINT_IMPULSES)) {
            o.insert("constraint_impulses".into(), vec(&r.constraint_impulses));
            if let Some(w) = &r.constraint_wrench {
                o.insert(
                    "constraint_wrench".into(),
                    json!({ "force": vec(&w.force), "moment": vec(&w.moment) }),
                );
            }
            if !c.joints.is_empty() {
                let joints = c.joints.iter().zip(&r.joint_reactions).map(|(j, w)| {
                    json!({
                        "kind": j.kind,
                        "about": if j.has_point { "point" } else { "centre-of-mass" },
                        "point": vec(&w.point),
                        "force": vec(&w.force),
                        "moment": vec(&w.moment),
                    })
                });
                o.insert("joint_reactions".into(), Json::Array(joints.collect()));
            }
        }
        o.insert("law".into(), r.law.name().into());
        o.insert("admissible".into(), r.inadmissible.is_empty().into());
        o.insert(
            "inadmissible".into(),
            r.inadmissible
                .iter()
                .map(|v| json!({ "reason": v.name(), "contact": v.contact(), "message": v.to_string() }))
                .collect(),
        );
        if let Some(a) = &r.activity {
            o.insert("active".into(), r.active.clone().into());
            o.insert("impulses_unique".into(), a.impulses_unique.into());
            o.insert("outcome_decided".into(), a.outcome_decided.into());
            if let Some(range) = &r.outcome_range {
                o.insert(
                    "outcome_range".into(),
                    json!({
                        "twist_min": range.iter().map(|(lo, _)| lo.json()).collect::<Vec<_>>(),
                        "twist_max": range.iter().map(|(_, hi)| hi.json()).collect::<Vec<_>>(),
                    }),
                );
            }
        }
        Json::Object(o)
    }
}

/// One contact point's velocities before and after impact.
fn contact_json(b: &PointVelocity, a: &PointVelocity) -> Json {
    json!({
        "velocity_before": vec(&b.components),
        "velocity_after": vec(&a.components),
        "angle_before_deg": b.angle.as_ref().map(|x| json_f64(x.degrees)),
        "angle_after_deg": a.angle.as_ref().map(|x| json_f64(x.degrees)),
    })
}

impl FrictionReport {
    /// One frictional law's object under the report's `friction` (keys in guide/friction.md).
    pub fn to_json(&self) -> Json {
        friction_json(self)
    }
}

fn friction_json(f: &FrictionReport) -> Json {
    json!({
        "method": f.method,
        "contacts": f.contacts.iter().map(|c| json!({
            "normal_impulse": c.normal_impulse.json(),
            "compression_impulse": c.compression_impulse.json(),
            "tangential_impulse": vec(&c.tangential_impulse),
            "normal_velocity_after": c.normal_velocity.json(),
            "velocity_after": vec(&c.velocity),
            "modes": c.history.iter().map(|m| m.name()).collect::<Vec<_>>(),
            "sticks": c.sticks,
        })).collect::<Vec<_>>(),
        "angular_velocity": vec(&f.angular_velocity),
        "velocity": vec(&f.velocity),
        "lost_velocity_energy": f.lost_velocity_energy.json(),
        "kinetic_energy_loss": f.kinetic_energy_loss.json(),
        "friction_dissipation": f.friction_dissipation.json(),
        "events": vec(&f.events),
        "end": f.end.json(),
        "verdicts": f.verdicts,
        "error_estimate": f.error_estimate.map(json_f64),
        "tolerance": f.tolerance.map(json_f64),
    })
}
