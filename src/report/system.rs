//! What a solve of a system of bodies reports ([`crate::mechanics::system`]): per contact the
//! impulse and the relative velocities before and after, per body its twist after impact and
//! its kinetic energy, per joint its reaction at its anchor, the energies in total, and for a
//! free system its momentum before and after — an exact check on every exact solve. Values are
//! in the paper's units (N s, m/s, rad/s, J), vectors in world axes, positions in the world.

use serde_json::{Map, Value as Json, json};

use super::system_friction::SystemFrictionReport;
use super::{
    PointVelocity, Value, WrenchReport, determinant, impulses, inertances, point_velocities,
    unit_axes,
};
use crate::impact::admissibility::Inadmissible;
use crate::impact::friction::Restitution;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::impact::unilateral::{Activity, Law};
use crate::mechanics::contact::TangentRule;
use crate::mechanics::screw::Vec3;
use crate::mechanics::system::{Pair, System, SystemScrew};
use crate::scalar::Scalar;

/// A system's readout (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct SystemReport {
    /// The scene's name.
    pub scene: String,
    /// `"f64"`, `"exact"`, …
    pub scalar: &'static str,
    /// The effects simulated, e.g. `["joints", "newton"]`.
    pub effects: Vec<String>,
    /// The bodies' names.
    pub bodies: Vec<String>,
    /// Per contact, what it joins: its first body's name and its second's (`None`: an obstacle).
    pub pairs: Vec<(String, Option<String>)>,
    /// Per contact, the obstacle it touches, by name (`obstacle[i]` when unnamed; `None` for a
    /// contact between bodies or with a written normal), as the scene reader gives them;
    /// empty for a system built without a scene.
    pub obstacles: Vec<Option<String>>,
    /// Per joint: its kind, the bodies it joins (the second `None`: the ground).
    pub joints: Vec<(&'static str, String, Option<String>)>,
    /// G = \[g_ij,xx\] (1/kg).
    pub inertance: Vec<Vec<Value>>,
    /// Δ = det G.
    pub det: Value,
    /// Each contact's unit axes, and how y_i was chosen.
    pub frames: Vec<([[Value; 3]; 3], TangentRule)>,
    /// Each contact point's velocity relative to its second body, in its frame, before impact.
    pub contacts_before: Vec<PointVelocity>,
    /// Each body's kinetic energy before impact.
    pub kinetic_energy_before: Vec<Value>,
    /// Whether no obstacle and no joint to the ground acts on the system, so that its
    /// momentum is conserved.
    pub free: bool,
    /// Its linear momentum and angular momentum about the world origin before impact.
    pub momentum_before: ([Value; 3], [Value; 3]),
    /// One readout per model solved.
    pub models: Vec<SystemModelReport>,
    /// The models without an answer while others have one: the model, why, the status.
    pub model_failures: Vec<(Model, String, &'static str)>,
    /// A frictional scene: one readout per restitution law integrated (then `models` is
    /// empty).
    pub friction: Vec<SystemFrictionReport>,
    /// The frictional laws without an answer while others have one: the law, why, the status.
    pub friction_failures: Vec<(Restitution, String, &'static str)>,
}

/// One restitution model's readout of a system.
#[derive(Clone, Debug, PartialEq)]
pub struct SystemModelReport {
    /// Which model.
    pub model: Model,
    /// The law it was solved under.
    pub law: Law,
    /// P_i along each contact's normal as written (N s): −P_i n_i on the first body, +P_i n_i
    /// on the second.
    pub impulses: Vec<Value>,
    /// P_i^c (Poisson).
    pub compression_impulses: Option<Vec<Value>>,
    /// Each body's (ω, v_C) after impact.
    pub twists: Vec<([Value; 3], [Value; 3])>,
    /// Each contact point's relative velocity after impact, in its frame.
    pub contacts: Vec<PointVelocity>,
    /// E_p (eq. 28), the system's.
    pub lost_velocity_energy: Value,
    /// ΔE_c (eq. 32), the system's.
    pub kinetic_energy_loss: Value,
    /// Each body's kinetic energy after impact.
    pub kinetic_energy_after: Vec<Value>,
    /// Linear momentum and angular momentum about the origin after impact.
    pub momentum_after: ([Value; 3], [Value; 3]),
    /// Each joint's reaction on its first body, at its anchor.
    pub joint_reactions: Vec<WrenchReport>,
    /// Why the simultaneous answer is not physical (empty: admissible).
    pub inadmissible: Vec<Inadmissible>,
    /// The unilateral law's activity.
    pub activity: Option<Activity>,
    /// Unilateral: per contact, whether it takes an impulse.
    pub active: Vec<bool>,
}

fn triple<T: Scalar>(v: &Vec3<T>) -> [Value; 3] {
    [0, 1, 2].map(|k| Value::of(&v[k]))
}

fn momentum<T: Scalar>(system: &System<T>, v: &SystemScrew<T>) -> ([Value; 3], [Value; 3]) {
    let (p, l) = system.momentum(v);
    (triple(&p), triple(&l))
}

impl SystemReport {
    /// Read out an assembled system impact and the outcomes of its models; `names` are the
    /// bodies' names.
    pub fn new<T: Scalar>(
        scene: &str,
        effects: Vec<String>,
        names: &[String],
        impact: &Impact<T, System<T>>,
        outcomes: &[(Model, Outcome<T, SystemScrew<T>>)],
    ) -> SystemReport {
        let system = impact.problem();
        let frames = impact.frames();
        let n = impact.contacts();
        let name = |p: &Pair| (names[p.first].clone(), p.second.map(|b| names[b].clone()));
        let free = system.pairs().iter().all(|p| p.second.is_some())
            && system.joints().iter().all(|j| j.pair.second.is_some());
        SystemReport {
            scene: scene.to_string(),
            scalar: T::NAME,
            effects,
            bodies: names.to_vec(),
            pairs: system.pairs().iter().map(name).collect(),
            obstacles: Vec::new(),
            joints: system
                .joints()
                .iter()
                .map(|j| {
                    let (a, b) = name(&j.pair);
                    (j.joint.name(), a, b)
                })
                .collect(),
            inertance: inertances(impact.g_hat(), frames, n, 0),
            det: determinant(impact.det_hat(), frames),
            frames: frames.iter().map(|f| unit_axes(f, true)).collect(),
            contacts_before: point_velocities(impact.before_hat(), frames, true),
            kinetic_energy_before: system
                .kinetic_energies(system.velocity())
                .iter()
                .map(Value::of)
                .collect(),
            free,
            momentum_before: momentum(system, system.velocity()),
            models: outcomes
                .iter()
                .map(|(m, o)| SystemModelReport {
                    model: *m,
                    law: Law::Simultaneous,
                    impulses: impulses(&o.impulses_hat, frames),
                    compression_impulses: match m {
                        Model::Newton => None,
                        Model::Poisson => Some(impulses(&o.compression_hat, frames)),
                    },
                    twists: o
                        .velocity
                        .0
                        .iter()
                        .map(|s| (triple(&s.top()), triple(&s.bottom())))
                        .collect(),
                    contacts: point_velocities(&o.after_hat, frames, true),
                    lost_velocity_energy: Value::of(&o.lost_velocity_energy),
                    kinetic_energy_loss: Value::of(&o.kinetic_energy_loss),
                    kinetic_energy_after: system
                        .kinetic_energies(&o.velocity)
                        .iter()
                        .map(Value::of)
                        .collect(),
                    momentum_after: momentum(system, &o.velocity),
                    joint_reactions: system
                        .joint_reactions(&o.constraint_impulses)
                        .iter()
                        .map(WrenchReport::of)
                        .collect(),
                    inadmissible: Vec::new(),
                    activity: None,
                    active: Vec::new(),
                })
                .collect(),
            model_failures: Vec::new(),
            friction: Vec::new(),
            friction_failures: Vec::new(),
        }
    }

    /// The JSON report (keys documented in guide/systems.md).
    pub fn to_json(&self) -> Json {
        let vec = |v: &[Value]| Json::Array(v.iter().map(Value::json).collect());
        let pv = |p: &PointVelocity| {
            json!({
                "velocity": vec(&p.components),
                "angle_deg": p.angle.as_ref().map(|a| a.degrees),
            })
        };
        let mut models = Map::new();
        for m in &self.models {
            let mut obj = json!({
                "law": m.law.name(),
                "impulses": vec(&m.impulses),
                "bodies": self.bodies.iter().zip(&m.twists).zip(&m.kinetic_energy_after)
                    .map(|((name, (w, v)), t)| json!({
                        "name": name,
                        "angular_velocity": vec(w),
                        "velocity": vec(v),
                        "kinetic_energy": t.json(),
                    }))
                    .collect::<Vec<_>>(),
                "contacts": m.contacts.iter().map(pv).collect::<Vec<_>>(),
                "lost_velocity_energy": m.lost_velocity_energy.json(),
                "kinetic_energy_loss": m.kinetic_energy_loss.json(),
                "joint_reactions": m.joint_reactions.iter().map(|w| json!({
                    "anchor": vec(&w.point),
                    "force": vec(&w.force),
                    "moment": vec(&w.moment),
                })).collect::<Vec<_>>(),
                "momentum_after": {
                    "linear": vec(&m.momentum_after.0),
                    "angular": vec(&m.momentum_after.1),
                },
                "admissible": m.inadmissible.is_empty(),
                "inadmissible": m.inadmissible.iter().map(|v| json!({
                    "reason": v.name(),
                    "message": v.to_string(),
                })).collect::<Vec<_>>(),
            });
            if let (Some(c), Some(o)) = (&m.compression_impulses, obj.as_object_mut()) {
                o.insert("compression_impulses".into(), vec(c));
            }
            if let (false, Some(o)) = (m.active.is_empty(), obj.as_object_mut()) {
                o.insert("active".into(), json!(m.active));
            }
            if let (Some(a), Some(o)) = (&m.activity, obj.as_object_mut()) {
                o.insert("impulses_unique".into(), a.impulses_unique.into());
                o.insert("outcome_decided".into(), a.outcome_decided.into());
            }
            models.insert(m.model.name().into(), obj);
        }
        for (model, message, status) in &self.model_failures {
            models.insert(
                model.name().into(),
                json!({ "error": message, "status": status }),
            );
        }
        let mut friction = Map::new();
        for f in &self.friction {
            friction.insert(f.law.name().into(), f.to_json(&self.bodies));
        }
        for (law, message, status) in &self.friction_failures {
            friction.insert(
                law.name().into(),
                json!({ "error": message, "status": status }),
            );
        }
        let mut top = json!({
            "scene": self.scene,
            "scalar": self.scalar,
            "effects": self.effects,
            "bodies": self.bodies.iter().zip(&self.kinetic_energy_before).map(|(n, t)| json!({
                "name": n, "kinetic_energy_before": t.json(),
            })).collect::<Vec<_>>(),
            "contacts": self.pairs.iter().zip(&self.frames).zip(&self.contacts_before).enumerate()
                .map(|(i, (((a, b), (axes, _)), before))| json!({
                    "bodies": match b { Some(b) => json!([a, b]), None => json!([a]) },
                    "obstacle": self.obstacles.get(i).cloned().flatten(),
                    "normal": vec(&axes[0]),
                    "velocity_before": vec(&before.components),
                }))
                .collect::<Vec<_>>(),
            "joints": self.joints.iter().map(|(kind, a, b)| json!({
                "kind": kind,
                "bodies": match b { Some(b) => json!([a, b]), None => json!([a]) },
            })).collect::<Vec<_>>(),
            "inertance": self.inertance.iter().map(|r| vec(r)).collect::<Vec<_>>(),
            "det": self.det.json(),
            "free": self.free,
            "momentum_before": {
                "linear": vec(&self.momentum_before.0),
                "angular": vec(&self.momentum_before.1),
            },
            "models": Json::Object(models),
        });
        if let (false, Some(o)) = (friction.is_empty(), top.as_object_mut()) {
            o.insert("friction".into(), Json::Object(friction));
        }
        top
    }

    /// The report as text.
    pub fn to_table(&self) -> String {
        let mut out = format!(
            "{} — {} ({})\n\n",
            self.scene,
            self.scalar,
            self.effects.join(", ")
        );
        out += "Vectors in world axes; each body's twist about its own centre of mass.\n\n";
        out += "Contacts:\n";
        for (i, ((a, b), before)) in self.pairs.iter().zip(&self.contacts_before).enumerate() {
            let other = match (b, self.obstacles.get(i)) {
                (Some(b), _) => format!("\"{b}\""),
                (None, Some(Some(o))) => format!("obstacle \"{o}\""),
                (None, _) => "an obstacle".into(),
            };
            out += &format!(
                "  A{}: \"{a}\" against {other}, approaching at v_x = {} m/s\n",
                i + 1,
                before.components[0].text()
            );
        }
        for (j, (kind, a, b)) in self.joints.iter().enumerate() {
            out += &format!(
                "  J{}: {kind} joint, \"{a}\" to {}\n",
                j + 1,
                match b {
                    Some(b) => format!("\"{b}\""),
                    None => "the ground".into(),
                }
            );
        }
        out += "\nInertances G = [g_ij,xx] [1/kg]:\n";
        for r in &self.inertance {
            out += &format!(
                "  {}\n",
                r.iter().map(Value::text).collect::<Vec<_>>().join("  ")
            );
        }
        out += &format!("Δ = det G = {}\n", self.det.text());
        if !self.friction.is_empty() || !self.friction_failures.is_empty() {
            for f in &self.friction {
                out += &f.to_text(&self.bodies, self.free);
            }
            for (law, message, _) in &self.friction_failures {
                out += &format!(
                    "\nAfter impact, with friction — {law} restitution: no answer: {message}\n"
                );
            }
            return out;
        }
        out += "\nAfter impact:\n";
        let header: Vec<String> = self
            .models
            .iter()
            .map(|m| m.model.name().to_string())
            .collect();
        let mut rows: Vec<(String, Vec<String>)> = Vec::new();
        let each = |f: &dyn Fn(&SystemModelReport) -> String| -> Vec<String> {
            self.models.iter().map(f).collect()
        };
        for i in 0..self.pairs.len() {
            rows.push((format!("P{} [N s]", i + 1), each(&|m| m.impulses[i].text())));
        }
        let vector = |v: &[Value; 3]| {
            format!(
                "({})",
                v.iter().map(Value::text).collect::<Vec<_>>().join(", ")
            )
        };
        for (b, name) in self.bodies.iter().enumerate() {
            rows.push((
                format!("{name} ω [rad/s]"),
                each(&|m| vector(&m.twists[b].0)),
            ));
            rows.push((
                format!("{name} v_C [m/s]"),
                each(&|m| vector(&m.twists[b].1)),
            ));
        }
        for i in 0..self.pairs.len() {
            rows.push((
                format!("v{}x [m/s]", i + 1),
                each(&|m| m.contacts[i].components[0].text()),
            ));
        }
        for (j, _) in self.joints.iter().enumerate() {
            rows.push((
                format!("J{} F [N s]", j + 1),
                each(&|m| vector(&m.joint_reactions[j].force)),
            ));
            rows.push((
                format!("J{} M [N m s]", j + 1),
                each(&|m| vector(&m.joint_reactions[j].moment)),
            ));
        }
        rows.push(("E_p [J]".into(), each(&|m| m.lost_velocity_energy.text())));
        rows.push(("ΔE_c [J]".into(), each(&|m| m.kinetic_energy_loss.text())));
        out += &super::table::aligned(&header, &rows);
        for m in &self.models {
            if let Some(a) = &m.activity {
                out += &super::table::activity_note(m.model, a);
            }
        }
        if self.free {
            out += "Momentum (a free system: conserved):\n";
            let show = |(p, l): &([Value; 3], [Value; 3])| {
                let t = |v: &[Value; 3]| v.iter().map(Value::text).collect::<Vec<_>>().join(", ");
                format!("linear ({}) N s, angular about O ({}) N m s", t(p), t(l))
            };
            out += &format!("  before: {}\n", show(&self.momentum_before));
            for m in &self.models {
                out += &format!("  {} after: {}\n", m.model, show(&m.momentum_after));
            }
        }
        for (model, message, _) in &self.model_failures {
            out += &format!("{model}: no answer: {message}\n");
        }
        out
    }
}
