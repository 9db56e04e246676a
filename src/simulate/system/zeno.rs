//! The accumulation of impacts (Zeno) in a system: the single body's closed form
//! ([`crate::simulate::run`], module docs) where one member bounces on something that stays
//! put — a ball on a box resting on the floor, a box dropped flat on another.
//!
//! **When.** The last three impacts struck the same contacts (the same open ones, the same
//! closed ones persisting), and over all three:
//!
//! - one member m moved and every other stayed put: slower than 10⁻¹² of the speed scale
//!   before and after each impact, at the same place (to 10⁻¹² of the length scale);
//! - m does not turn (no spin, or a sphere's spin that no contact feels: [`super::members`]),
//!   so every point of m moves with its centre, and no joint holds it;
//! - every open contact struck is m's against the same unit normal d (pushing m; a plane's, a
//!   still box's face; or, with m moving along d, a still sphere's, edge's or corner's), and no
//!   closed contact touches m: between impacts m is in free flight;
//! - the last impact left m's velocity across d unchanged (to 10⁻¹² of the speed scale: no
//!   friction acted), and the rebound speeds u₁, u₂, u₃ along d are in a constant ratio
//!   r = u₂/u₁ = u₃/u₂ < 1 (to 10⁻⁹; within 10⁻⁹ of 1 a bounce is elastic, not accumulating);
//! - gravity presses m onto the contacts: g_n = −d · g > 0.
//!
//! **The closed form.** m's height above the contacts along d is then a chain of parabolas of
//! acceleration −g_n, each flight 2u/g_n long and each rebound r times the last, so the
//! remaining flights sum to
//!
//! ```text
//! t∞ − t = Σ_{j≥0} 2 u₃ rʲ / g_n = 2 u₃ / (g_n (1 − r))
//! ```
//!
//! (the bouncing ball's t∞ = 2v₀/(g(1 − e)) of issue 27, v₀ the first rebound). Across d, m
//! moves ballistically: x_⊥(τ) = x_⊥ + v_⊥ τ + ½ g_⊥ τ². It is moved there, at zero gap and
//! zero normal speed, the struck contacts persist, and the energy the accumulated impacts
//! dissipated is m's kinetic energy along d at the last rebound, ½ m u₃² (the flights conserve
//! energy).
//!
//! **The way there.** A contact on a box's face holds only while m's point stays over the face
//! ([`super::gaps`]): across d each of its coordinates along the face's axes is a quadratic in
//! τ, so it stays within the face's edges over [0, t∞ − t] if it does at both ends and where
//! the quadratic turns (τ = −(e · v_⊥)/(e · g_⊥) inside the interval); that is checked, and
//! so is every other contact still open at t∞ (its gap positive). As for the single body, the
//! flights in between are not checked against the other obstacles.

use super::super::body::V3;
use super::super::run::ImpactRecord;
use super::super::world::Plane;
use super::gaps::{Candidate, Touch, gap};
use super::joints::Link;
use super::members::{Member, SystemState};

/// What one impact left, for the test above: where every member was, and which moved.
#[derive(Clone, Debug, PartialEq)]
pub struct Bounce {
    /// x_b at the impact.
    pub x: Vec<V3>,
    /// Whether member b moved before or after it (faster than 10⁻¹² of the speed scale, its
    /// spin counted where it turns).
    pub moving: Vec<bool>,
    /// The open contacts it struck (candidate indices, ascending).
    pub open: Vec<usize>,
}

impl Bounce {
    /// The impact at `x` from `before` to `after`, striking the open contacts `open`.
    pub fn new(
        members: &[Member],
        before: &SystemState,
        after: &SystemState,
        open: Vec<usize>,
        speed: f64,
    ) -> Bounce {
        let moves = |s: &SystemState, b: usize| {
            let spin = if members[b].turns() {
                s.w[b].norm() * members[b].body.reach()
            } else {
                0.0
            };
            s.v[b].norm() + spin > 1e-12 * speed
        };
        Bounce {
            x: before.x.clone(),
            moving: (0..members.len())
                .map(|b| moves(before, b) || moves(after, b))
                .collect(),
            open,
        }
    }
}

/// The jump to the accumulation.
#[derive(Clone, Debug, PartialEq)]
pub struct Jump {
    /// t∞ − t (s).
    pub dt: f64,
    /// The state at t∞.
    pub state: SystemState,
    /// r.
    pub ratio: f64,
    /// The open contacts that persist from t∞.
    pub close: Vec<usize>,
    /// ½ m u₃² (J).
    pub dissipated: f64,
}

/// What the test reads: the system, its scales and the run so far.
pub struct Scene<'a> {
    /// The members.
    pub members: &'a [Member],
    /// The joints (a member a joint holds is never in free flight).
    pub joints: &'a [Link],
    /// The obstacle planes.
    pub planes: &'a [Plane],
    /// The contacts watched.
    pub candidates: &'a [Candidate],
    /// g (m/s²).
    pub gravity: V3,
    /// The speed scale (m/s).
    pub speed: f64,
    /// The length scale (m).
    pub length: f64,
}

/// The jump to the accumulation after the last of `impacts` (module docs), if the last three
/// make one: `trail` their bounces, `before` the state just before the last, `s` just after
/// it, `closed` the contacts closed after it, `left` the time left in the run.
pub fn accumulation(
    scene: &Scene,
    impacts: &[ImpactRecord],
    trail: &[Bounce],
    before: &SystemState,
    s: &SystemState,
    closed: &[usize],
    left: f64,
) -> Option<Jump> {
    let n = impacts.len();
    if n < 3 || trail.len() < 3 {
        return None;
    }
    let (records, bounces) = (&impacts[n - 3..], &trail[trail.len() - 3..]);
    // the same contacts struck, open and persisting alike
    let same = |r: &ImpactRecord| {
        r.contacts.len() == records[2].contacts.len()
            && r.contacts.iter().zip(&records[2].contacts).all(|(a, b)| {
                a.feature == b.feature && a.plane == b.plane && a.persisting == b.persisting
            })
    };
    let open = &bounces[2].open;
    if open.is_empty() || !records.iter().all(same) || bounces.iter().any(|b| &b.open != open) {
        return None;
    }
    // one member moved, the others stayed put
    let members = scene.members;
    let moved: Vec<usize> = (0..members.len())
        .filter(|&b| bounces.iter().any(|i| i.moving[b]))
        .collect();
    let [m] = moved[..] else {
        return None;
    };
    let put = (0..members.len()).filter(|&b| b != m).all(|b| {
        bounces
            .iter()
            .all(|i| (i.x[b] - bounces[0].x[b]).norm() <= 1e-12 * scene.length)
    });
    let spins = |st: &SystemState| {
        members[m].turns() && st.w[m].norm() * members[m].body.reach() > 1e-12 * scene.speed
    };
    if !put || spins(before) || spins(s) || scene.joints.iter().any(|j| j.holds(m)) {
        return None;
    }
    // every open contact m's, against one normal d that pushes m; no closed one on m
    let touches_m = |k: usize| {
        gap(&scene.candidates[k].touch, members, scene.planes, s)
            .sides()
            .any(|i| i.body == m)
    };
    if closed.iter().any(|&k| !open.contains(&k) && touches_m(k)) {
        return None;
    }
    let mut d: Option<V3> = None;
    for &k in open {
        let g = gap(&scene.candidates[k].touch, members, scene.planes, s);
        let mut sides = g.sides();
        let (Some(i), None) = (sides.find(|i| i.body == m), sides.find(|i| i.body == m)) else {
            return None;
        };
        let dk = g.normal * i.sign;
        match d {
            None => d = Some(dk),
            Some(d) if (d - dk).norm() <= 1e-12 => {}
            Some(_) => return None,
        }
    }
    let d = d?;
    let g = scene.gravity;
    let gn = -d.dot(&g);
    let (vt, gt) = (s.v[m] - d * d.dot(&s.v[m]), g + d * gn);
    let dv = (s.v[m] - before.v[m]) - d * d.dot(&(s.v[m] - before.v[m]));
    if gn <= 0.0 || dv.norm() > 1e-12 * scene.speed {
        return None;
    }
    // a pair's normal, or a sphere's on an edge or a corner, stays put only while m moves along
    // it; an edge on an edge is taken only so too (where its closest points stay on the edges
    // is not followed along the way)
    let pair = open.iter().any(|&k| {
        !matches!(
            scene.candidates[k].touch,
            Touch::Plane { .. } | Touch::Face { .. }
        )
    });
    if pair && (vt.norm() > 1e-12 * scene.speed || gt.norm() > 1e-12 * g.norm()) {
        return None;
    }
    let rebound = |r: &ImpactRecord| {
        r.contacts
            .iter()
            .filter(|c| !c.persisting)
            .map(|c| c.after)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let u: Vec<f64> = records.iter().map(rebound).collect();
    let (r1, r2) = (u[1] / u[0], u[2] / u[1]);
    if !(r2 > 0.0 && r2 < 1.0 - 1e-9 && (r1 - r2).abs() <= 1e-9 * r2) {
        return None;
    }
    let dt = 2.0 * u[2] / (gn * (1.0 - r2));
    if dt > left {
        return None;
    }
    // m at τ across d: every face contact still over its face along the way
    let at = |tau: f64| {
        let mut st = s.clone();
        st.x[m] += vt * tau + gt * (0.5 * tau * tau);
        st.v[m] = vt + gt * tau;
        st
    };
    let mut times = vec![dt];
    for &k in open {
        if let Touch::Face { b, .. } = scene.candidates[k].touch {
            let r = s.rotation(b);
            for e in r.column_iter() {
                let (ev, eg) = (e.dot(&vt), e.dot(&gt));
                if eg != 0.0 && -ev / eg > 0.0 && -ev / eg < dt {
                    times.push(-ev / eg);
                }
            }
        }
    }
    let over = |st: &SystemState| {
        open.iter().all(|&k| {
            gap(&scene.candidates[k].touch, members, scene.planes, st)
                .gap
                .is_finite()
        })
    };
    if !times.iter().all(|&tau| over(&at(tau))) {
        return None;
    }
    let mut state = at(dt);
    let lowest = open
        .iter()
        .map(|&k| gap(&scene.candidates[k].touch, members, scene.planes, &state).gap)
        .fold(f64::INFINITY, f64::min);
    state.x[m] -= d * lowest;
    // every other open contact still open there
    let clear = (0..scene.candidates.len())
        .filter(|k| !open.contains(k) && !closed.contains(k))
        .all(|k| gap(&scene.candidates[k].touch, members, scene.planes, &state).gap > 0.0);
    if !clear {
        return None;
    }
    Some(Jump {
        dt,
        state,
        ratio: r2,
        close: open.clone(),
        dissipated: 0.5 * members[m].mass() * u[2] * u[2],
    })
}
