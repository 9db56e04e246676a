//! The same exact scaling for a scene of several bodies ([`crate::scene::system_pipeline`]):
//! one mass, length and time unit m = 2^a kg, L = 2^b m, T = 2^c s for the whole system,
//! chosen from all its bodies as the parent module chooses them for one body —
//!
//! - b from the largest world position: a body's centre, a contact point, a joint's anchor (a
//!   system's points are world points, and its lever arms r = A − C are their differences);
//! - a midway, in the exponent, between the largest mass and the smallest moment over L²
//!   (over every body: the largest mass and the smallest moment);
//! - c making the largest speed of approach of a contact, |n·(v_a(A) − v_b(A))|/|n| computed
//!   exactly, about 1, as far as the largest velocity (|v_C| or |ω|·L of any body) may grow
//!   ([`super::HEADROOM`]).
//!
//! Every body's m′ = m/2^a, J′ = J/2^(a+2b) (products of inertia too), C′ = C/2^b,
//! v_C′ = v_C·2^(c−b), ω′ = ω·2^c; a contact's point /2^b, its normal and tangent each divided
//! by its own power of two (directions); a joint's anchor /2^b and its axis (a direction, a
//! planar joint's normal) by its own. Joints carry no written screw: their blocked screws are
//! built from anchor and axis in either units, and only their reactions are reported — a wrench
//! [F; M] at its anchor, F an impulse (M·L/T) and M an impulse's moment (M·L²/T). The report is
//! scaled back output by output ([`unscale_system`]); what f64 cannot hold is refused as for one
//! body, naming the output ([`system_out_of_range`], [`system_precision_lost`]).

use num_rational::BigRational;
use num_traits::Zero;

use super::{
    HEADROOM, Units, exponent, largest, number_exponent, point, scale_number, times, times_wide,
};
use crate::number::Number;
use crate::report::system::SystemReport;
use crate::report::{Value, WrenchReport};
use crate::scene::Scene;

/// `scene`, a system scene, in units chosen from its own numbers (module docs), or `None` when
/// it is not scaled (not a system, a symbolic number, a `[surface]`, or units of 1 already).
/// [`Units::free`] and [`Units::blocked`] are empty: a system's joints write no screws.
pub fn scale_system(scene: &Scene) -> Option<(Scene, Units)> {
    let spec = scene.system.as_ref()?;
    let symbolic = |n: &Number| !n.symbols.is_empty();
    if scene.surface.is_some()
        || scene.numbers().any(|(_, n)| symbolic(n))
        || spec.numbers().iter().any(|(_, n)| symbolic(n))
    {
        return None;
    }
    let positions = spec
        .bodies
        .iter()
        .flat_map(|body| body.centre.iter())
        .chain(scene.contacts.iter().flat_map(|c| c.point.iter()))
        .chain(spec.joints.iter().flat_map(|j| j.anchor.iter().flatten()));
    let b = largest(positions).unwrap_or(0);
    let mass = largest(spec.bodies.iter().map(|body| &body.mass)).unwrap_or(0);
    let moments = spec
        .bodies
        .iter()
        .flat_map(|body| body.inertia.iter())
        .filter_map(number_exponent)
        .min()
        .map(|j| j - 2 * b);
    let a = moments.map_or(mass, |j| (mass + j).div_euclid(2));
    let v = largest(spec.bodies.iter().flat_map(|body| body.velocity.iter()));
    let w = largest(
        spec.bodies
            .iter()
            .flat_map(|body| body.angular_velocity.iter()),
    )
    .map(|e| e + b);
    let speed = match (v, w) {
        (Some(x), Some(y)) => Some(x.max(y)),
        (x, y) => x.or(y),
    };
    let c = speed.map_or(0, |s| {
        let approach = approach_exponent(scene).unwrap_or(s);
        b - approach.clamp(s - HEADROOM, s)
    });
    let mut s = scene.clone();
    let spec = s.system.as_mut()?;
    for body in &mut spec.bodies {
        scale_number(&mut body.mass, -a);
        for j in body
            .inertia
            .iter_mut()
            .chain(body.inertia_products.iter_mut().flatten())
        {
            scale_number(j, -a - 2 * b);
        }
        body.centre.iter_mut().for_each(|x| scale_number(x, -b));
        body.velocity
            .iter_mut()
            .for_each(|x| scale_number(x, c - b));
        body.angular_velocity
            .iter_mut()
            .for_each(|x| scale_number(x, c));
    }
    for joint in &mut spec.joints {
        for x in joint.anchor.iter_mut().flatten() {
            scale_number(x, -b);
        }
        if let Some(axis) = &mut joint.axis {
            own_scale(axis);
        }
    }
    for (first, second) in &mut spec.levers {
        for x in first.iter_mut().chain(second.iter_mut().flatten()) {
            scale_number(x, -b);
        }
    }
    let mut normals = Vec::with_capacity(s.contacts.len());
    for contact in &mut s.contacts {
        contact.point.iter_mut().for_each(|x| scale_number(x, -b));
        normals.push(contact.normal.as_mut().map_or(0, own_scale));
        if let Some(t) = &mut contact.tangent {
            own_scale(t);
        }
    }
    let units = Units {
        mass: a,
        length: b,
        time: c,
        normals,
        free: Vec::new(),
        blocked: Vec::new(),
    };
    (a != 0 || b != 0 || c != 0 || units.normals.iter().any(|&e| e != 0)).then_some((s, units))
}

/// Divide a direction by the power of two of its largest component; that power.
fn own_scale(direction: &mut [Number; 3]) -> i64 {
    let e = largest(direction.iter()).unwrap_or(0);
    direction.iter_mut().for_each(|x| scale_number(x, -e));
    e
}

/// ⌊log₂⌋ within two of the largest speed of approach |n_i·(v_a(A_i) − v_b(A_i))|/|n_i| of a
/// system scene (m/s), computed exactly (v_b(A) = v_Cb + ω_b × (A − C_b); an obstacle's is 0);
/// `None` when every one is zero or one cannot be computed exactly.
fn approach_exponent(scene: &Scene) -> Option<i64> {
    fn triple(x: &[Number; 3]) -> Option<[&BigRational; 3]> {
        let exact = |k: usize| x[k].exact.as_ref().ok();
        Some([exact(0)?, exact(1)?, exact(2)?])
    }
    let spec = scene.system.as_ref()?;
    let mut most: Option<i64> = None;
    for (contact, pair) in scene.contacts.iter().zip(&spec.pairs) {
        let normal = contact.normal.as_ref()?;
        let (p, n) = (triple(&contact.point)?, triple(normal)?);
        // n · v_b(A) = n · v_C + ω · ((A − C) × n).
        let along = |body: usize| -> Option<BigRational> {
            let body = &spec.bodies[body];
            let (centre, v, w) = (
                triple(&body.centre)?,
                triple(&body.velocity)?,
                triple(&body.angular_velocity)?,
            );
            let r: Vec<BigRational> = (0..3).map(|k| p[k] - centre[k]).collect();
            let mut speed = BigRational::zero();
            for k in 0..3 {
                let (i, j) = ((k + 1) % 3, (k + 2) % 3);
                speed += v[k] * n[k] + w[k] * (&r[i] * n[j] - &r[j] * n[i]);
            }
            Some(speed)
        };
        let mut speed = along(pair.first)?;
        if let Some(second) = pair.second {
            speed -= along(second)?;
        }
        let size = largest(normal.iter())?;
        if let Some(e) = exponent(&speed) {
            most = Some(most.map_or(e - size, |m| m.max(e - size)));
        }
    }
    most
}

/// A twist (ω 1/T, v_C L/T) scaled back.
fn twist(t: &mut ([Value; 3], [Value; 3]), b: i64, c: i64) {
    t.0.iter_mut().for_each(|x| times(x, -c));
    t.1.iter_mut().for_each(|x| times(x, b - c));
}

/// A momentum (linear M·L/T, angular M·L²/T) scaled back.
fn momentum(p: &mut ([Value; 3], [Value; 3]), u: &Units) {
    let (a, b, c) = (u.mass, u.length, u.time);
    p.0.iter_mut().for_each(|x| times(x, a + b - c));
    p.1.iter_mut().for_each(|x| times(x, a + 2 * b - c));
}

/// A joint's reaction scaled back: its anchor a length, its force an impulse (M·L/T), its
/// moment about the anchor an impulse's moment (M·L²/T).
fn reaction(w: &mut WrenchReport, u: &Units) {
    let (a, b, c) = (u.mass, u.length, u.time);
    for k in 0..3 {
        times(&mut w.point[k], b);
        times(&mut w.force[k], a + b - c);
        times(&mut w.moment[k], a + 2 * b - c);
    }
}

/// Put a system report computed in the scaled units `u` back into the scene's own: G (1/M)
/// and Δ (1/M^N) held wide where f64 cannot hold them, every physical output by its
/// dimension (module docs).
pub fn unscale_system(report: &mut SystemReport, u: &Units) {
    let (a, b, c) = (u.mass, u.length, u.time);
    let energy = a + 2 * b - 2 * c;
    let n = report.inertance.len() as i64;
    report
        .inertance
        .iter_mut()
        .flatten()
        .for_each(|g| times_wide(g, -a));
    times_wide(&mut report.det, -a * n);
    report
        .contacts_before
        .iter_mut()
        .for_each(|p| point(p, b - c));
    report
        .kinetic_energy_before
        .iter_mut()
        .for_each(|e| times(e, energy));
    momentum(&mut report.momentum_before, u);
    for m in &mut report.models {
        for p in m
            .impulses
            .iter_mut()
            .chain(m.compression_impulses.iter_mut().flatten())
        {
            times(p, a + b - c);
        }
        m.twists.iter_mut().for_each(|t| twist(t, b, c));
        m.contacts.iter_mut().for_each(|p| point(p, b - c));
        for e in [&mut m.lost_velocity_energy, &mut m.kinetic_energy_loss]
            .into_iter()
            .chain(&mut m.kinetic_energy_after)
        {
            times(e, energy);
        }
        momentum(&mut m.momentum_after, u);
        m.joint_reactions.iter_mut().for_each(|w| reaction(w, u));
    }
    for f in &mut report.friction {
        f.contacts
            .iter_mut()
            .for_each(|p| super::friction_contact(p, a, b, c));
        f.twists.iter_mut().for_each(|t| twist(t, b, c));
        for e in [
            &mut f.lost_velocity_energy,
            &mut f.kinetic_energy_loss,
            &mut f.friction_dissipation,
        ]
        .into_iter()
        .chain(&mut f.kinetic_energy_after)
        {
            times(e, energy);
        }
        momentum(&mut f.momentum_after, u);
        f.joint_reactions.iter_mut().for_each(|w| reaction(w, u));
        if let Some(e) = &mut f.error_estimate {
            *e = super::ldexp(*e, a + b - c);
        }
    }
}

/// Every value of a system report's physical outputs, by the name a refusal gives them.
fn outputs(report: &SystemReport) -> Vec<(&'static str, Vec<&Value>)> {
    let mut groups: Vec<(&'static str, Vec<&Value>)> = Vec::new();
    fn wrenches(w: &[WrenchReport]) -> Vec<&Value> {
        w.iter()
            .flat_map(|w| w.point.iter().chain(&w.force).chain(&w.moment))
            .collect()
    }
    fn momenta(p: &([Value; 3], [Value; 3])) -> Vec<&Value> {
        p.0.iter().chain(&p.1).collect()
    }
    for m in &report.models {
        groups.extend([
            (
                "impulses",
                m.impulses
                    .iter()
                    .chain(m.compression_impulses.iter().flatten())
                    .collect(),
            ),
            (
                "velocities after impact",
                m.twists
                    .iter()
                    .flat_map(|(w, v)| w.iter().chain(v))
                    .chain(m.contacts.iter().flat_map(|p| &p.components))
                    .collect(),
            ),
            (
                "energies",
                [&m.lost_velocity_energy, &m.kinetic_energy_loss]
                    .into_iter()
                    .chain(&m.kinetic_energy_after)
                    .collect(),
            ),
            ("joint reactions", wrenches(&m.joint_reactions)),
            ("momentum", momenta(&m.momentum_after)),
        ]);
    }
    for f in &report.friction {
        groups.extend([
            (
                "impulses",
                f.contacts
                    .iter()
                    .flat_map(|p| {
                        [&p.normal_impulse, &p.compression_impulse]
                            .into_iter()
                            .chain(&p.tangential_impulse)
                    })
                    .collect(),
            ),
            (
                "velocities after impact",
                f.twists
                    .iter()
                    .flat_map(|(w, v)| w.iter().chain(v))
                    .chain(
                        f.contacts
                            .iter()
                            .flat_map(|p| std::iter::once(&p.normal_velocity).chain(&p.velocity)),
                    )
                    .collect(),
            ),
            (
                "energies",
                [
                    &f.lost_velocity_energy,
                    &f.kinetic_energy_loss,
                    &f.friction_dissipation,
                ]
                .into_iter()
                .chain(&f.kinetic_energy_after)
                .collect(),
            ),
            ("joint reactions", wrenches(&f.joint_reactions)),
            ("momentum", momenta(&f.momentum_after)),
        ]);
    }
    // Before impact last: a refusal names what the impact gives first.
    groups.push((
        "contact velocities before impact",
        report
            .contacts_before
            .iter()
            .flat_map(|p| &p.components)
            .collect(),
    ));
    groups.push((
        "kinetic energies",
        report.kinetic_energy_before.iter().collect(),
    ));
    groups.push(("momentum", momenta(&report.momentum_before)));
    groups
}

/// The first output of a system report that f64 does not hold, by name (`None`: all are
/// finite). G and Δ depend on the units: beyond f64 they are held wide ([`Value::wide`]).
pub fn system_out_of_range(report: &SystemReport) -> Option<&'static str> {
    let held = |v: &Value| v.f64.is_finite() || v.wide.is_some();
    if !report.inertance.iter().flatten().all(held) {
        return Some("inertances G");
    }
    if !held(&report.det) {
        return Some("Δ = det G");
    }
    outputs(report)
        .into_iter()
        .find(|(_, values)| !values.iter().all(|v| v.f64.is_finite()))
        .map(|(name, _)| name)
}

/// The first physical output of a system report, in the units it was solved in, whose
/// computation left f64's precision (as [`super::precision_lost`] for one body; `None`: none
/// did): a group whose largest magnitude is subnormal, or energies whose terms — the largest
/// impulse times the largest speed of approach — fall below [`super::LEAST_WORK`] (a flushed
/// energy is simply 0).
pub fn system_precision_lost(report: &SystemReport) -> Option<&'static str> {
    let largest = |values: &[&Value]| values.iter().map(|v| v.f64.abs()).fold(0.0, f64::max);
    let approach = report
        .contacts_before
        .iter()
        .map(|p| p.components[0].f64.abs())
        .fold(0.0, f64::max);
    outputs(report).into_iter().find_map(|(name, values)| {
        let m = largest(&values);
        let work = m.log2() + approach.log2();
        let flushed =
            name == "impulses" && m > 0.0 && approach > 0.0 && work < super::LEAST_WORK.log2();
        if flushed {
            return Some("energies");
        }
        (m > 0.0 && m < f64::MIN_POSITIVE).then_some(name)
    })
}
