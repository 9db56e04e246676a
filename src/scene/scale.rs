//! Exact scaling before rounding: a scene whose numbers span the range of f64 is solved in
//! units of mass, length and time that are powers of two chosen from its own numbers, and the
//! report is scaled back.
//!
//! Numbers are read exactly, so the scaled scene is exact too; multiplying a float by a power
//! of two is exact unless it leaves the exponent range. With m = 2^a kg, L = 2^b m and
//! T = 2^c s the scene's numbers become
//!
//! ```text
//! m′ = m/2^a,  J′ = J/2^(a+2b),  A′ = A/2^b,  v_C′ = v_C·2^(c−b),  ω′ = ω·2^c,
//! n_i′ = n_i/2^(e_i),  y_i′ = y_i/2^(f_i)    (an axis is a direction: any length serves)
//! ```
//!
//! with b from the largest contact coordinate, a midway between the mass and the moments
//! over L² ([`mass_exponent`]), c making the largest speed of approach |v_ix⁰| about 1 —
//! impulses and energies scale with it — as far as the largest velocity (|v_C| or |ω|·L) may
//! grow, to 2⁹⁶⁰ ([`HEADROOM`]; the largest velocity about 1 when the speeds of approach are
//! not computed exactly), and e_i, f_i the axes' own scales; J′ scales every entry of the
//! inertia tensor (a full tensor's entries off the diagonal as well). The laws are invariant
//! under this change of units (k and μ are dimensionless), and every output is scaled back by its
//! dimension: impulses M·L/T, velocities L/T, ω 1/T, energies M·L²/T², inertances 1/M, Δ 1/M^N.
//! So any scene whose results are representable is solved in f32, f64 and double-double; what
//! is not representable is refused by the caller, never reported as NaN or ∞.
//!
//! **Constraints.** A joint's point is a length, p′ = p/2^b, and its axis a direction. A free
//! screw is a twist per unit of its coordinate ξ_a (eq. 79), a blocked one a wrench per unit
//! of its multiplier q_a (eq. 75); their columns may be rescaled at will, so each written screw
//! is put in the new units and then divided by its own power of two:
//!
//! ```text
//! D_a = [ω; v]  →  D′_a = [ω; v/2^b]/2^(f_a),     U_a = [F; M]  →  U′_a = [F; M/2^b]/2^(g_a)
//! ```
//!
//! (a twist's v/ω and a wrench's M/F are lengths; joints' screws come out with f_a = 0 or −b,
//! derived ones with g_a = 0 or −b, read off by comparing the exact screws in both units). The
//! reaction U q = r = M Δv + Σ P_i E_i is a wrench [impulse; impulse·length]: in the scaled units
//! U′_a q′_a is the wrench [F; M]·q′_a·2^(a+b−c−g_a), so
//!
//! ```text
//! q_a = q′_a · 2^(a+b−c−g_a),      (M_red)_ab = (M′_red)_ab · 2^(a+2b+f_a+f_b)
//! ```
//!
//! the second because M_red = Dᵀ η M D is a kinetic energy (M·L²/T²) per ξ_a ξ_b, with
//! ξ′_a = ξ_a·2^(f_a)… per unit twist: D′_a is the scaled image of the twist D_a·2^(−c−f_a).
//! The reported D and U are scaled back too.
//!
//! **Surfaces and irrational numbers.** Scenes are scaled with or without a `[surface]`: in
//! the length unit 2^b the surface
//! f(x, y, z) = 0 becomes f(2^b x′, 2^b y′, 2^b z′) = 0 ([`Surface::scaled`]). A number given
//! as an irrational expression is scaled as an expression: its text times 2^k, whose f64
//! value is its own f64 evaluation times 2^k, exactly. Symbolic scenes are exact and not scaled.
//!
//! What f64 cannot hold after scaling back is either a quantity whose size the units or the
//! user's own scale of a screw set — Δ, the inertances, the constraint screws, M_red and the
//! constraint impulses, reported from their scaled value and power of two
//! ([`crate::report::Wide`]) — or a physical output (impulses, velocities, energies), which is
//! refused, naming it and the input that sets the extreme scale. So is a physical output that
//! lost its precision to underflow in the scaled units themselves ([`precision_lost`]): when
//! the speeds span more than the units can hold, a flushed energy is refused, not printed.
//!
//! **Sensitivities.** In a dual-number run ([`crate::scalar::dual`]) a seeded input's tangent
//! is scaled with its value and each output's derivative is scaled back like the output: with
//! x′ = 2^k x and y = 2^K y′, dy/dx = 2^(K−k) dy′/dx′, and the seed dx′ = 2^k dx carries the
//! 2^−k. The units are constant near the point (they move only where a number's binary
//! exponent does, where they stay valid on either side), so they add no derivative of their own.

use num_rational::BigRational;
use num_traits::{Signed, Zero};

pub mod system;

use super::{ConstraintsSpec, Scene, SurfaceSpec};
use crate::mechanics::constraint::complement;
use crate::mechanics::screw::Screw;
use crate::mechanics::surface::Surface;
use crate::number::{Number, format_rational, rational_to_f64};
use crate::report::{FrictionContact, PointVelocity, Report, Value, Wide};
use crate::scalar::{Exact, Scalar};

/// The powers of two of a scaled scene: mass 2^a, length 2^b, time 2^c, and each contact's
/// normal and tangent scale.
#[derive(Clone, Debug, PartialEq)]
pub struct Units {
    /// a: the unit of mass is 2^a kg.
    pub mass: i64,
    /// b: the unit of length is 2^b m.
    pub length: i64,
    /// c: the unit of time is 2^c s.
    pub time: i64,
    /// e_i: the normal of contact i was divided by 2^(e_i).
    pub normals: Vec<i64>,
    /// f_a: the free screw D_a = [ω; v] became [ω; v/2^b]/2^(f_a) (empty for a free body).
    pub free: Vec<i64>,
    /// g_a: the blocked screw U_a = [F; M] became [F; M/2^b]/2^(g_a).
    pub blocked: Vec<i64>,
}

/// ⌊log₂|q|⌋ within one: the bit lengths of numerator and denominator; `None` for zero.
fn exponent(q: &BigRational) -> Option<i64> {
    if q.is_zero() {
        return None;
    }
    Some(q.numer().bits() as i64 - q.denom().bits() as i64)
}

/// ⌊log₂|n|⌋ within one: from the exact value, or from the f64 evaluation of an irrational
/// expression; `None` for zero.
fn number_exponent(n: &Number) -> Option<i64> {
    match &n.exact {
        Ok(q) => exponent(q),
        Err(_) => float_exponent(n.approx),
    }
}

/// ⌊log₂|x|⌋ of a normal f64, read from its bits (so that x·2^k has exactly k more);
/// `None` for zero, subnormals and non-finite values.
fn float_exponent(x: f64) -> Option<i64> {
    let biased = ((x.to_bits() >> 52) & 0x7ff) as i64;
    (biased != 0 && biased != 0x7ff).then_some(biased - 1023)
}

/// The largest exponent among `numbers` (`None` if all are zero).
fn largest<'a>(numbers: impl IntoIterator<Item = &'a Number>) -> Option<i64> {
    numbers.into_iter().filter_map(number_exponent).max()
}

/// q · 2^k, exactly: a shift of the numerator or of the denominator (then reduced).
fn shifted(q: &BigRational, k: i64) -> BigRational {
    let bits = k.unsigned_abs() as usize;
    if k >= 0 {
        BigRational::new(q.numer() << bits, q.denom().clone())
    } else {
        BigRational::new(q.numer().clone(), q.denom() << bits)
    }
}

/// The number `n` times 2^k, as a number (its text the exact scaled value); its derivative
/// ([`Number::tangent`], a sensitivity run's seed) is scaled with it, exactly: the powers of
/// two are constant near the point (they change only where an exponent does), so the scaled
/// input's derivative is 2^k times the input's.
fn scale_number(n: &mut Number, k: i64) {
    if k == 0 {
        return;
    }
    match &n.exact {
        Ok(q) => {
            let q = shifted(q, k);
            n.text = format_rational(&q);
            n.approx = rational_to_f64(&q);
            n.exact = Ok(q);
        }
        // An expression: its text times 2^k, whose f64 evaluation is the f64 evaluation of
        // the text times 2^k — exact, the text's own rounding kept.
        Err(_) => {
            n.text = format!("({})*2^({k})", n.text);
            n.approx = ldexp(n.approx, k);
        }
    }
    n.tangent = ldexp(n.tangent, k);
}

/// `scene` in units chosen from its own numbers, or `None` when it is not scaled (a symbolic
/// number, constraint screws whose scaling cannot be read off exactly, or units of 1 already).
pub fn scale(scene: &Scene) -> Option<(Scene, Units)> {
    if scene.numbers().any(|(_, n)| !n.symbols.is_empty()) {
        return None;
    }
    let b = largest(scene.contacts.iter().flat_map(|c| c.point.iter())).unwrap_or(0);
    let a = mass_exponent(scene, b);
    let v = largest(scene.velocity.iter());
    let w = largest(scene.angular_velocity.iter()).map(|e| e + b);
    let speed = match (v, w) {
        (Some(x), Some(y)) => Some(x.max(y)),
        (x, y) => x.or(y),
    };
    let c = speed.map_or(0, |s| {
        let approach = approach_exponent(scene).unwrap_or(s);
        b - approach.clamp(s - HEADROOM, s)
    });
    let mut s = scene.clone();
    scale_number(&mut s.mass, -a);
    // The products of inertia have the moments' dimension, M·L².
    for j in s
        .inertia
        .iter_mut()
        .chain(s.inertia_products.iter_mut().flatten())
    {
        scale_number(j, -a - 2 * b);
    }
    for x in &mut s.velocity {
        scale_number(x, c - b);
    }
    for x in &mut s.angular_velocity {
        scale_number(x, c);
    }
    let mut normals = Vec::with_capacity(s.contacts.len());
    for contact in &mut s.contacts {
        for x in &mut contact.point {
            scale_number(x, -b);
        }
        let e = contact
            .normal
            .as_ref()
            .and_then(|n| largest(n.iter()))
            .unwrap_or(0);
        if let Some(n) = &mut contact.normal {
            for x in n.iter_mut() {
                scale_number(x, -e);
            }
        }
        normals.push(e);
        if let Some(t) = &mut contact.tangent {
            let f = largest(t.iter()).unwrap_or(0);
            for x in t.iter_mut() {
                scale_number(x, -f);
            }
        }
    }
    if let Some(surface) = &mut s.surface {
        surface.surface = scaled_surface(surface, b)?;
    }
    scale_constraints(&mut s, b);
    let (free, blocked) = match constraint_exponents(scene, &s, b) {
        Ok(x) => x,
        Err(()) => return None,
    };
    let units = Units {
        mass: a,
        length: b,
        time: c,
        normals,
        free,
        blocked,
    };
    (units.mass != 0
        || units.length != 0
        || units.time != 0
        || units.normals.iter().any(|&e| e != 0)
        || units.free.iter().chain(&units.blocked).any(|&e| e != 0))
    .then_some((s, units))
}

/// a, the unit of mass 2^a kg: midway, in the exponent, between the mass m and the smallest
/// moment over the length unit squared, J/L² (also a mass), so that both terms of an
/// inertance, 1/m′ and r′²/J′, are within range. From the mass alone, a body of 2^1024 kg
/// with moments of 12 kg m² had J′ ≈ 2^−1022 (subnormal) and f64 called its G, of cond₂ 1,
/// singular; so did 10³⁰⁸ kg with moments of 1 kg m² (cond₂ G = 63).
fn mass_exponent(scene: &Scene, b: i64) -> i64 {
    let m = largest([&scene.mass]).unwrap_or(0);
    let moments = scene
        .inertia
        .iter()
        .filter_map(number_exponent)
        .min()
        .map(|j| j - 2 * b);
    moments.map_or(m, |j| (m + j).div_euclid(2))
}

/// How far above 1 the largest velocity may be put, as a power of two, for the velocities
/// along the normals to come out near 1: the largest velocity, a contact point's (|r′| < 2√3)
/// and its components along the axes then stay below 2^970, well inside f64.
const HEADROOM: i64 = 960;

/// ⌊log₂⌋ within two of the largest speed of approach |v_ix⁰| = |n_i·v_C + ω·(r_i × n_i)|/|n_i|
/// (m/s), computed exactly; `None` when every one is zero, or one cannot be computed exactly
/// (an irrational number, or a normal from the `[surface]`).
///
/// Impulses and energies scale with these speeds, not with the largest velocity: a unit sphere
/// spinning at ω = 10³⁰⁸ rad/s that hits a floor at 1 m/s, put in a time unit that makes
/// ω about 1, had v_C = 2⁻¹⁰²³ (subnormal) and both energies, of order 2⁻²⁰⁴⁶ in those units,
/// flushed to zero (they are 9/8 J and 3/8 J). The time unit is therefore chosen to make the
/// speeds of approach about 1, as far as [`HEADROOM`] allows the other velocities to grow.
fn approach_exponent(scene: &Scene) -> Option<i64> {
    fn triple(x: &[Number; 3]) -> Option<[&BigRational; 3]> {
        let exact = |k: usize| x[k].exact.as_ref().ok();
        Some([exact(0)?, exact(1)?, exact(2)?])
    }
    let v = triple(&scene.velocity)?;
    let w = triple(&scene.angular_velocity)?;
    let mut most: Option<i64> = None;
    for contact in &scene.contacts {
        let normal = contact.normal.as_ref()?;
        let (r, n) = (triple(&contact.point)?, triple(normal)?);
        let mut speed = BigRational::zero();
        for k in 0..3 {
            let (i, j) = ((k + 1) % 3, (k + 2) % 3);
            let moment = r[i] * n[j] - r[j] * n[i];
            speed += v[k] * n[k] + w[k] * moment;
        }
        let size = largest(normal.iter())?;
        if let Some(e) = exponent(&speed) {
            most = Some(most.map_or(e - size, |m| m.max(e - size)));
        }
    }
    most
}

/// The constraints in units of length 2^b: a joint's point divided by 2^b (its axis is a
/// direction, kept); a screw written out, [ω; v] or [F; M], becomes [ω; v/2^b] or
/// [F; M/2^b], divided by the power of two of its largest coordinate so that it is of order 1.
fn scale_constraints(s: &mut Scene, b: i64) {
    match &mut s.constraints {
        None => {}
        Some(ConstraintsSpec::Joints(joints)) => {
            for joint in joints {
                let keys = joint.kind.keys();
                for (name, v) in keys.iter().zip(joint.vectors.iter_mut()) {
                    if *name == "point" {
                        v.iter_mut().for_each(|x| scale_number(x, -b));
                    }
                }
            }
        }
        Some(ConstraintsSpec::Screws { free, blocked }) => {
            for screw in free.iter_mut().chain(blocked.iter_mut().flatten()) {
                for x in &mut screw[3..] {
                    scale_number(x, -b);
                }
                let own = largest(screw.iter()).unwrap_or(0);
                screw.iter_mut().for_each(|x| scale_number(x, -own));
            }
        }
    }
}

/// f_a and g_a of [`Units`], read off the screws themselves: the exact free screws of the
/// scene as written and as scaled, and their blocked screws (given, or derived as
/// [`complement`] does, which picks the same free columns of the same echelon form in either
/// units: scaling the coordinates of a wrench by powers of two changes no rank), must be
/// related by D′_a = [ω; v/2^b]/2^(f_a), U′_a = [F; M/2^b]/2^(g_a). `Err` if they are not
/// (then the scene runs as written).
fn constraint_exponents(scene: &Scene, scaled: &Scene, b: i64) -> Result<(Vec<i64>, Vec<i64>), ()> {
    let screws = |s: &Scene| match s.constraint_screws::<Exact>() {
        Ok(Some(c)) => {
            let u = c.blocked.unwrap_or_else(|| complement(&c.free));
            Ok(Some((c.free, u)))
        }
        Ok(None) => Ok(None),
        Err(_) => Err(()),
    };
    let (Some((d, u)), Some((d2, u2))) = (screws(scene)?, screws(scaled)?) else {
        return Ok((Vec::new(), Vec::new()));
    };
    if d.len() != d2.len() || u.len() != u2.len() {
        return Err(());
    }
    let exponents = |x: &[Screw<Exact>], y: &[Screw<Exact>]| -> Result<Vec<i64>, ()> {
        x.iter().zip(y).map(|(x, y)| power(x, y, b)).collect()
    };
    Ok((exponents(&d, &d2)?, exponents(&u, &u2)?))
}

/// The k with y = [x_top; x_bottom/2^b]/2^k, if there is one.
fn power(x: &Screw<Exact>, y: &Screw<Exact>, b: i64) -> Result<i64, ()> {
    let value = |v: &Exact| v.to_rational().ok_or(());
    let mut x2 = Vec::with_capacity(6);
    let mut y2 = Vec::with_capacity(6);
    for j in 0..6 {
        let v = value(&x.0[j])?;
        x2.push(if j < 3 { v } else { shifted(&v, -b) });
        y2.push(value(&y.0[j])?);
    }
    let j = x2.iter().position(|v| !v.is_zero()).ok_or(())?;
    let k = -exponent(&(&y2[j] / &x2[j])).ok_or(())?;
    let same = (0..6).all(|i| shifted(&x2[i], -k) == y2[i]);
    same.then_some(k).ok_or(())
}

/// The `[surface]` f(x, y, z) = 0 in the length unit 2^b: f(2^b x′, 2^b y′, 2^b z′) = 0
/// ([`crate::mechanics::surface::Surface::scaled`]). Its gradient keeps its direction (the
/// normals are directions), f′ at a scaled contact point equals f at the point exactly, and the
/// float on-surface test |f|/|∇f| ≤ 10⁻⁹·max(|p|, 1) then reads max(|p|, 1) in the scene's own
/// length unit: it is relative to the scene's size, not to the metre. `None` (the scene is not
/// scaled) when the scaled derivatives exceed the size limit.
fn scaled_surface(surface: &SurfaceSpec, b: i64) -> Option<Surface> {
    if b == 0 {
        return Some(surface.surface.clone());
    }
    surface.surface.scaled(b).ok()
}

/// x · 2^k in f64, exactly unless the result leaves the range (then ±∞ or 0).
pub(crate) fn ldexp(x: f64, k: i64) -> f64 {
    let mut y = x;
    let mut k = k;
    while k != 0 {
        let step = k.clamp(-1000, 1000);
        y *= 2f64.powi(step as i32);
        k -= step;
    }
    y
}

/// Multiply a reported value by 2^k (a float report: no exact text to change), and its
/// derivative with it (a derivative has the dimension of its output over that of the seeded
/// input, whose scaling [`scale_number`] already applied to the seed).
fn times(v: &mut Value, k: i64) {
    v.f64 = ldexp(v.f64, k);
    if let Some(d) = &mut v.derivative {
        d.f64 = ldexp(d.f64, k);
    }
}

/// As [`times`], for an output that is a pure power of the units and no physical quantity
/// (Δ, an inertance): where the product leaves f64 the value keeps its scaled value and power
/// of two ([`Wide`]), and its derivative likewise.
fn times_wide(v: &mut Value, k: i64) {
    v.wide = Wide::of(v.f64, k);
    v.f64 = ldexp(v.f64, k);
    if let Some(d) = &mut v.derivative {
        times_wide(d, k);
    }
}

/// Scale a contact point's velocities (L/T) back.
fn point(p: &mut PointVelocity, k: i64) {
    for c in &mut p.components {
        times(c, k);
    }
}

/// Put a report computed in the scaled units back into the scene's own.
pub fn unscale(report: &mut Report, u: &Units) {
    let (a, b, c) = (u.mass, u.length, u.time);
    let n = report.inertance.len() as i64;
    for m in [
        &mut report.inertance,
        &mut report.inertance_yx,
        &mut report.inertance_zx,
    ] {
        for row in m.iter_mut() {
            for g in row.iter_mut() {
                times_wide(g, -a);
            }
        }
    }
    times_wide(&mut report.det, -a * n);
    for p in &mut report.contacts_before {
        point(p, b - c);
    }
    if let Some(c) = &mut report.constraints {
        // D_a = [ω′; v′·2^b]·2^(f_a), U_a = [F′; M′·2^b]·2^(g_a), and M_red = Dᵀ η M D has
        // the dimension of an energy per unit of each screw's own scale. A screw's scale is
        // the user's (a blocked screw written "10^400"), so these may leave f64: held wide.
        for (screws, exps) in [(&mut c.free, &u.free), (&mut c.blocked, &u.blocked)] {
            for (screw, &f) in screws.iter_mut().zip(exps) {
                for (k, x) in screw.iter_mut().enumerate() {
                    times_wide(x, if k < 3 { f } else { f + b });
                }
            }
        }
        for (row, &fa) in c.reduced_mass.iter_mut().zip(&u.free) {
            for (x, &fb) in row.iter_mut().zip(&u.free) {
                times_wide(x, a + 2 * b + fa + fb);
            }
        }
    }
    for m in &mut report.models {
        // U q = r: [F′; M′] q′ in the scaled units is the wrench [F′; M′·2^b]·q′·2^(a+b−c);
        // q_a is per unit of U_a as written, so it is as wide as U_a's scale is.
        for (q, &g) in m.constraint_impulses.iter_mut().zip(&u.blocked) {
            times_wide(q, a + b - c - g);
        }
        // The wrench U q itself: a force (impulse) about a point (length).
        for w in m.constraint_wrench.iter_mut().chain(&mut m.joint_reactions) {
            for k in 0..3 {
                times(&mut w.point[k], b);
                times(&mut w.force[k], a + b - c);
                times(&mut w.moment[k], a + 2 * b - c);
            }
        }
        for p in &mut m.impulses {
            times(p, a + b - c);
        }
        for (p, e) in m.impulse_multiples.iter_mut().zip(&u.normals) {
            times(p, a + b - c - e);
        }
        for p in m.compression_impulses.iter_mut().flatten() {
            times(p, a + b - c);
        }
        for w in &mut m.angular_velocity {
            times(w, -c);
        }
        for v in &mut m.velocity {
            times(v, b - c);
        }
        for p in &mut m.contacts {
            point(p, b - c);
        }
        times(&mut m.lost_velocity_energy, a + 2 * b - 2 * c);
        times(&mut m.kinetic_energy_loss, a + 2 * b - 2 * c);
        if let Some(range) = &mut m.outcome_range {
            for (k, (lo, hi)) in range.iter_mut().enumerate() {
                let e = if k < 3 { -c } else { b - c };
                times(lo, e);
                times(hi, e);
            }
        }
    }
    for f in &mut report.friction {
        for p in &mut f.contacts {
            friction_contact(p, a, b, c);
        }
        for w in &mut f.angular_velocity {
            times(w, -c);
        }
        for v in &mut f.velocity {
            times(v, b - c);
        }
        for e in [
            &mut f.lost_velocity_energy,
            &mut f.kinetic_energy_loss,
            &mut f.friction_dissipation,
        ] {
            times(e, a + 2 * b - 2 * c);
        }
        if let Some(e) = &mut f.error_estimate {
            *e *= 2f64.powi((a + b - c) as i32);
        }
        for point in &mut f.trajectory {
            for p in &mut point.contacts {
                p.normal_impulse = ldexp(p.normal_impulse, a + b - c);
                for t in p.tangential_impulse.iter_mut() {
                    *t = ldexp(*t, a + b - c);
                }
                for v in p.slip.iter_mut() {
                    *v = ldexp(*v, b - c);
                }
            }
        }
    }
}

/// A frictional contact's readout (one body's or a system's) scaled back: its impulses
/// M·L/T, its velocities L/T.
fn friction_contact(p: &mut FrictionContact, a: i64, b: i64, c: i64) {
    for i in [&mut p.normal_impulse, &mut p.compression_impulse]
        .into_iter()
        .chain(&mut p.tangential_impulse)
    {
        times(i, a + b - c);
    }
    for v in std::iter::once(&mut p.normal_velocity).chain(&mut p.velocity) {
        times(v, b - c);
    }
}

/// The first output of `report` that f64 does not hold, by name (`None`: all are finite).
/// Δ, the inertances, the constraints' screws, M_red and the constraint impulses depend on
/// the units or on the scale the user gave a screw: beyond f64 they are reported from their
/// scaled value ([`Value::wide`]), or a written screw as written (its text), and count as held.
pub fn out_of_range(report: &Report) -> Option<&'static str> {
    let ok = |v: &Value| v.f64.is_finite();
    let held = |v: &Value| ok(v) || v.wide.is_some() || v.exact.is_some();
    let point = |p: &PointVelocity| p.components.iter().all(ok);
    let mut checks: Vec<(&'static str, bool)> = vec![
        (
            "inertances G",
            report
                .inertance
                .iter()
                .chain(&report.inertance_yx)
                .chain(&report.inertance_zx)
                .flatten()
                .all(held),
        ),
        ("Δ = det G", held(&report.det)),
        (
            "contact velocities before impact",
            report.contacts_before.iter().all(point),
        ),
        (
            "constraints",
            report.constraints.as_ref().is_none_or(|c| {
                c.free.iter().chain(&c.blocked).flatten().all(held)
                    && c.reduced_mass.iter().flatten().all(held)
            }),
        ),
    ];
    for m in &report.models {
        checks.extend([
            (
                "impulses",
                m.impulses.iter().chain(&m.impulse_multiples).all(ok)
                    && m.compression_impulses.iter().flatten().all(ok),
            ),
            (
                "velocities after impact",
                m.angular_velocity.iter().chain(&m.velocity).all(ok)
                    && m.contacts.iter().all(point),
            ),
            (
                "energies",
                ok(&m.lost_velocity_energy) && ok(&m.kinetic_energy_loss),
            ),
            (
                "constraint impulses",
                m.constraint_impulses.iter().all(held),
            ),
            (
                "constraint wrench",
                m.constraint_wrench
                    .iter()
                    .chain(&m.joint_reactions)
                    .all(|w| w.point.iter().chain(&w.force).chain(&w.moment).all(ok)),
            ),
        ]);
    }
    for f in &report.friction {
        checks.extend([
            (
                "impulses",
                f.contacts.iter().all(|p| {
                    [&p.normal_impulse, &p.compression_impulse]
                        .into_iter()
                        .chain(&p.tangential_impulse)
                        .all(ok)
                }),
            ),
            (
                "velocities after impact",
                f.contacts.iter().all(|p| {
                    std::iter::once(&p.normal_velocity)
                        .chain(&p.velocity)
                        .all(ok)
                }) && f.angular_velocity.iter().chain(&f.velocity).all(ok),
            ),
            (
                "energies",
                [
                    &f.lost_velocity_energy,
                    &f.kinetic_energy_loss,
                    &f.friction_dissipation,
                ]
                .into_iter()
                .all(ok),
            ),
        ]);
    }
    checks
        .into_iter()
        .find(|(_, held)| !held)
        .map(|(name, _)| name)
}

/// The least work P_i v_ix⁰ (the largest impulse times the largest speed of approach) whose
/// energies keep f64's precision: a term of their sums below 2⁻¹⁰²² is subnormal, off by up
/// to 2⁻¹⁰⁷⁵, and at most 300 terms (the unilateral law's limit) stay within ε of the energy
/// when it is at least 300·2⁻¹⁰⁷⁵/2⁻⁵³ < 2⁻¹⁰¹².
const LEAST_WORK: f64 = f64::MIN_POSITIVE * 1024.0;

/// The first physical output of `report`, computed in whatever units it was solved in, whose
/// computation left f64's full precision (`None`: none did). Per group — the impulses, the
/// velocities after impact — the largest magnitude must be 0 or a normal number (≥ 2⁻¹⁰²²);
/// the energies are checked on their terms, which must reach [`LEAST_WORK`], since a flushed
/// energy is simply 0. A group's small members are not checked: a component 10⁻³¹⁰ of the
/// largest one meets the contract, whose bounds are norms.
///
/// So a solve that flushed a result is refused rather than printed: before the time unit was
/// chosen from the speeds of approach, a sphere spinning at 10³⁰⁸ rad/s gave E_p = ΔE_c = 0.
pub fn precision_lost(report: &Report) -> Option<&'static str> {
    let largest =
        |values: &mut dyn Iterator<Item = &Value>| values.map(|v| v.f64.abs()).fold(0.0, f64::max);
    let lost = |m: f64| m > 0.0 && m < f64::MIN_POSITIVE;
    let approach = largest(&mut report.contacts_before.iter().map(|p| &p.components[0]));
    for m in &report.models {
        let impulses = largest(
            &mut m
                .impulses
                .iter()
                .chain(m.compression_impulses.iter().flatten()),
        );
        let velocities = largest(
            &mut m
                .angular_velocity
                .iter()
                .chain(&m.velocity)
                .chain(m.contacts.iter().flat_map(|p| &p.components)),
        );
        let work = impulses.log2() + approach.log2();
        let energies_lost = impulses > 0.0 && approach > 0.0 && work < LEAST_WORK.log2();
        for (name, gone) in [
            ("impulses", lost(impulses)),
            ("velocities after impact", lost(velocities)),
            ("energies", energies_lost),
        ] {
            if gone {
                return Some(name);
            }
        }
    }
    for f in &report.friction {
        let impulses = largest(&mut f.contacts.iter().map(|p| &p.normal_impulse));
        let velocities = largest(&mut f.angular_velocity.iter().chain(&f.velocity));
        let energies = largest(
            &mut [
                &f.lost_velocity_energy,
                &f.kinetic_energy_loss,
                &f.friction_dissipation,
            ]
            .into_iter(),
        );
        for (name, m) in [
            ("impulses", impulses),
            ("velocities after impact", velocities),
            ("energies", energies),
        ] {
            if lost(m) {
                return Some(name);
            }
        }
    }
    None
}

/// The key of the scene's number farthest from 1 in magnitude (the likeliest culprit when a
/// result is out of range), with its text.
pub fn most_extreme(scene: &Scene) -> Option<(String, String)> {
    let bodies = scene
        .system
        .as_ref()
        .map(|s| s.numbers())
        .unwrap_or_default();
    scene
        .numbers()
        .chain(bodies)
        .filter_map(|(k, n)| {
            let e = n.exact.as_ref().ok().and_then(exponent).or_else(|| {
                (n.approx != 0.0 && n.approx.is_finite()).then(|| n.approx.abs().log2() as i64)
            })?;
            Some((e.abs(), k, n.text.clone()))
        })
        .max_by_key(|(e, _, _)| *e)
        .map(|(_, k, t)| (k, t))
}

/// The refusal of a physical `output` (impulses, velocities, energies) that the float type
/// `name` does not hold even in units scaled to the scene (`how`): names the output and the
/// input farthest from 1, which sets the extreme scale.
pub fn output_beyond(scene: &Scene, name: &str, output: &str, how: &str) -> super::SceneError {
    let (key, value) = most_extreme(scene).unwrap_or_default();
    super::SceneError {
        file: scene.file.clone(),
        key,
        value: Some(value),
        message: format!(
            "the {output} are beyond the range of {name}{how}; this number sets the extreme \
             scale — {}",
            super::OUT_OF_RANGE
        ),
    }
}

/// The refusal of a physical `output` whose computation in the float type `name` lost its
/// precision to underflow ([`precision_lost`]) even in units scaled to the scene (`how`):
/// names the output and the input farthest from 1.
pub fn output_below(scene: &Scene, name: &str, output: &str, how: &str) -> super::SceneError {
    let (key, value) = most_extreme(scene).unwrap_or_default();
    super::SceneError {
        file: scene.file.clone(),
        key,
        value: Some(value),
        message: format!(
            "the {output} fall below the range where {name} keeps its precision{how}, so they \
             would be printed wrong; this number sets the extreme scale — {}",
            super::OUT_OF_RANGE
        ),
    }
}

/// The refusal of a float result that is not representable: the scene's numbers span more than
/// the type `name` can hold (`how`: in which units it was tried); names the input farthest from 1.
pub fn unrepresentable(scene: &Scene, name: &str, how: &str) -> super::SceneError {
    let (key, value) = most_extreme(scene).unwrap_or_default();
    super::SceneError {
        file: scene.file.clone(),
        key,
        value: Some(value),
        message: format!(
            "the scene's numbers span more than {name} can hold{how}; this number sets the \
             extreme scale — {}",
            super::OUT_OF_RANGE
        ),
    }
}

/// |q| as a power of two, for messages.
pub fn magnitude(q: &BigRational) -> String {
    exponent(&q.abs()).map_or("0".into(), |e| format!("2^{e}"))
}
