//! Joints in flight: the bilateral constraints a `[[joint]]` puts on the accelerations,
//! velocities and positions of its members between impacts (at an impact the joint is the
//! impact layer's, [`crate::mechanics::system`], built by [`super::impact`] from [`Link::at`]).
//!
//! **The rows.** A joint's geometry is fixed in each member's axes at t = 0 (its anchor ρ and a
//! frame e₀, e₁, e₂ — e₀ the axis, or a planar joint's normal — in the first member's axes and
//! in the second's, or in the world for the ground), so it moves with them. Its blocked
//! relative motions are scalar constraints C(x, q) = 0 of three forms, each with its row
//! J = ∂Ċ/∂(v, ω) per member and its velocity-product term c = C̈ − J (a, α):
//!
//! ```text
//! point  C = e·(p_a − p_b)          J_a = [e; r_a × e],  J_b = −[e; r_b × e]
//!        c = e·(ω_a × (ω_a × r_a) − ω_b × (ω_b × r_b))                       (J1)
//! perp   C = u_b · t_a              J_a = [0; t × u],    J_b = −[0; t × u]
//!        c = (ω_b × (ω_b × u))·t + 2 (ω_b × u)·(ω_a × t) + u·(ω_a × (ω_a × t))  (J2)
//! line   C = t_a · (p_b − p_a)      J_a = −[t; (p_b − x_a) × t],  J_b = [t; r_b × t]
//!        c = t·(ω_b × (ω_b × r_b) − ω_a × (ω_a × r_a)) + 2 (ṗ_b − ṗ_a)·(ω_a × t)
//!            + d·(ω_a × (ω_a × t)),   d = p_b − p_a                           (J3)
//! ```
//!
//! (p = x + R ρ the anchor on each member, r = p − x its arm, e a world axis, t and u frame
//! vectors carried by a and b; a point row's arms both from p_a, which the position projection
//! keeps on p_b, so that its rate is the impact layer's.) The kinds:
//!
//! | kind | rows |
//! |---|---|
//! | spherical | point × 3 |
//! | revolute | point × 3, perp (e₀_b, e₁_a), perp (e₀_b, e₂_a) |
//! | fixed | point × 3, perp (e₀_b, e₁_a), (e₀_b, e₂_a), (e₁_b, e₂_a) |
//! | cylindrical | perp (e₀_b, e₁_a), (e₀_b, e₂_a), line e₁_a, line e₂_a |
//! | prismatic | perp × 3 (as fixed), line e₁_a, line e₂_a |
//! | planar | perp (e₀_b, e₁_a), (e₀_b, e₂_a), line e₀_a |
//!
//! **Elimination** (Gauss's principle; the acceleration-level twin of
//! [`crate::mechanics::system::mobility`]). With H the rows, M the block-diagonal mass matrix
//! and K = H M⁻¹ Hᵀ, the accelerations a = M⁻¹ (f + Hᵀ λ) with H a + c = 0 are the
//! M-orthogonal projection of the unconstrained ones,
//!
//! ```text
//! a = a_u − M⁻¹ Hᵀ K⁺ (H a_u + c)                                             (J4)
//! ```
//!
//! (K⁺ the pseudo-inverse: redundant joints leave K singular, the right-hand side in its range).
//! A contact problem over the jointed system sees the constrained mobility
//! W_c = M⁻¹ − M⁻¹ Hᵀ K⁺ H M⁻¹: its entry between rows d and e is
//! J_d M⁻¹ J_eᵀ − z_dᵀ K⁺ z_e with z = H M⁻¹ Jᵀ ([`Frozen::coupling`]), its bias J a⁰_c + c with
//! a⁰_c the free accelerations projected by (J4).
//!
//! **Drift.** After every step the positions are moved by Δ(x, θ) = −M⁻¹ Hᵀ K⁺ C (Newton's
//! iteration on C = 0, the smallest move in the kinetic metric) and the velocities by
//! Δ(v, ω) = −M⁻¹ Hᵀ K⁺ H (v, ω): H (v, ω) = 0 to rounding after it.

use nalgebra::{DMatrix, DVector, Matrix3, UnitQuaternion};

use super::super::body::V3;
use super::super::contact::tangents;
use super::members::{Member, SystemState};
use crate::mechanics::constraint::Joint;
use crate::mechanics::screw::Vec3;
use crate::mechanics::system::{Pair, SystemJoint};

/// One joint of a simulated system: its kind as read (world, t = 0) and its geometry carried
/// by its members.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// The joint as written, in the world at t = 0 (its kind names it in errors).
    pub joint: Joint<f64>,
    /// Its members: the second `None` for the ground.
    pub pair: Pair,
    /// The anchor ρ in the first member's axes (from its centre), and in the second's (the
    /// world point itself for the ground).
    pub anchor: (V3, V3),
    /// The frame (e₀ the axis, e₁, e₂) in the first member's axes, and in the second's (the
    /// world's for the ground).
    pub frame: ([V3; 3], [V3; 3]),
}

impl Link {
    /// The link of `joint` between `pair` at the state `s` (t = 0): its anchor, for a kind
    /// without one (prismatic, planar) the second member's centre (the first's, on the ground).
    pub fn new(joint: Joint<f64>, pair: Pair, s: &SystemState) -> Link {
        let v = |p: &Vec3<f64>| V3::new(p[0], p[1], p[2]);
        let (anchor, axis) = match &joint {
            Joint::Revolute { point, axis } | Joint::Cylindrical { point, axis } => {
                (Some(v(point)), Some(v(axis)))
            }
            Joint::Spherical { point } | Joint::Fixed { point } => (Some(v(point)), None),
            Joint::Prismatic { axis } => (None, Some(v(axis))),
            Joint::Planar { normal } => (None, Some(v(normal))),
        };
        let anchor = anchor.unwrap_or(s.x[pair.second.unwrap_or(pair.first)]);
        let frame: [V3; 3] = match axis {
            Some(e0) => {
                let e0 = e0.normalize();
                let (e1, e2) = tangents(&e0);
                [e0, e1, e2]
            }
            None => [V3::x(), V3::y(), V3::z()],
        };
        let local = |b: Option<usize>| -> (V3, [V3; 3]) {
            match b {
                Some(b) => {
                    let rt = s.rotation(b).transpose();
                    (rt * (anchor - s.x[b]), frame.map(|e| rt * e))
                }
                None => (anchor, frame),
            }
        };
        let (ra, fa) = local(Some(pair.first));
        let (rb, fb) = local(pair.second);
        Link {
            joint,
            pair,
            anchor: (ra, rb),
            frame: (fa, fb),
        }
    }

    /// The joint at the state `s`, in the world, for the impact layer: its anchor where the
    /// first member carries it, its axis as the first member carries it.
    pub fn at(&self, s: &SystemState) -> SystemJoint<f64> {
        let a = self.pair.first;
        let r = s.rotation(a);
        let p = s.x[a] + r * self.anchor.0;
        let e0 = r * self.frame.0[0];
        let (point, axis) = (Vec3::new(p.x, p.y, p.z), Vec3::new(e0.x, e0.y, e0.z));
        SystemJoint {
            joint: match self.joint {
                Joint::Revolute { .. } => Joint::Revolute { point, axis },
                Joint::Cylindrical { .. } => Joint::Cylindrical { point, axis },
                Joint::Spherical { .. } => Joint::Spherical { point },
                Joint::Fixed { .. } => Joint::Fixed { point },
                Joint::Prismatic { .. } => Joint::Prismatic { axis },
                Joint::Planar { .. } => Joint::Planar { normal: axis },
            },
            pair: self.pair,
        }
    }

    /// The world anchor on each member at `s` (p_a, p_b; p_b fixed on the ground).
    pub fn anchors(&self, s: &SystemState) -> (V3, V3) {
        let a = self.pair.first;
        let pa = s.x[a] + s.rotation(a) * self.anchor.0;
        let pb = match self.pair.second {
            Some(b) => s.x[b] + s.rotation(b) * self.anchor.1,
            None => self.anchor.1,
        };
        (pa, pb)
    }

    /// Whether it holds member `m` (to another or to the ground).
    pub fn holds(&self, m: usize) -> bool {
        self.pair.first == m || self.pair.second == Some(m)
    }

    /// Whether it joins members `a` and `b` (either way round).
    pub fn joins(&self, a: usize, b: usize) -> bool {
        let p = self.pair;
        (p.first, p.second) == (a, Some(b)) || (p.first, p.second) == (b, Some(a))
    }
}

/// One side of a row: the member, the row's linear and angular parts on it.
type Entry = (usize, V3, V3);

/// One blocked row at a state: its entries, its velocity-product term c and its value C
/// (an angle's for a perp row, scaled by the first member's reach in [`Frozen::drift`]).
#[derive(Clone, Debug, PartialEq)]
struct Row {
    entries: Vec<Entry>,
    bias: f64,
    value: f64,
    /// Whether C is an angle (a perp row).
    angle: bool,
}

/// The rows of every link at `s` (module docs, J1–J3).
fn rows(links: &[Link], s: &SystemState) -> Vec<Row> {
    let mut out = Vec::new();
    for l in links {
        let a = l.pair.first;
        let ra_m = s.rotation(a);
        let (pa, pb) = l.anchors(s);
        let wa = s.w[a];
        let (xb, wb, vb) = match l.pair.second {
            Some(b) => (s.x[b], s.w[b], s.v[b]),
            None => (pb, V3::zeros(), V3::zeros()),
        };
        let frame_b = |k: usize| match l.pair.second {
            Some(b) => s.rotation(b) * l.frame.1[k],
            None => l.frame.1[k],
        };
        let frame_a = |k: usize| ra_m * l.frame.0[k];
        let with_b = |entries: &mut Vec<Entry>, lin: V3, ang: V3| {
            if let Some(b) = l.pair.second {
                entries.push((b, lin, ang));
            }
        };
        let point = |out: &mut Vec<Row>| {
            let r_a = pa - s.x[a];
            let r_b = pa - xb;
            let acc = wa.cross(&wa.cross(&r_a)) - wb.cross(&wb.cross(&(pb - xb)));
            for e in [V3::x(), V3::y(), V3::z()] {
                let mut entries = vec![(a, e, r_a.cross(&e))];
                with_b(&mut entries, -e, -r_b.cross(&e));
                out.push(Row {
                    entries,
                    bias: e.dot(&acc),
                    value: e.dot(&(pa - pb)),
                    angle: false,
                });
            }
        };
        let perp = |out: &mut Vec<Row>, kb: usize, ka: usize| {
            let (u, t) = (frame_b(kb), frame_a(ka));
            let j = t.cross(&u);
            let mut entries = vec![(a, V3::zeros(), j)];
            with_b(&mut entries, V3::zeros(), -j);
            let bias = wb.cross(&wb.cross(&u)).dot(&t)
                + 2.0 * wb.cross(&u).dot(&wa.cross(&t))
                + u.dot(&wa.cross(&wa.cross(&t)));
            out.push(Row {
                entries,
                bias,
                value: u.dot(&t),
                angle: true,
            });
        };
        let line = |out: &mut Vec<Row>, ka: usize| {
            let t = frame_a(ka);
            let (r_a, r_b) = (pa - s.x[a], pb - xb);
            let d = pb - pa;
            let mut entries = vec![(a, -t, -(pb - s.x[a]).cross(&t))];
            with_b(&mut entries, t, r_b.cross(&t));
            let rate = (vb + wb.cross(&r_b)) - (s.v[a] + wa.cross(&r_a));
            let bias = t.dot(&(wb.cross(&wb.cross(&r_b)) - wa.cross(&wa.cross(&r_a))))
                + 2.0 * rate.dot(&wa.cross(&t))
                + d.dot(&wa.cross(&wa.cross(&t)));
            out.push(Row {
                entries,
                bias,
                value: t.dot(&d),
                angle: false,
            });
        };
        match l.joint {
            Joint::Spherical { .. } => point(&mut out),
            Joint::Revolute { .. } => {
                point(&mut out);
                perp(&mut out, 0, 1);
                perp(&mut out, 0, 2);
            }
            Joint::Fixed { .. } => {
                point(&mut out);
                perp(&mut out, 0, 1);
                perp(&mut out, 0, 2);
                perp(&mut out, 1, 2);
            }
            Joint::Cylindrical { .. } => {
                perp(&mut out, 0, 1);
                perp(&mut out, 0, 2);
                line(&mut out, 1);
                line(&mut out, 2);
            }
            Joint::Prismatic { .. } => {
                perp(&mut out, 0, 1);
                perp(&mut out, 0, 2);
                perp(&mut out, 1, 2);
                line(&mut out, 1);
                line(&mut out, 2);
            }
            Joint::Planar { .. } => {
                perp(&mut out, 0, 1);
                perp(&mut out, 0, 2);
                line(&mut out, 0);
            }
        }
    }
    out
}

/// The joints frozen at one state: their rows, each member's M⁻¹ and K⁺ (module docs).
#[derive(Clone, Debug)]
pub struct Frozen {
    rows: Vec<Row>,
    /// Per member: 1/m and Ĩ = R J⁻¹ Rᵀ (`None` for a sphere that does not turn).
    inverse: Vec<(f64, Option<Matrix3<f64>>)>,
    /// K⁺ (singular values below 10⁻¹² of the largest taken as zero).
    pinv: DMatrix<f64>,
}

impl Frozen {
    /// The joints `links` of `members` at `s`; `None` when there are none.
    pub fn new(links: &[Link], members: &[Member], s: &SystemState) -> Option<Frozen> {
        if links.is_empty() {
            return None;
        }
        let rows = rows(links, s);
        let inverse = members
            .iter()
            .enumerate()
            .map(|(b, m)| {
                (
                    1.0 / m.mass(),
                    m.turns().then(|| m.body.world_inverse(&s.rotation(b))),
                )
            })
            .collect();
        let mut f = Frozen {
            rows,
            inverse,
            pinv: DMatrix::zeros(0, 0),
        };
        let n = f.rows.len();
        let z: Vec<DVector<f64>> = f.rows.iter().map(|r| f.z(&r.entries)).collect();
        let k = DMatrix::from_fn(n, n, |p, q| z[q][p]);
        let svd = k.svd(true, true);
        let eps = 1e-12 * svd.singular_values.max();
        f.pinv = svd
            .pseudo_inverse(eps)
            .unwrap_or_else(|_| DMatrix::zeros(n, n));
        Some(f)
    }

    /// M⁻¹ of the generalised force `entries` on member b: (lin / m, Ĩ ang).
    fn respond(&self, (b, lin, ang): &Entry) -> (V3, V3) {
        let (im, inv) = &self.inverse[*b];
        (lin * *im, inv.map_or_else(V3::zeros, |i| i * ang))
    }

    /// z = H M⁻¹ Jᵀ of the row `dir` (a contact's, or a joint's).
    pub fn z(&self, dir: &[Entry]) -> DVector<f64> {
        DVector::from_fn(self.rows.len(), |k, _| {
            let mut sum = 0.0;
            for e in dir {
                let (l, w) = self.respond(e);
                for (b, hl, ha) in &self.rows[k].entries {
                    if *b == e.0 {
                        sum += hl.dot(&l) + ha.dot(&w);
                    }
                }
            }
            sum
        })
    }

    /// z_dᵀ K⁺ z_e: what the joints take off the entry of W between rows d and e.
    pub fn coupling(&self, zd: &DVector<f64>, ze: &DVector<f64>) -> f64 {
        zd.dot(&(&self.pinv * ze))
    }

    /// The M-orthogonal projection onto the rows: (lin, ang) ← (lin, ang) − M⁻¹ Hᵀ K⁺ (H (lin,
    /// ang) + c), with c the rows' velocity-product terms when `bias` (accelerations, J4), zero
    /// otherwise (a change of velocity, or a velocity projected).
    pub fn project(&self, lin: &mut [V3], ang: &mut [V3], bias: bool) {
        let h = DVector::from_fn(self.rows.len(), |k, _| {
            let r = &self.rows[k];
            let c = if bias { r.bias } else { 0.0 };
            c + r
                .entries
                .iter()
                .map(|(b, l, a)| l.dot(&lin[*b]) + a.dot(&ang[*b]))
                .sum::<f64>()
        });
        let lambda = &self.pinv * h;
        self.push(&lambda, -1.0, lin, ang);
    }

    /// Add `sign` M⁻¹ Hᵀ λ to (lin, ang).
    fn push(&self, lambda: &DVector<f64>, sign: f64, lin: &mut [V3], ang: &mut [V3]) {
        for (k, r) in self.rows.iter().enumerate() {
            for e in &r.entries {
                let (l, w) = self.respond(e);
                lin[e.0] += l * (sign * lambda[k]);
                ang[e.0] += w * (sign * lambda[k]);
            }
        }
    }

    /// The largest value |C| of the rows, an angle scaled by `reach` of the first member of
    /// its row (m).
    fn drift(&self, reaches: &[f64]) -> f64 {
        self.rows
            .iter()
            .map(|r| {
                if r.angle {
                    r.value.abs() * reaches[r.entries[0].0]
                } else {
                    r.value.abs()
                }
            })
            .fold(0.0, f64::max)
    }
}

/// Hold the joints at `s`: positions moved back onto C = 0 by Newton's iteration in the kinetic
/// metric (at most 8 iterations, until |C| ≤ 10⁻¹⁴ of the members' reach), then velocities
/// projected onto H (v, ω) = 0 (module docs). Returns the largest |C| corrected (m).
pub fn hold(links: &[Link], members: &[Member], s: &mut SystemState) -> f64 {
    if links.is_empty() {
        return 0.0;
    }
    let reaches: Vec<f64> = members.iter().map(|m| m.body.reach()).collect();
    let scale = reaches.iter().fold(0.0, |m: f64, r| m.max(*r));
    let mut worst = None;
    for _ in 0..8 {
        let Some(f) = Frozen::new(links, members, s) else {
            return 0.0;
        };
        let d = f.drift(&reaches);
        worst.get_or_insert(d);
        if d <= 1e-14 * scale {
            break;
        }
        let c = DVector::from_fn(f.rows.len(), |k, _| f.rows[k].value);
        let lambda = &f.pinv * c;
        let b = members.len();
        let (mut dx, mut dth) = (vec![V3::zeros(); b], vec![V3::zeros(); b]);
        f.push(&lambda, -1.0, &mut dx, &mut dth);
        for k in 0..b {
            s.x[k] += dx[k];
            if dth[k] != V3::zeros() {
                s.q[k] = UnitQuaternion::from_scaled_axis(dth[k]) * s.q[k];
            }
        }
    }
    settle(links, members, s);
    worst.unwrap_or(0.0)
}

/// The velocities at `s` projected onto the joints' rows: H (v, ω) = 0 to rounding.
pub fn settle(links: &[Link], members: &[Member], s: &mut SystemState) {
    if let Some(f) = Frozen::new(links, members, s) {
        f.project(&mut s.v, &mut s.w, false);
    }
}

/// The largest joint rate |H (v, ω)| at `s` (m/s; a perp row's, rad/s, times its first member's
/// reach): zero to rounding on a consistent state.
pub fn rate(links: &[Link], members: &[Member], s: &SystemState) -> f64 {
    rows(links, s)
        .iter()
        .map(|r| {
            let v: f64 = r
                .entries
                .iter()
                .map(|(b, l, a)| l.dot(&s.v[*b]) + a.dot(&s.w[*b]))
                .sum();
            if r.angle {
                v.abs() * members[r.entries[0].0].body.reach()
            } else {
                v.abs()
            }
        })
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two members at a general pose, moving with given (v, ω) and accelerating at given
    /// (a, α): each row's C along that motion — x(h) = x + v h + ½ a h², R(h) = exp(ω h + ½ α h²)
    /// R, whose second derivative at 0 is ([α]× + [ω]×²) R as a rigid body's — has
    /// Ċ = J (v, ω) and C̈ = J (a, α) + c (J1–J3), against central differences (h = 10⁻⁴: the
    /// truncation h² C⁗/12 and the rounding ε C/h² both below 10⁻⁶ of the terms).
    #[test]
    fn rows_are_the_derivatives_of_their_constraints() {
        let x = vec![V3::new(0.1, -0.2, 0.3), V3::new(0.7, 0.4, -0.1)];
        let q = vec![
            UnitQuaternion::from_scaled_axis(V3::new(0.3, -0.4, 0.5)),
            UnitQuaternion::from_scaled_axis(V3::new(-0.6, 0.2, 0.1)),
        ];
        let v = vec![V3::new(0.5, -1.0, 0.2), V3::new(-0.3, 0.8, 1.1)];
        let w = vec![V3::new(1.5, -0.7, 2.0), V3::new(-0.4, 1.2, 0.9)];
        let a = [V3::new(0.2, 0.3, -9.8), V3::new(1.0, -2.0, 0.5)];
        let alpha = [V3::new(3.0, -1.0, 0.5), V3::new(-2.0, 0.7, 1.5)];
        let s0 = SystemState { x, v, q, w };
        let at = |h: f64| -> SystemState {
            let mut s = s0.clone();
            for b in 0..2 {
                s.x[b] += s0.v[b] * h + a[b] * (0.5 * h * h);
                s.q[b] = UnitQuaternion::from_scaled_axis(s0.w[b] * h + alpha[b] * (0.5 * h * h))
                    * s0.q[b];
            }
            s
        };
        let point = Vec3::new(0.4, 0.1, 0.1);
        let axis = Vec3::new(1.0, 2.0, -0.5);
        let joints = [
            Joint::Fixed { point },
            Joint::Prismatic { axis },
            Joint::Planar { normal: axis },
            Joint::Cylindrical { point, axis },
        ];
        for joint in joints {
            for second in [Some(1), None] {
                let pair = Pair { first: 0, second };
                let link = Link::new(joint.clone(), pair, &s0);
                let here = rows(std::slice::from_ref(&link), &s0);
                let h = 1e-4;
                let (plus, minus) = (
                    rows(std::slice::from_ref(&link), &at(h)),
                    rows(std::slice::from_ref(&link), &at(-h)),
                );
                for (k, r) in here.iter().enumerate() {
                    let apply = |v: &[V3], w: &[V3]| -> f64 {
                        r.entries
                            .iter()
                            .map(|(b, l, an)| l.dot(&v[*b]) + an.dot(&w[*b]))
                            .sum()
                    };
                    let rate = (plus[k].value - minus[k].value) / (2.0 * h);
                    let second_rate = (plus[k].value - 2.0 * r.value + minus[k].value) / (h * h);
                    let jv = apply(&s0.v, &s0.w);
                    let ja = apply(&a, &alpha) + r.bias;
                    let scale = 1.0 + jv.abs() + ja.abs();
                    let name = joint.name();
                    assert!(r.value.abs() < 1e-15, "{name} row {k}: C = {}", r.value);
                    assert!(
                        (rate - jv).abs() < 1e-6 * scale,
                        "{name} {second:?} row {k}: Ċ {rate} vs J v {jv}"
                    );
                    assert!(
                        (second_rate - ja).abs() < 1e-6 * scale,
                        "{name} {second:?} row {k}: C̈ {second_rate} vs J a + c {ja}"
                    );
                }
            }
        }
    }
}
