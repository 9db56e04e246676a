//! The contacts a system can make and their gap functions: every feature of every member
//! against every obstacle plane, every pair of spheres against each other, every feature of a
//! member (a box's corner, a rod's end, a sphere) against every face of a box, every edge (a
//! box's twelve, a thin rod's segment) against every edge of another member, and every sphere
//! against every edge and corner (a box's, a rod's segment and ends). Between spheres, boxes
//! and thin rods nothing else can touch first.
//!
//! A feature of member b against a plane (unit normal N out of it, through P) is the single
//! body's gap ([`crate::simulate::world::gap`]); for a sphere (centre x_b, radius r_b):
//!
//! ```text
//! g = N · (x_b − P) − r_b,     ġ = N · v_b,     g̈ = N · a_b
//! ```
//!
//! Two spheres a, b, with d = x_b − x_a, n = d/|d| and u = v_b − v_a:
//!
//! ```text
//! g = |d| − r_a − r_b,     ġ = n · u,     g̈ = n · (a_b − a_a) + (|u|² − (n · u)²)/|d|
//! ```
//!
//! (the last term: n turns as the pair does). A feature of a, at p, against the face of box b
//! whose outward unit normal is n = R_b e (e = ±x, ±y or ±z of b's axes) at the half edge h
//! from b's centre, with D = p − x_b:
//!
//! ```text
//! g = n · D − h,    ġ = ṅ · D + n · Ḋ,    g̈ = n̈ · D + 2 ṅ · Ḋ + n · D̈,    ṅ = ω_b × n
//! ```
//!
//! with p = x_a + r_a for a corner (r_a = R_a a, ṗ = v_a + ω_a × r_a, p̈ = a_a + α_a × r_a +
//! ω_a × (ω_a × r_a)) and p = x_a − ρ n for a sphere of radius ρ (ṗ = v_a − ρ ṅ). The face
//! contact is watched where it can be one: while p (a sphere's centre) lies over the face —
//! its coordinates ℓ along b's two other axes within the half edges h_j, to 10⁻⁹ of b's reach,
//! on the face's side of b's centre, and nearer the face's plane than any other face's
//! (±ℓ_k − h_k ≥ max_j (|ℓ_j| − h_j): a point at an edge or inside the box belongs to the face
//! it is least deep under); elsewhere its gap is +∞ (the face's plane beside b is no
//! obstacle).
//!
//! Each is g̈ = J a + c: the row J of the contact acts on each member i it touches as
//! σ_i [n; r_i × n] (σ_i = ±1 the side, r_i = the contact point − x_i: the force λ σ_i n at the
//! point), and c is the curvature term — the part of g̈ in the velocities alone:
//! n · (ω × (ω × r)) for a corner on a plane, 0 for a sphere on it, the pair's above, and
//! n̈_v · D + 2 ṅ · Ḋ + n · p̈_v on a face (n̈_v = ω_b × ṅ; p̈_v = ω_a × (ω_a × r_a) for a corner,
//! −ρ n̈_v for a sphere). That is what the acceleration-level problem of [`super::persist`]
//! assembles, and ġ = J u. A contact force λ ≥ 0 acts along Jᵀ: it opens the gap. The
//! moments r × n of a sphere's side are zero (its force passes through its centre), written
//! as zeros.
//!
//! **Edge on edge** (derivations/system-edges.md §1). Edges p_a + s d_a and p_b + t d_b (unit
//! d, |s| ≤ h_a, |t| ≤ h_b), m = d_a × d_b, ν = |m| > [`PARALLEL`], n = σ m/ν out of a:
//!
//! ```text
//! g = n · (p_b − p_a),   ġ = n · (V_b − V_a),   V_i = v_i + ω_i × r_i,  r_i = q_i − x_i
//! c = ṅ · (V_b − V_a) + n · (ω_b × ṙ_b − ω_a × ṙ_a),   ṙ_i = ω_i × r_i + ṡ_i d_i
//! ṅ = σ (ṁ − n (n · ṁ))/ν,   ṁ = (ω_a × d_a) × d_b + d_a × (ω_b × d_b)
//! ```
//!
//! with q_a = p_a + s d_a, q_b = p_b + t d_b the closest points (s = (α − c β)/(1 − c²),
//! t = (c α − β)/(1 − c²), c = d_a · d_b, α = d_a · D, β = d_b · D, D = p_b − p_a) and ṡ_a = ṡ,
//! ṡ_b = ṫ their slide along the edges (their rates from differentiating those). As n ⟂ both
//! edges, the slide does not change g to first order: ġ is the normal relative velocity of the
//! two material points at q_a, q_b, J u for the row σ_a = −1, σ_b = +1. Watched where the
//! closest points lie on both segments (to 10⁻⁹ of the reach), n lies in a's cone of outward
//! face normals and −n in b's (a rod's cone: every direction ⟂ to it), and n · (x_b − x_a) +
//! g ≥ 0 (the pair on the far side of both bodies is in the cones too, at a gap of about minus
//! their size); σ puts n in a's cone (or −n in b's for a rod a; for two rods, g ≥ 0: their
//! distance). Its `inside` is how far the nearer closest point is from its edge's end.
//!
//! **A sphere on an edge or a corner** (§2). For the point p of member b nearest the sphere's
//! centre c on an edge (p = p_b + t d, t = d · (c − p_b), sliding at ṫ) or at a corner:
//!
//! ```text
//! g = |c − p| − ρ,   n = (c − p)/|c − p|,   ġ = n · u,   u = v_a − v_b − ω_b × r_b
//! c = ṅ · u − n · (ω_b × ṙ_b),   ṅ = (ẇ − n (n · ẇ))/|c − p|,   ẇ = u − ṫ d,
//! ṙ_b = ω_b × r_b + ṫ d
//! ```
//!
//! (r_b = p − x_b; ṫ = 0 at a corner). Watched where c is in the feature's region: beyond both
//! faces' planes and within the length of a box's edge, within a rod's length, beyond a box
//! corner's three faces' planes, beyond a rod's end along its axis; `inside` is how far (m) it
//! is within the nearest of those bounds. The sphere's side is σ = +1, b's σ = −1.

use super::super::body::{Feature, Shape, State, V3};
use super::super::world::{ContactLaw, Plane};
use super::members::{Member, SystemState};

/// What touches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Touch {
    /// Feature `feature` of member `body` on obstacle `plane`.
    Plane {
        /// The member.
        body: usize,
        /// Its feature (index in its [`crate::simulate::body::Body::features`]).
        feature: usize,
        /// The plane.
        plane: usize,
    },
    /// Sphere `a` on sphere `b` (a < b).
    Pair {
        /// The first sphere.
        a: usize,
        /// The second.
        b: usize,
    },
    /// Feature `feature` of member `a` on face `face` of box `b` (face 2k + 0 is +e_k, 2k + 1
    /// is −e_k, in b's axes).
    Face {
        /// The member whose feature strikes.
        a: usize,
        /// Its feature.
        feature: usize,
        /// The box.
        b: usize,
        /// Its face.
        face: usize,
    },
    /// Edge `edge_a` of member `a` on edge `edge_b` of member `b` (a < b; a box's edges or a
    /// rod's segment: [`edge`]).
    Edges {
        /// The first member.
        a: usize,
        /// Its edge.
        edge_a: usize,
        /// The second member.
        b: usize,
        /// Its edge.
        edge_b: usize,
    },
    /// Sphere `a` on edge `edge` of member `b` (a box's edge or a rod's segment).
    OnEdge {
        /// The sphere.
        a: usize,
        /// The member with the edge.
        b: usize,
        /// Its edge.
        edge: usize,
    },
    /// Sphere `a` on the point feature `feature` of member `b` (a box's corner, a rod's end).
    OnCorner {
        /// The sphere.
        a: usize,
        /// The member with the corner.
        b: usize,
        /// Its feature (a [`Feature::Point`]).
        feature: usize,
    },
}

/// A straight edge of a member, in its body axes: a box's edge (between two faces) or a rod's
/// segment (no faces: every direction perpendicular to it is outward).
#[derive(Clone, Debug, PartialEq)]
pub struct Edge {
    /// Its midpoint (from C).
    pub mid: V3,
    /// Its unit direction.
    pub dir: V3,
    /// Half its length.
    pub half: f64,
    /// The outward unit normals of its two faces (none for a rod).
    pub faces: Option<[V3; 2]>,
    /// Its name in the log: `edge [1, *, -1]` (the signs of the two faces' axes, `*` along
    /// it), `rod`.
    pub label: String,
}

/// How many edges a shape has: a box 12, a rod 1 (its segment), any other none.
pub fn edge_count(shape: &Shape) -> usize {
    match shape {
        Shape::Box { .. } => 12,
        Shape::Rod { .. } => 1,
        _ => 0,
    }
}

/// Edge `e` of a shape (`e` < [`edge_count`]): of a box, the edge along axis k = e / 4 on the
/// faces of signs s₁ = + for e mod 4 < 2 (else −) and s₂ = + for e even (else −) of its
/// other two axes in increasing order; of a rod, its segment along body z.
pub fn edge(shape: &Shape, e: usize) -> Option<Edge> {
    match *shape {
        Shape::Box { half } => {
            let k = e / 4;
            if k > 2 {
                return None;
            }
            let (p, q) = ((k + 1) % 3, (k + 2) % 3);
            let (j1, j2) = (p.min(q), p.max(q));
            let (s1, s2) = (
                if e % 4 < 2 { 1.0 } else { -1.0 },
                if e.is_multiple_of(2) { 1.0 } else { -1.0 },
            );
            let axis = |j: usize| V3::from_fn(|i, _| if i == j { 1.0 } else { 0.0 });
            let mut signs = ["*".to_string(), "*".to_string(), "*".to_string()];
            signs[j1] = format!("{}", s1 as i64);
            signs[j2] = format!("{}", s2 as i64);
            Some(Edge {
                mid: axis(j1) * (s1 * half[j1]) + axis(j2) * (s2 * half[j2]),
                dir: axis(k),
                half: half[k],
                faces: Some([axis(j1) * s1, axis(j2) * s2]),
                label: format!("edge [{}]", signs.join(", ")),
            })
        }
        Shape::Rod { half_length } if e == 0 => Some(Edge {
            mid: V3::zeros(),
            dir: V3::z(),
            half: half_length,
            faces: None,
            label: "rod".into(),
        }),
        _ => None,
    }
}

/// Below this |d_a × d_b| (the sine of the angle between two edges) they are parallel, and no
/// edge contact is watched between them: their contact is a corner's on a face (or, for two
/// rods, an end's on the other's segment, a contact of measure zero). 10⁻⁶ keeps the normal
/// (d_a × d_b)/|d_a × d_b| good to 10⁻¹⁰ of its length where f64 rounds the cross product at
/// 10⁻¹⁶.
pub const PARALLEL: f64 = 1e-6;

/// How far (a cosine) a normal may fall outside an edge's cone of face normals and the contact
/// still be watched: at the cone's boundary the edge contact and a corner's on the face are the
/// same contact, and both are watched.
const CONE: f64 = 1e-9;

/// A contact the simulation watches, and its law.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    /// What touches.
    pub touch: Touch,
    /// Its law (k, μ = 0, the LZB stiffness and exponent).
    pub law: ContactLaw,
}

/// One member a contact's row acts on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Side {
    /// The member.
    pub body: usize,
    /// σ: +1 where the force λ n pushes it, −1 where it pushes it along −n.
    pub sign: f64,
    /// r: the contact point − its centre (world).
    pub arm: V3,
    /// r × n (zero for a sphere).
    pub moment: V3,
    /// ṙ: how fast the arm turns and slides — ω × r for a material point (a corner), the rate
    /// of a sphere's r = ∓ρ n as n turns (zero on a plane), for a box's face the rate of
    /// the contact point less its centre's, ṗ − v_b, and for an edge ω × r + ṡ d (the contact
    /// point is no material point: it slides along the edge at ṡ). The slip u = Σ σ_i (v_i + ω_i × r_i) of
    /// the contact then changes at u̇ = Σ σ_i (a_i + α_i × r_i + ω_i × ṙ_i): what a sticking
    /// contact holds at zero along its tangents ([`super::persist`]).
    pub arm_rate: V3,
}

/// A contact's gap at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gap {
    /// g (m); +∞ for a face, edge or corner contact out of its region (module docs).
    pub gap: f64,
    /// ġ (m/s): negative approaching.
    pub rate: f64,
    /// The unit normal n (a plane's N; from a's centre to b's; a face's outward normal; out of
    /// a's edge; from an edge or a corner to the sphere).
    pub normal: V3,
    /// The curvature term c of g̈ = J a + c (m/s²).
    pub curvature: f64,
    /// The contact point (world): on the first member's surface (on a's edge, on the sphere).
    pub point: V3,
    /// How far the point lies inside its face's edges, its edges' ends, or the sphere's centre
    /// inside its feature's region (m; +∞ on a plane and between spheres).
    pub inside: f64,
    /// The rate of `inside` (m/s; negative: the point moves out over the nearest edge).
    pub inside_rate: f64,
    /// The members the row acts on: one on a plane, two between members.
    pub sides: [Option<Side>; 2],
}

impl Gap {
    /// The sides the row acts on.
    pub fn sides(&self) -> impl Iterator<Item = &Side> {
        self.sides.iter().flatten()
    }
}

impl Touch {
    /// The members the contact's row J acts on, with the sign of the normal on each
    /// (+1: the force λ n pushes it; −1: λ n pulls it, i.e. pushes along −n).
    pub fn bodies(&self) -> Vec<(usize, f64)> {
        match *self {
            Touch::Plane { body, .. } => vec![(body, 1.0)],
            Touch::Pair { a, b } => vec![(a, -1.0), (b, 1.0)],
            Touch::Face { a, b, .. }
            | Touch::OnEdge { a, b, .. }
            | Touch::OnCorner { a, b, .. } => vec![(a, 1.0), (b, -1.0)],
            Touch::Edges { a, b, .. } => vec![(a, -1.0), (b, 1.0)],
        }
    }

    /// What the log says when it lets go of the region where its gap is defined: `leaves the
    /// face` (a face contact's point over its edge), `leaves the edge` (an edge contact's point
    /// off an end, a sphere out of an edge's region), `leaves the corner`.
    pub fn leaving(&self) -> &'static str {
        match self {
            Touch::Face { .. } => "leaves the face",
            Touch::OnCorner { .. } => "leaves the corner",
            Touch::Edges { .. } | Touch::OnEdge { .. } => "leaves the edge",
            // a plane's or a pair's contact is defined everywhere: only lift-off ends it
            Touch::Plane { .. } | Touch::Pair { .. } => "lifts off",
        }
    }

    /// Its name in the log: `bead 1 on floor`, `bead 1 on bead 2`, `top corner [1, 1, -1]` on
    /// `base face +z`, `top edge [*, 1, -1]` on `base edge [1, *, 1]`, `stick rod` on `base
    /// edge [1, *, 1]`, `ball` on `base corner [1, 1, 1]` or `stick end [0, 0, 1]` — the first
    /// and the second of `a on b`.
    pub fn name(&self, members: &[Member], planes: &[Plane]) -> (String, String) {
        let edge_name = |m: usize, e: usize| -> String {
            let member = &members[m];
            let label =
                edge(&member.body.shape, e).map_or_else(|| format!("edge {e}"), |e| e.label);
            format!("{} {label}", member.name)
        };
        let feature = |m: usize, f: usize| -> String {
            let member = &members[m];
            match &member.body.shape {
                Shape::Sphere { .. } => member.name.clone(),
                _ => format!("{} {}", member.name, member.body.features[f].label()),
            }
        };
        match *self {
            Touch::Plane {
                body,
                feature: f,
                plane,
            } => (feature(body, f), planes[plane].name.clone()),
            Touch::Pair { a, b } => (members[a].name.clone(), members[b].name.clone()),
            Touch::Face {
                a,
                feature: f,
                b,
                face,
            } => (
                feature(a, f),
                format!(
                    "{} face {}{}",
                    members[b].name,
                    if face.is_multiple_of(2) { '+' } else { '-' },
                    ['x', 'y', 'z'][face / 2]
                ),
            ),
            Touch::Edges {
                a,
                edge_a,
                b,
                edge_b,
            } => (edge_name(a, edge_a), edge_name(b, edge_b)),
            Touch::OnEdge { a, b, edge } => (members[a].name.clone(), edge_name(b, edge)),
            Touch::OnCorner { a, b, feature: f } => (members[a].name.clone(), feature(b, f)),
        }
    }
}

/// Member `b`'s state as the single body's.
pub fn state_of(s: &SystemState, b: usize) -> State {
    State {
        x: s.x[b],
        q: s.q[b],
        v: s.v[b],
        w: s.w[b],
    }
}

/// A sphere's side: its normal force passes through its centre.
fn round_side(body: usize, sign: f64, arm: V3, arm_rate: V3) -> Side {
    Side {
        body,
        sign,
        arm,
        moment: V3::zeros(),
        arm_rate,
    }
}

/// The gap of `touch` at `s` (module docs).
pub fn gap(touch: &Touch, members: &[Member], planes: &[Plane], s: &SystemState) -> Gap {
    match *touch {
        Touch::Plane {
            body,
            feature,
            plane,
        } => {
            let p = &planes[plane];
            let n = p.normal;
            let f = &members[body].body.features[feature];
            if let Feature::Sphere { radius: r } = f {
                return Gap {
                    gap: n.dot(&(s.x[body] - p.point)) - r,
                    rate: n.dot(&s.v[body]),
                    normal: n,
                    curvature: 0.0,
                    point: s.x[body] - n * *r,
                    inside: f64::INFINITY,
                    inside_rate: 0.0,
                    sides: [Some(round_side(body, 1.0, -n * *r, V3::zeros())), None],
                };
            }
            let st = state_of(s, body);
            let g = super::super::world::gap(f, p, &st);
            let r = g.point - st.x;
            Gap {
                gap: g.gap,
                rate: g.rate,
                normal: n,
                curvature: n.dot(&st.w.cross(&g.drift)),
                point: g.point,
                inside: f64::INFINITY,
                inside_rate: 0.0,
                sides: [
                    Some(Side {
                        body,
                        sign: 1.0,
                        arm: r,
                        moment: r.cross(&n),
                        arm_rate: g.drift,
                    }),
                    None,
                ],
            }
        }
        Touch::Pair { a, b } => {
            let d = s.x[b] - s.x[a];
            let len = d.norm();
            let n = d / len;
            let u = s.v[b] - s.v[a];
            let along = n.dot(&u);
            let (ra, rb) = (
                members[a].radius().unwrap_or(0.0),
                members[b].radius().unwrap_or(0.0),
            );
            let point = s.x[a] + n * ra;
            // ṅ: n turns as the pair does
            let ndot = (u - n * along) / len;
            Gap {
                gap: len - ra - rb,
                rate: along,
                normal: n,
                curvature: (u.norm_squared() - along * along).max(0.0) / len,
                point,
                inside: f64::INFINITY,
                inside_rate: 0.0,
                sides: [
                    Some(round_side(a, -1.0, n * ra, ndot * ra)),
                    Some(round_side(
                        b,
                        1.0,
                        point - s.x[b],
                        s.v[a] + ndot * ra - s.v[b],
                    )),
                ],
            }
        }
        Touch::Face {
            a,
            feature,
            b,
            face,
        } => face_gap(members, s, a, feature, b, face),
        Touch::Edges {
            a,
            edge_a,
            b,
            edge_b,
        } => edges_gap(members, s, (a, edge_a), (b, edge_b)),
        Touch::OnEdge { a, b, edge } => on_edge_gap(members, s, a, b, edge),
        Touch::OnCorner { a, b, feature } => on_corner_gap(members, s, a, b, feature),
    }
}

/// An edge of member `b` in the world at `s`: its midpoint, its direction, the velocity of its
/// midpoint, the rate of its direction, and its faces' outward normals.
struct WorldEdge {
    mid: V3,
    dir: V3,
    mid_rate: V3,
    dir_rate: V3,
    half: f64,
    faces: Option<[V3; 2]>,
}

fn world_edge(members: &[Member], s: &SystemState, b: usize, e: usize) -> Option<WorldEdge> {
    let edge = edge(&members[b].body.shape, e)?;
    let r = s.rotation(b);
    let arm = r * edge.mid;
    let dir = r * edge.dir;
    Some(WorldEdge {
        mid: s.x[b] + arm,
        dir,
        mid_rate: s.v[b] + s.w[b].cross(&arm),
        dir_rate: s.w[b].cross(&dir),
        half: edge.half,
        faces: edge.faces.map(|f| f.map(|f| r * f)),
    })
}

/// Whether the unit normal `n` lies in the cone of the outward normals `faces` (a rod's cone
/// is every direction perpendicular to it).
fn in_cone(n: &V3, faces: &Option<[V3; 2]>) -> bool {
    faces
        .as_ref()
        .is_none_or(|f| f.iter().all(|f| n.dot(f) >= -CONE))
}

/// Edge `ea` of `a` on edge `eb` of `b` (module docs).
fn edges_gap(
    members: &[Member],
    s: &SystemState,
    (a, ea): (usize, usize),
    (b, eb): (usize, usize),
) -> Gap {
    let (Some(ka), Some(kb)) = (world_edge(members, s, a, ea), world_edge(members, s, b, eb))
    else {
        return apart(s, a);
    };
    let (da, db) = (ka.dir, kb.dir);
    let m = da.cross(&db);
    let nu = m.norm();
    if nu <= PARALLEL {
        return apart(s, a);
    }
    let d = kb.mid - ka.mid;
    let n0 = m / nu;
    // n out of a: into a box's cone of face normals, or out of b's, or (two rods) along the
    // line from a's edge to b's
    let sigma = match (&ka.faces, &kb.faces) {
        (Some(f), _) => n0.dot(&(f[0] + f[1])).signum(),
        (None, Some(f)) => -n0.dot(&(f[0] + f[1])).signum(),
        (None, None) => {
            if n0.dot(&d) < 0.0 {
                -1.0
            } else {
                1.0
            }
        }
    };
    let n = n0 * sigma;
    // the closest points q_a = p_a + s d_a, q_b = p_b + t d_b
    let c = da.dot(&db);
    let kappa = 1.0 - c * c;
    let (alpha, beta) = (da.dot(&d), db.dot(&d));
    let sa = (alpha - c * beta) / kappa;
    let tb = (c * alpha - beta) / kappa;
    let (qa, qb) = (ka.mid + da * sa, kb.mid + db * tb);
    let (ra, rb) = (qa - s.x[a], qb - s.x[b]);
    let (wa, wb) = (s.w[a], s.w[b]);
    // how fast the closest points slide along the edges
    let ddot = kb.mid_rate - ka.mid_rate;
    let cdot = ka.dir_rate.dot(&db) + da.dot(&kb.dir_rate);
    let kdot = -2.0 * c * cdot;
    let adot = ka.dir_rate.dot(&d) + da.dot(&ddot);
    let bdot = kb.dir_rate.dot(&d) + db.dot(&ddot);
    let sdot = (adot - cdot * beta - c * bdot - sa * kdot) / kappa;
    let tdot = (cdot * alpha + c * adot - bdot - tb * kdot) / kappa;
    // the material velocities at the closest points, and ṅ
    let (va, vb) = (s.v[a] + wa.cross(&ra), s.v[b] + wb.cross(&rb));
    let mdot = ka.dir_rate.cross(&db) + da.cross(&kb.dir_rate);
    let ndot = (mdot - n0 * n0.dot(&mdot)) * (sigma / nu);
    let (ra_dot, rb_dot) = (wa.cross(&ra) + da * sdot, wb.cross(&rb) + db * tdot);
    let margin = 1e-9 * members[a].body.reach().max(members[b].body.reach());
    let (in_a, in_b) = (ka.half - sa.abs(), kb.half - tb.abs());
    let (inside, inside_rate) = if in_a <= in_b {
        (in_a, -sa.signum() * sdot)
    } else {
        (in_b, -tb.signum() * tdot)
    };
    let g = n.dot(&d);
    // the pair on the far side of both bodies has its normal in both cones too, at a gap of
    // about minus their size: n · (x_b − x_a) + g ≥ 0 (g ≥ −(w_a + w_b)/2, w the bodies'
    // widths along n) keeps the near one
    let genuine = inside >= -margin
        && in_cone(&n, &ka.faces)
        && in_cone(&(-n), &kb.faces)
        && n.dot(&(s.x[b] - s.x[a])) + g >= 0.0;
    Gap {
        gap: if genuine { g } else { f64::INFINITY },
        rate: n.dot(&(vb - va)),
        normal: n,
        curvature: ndot.dot(&(vb - va)) + n.dot(&(wb.cross(&rb_dot) - wa.cross(&ra_dot))),
        point: qa,
        inside,
        inside_rate,
        sides: [
            Some(Side {
                body: a,
                sign: -1.0,
                arm: ra,
                moment: ra.cross(&n),
                arm_rate: ra_dot,
            }),
            Some(Side {
                body: b,
                sign: 1.0,
                arm: rb,
                moment: rb.cross(&n),
                arm_rate: rb_dot,
            }),
        ],
    }
}

/// The gap of sphere `a` (centre c, radius ρ) on the point p of member `b` (of arm r_b =
/// p − x_b, sliding along the edge at `slide`): g = |c − p| − ρ, n = (c − p)/|c − p| (module
/// docs), with how far inside its region it is.
fn round_on_point(
    members: &[Member],
    s: &SystemState,
    (a, b): (usize, usize),
    (rb, slide): (V3, V3),
    (inside, inside_rate): (f64, f64),
) -> Gap {
    let rho = members[a].radius().unwrap_or(0.0);
    let p = s.x[b] + rb;
    let w = s.x[a] - p;
    let len = w.norm();
    if len == 0.0 {
        return apart(s, a);
    }
    let n = w / len;
    let wb = s.w[b];
    let rb_dot = wb.cross(&rb) + slide;
    // the relative velocity of the sphere's centre and b's material point at p
    let u = s.v[a] - s.v[b] - wb.cross(&rb);
    let ndot = (u - slide - n * n.dot(&(u - slide))) / len;
    Gap {
        gap: len - rho,
        rate: n.dot(&u),
        normal: n,
        curvature: ndot.dot(&u) - n.dot(&wb.cross(&rb_dot)),
        point: s.x[a] - n * rho,
        inside,
        inside_rate,
        sides: [
            Some(round_side(a, 1.0, -n * rho, -ndot * rho)),
            Some(Side {
                body: b,
                sign: -1.0,
                arm: rb,
                moment: rb.cross(&n),
                arm_rate: rb_dot,
            }),
        ],
    }
}

/// Sphere `a` on edge `e` of `b` (module docs).
fn on_edge_gap(members: &[Member], s: &SystemState, a: usize, b: usize, e: usize) -> Gap {
    let Some(k) = world_edge(members, s, b, e) else {
        return apart(s, a);
    };
    let d = s.x[a] - k.mid;
    let t = k.dir.dot(&d);
    let tdot = k.dir_rate.dot(&d) + k.dir.dot(&(s.v[a] - k.mid_rate));
    let rb = k.mid + k.dir * t - s.x[b];
    let w = d - k.dir * t;
    let wdot_rel = s.v[a] - s.v[b] - s.w[b].cross(&rb) - k.dir * tdot;
    // how far inside the edge's region: within its length, and beyond both faces' planes
    let mut inside = (k.half - t.abs(), -t.signum() * tdot);
    if let Some(f) = k.faces {
        for f in f {
            // d/dt (w · f) = ẇ · f + w · (ω_b × f), ẇ · f = (v_a − v_p) · f as f ⟂ the edge
            let at = (w.dot(&f), wdot_rel.dot(&f) + w.dot(&s.w[b].cross(&f)));
            if at.0 < inside.0 {
                inside = at;
            }
        }
    }
    let margin = 1e-9 * members[b].body.reach();
    let mut g = round_on_point(members, s, (a, b), (rb, k.dir * tdot), inside);
    if inside.0 < -margin {
        g.gap = f64::INFINITY;
    }
    g
}

/// Sphere `a` on the point feature `feature` of `b` (module docs).
fn on_corner_gap(members: &[Member], s: &SystemState, a: usize, b: usize, feature: usize) -> Gap {
    let Some(Feature::Point { at, .. }) = members[b].body.features.get(feature) else {
        return apart(s, a);
    };
    let r = s.rotation(b);
    let rb = r * at;
    let w = s.x[a] - s.x[b] - rb;
    let wdot = s.v[a] - s.v[b] - s.w[b].cross(&rb);
    // the outward normals whose planes bound the corner's region: a box's three faces there, a
    // rod's axis beyond its end
    let outward: Vec<V3> = match members[b].body.shape {
        Shape::Box { .. } => (0..3)
            .filter(|&k| at[k] != 0.0)
            .map(|k| r.column(k) * at[k].signum())
            .collect(),
        _ => vec![rb.normalize()],
    };
    let inside = outward
        .iter()
        .map(|f| (w.dot(f), wdot.dot(f) + w.dot(&s.w[b].cross(f))))
        .fold((f64::INFINITY, 0.0), |m, e| if e.0 < m.0 { e } else { m });
    let margin = 1e-9 * members[b].body.reach();
    let mut g = round_on_point(members, s, (a, b), (rb, V3::zeros()), inside);
    if inside.0 < -margin {
        g.gap = f64::INFINITY;
    }
    g
}

/// A feature of `a` on face `face` of box `b` (module docs).
fn face_gap(
    members: &[Member],
    s: &SystemState,
    a: usize,
    feature: usize,
    b: usize,
    face: usize,
) -> Gap {
    // a face contact is on a box ([`super::run::SystemSetup::candidates`]); none else is
    let Shape::Box { half } = members[b].body.shape else {
        return apart(s, a);
    };
    let (k, sign) = (face / 2, if face.is_multiple_of(2) { 1.0 } else { -1.0 });
    let rb = s.rotation(b);
    let n = rb.column(k) * sign;
    let wb = s.w[b];
    let ndot = wb.cross(&n);
    let nddot = wb.cross(&ndot);
    // the point, its velocity and the velocity part of its acceleration; the side on a; the
    // point whose place over the face decides (a sphere's centre) and its velocity
    let (p, pdot, pddot, side_a, (centre, centre_dot)) = match &members[a].body.features[feature] {
        Feature::Sphere { radius } => (
            s.x[a] - n * *radius,
            s.v[a] - ndot * *radius,
            -nddot * *radius,
            round_side(a, 1.0, -n * *radius, -ndot * *radius),
            (s.x[a], s.v[a]),
        ),
        Feature::Point { at, .. } => {
            let r = s.rotation(a) * at;
            let wa = s.w[a];
            let p = s.x[a] + r;
            let pdot = s.v[a] + wa.cross(&r);
            (
                p,
                pdot,
                wa.cross(&wa.cross(&r)),
                Side {
                    body: a,
                    sign: 1.0,
                    arm: r,
                    moment: r.cross(&n),
                    arm_rate: wa.cross(&r),
                },
                (p, pdot),
            )
        }
        // no rim strikes a face ([`super::run::SystemSetup::candidates`])
        Feature::Rim { .. } => return apart(s, a),
    };
    let d = p - s.x[b];
    let local = rb.transpose() * (centre - s.x[b]);
    // the nearest edge j, and how fast the point moves out over it (in b's axes, relative to
    // b's material point there)
    let (nearest, inside) = (0..3)
        .filter(|&j| j != k)
        .map(|j| (j, half[j] - local[j].abs()))
        .fold((k, f64::INFINITY), |m, e| if e.1 < m.1 { e } else { m });
    let relative = rb.transpose() * (centre_dot - s.v[b] - wb.cross(&(centre - s.x[b])));
    let inside_rate = -local[nearest].signum() * relative[nearest];
    let ddot = pdot - s.v[b];
    // over the face: within its edges, on its side of the centre, and nearer its plane than
    // any other face's (a point inside the box belongs to the face it is least deep under)
    let margin = 1e-9 * members[b].body.reach();
    let over =
        sign * local[k] > 0.0 && inside >= -margin && sign * local[k] - half[k] >= -inside - margin;
    Gap {
        gap: if over {
            n.dot(&d) - half[k]
        } else {
            f64::INFINITY
        },
        rate: ndot.dot(&d) + n.dot(&ddot),
        normal: n,
        curvature: nddot.dot(&d) + 2.0 * ndot.dot(&ddot) + n.dot(&pddot),
        point: p,
        inside,
        inside_rate,
        sides: [
            Some(side_a),
            Some(Side {
                body: b,
                sign: -1.0,
                arm: d,
                moment: d.cross(&n),
                arm_rate: ddot,
            }),
        ],
    }
}

/// A contact that is no contact (+∞ gap, no rows): what a face contact the candidates never
/// make would be.
fn apart(s: &SystemState, a: usize) -> Gap {
    Gap {
        gap: f64::INFINITY,
        rate: 0.0,
        normal: V3::z(),
        curvature: 0.0,
        point: s.x[a],
        inside: f64::NEG_INFINITY,
        inside_rate: 0.0,
        sides: [None, None],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::body::Body;
    use nalgebra::{Matrix3, UnitQuaternion};

    fn cuboid(name: &str, half: V3) -> Member {
        let m = 2.0;
        let j = |a: f64, b: f64| m * (a * a + b * b) / 3.0;
        Member {
            name: name.into(),
            body: Body::new(
                m,
                Matrix3::from_diagonal(&V3::new(
                    j(half.y, half.z),
                    j(half.x, half.z),
                    j(half.x, half.y),
                )),
                Shape::Box { half },
                None,
            )
            .expect("a box"),
            spins: false,
        }
    }

    fn ball(name: &str, radius: f64) -> Member {
        Member {
            name: name.into(),
            body: Body::new(
                1.0,
                Matrix3::identity() * 0.4 * radius * radius,
                Shape::Sphere { radius },
                None,
            )
            .expect("a ball"),
            spins: false,
        }
    }

    /// Both members moving rigidly at constant v and ω (no acceleration, no angular
    /// acceleration): then ġ = J u and g̈ = c, the curvature term alone. Central differences
    /// of g(t) over h = 10⁻⁴ s (errors O(h²) ≈ 10⁻⁸ of the motion's scales) check the rate and
    /// the curvature of a corner and of a sphere on a turning box's faces — the derivation of
    /// the module docs against the definition g = n · (p − x_b) − h.
    #[test]
    fn a_face_gaps_rate_and_curvature_are_its_derivatives() {
        let members = vec![
            cuboid("a", V3::new(0.2, 0.1, 0.05)),
            cuboid("b", V3::new(0.5, 0.4, 0.1)),
            ball("c", 0.05),
        ];
        let q0 = [
            UnitQuaternion::from_scaled_axis(V3::new(0.3, -0.2, 0.4)),
            UnitQuaternion::from_scaled_axis(V3::new(-0.1, 0.25, 0.2)),
            UnitQuaternion::identity(),
        ];
        let x0 = [
            V3::new(0.05, 0.02, 0.45),
            V3::new(0.0, 0.0, 0.0),
            V3::new(-0.1, 0.1, 0.3),
        ];
        let v = [
            V3::new(0.3, -0.1, -1.2),
            V3::new(-0.2, 0.4, 0.1),
            V3::new(0.1, 0.2, -0.7),
        ];
        let w = [
            V3::new(1.1, -2.3, 0.7),
            V3::new(0.6, 0.9, -1.4),
            V3::zeros(),
        ];
        let at = |t: f64| SystemState {
            x: (0..3).map(|b| x0[b] + v[b] * t).collect(),
            v: v.to_vec(),
            q: (0..3)
                .map(|b| UnitQuaternion::from_scaled_axis(w[b] * t) * q0[b])
                .collect(),
            w: w.to_vec(),
        };
        let planes: Vec<Plane> = Vec::new();
        let h = 1e-4;
        let mut checked = 0;
        for (a, feature) in [(0, 0), (0, 3), (0, 5), (2, 0)] {
            for face in 0..6 {
                let touch = Touch::Face {
                    a,
                    feature,
                    b: 1,
                    face,
                };
                let g0 = gap(&touch, &members, &planes, &at(0.0));
                if !g0.gap.is_finite() {
                    continue;
                }
                let (gp, gm) = (
                    gap(&touch, &members, &planes, &at(h)).gap,
                    gap(&touch, &members, &planes, &at(-h)).gap,
                );
                let rate = (gp - gm) / (2.0 * h);
                let second = (gp - 2.0 * g0.gap + gm) / (h * h);
                assert!(
                    (rate - g0.rate).abs() <= 1e-7,
                    "{touch:?}: ġ {rate} ≠ {}",
                    g0.rate
                );
                assert!(
                    (second - g0.curvature).abs() <= 1e-5,
                    "{touch:?}: g̈ {second} ≠ {}",
                    g0.curvature
                );
                // ġ = J u over the sides
                let ju: f64 = g0
                    .sides()
                    .map(|i| i.sign * (g0.normal.dot(&v[i.body]) + i.moment.dot(&w[i.body])))
                    .sum();
                assert!((ju - g0.rate).abs() <= 1e-14, "{touch:?}: J u {ju}");
                checked += 1;
            }
        }
        // each feature is over one face of b (the top, +z)
        assert_eq!(checked, 4);
    }

    fn rod(name: &str, length: f64) -> Member {
        let m = 1.5;
        let j = m * length * length / 12.0;
        Member {
            name: name.into(),
            body: Body::new(
                m,
                Matrix3::from_diagonal(&V3::new(j, j, j)),
                Shape::Rod {
                    half_length: length / 2.0,
                },
                None,
            )
            .expect("a rod"),
            spins: false,
        }
    }

    /// Members moving rigidly at constant v and ω from `x0`, `q0`.
    fn rigid(
        x0: Vec<V3>,
        q0: Vec<UnitQuaternion<f64>>,
        v: Vec<V3>,
        w: Vec<V3>,
    ) -> impl Fn(f64) -> SystemState {
        move |t: f64| SystemState {
            x: (0..x0.len()).map(|b| x0[b] + v[b] * t).collect(),
            v: v.clone(),
            q: (0..x0.len())
                .map(|b| UnitQuaternion::from_scaled_axis(w[b] * t) * q0[b])
                .collect(),
            w: w.clone(),
        }
    }

    /// The checks of [`a_face_gaps_rate_and_curvature_are_its_derivatives`] on `touch` where
    /// its gap is finite (returns whether it was), with the five-point differences over
    /// h = 10⁻⁴ s (errors O(h⁴): edges near parallel turn their normal fast, and the
    /// three-point differences' O(h²) g‴ reaches 10⁻⁷ there; rounding 10⁻¹⁶/h² ≈ 10⁻⁸ in
    /// the second): ġ and c against those of g(t), ġ = J u to rounding, the arms' rates
    /// against those of the contact's velocity u = Σ σ_i (v_i + ω_i × r_i) (at constant v and
    /// ω, u̇ = Σ σ_i ω_i × ṙ_i), and how far inside its region the contact is, against its rate.
    fn derivatives_check(
        touch: &Touch,
        members: &[Member],
        at: &dyn Fn(f64) -> SystemState,
    ) -> bool {
        let planes: Vec<Plane> = Vec::new();
        let s0 = at(0.0);
        let g0 = gap(touch, members, &planes, &s0);
        if !g0.gap.is_finite() {
            return false;
        }
        let h = 1e-4;
        let ats = [-2.0, -1.0, 1.0, 2.0].map(|k| at(k * h));
        let gs = ats.clone().map(|s| gap(touch, members, &planes, &s));
        assert!(gs.iter().all(|g| g.gap.is_finite()), "{touch:?}: at an end");
        let first = |f: [f64; 4]| (f[0] - 8.0 * f[1] + 8.0 * f[2] - f[3]) / (12.0 * h);
        let rate = first(gs.map(|g| g.gap));
        let second = (-gs[0].gap + 16.0 * gs[1].gap - 30.0 * g0.gap + 16.0 * gs[2].gap - gs[3].gap)
            / (12.0 * h * h);
        assert!(
            (rate - g0.rate).abs() <= 1e-7,
            "{touch:?}: ġ {rate} ≠ {}",
            g0.rate
        );
        assert!(
            (second - g0.curvature).abs() <= 1e-5,
            "{touch:?}: g̈ {second} ≠ {}",
            g0.curvature
        );
        let ju: f64 = g0
            .sides()
            .map(|i| i.sign * (g0.normal.dot(&s0.v[i.body]) + i.moment.dot(&s0.w[i.body])))
            .sum();
        assert!((ju - g0.rate).abs() <= 1e-14, "{touch:?}: J u {ju}");
        let u = |g: &Gap, s: &SystemState| -> V3 {
            g.sides()
                .map(|i| (s.v[i.body] + s.w[i.body].cross(&i.arm)) * i.sign)
                .sum()
        };
        let us: Vec<V3> = gs.iter().zip(&ats).map(|(g, s)| u(g, s)).collect();
        let du = (us[0] - us[1] * 8.0 + us[2] * 8.0 - us[3]) / (12.0 * h);
        let want: V3 = g0
            .sides()
            .map(|i| s0.w[i.body].cross(&i.arm_rate) * i.sign)
            .sum();
        assert!((du - want).norm() <= 1e-6, "{touch:?}: u̇ {du} ≠ {want}");
        if g0.inside.is_finite() {
            let rate = first(gs.map(|g| g.inside));
            assert!(
                (rate - g0.inside_rate).abs() <= 1e-7,
                "{touch:?}: inside {rate} ≠ {}",
                g0.inside_rate
            );
        }
        true
    }

    /// Two boxes crossed edge over edge (one turned about 45° about x above one turned about
    /// 45° about y), a rod crossing under the lower box's lowest edge and a rod crossing that
    /// rod, all tumbling: the edge–edge gaps' derivatives (module docs) against the definition
    /// g = n · (p_b − p_a), for every edge pair whose gap is finite.
    #[test]
    fn an_edge_gaps_rate_and_curvature_are_its_derivatives() {
        let members = vec![
            cuboid("a", V3::new(0.3, 0.2, 0.15)),
            cuboid("b", V3::new(0.5, 0.4, 0.1)),
            rod("c", 0.9),
            rod("d", 0.7),
        ];
        let quarter = std::f64::consts::FRAC_PI_4;
        let at = rigid(
            vec![
                V3::new(-0.25, 0.02, 0.69),
                V3::zeros(),
                V3::new(0.1, -0.05, -0.45),
                V3::new(0.05, 0.03, -0.5),
            ],
            vec![
                UnitQuaternion::from_scaled_axis(V3::new(quarter + 0.05, 0.03, 0.02)),
                UnitQuaternion::from_scaled_axis(V3::new(-0.02, quarter - 0.04, 0.03)),
                UnitQuaternion::from_scaled_axis(V3::new(0.1, 2.0 * quarter + 0.1, 0.0)),
                UnitQuaternion::from_scaled_axis(V3::new(2.0 * quarter - 0.1, 0.0, 0.2)),
            ],
            vec![
                V3::new(0.3, -0.1, -1.2),
                V3::new(-0.2, 0.4, 0.1),
                V3::new(0.1, 0.2, 0.7),
                V3::new(-0.3, 0.1, -0.2),
            ],
            vec![
                V3::new(1.1, -2.3, 0.7),
                V3::new(0.6, 0.9, -1.4),
                V3::new(-0.8, 0.5, 1.9),
                V3::new(0.4, 1.5, -0.6),
            ],
        );
        let mut checked = [0; 3];
        for (pair, (a, b)) in [(0, 1), (1, 2), (2, 3)].into_iter().enumerate() {
            for edge_a in 0..edge_count(&members[a].body.shape) {
                for edge_b in 0..edge_count(&members[b].body.shape) {
                    let touch = Touch::Edges {
                        a,
                        edge_a,
                        b,
                        edge_b,
                    };
                    if derivatives_check(&touch, &members, &at) {
                        checked[pair] += 1;
                    }
                }
            }
        }
        // the crossed edges of each pair (box on box, box on rod, rod on rod)
        assert!(checked.iter().all(|&c| c >= 1), "{checked:?}");
    }

    /// A ball beyond a turning box's edges and corners, and beside a rod's segment and beyond
    /// its end: the gaps g = |c − p| − ρ' derivatives (module docs), the expected contact
    /// finite at each place, and every other finite one checked too.
    #[test]
    fn a_sphere_on_an_edge_or_corner_gaps_rate_and_curvature_are_its_derivatives() {
        let members = vec![
            ball("ball", 0.05),
            cuboid("box", V3::new(0.5, 0.4, 0.1)),
            rod("rod", 0.6),
        ];
        let q0 = vec![
            UnitQuaternion::identity(),
            UnitQuaternion::from_scaled_axis(V3::new(-0.1, 0.25, 0.2)),
            UnitQuaternion::from_scaled_axis(V3::new(0.2, 1.3, 0.1)),
        ];
        let v = vec![
            V3::new(0.1, 0.2, -0.7),
            V3::new(-0.2, 0.4, 0.1),
            V3::new(0.3, 0.0, 0.2),
        ];
        let w = vec![
            V3::zeros(),
            V3::new(0.6, 0.9, -1.4),
            V3::new(1.2, -0.4, 0.8),
        ];
        let r = q0[1].to_rotation_matrix();
        let rr = q0[2].to_rotation_matrix();
        let rod_at = V3::new(2.0, 0.0, 0.0);
        // (the ball's centre, the contact whose region it is in): edge 4 of the box is along y
        // at x = +, z = +; edge 2 along x at y = −, z = +; corner 0 is [1, 1, 1], 7 [-1, -1,
        // -1]; the rod's feature 0 its end [0, 0, 1]
        let places = [
            (
                r * V3::new(0.55, 0.1, 0.16),
                Touch::OnEdge {
                    a: 0,
                    b: 1,
                    edge: 4,
                },
            ),
            (
                r * V3::new(0.2, -0.45, 0.14),
                Touch::OnEdge {
                    a: 0,
                    b: 1,
                    edge: 2,
                },
            ),
            (
                r * V3::new(0.56, 0.45, 0.13),
                Touch::OnCorner {
                    a: 0,
                    b: 1,
                    feature: 0,
                },
            ),
            (
                r * V3::new(-0.54, -0.47, -0.15),
                Touch::OnCorner {
                    a: 0,
                    b: 1,
                    feature: 7,
                },
            ),
            (
                rr * V3::new(0.08, 0.02, 0.1) + rod_at,
                Touch::OnEdge {
                    a: 0,
                    b: 2,
                    edge: 0,
                },
            ),
            (
                rr * V3::new(0.02, -0.03, 0.36) + rod_at,
                Touch::OnCorner {
                    a: 0,
                    b: 2,
                    feature: 0,
                },
            ),
        ];
        for (c, expected) in places {
            let at = rigid(
                vec![c, V3::zeros(), rod_at],
                q0.clone(),
                v.clone(),
                w.clone(),
            );
            assert!(derivatives_check(&expected, &members, &at), "{expected:?}");
            for b in [1, 2] {
                for edge in 0..edge_count(&members[b].body.shape) {
                    derivatives_check(&Touch::OnEdge { a: 0, b, edge }, &members, &at);
                }
                for feature in 0..members[b].body.features.len() {
                    derivatives_check(&Touch::OnCorner { a: 0, b, feature }, &members, &at);
                }
            }
        }
    }

    /// Two cubes crossed edge on edge, the top one turned 45° about x and the bottom one 45°
    /// about y: their lowest and highest edges (√2/2 from each centre) are the one genuine edge
    /// pair, at the gap d − √2 along z; every other pair is +∞ (its normal leaves a cone).
    #[test]
    fn crossed_cubes_touch_at_one_edge_pair() {
        let members = vec![
            cuboid("top", V3::new(0.5, 0.5, 0.5)),
            cuboid("base", V3::new(0.5, 0.5, 0.5)),
        ];
        let quarter = std::f64::consts::FRAC_PI_4;
        let s = SystemState {
            x: vec![V3::new(0.0, 0.0, 1.5), V3::zeros()],
            v: vec![V3::new(0.0, 0.0, -1.0), V3::zeros()],
            q: vec![
                UnitQuaternion::from_scaled_axis(V3::x() * quarter),
                UnitQuaternion::from_scaled_axis(V3::y() * quarter),
            ],
            w: vec![V3::zeros(); 2],
        };
        let planes: Vec<Plane> = Vec::new();
        let mut found = Vec::new();
        for edge_a in 0..12 {
            for edge_b in 0..12 {
                let touch = Touch::Edges {
                    a: 0,
                    edge_a,
                    b: 1,
                    edge_b,
                };
                let g = gap(&touch, &members, &planes, &s);
                if g.gap.is_finite() && g.gap < 1.0 {
                    found.push((touch.name(&members, &planes), g));
                }
            }
        }
        assert_eq!(found.len(), 1, "{found:?}");
        let ((first, second), g) = &found[0];
        assert!((g.gap - (1.5 - 2f64.sqrt())).abs() < 1e-15, "{}", g.gap);
        assert!((g.normal + V3::z()).norm() < 1e-15, "{}", g.normal);
        // approaching at 1 m/s
        assert!((g.rate + 1.0).abs() < 1e-15, "{}", g.rate);
        // the top's lowest edge is along x (y = z = −1 in its axes turned 45° about x); the
        // base's highest along y (x = −1, z = 1 in its axes turned 45° about y)
        assert_eq!(first, "top edge [*, -1, -1]");
        assert_eq!(second, "base edge [-1, *, 1]");
    }

    /// A corner beside a box, below its top face's plane, is over no face (+∞): the plane of a
    /// face is no obstacle beyond its edges; and at a box's edge the corner belongs to the face
    /// it is nearest.
    #[test]
    fn a_face_is_an_obstacle_over_itself_only() {
        let members = vec![
            cuboid("a", V3::new(0.1, 0.1, 0.1)),
            cuboid("b", V3::new(0.5, 0.5, 0.1)),
        ];
        let state = |xa: V3| SystemState {
            x: vec![xa, V3::zeros()],
            v: vec![V3::zeros(); 2],
            q: vec![UnitQuaternion::identity(); 2],
            w: vec![V3::zeros(); 2],
        };
        let planes: Vec<Plane> = Vec::new();
        // corner [-1, -1, -1] of a is feature 7 (signs +, − in x, y, z order: see Body)
        let lowest = members[0]
            .body
            .features
            .iter()
            .position(|f| f.label() == "corner [-1, -1, -1]")
            .expect("corner");
        let face = |xa: V3, face: usize| {
            gap(
                &Touch::Face {
                    a: 0,
                    feature: lowest,
                    b: 1,
                    face,
                },
                &members,
                &planes,
                &state(xa),
            )
            .gap
        };
        // 0.05 above the top face, over it: the gap
        assert!((face(V3::new(0.0, 0.0, 0.25), 4) - 0.05).abs() < 1e-15);
        // beside the box (its corner at x = 0.6 > 0.5), below the top's plane: no obstacle
        assert_eq!(face(V3::new(0.7, 0.0, 0.15), 4), f64::INFINITY);
        // beside the +x face, within its edges: that face's gap, not the top's
        assert!((face(V3::new(0.65, 0.0, 0.1), 0) - 0.05).abs() < 1e-15);
        assert_eq!(face(V3::new(0.65, 0.0, 0.1), 4), f64::INFINITY);
    }
}
