//! The text table: what was assembled (G, Δ, the surface, the constraints), the contact
//! velocities before impact, then the models side by side after impact, in SI units.

use super::{FrictionReport, ModelReport, Report, Value, WrenchReport, fmt_f64};
use crate::impact::outputs::Outputs;
use crate::impact::restitution::Model;
use crate::impact::unilateral::Activity;

/// A row of the after-impact table: its label, and one cell per model.
type Row = (String, Vec<String>);

/// Values as `[a, b, c]`.
fn bracketed(values: &[Value]) -> String {
    format!(
        "[{}]",
        values
            .iter()
            .map(Value::text)
            .collect::<Vec<_>>()
            .join(", ")
    )
}

impl Report {
    /// A readable table: models side by side, SI units.
    pub fn to_table(&self) -> String {
        let mut out = format!(
            "{} — {} ({})\n\n",
            self.scene,
            self.scalar,
            self.effects.join(", ")
        );
        if let Some(axes) = self.axes {
            out += &format!("Vectors in {axes} axes, positions from the centre of mass C.\n\n");
        }
        out += &self.assembled();
        out += &self.before();
        if !self.friction.is_empty() {
            for f in &self.friction {
                out += &f.to_text();
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
        out += &aligned(&header, &self.after_rows());
        for m in &self.models {
            let Some(a) = &m.activity else { continue };
            out += &activity_note(m.model, a);
            if let (false, Some(r)) = (a.outcome_decided, &m.outcome_range) {
                let names = ["ωx", "ωy", "ωz", "vCx", "vCy", "vCz"];
                let varying: Vec<String> = names
                    .iter()
                    .zip(r)
                    .filter(|(_, (lo, hi))| lo.f64 != hi.f64 || lo.exact != hi.exact)
                    .map(|(n, (lo, hi))| format!("{n} ∈ [{}, {}]", lo.text(), hi.text()))
                    .collect();
                out += &format!(
                    "  over the vertices of the set of compression impulses: {}\n",
                    if varying.is_empty() {
                        "the same twist".to_string()
                    } else {
                        varying.join(", ")
                    }
                );
            }
        }
        for (model, message, _) in &self.model_failures {
            out += &format!("{model}: no answer: {message}\n");
        }
        out
    }

    /// G, Δ, and the surface and constraints when there are any.
    fn assembled(&self) -> String {
        let mut out = "Inertances G = [g_ij,xx] [1/kg]:\n".to_string();
        for r in &self.inertance {
            out += &format!(
                "  {}\n",
                r.iter().map(Value::text).collect::<Vec<_>>().join("  ")
            );
        }
        out += &format!("Δ = det G = {}\n", self.det.text());
        if let Some((f, g)) = &self.surface {
            out += &format!(
                "Surface: f = {f} = 0, ∇f = ({}, {}, {})\n",
                g[0], g[1], g[2]
            );
        }
        if let Some(c) = &self.constraints {
            let screws = |l: &[[Value; 6]]| -> String {
                l.iter().map(|s| bracketed(s)).collect::<Vec<_>>().join(" ")
            };
            out += &format!(
                "Constraints: {} degree(s) of freedom\n  D = {}\n  U = {}{}\n",
                c.free.len(),
                screws(&c.free),
                screws(&c.blocked),
                if c.blocked_derived {
                    " (derived: η-orthogonal complement of D)"
                } else {
                    ""
                }
            );
            let m = c
                .reduced_mass
                .iter()
                .map(|r| bracketed(r))
                .collect::<Vec<_>>()
                .join(" ");
            out += &format!("  M_red = Dᵀ η M D = {m}\n");
            if let (false, Some(model)) = (c.joints.is_empty(), self.models.first()) {
                // The anchors are the same for every model.
                let anchors: Vec<String> = c
                    .joints
                    .iter()
                    .zip(&model.joint_reactions)
                    .enumerate()
                    .map(|(j, (joint, w))| match joint.has_point {
                        true => format!("J{} {} at {} m", j + 1, joint.kind, bracketed(&w.point)),
                        false => format!("J{} {} at C (it has no point)", j + 1, joint.kind),
                    })
                    .collect();
                if !anchors.is_empty() {
                    out += &format!(
                        "  Joint reactions on the body, about each anchor: {}\n",
                        anchors.join("; ")
                    );
                }
            }
        }
        out
    }

    /// The contact-point velocities before impact, one line per contact.
    fn before(&self) -> String {
        let mut out = "\nBefore impact:\n".to_string();
        if !self.outputs.contains(Outputs::TANGENTIAL) {
            for (i, b) in self.contacts_before.iter().enumerate() {
                out += &format!("  A{}: v_x = {} m/s\n", i + 1, b.components[0].text());
            }
            return out;
        }
        for (i, b) in self.contacts_before.iter().enumerate() {
            out += &format!(
                "  A{}: v = ({}, {}, {}) m/s, α⁰ = {}\n",
                i + 1,
                b.components[0].text(),
                b.components[1].text(),
                b.components[2].text(),
                b.angle
                    .as_ref()
                    .map_or("— (no tangential velocity)".into(), |x| format!(
                        "{}°",
                        fmt_f64(x.degrees)
                    ))
            );
        }
        out
    }

    /// The after-impact rows: impulses, velocities, contact velocities and angles, constraint
    /// impulses, energies.
    fn after_rows(&self) -> Vec<Row> {
        let mut rows: Vec<Row> = Vec::new();
        let n = self.inertance.len();
        let each = |f: &dyn Fn(&ModelReport) -> String| -> Vec<String> {
            self.models.iter().map(f).collect()
        };
        let asked = |x: Outputs| self.outputs.contains(x);
        for i in (0..n).filter(|_| asked(Outputs::IMPULSES)) {
            rows.push((format!("P{} [N s]", i + 1), each(&|m| m.impulses[i].text())));
        }
        if self.models.iter().any(|m| m.activity.is_some()) {
            // The unilateral law: which contacts take an impulse and which separate.
            for i in 0..n {
                rows.push((
                    format!("contact {}", i + 1),
                    each(&|m| match m.active.get(i) {
                        Some(true) => "active".into(),
                        Some(false) => "separates".into(),
                        None => "—".into(),
                    }),
                ));
            }
        }
        for i in (0..n).filter(|_| asked(Outputs::IMPULSES)) {
            if self.models.iter().any(|m| m.compression_impulses.is_some()) {
                rows.push((
                    format!("P{}c [N s]", i + 1),
                    each(&|m| {
                        m.compression_impulses
                            .as_ref()
                            .map_or("—".into(), |c| c[i].text())
                    }),
                ));
            }
        }
        let axes = ["x", "y", "z"];
        let twist = if asked(Outputs::TWIST) { 3 } else { 0 };
        for (k, a) in axes.iter().enumerate().take(twist) {
            rows.push((
                format!("ω{a} [rad/s]"),
                each(&|m| m.angular_velocity[k].text()),
            ));
        }
        for (k, a) in axes.iter().enumerate().take(twist) {
            rows.push((format!("vC{a} [m/s]"), each(&|m| m.velocity[k].text())));
        }
        for i in (0..n).filter(|_| !asked(Outputs::TANGENTIAL) && asked(Outputs::NORMAL_VELOCITIES))
        {
            rows.push((
                format!("v{}x [m/s]", i + 1),
                each(&|m| m.contacts[i].components[0].text()),
            ));
        }
        for i in (0..n).filter(|_| asked(Outputs::TANGENTIAL)) {
            for (k, a) in axes.iter().enumerate() {
                rows.push((
                    format!("v{}{a} [m/s]", i + 1),
                    each(&|m| m.contacts[i].components[k].text()),
                ));
            }
            rows.push((
                format!("α{} [deg]", i + 1),
                each(&|m| {
                    m.contacts[i]
                        .angle
                        .as_ref()
                        .map_or("—".into(), |x| fmt_f64(x.degrees))
                }),
            ));
        }
        if let (Some(c), true) = (&self.constraints, asked(Outputs::CONSTRAINT_IMPULSES)) {
            for a in 0..c.blocked.len() {
                rows.push((
                    format!("q{} [N s]", a + 1),
                    each(&|m| m.constraint_impulses[a].text()),
                ));
            }
            // U q as a force and a moment: per joint about its anchor, or about C.
            let named: Vec<(String, &str)> = match c.joints.len() {
                0 => vec![(String::new(), "MC")],
                n => (1..=n).map(|j| (format!("J{j} "), "M")).collect(),
            };
            for (j, (label, moment)) in named.iter().enumerate() {
                let cell = |m: &ModelReport, f: &dyn Fn(&WrenchReport) -> String| {
                    let wrench = match c.joints.is_empty() {
                        true => m.constraint_wrench.as_ref(),
                        false => m.joint_reactions.get(j),
                    };
                    wrench.map_or("—".into(), f)
                };
                for (k, a) in axes.iter().enumerate() {
                    rows.push((
                        format!("{label}F{a} [N s]"),
                        each(&|m| cell(m, &|w| w.force[k].text())),
                    ));
                }
                for (k, a) in axes.iter().enumerate() {
                    rows.push((
                        format!("{label}{moment}{a} [N m s]"),
                        each(&|m| cell(m, &|w| w.moment[k].text())),
                    ));
                }
            }
        }
        if asked(Outputs::ENERGIES) {
            rows.push(("E_p [J]".into(), each(&|m| m.lost_velocity_energy.text())));
            rows.push(("ΔE_c [J]".into(), each(&|m| m.kinetic_energy_loss.text())));
        }
        rows
    }
}

/// What the unilateral law leaves open for `model` (its `activity`): the outcome itself, or
/// only which impulses among a set; empty when both are unique. One body's report and a
/// system's say it in the same words.
pub(crate) fn activity_note(model: Model, a: &Activity) -> String {
    if !a.outcome_decided {
        format!(
            "{model}: the law does not decide the outcome — the compression impulses form a \
             set and the k_i differ, so the velocities after impact depend on which are \
             taken; shown: one possibility\n"
        )
    } else if !a.impulses_unique {
        format!(
            "{model}: the velocities after impact are unique; the impulses shown may be one of \
             a set (G is singular on the contacts that meet their law)\n"
        )
    } else {
        String::new()
    }
}

/// The header and rows as columns: labels left-aligned, cells right-aligned, each column as
/// wide as its widest cell (counted in characters, not bytes).
pub(super) fn aligned(header: &[String], rows: &[Row]) -> String {
    let w0 = rows.iter().map(|r| r.0.chars().count()).max().unwrap_or(0);
    let cols: Vec<usize> = (0..header.len())
        .map(|c| {
            rows.iter()
                .map(|r| r.1[c].chars().count())
                .chain([header[c].len()])
                .max()
                .unwrap_or(0)
        })
        .collect();
    let line = |name: &str, cells: &[String]| -> String {
        let mut s = format!("  {name}{}", " ".repeat(w0 - name.chars().count()));
        for (c, cell) in cells.iter().enumerate() {
            s += &format!("  {}{}", " ".repeat(cols[c] - cell.chars().count()), cell);
        }
        s + "\n"
    };
    let mut out = line("", header);
    for (name, cells) in rows {
        out += &line(name, cells);
    }
    out
}

impl FrictionReport {
    /// One frictional law's readout as text: per contact, the impulses, the velocity after
    /// and the modes; the twist, the energies, the events and the verdicts.
    pub fn to_text(&self) -> String {
        friction_table(self)
    }
}

fn friction_table(f: &FrictionReport) -> String {
    let mut out = format!(
        "\nAfter impact, with friction — {} restitution ({}):\n",
        f.law, f.method
    );
    for (i, c) in f.contacts.iter().enumerate() {
        out += &format!(
            "  A{}: P = {} N s (compression {}), tangential impulse {} N s\n      v = {} m/s \
             (normal {}); modes {}{}\n",
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
    out += &format!(
        "  ω = {} rad/s, v_C = {} m/s\n  E_p = {} J, ΔE_c = {} J, dissipated by friction {} J\n",
        bracketed(&f.angular_velocity),
        bracketed(&f.velocity),
        f.lost_velocity_energy.text(),
        f.kinetic_energy_loss.text(),
        f.friction_dissipation.text()
    );
    if !f.events.is_empty() {
        out += &format!(
            "  events at s = {} (end s = {})\n",
            f.events
                .iter()
                .map(Value::text)
                .collect::<Vec<_>>()
                .join(", "),
            f.end.text()
        );
    }
    if let Some(e) = f.error_estimate {
        out += &format!("  estimated error of the impulses: {} N s", fmt_f64(e));
        if let Some(t) = f.tolerance {
            out += &format!(" (relative tolerance {})", fmt_f64(t));
        }
        out.push('\n');
    }
    for v in &f.verdicts {
        out += &format!("  verdict: {v}\n");
    }
    out
}
