//! The inertance blocks g_ij,ab of the frictional impact (eq. 12, 126–128, 143) and the
//! test that decides whether a scene stays in one plane.
//!
//! Every contact i contributes its normal axis and, when μ_i > 0, its tangent axes; their
//! screws {E_q} are stacked in one list, and the impulses Λ = (p_1, τ_1, p_2, τ_2, …) act
//! along them. With the mechanism's mobility W (one body's, or a system's: the axis of a
//! contact between two bodies is its screw on the first minus its screw on the second,
//! [`Mechanism::contact_axis`]),
//!
//! ```text
//! K_qr = {E_q}ᵀ η W {E_r}          (a Gram matrix: symmetric, positive semidefinite)
//! v_q  = v_q⁰ − Σ_r K_qr Λ_r        (eq. 144, for every axis at once)
//! ```
//!
//! **Planar scenes, exactly.** In a plane with unit normal e, a contact's in-plane tangent is
//! t_i = ±e × n_i (in the sense of the contact's tangent y_i, given or chosen by §12, when y_i
//! lies in the plane: slide+ is slip along +y_i): it has the length of n_i, so with the hatted
//! (unnormalised) axes of
//! [`crate::mechanics::contact`] the Coulomb cone |τ_i| ≤ μ_i P_i reads |τ̂_i| ≤ μ_i p̂_i with
//! no square root, and every quantity stays in the scalar's field — as long as e itself is in
//! the field. The planes tried are the coordinate planes (z, y, x: every scene written in
//! principal axes), then, in exact types, the mechanism's ([`Mechanism::planes`]): the planes
//! whose normal is a
//! direction d built from the scene's own vectors (d = n_a × n_b for two frictional normals
//! that are not parallel; otherwise d = n × w, with n the common direction of the frictional
//! normals and w a contact point, a normal, v_C⁰ or ω⁰ — for a system, every body's, with
//! points taken from the first contact; or d = ω⁰) whose length |d| is
//! rational, so that e = d/|d| is: a scene posed in world axes by a rational rotation (a
//! body with a full inertia tensor) keeps its plane. A plane whose normal has an irrational
//! length (e ∝ (1, 1, 0)) would put μ_i/|d| in the cone; such a scene is integrated as a
//! spatial one (floats) instead.
//!
//! The scene is planar when no impulse along any stacked axis can move a frictional contact
//! out of the plane and none moves out of it before impact:
//! {Z_i}ᵀ η W {E_r} = 0 for every r and {Z_i}ᵀ η {v⁰} = 0, with Z_i the axis through A_i
//! along e — then v_iz ≡ 0 (eq. 144), slip stays along t_i and sticking needs no impulse
//! along e. The test is exact in exact types; it makes no assumption on the mechanism: a
//! constrained body qualifies, and so does a system whose frictional contacts stay in the
//! plane, its joints acting through W — it asks only what the integration uses, not that every
//! body moves in the plane.
//!
//! **Spatial scenes** use the contact frame's y and z axes, normalised (a square root: floats
//! only), so the cone is the Euclidean |τ_i| ≤ μ_i P_i.

use crate::impact::mechanism::Mechanism;
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::{Screw, Screws, Vec3, dot, norm2};
use crate::scalar::Scalar;

/// The stacked axes of a frictional impact and their inertance matrix K, in the screw space
/// `S` of the mechanism ([`Mechanism`]: one body's [`Screw`], a system's stack).
#[derive(Clone, Debug)]
pub struct Blocks<T: Scalar, S: Screws<T> = Screw<T>> {
    /// Tangential dimensions per contact: 0 when μ_i = 0, 1 in a planar scene, 2 in space.
    pub dims: Vec<usize>,
    /// Index in Λ of contact i's normal impulse; its tangential ones follow.
    pub offset: Vec<usize>,
    /// The axis screws {E_q}, in Λ order.
    pub axes: Vec<S>,
    /// The axes' directions (hatted in a planar scene, unit in a spatial one), in Λ order.
    pub directions: Vec<Vec3<T>>,
    /// W{E_q}: the twist change per unit impulse along axis q.
    pub responses: Vec<S>,
    /// K, `len × len`, row-major.
    pub k: Vec<T>,
    /// v_q⁰: the velocity along each axis before impact.
    pub v0: Vec<T>,
    /// μ_i per contact.
    pub mu: Vec<T>,
    /// The contact points A_i (one body: from C, body axes; a system: in the world).
    pub points: Vec<Vec3<T>>,
    /// The plane's unit normal e when the scene is planar.
    pub plane: Option<Vec3<T>>,
}

impl<T: Scalar, S: Screws<T>> Blocks<T, S> {
    /// The number of stacked axes (the length of Λ).
    pub fn len(&self) -> usize {
        self.axes.len()
    }

    /// Whether there is no axis (never, for a validated problem).
    pub fn is_empty(&self) -> bool {
        self.axes.is_empty()
    }

    /// The number of contacts.
    pub fn contacts(&self) -> usize {
        self.dims.len()
    }

    /// K_qr.
    pub fn at(&self, q: usize, r: usize) -> &T {
        &self.k[q * self.len() + r]
    }

    /// The planar blocks of `mechanism`, exact: tangents ±e × n_i in the first plane that
    /// passes the planarity test — a coordinate plane (z, y, x), then in exact types the
    /// mechanism's own [`Mechanism::planes`] (planes of rational unit normal found from the
    /// scene's vectors, see the module docs); `None` when none does.
    pub fn planar<M: Mechanism<T, Screw = S>>(mechanism: &M) -> Option<Self> {
        let mut blocks = Self::empty();
        blocks.planar_into(mechanism).then_some(blocks)
    }

    /// No axis: blocks to be filled by [`Blocks::planar_into`] (nothing is allocated).
    pub fn empty() -> Self {
        Blocks {
            dims: Vec::new(),
            offset: Vec::new(),
            axes: Vec::new(),
            directions: Vec::new(),
            responses: Vec::new(),
            k: Vec::new(),
            v0: Vec::new(),
            mu: Vec::new(),
            points: Vec::new(),
            plane: None,
        }
    }

    /// [`Blocks::planar`] refilled in place, for a caller that solves impact after impact on
    /// kept blocks ([`super::planar::PlanarFrictionWork`]): the same blocks, entry for entry,
    /// and nothing allocated once the vectors have grown. `false` when no plane passes the
    /// test (the blocks are then left unspecified).
    pub fn planar_into<M: Mechanism<T, Screw = S>>(&mut self, mechanism: &M) -> bool {
        for unit in coordinate_planes() {
            if self.in_plane(mechanism, unit) {
                return true;
            }
        }
        if !T::IS_EXACT {
            return false;
        }
        mechanism
            .planes()
            .into_iter()
            .any(|unit| self.in_plane(mechanism, unit))
    }

    /// Refill the blocks in the plane of unit normal `unit`; whether the scene stays in it.
    fn in_plane<M: Mechanism<T, Screw = S>>(&mut self, mechanism: &M, unit: Vec3<T>) -> bool {
        self.axes.clear();
        self.directions.clear();
        self.dims.clear();
        let velocity = mechanism.velocity();
        for (i, c) in mechanism.contacts().iter().enumerate() {
            self.axes.push(mechanism.contact_axis(i, &c.normal));
            self.directions.push(c.normal.clone());
            if c.mu.is_zero() {
                self.dims.push(0);
                continue;
            }
            if !dot(&unit, &c.normal).is_zero() {
                return false;
            }
            let z = mechanism.contact_axis(i, &unit);
            if !z.reciprocal(velocity).is_zero() {
                return false;
            }
            // slide+ is slip along +y_i, the tangent as given or as §12 chooses it (the frame
            // the report prints), so t_i takes the sense of y_i when y_i lies in the plane.
            let t = unit.cross(&c.normal);
            let y = mechanism.frame(i, true).map(|f| f.directions[1].clone());
            let t = match y {
                Ok(y) if dot(&y, &t).signum_i8() < 0 => -t,
                _ => t,
            };
            self.axes.push(mechanism.contact_axis(i, &t));
            self.directions.push(t);
            self.dims.push(1);
        }
        self.fill(mechanism, Some(unit.clone()));
        // No impulse moves a frictional contact out of the plane: its axis Z_i along e (built
        // again, as above) is reciprocal to every response.
        let contacts = mechanism.contacts();
        (0..contacts.len())
            .filter(|&i| !contacts[i].mu.is_zero())
            .all(|i| {
                let z = mechanism.contact_axis(i, &unit);
                self.responses.iter().all(|r| z.reciprocal(r).is_zero())
            })
    }

    /// The spatial blocks of `mechanism`: unit normals and the unit y, z axes of each
    /// contact's frame `frames` (§12). Floats: the normalisation takes square roots.
    ///
    /// # Panics
    /// Never for a validated problem in a float type; an exact type has no square root and is
    /// refused by the caller before this is reached.
    pub fn spatial<M: Mechanism<T, Screw = S>>(
        mechanism: &M,
        frames: &[crate::mechanics::contact::ContactFrame<T, S>],
    ) -> Self {
        let mut axes = Vec::new();
        let mut directions = Vec::new();
        let mut dims = Vec::new();
        let unit = |v: &Vec3<T>| -> Vec3<T> {
            let n = norm2(v).sqrt_value().expect("a float has a square root");
            v / n
        };
        for (i, (c, f)) in mechanism.contacts().iter().zip(frames).enumerate() {
            let mut push = |u: Vec3<T>| {
                axes.push(mechanism.contact_axis(i, &u));
                directions.push(u);
            };
            push(unit(&c.normal));
            if c.mu.is_zero() {
                dims.push(0);
            } else {
                push(unit(&f.directions[1]));
                push(unit(&f.directions[2]));
                dims.push(2);
            }
        }
        Self::from_axes(mechanism, axes, directions, dims, None)
    }

    fn from_axes<M: Mechanism<T, Screw = S>>(
        mechanism: &M,
        axes: Vec<S>,
        directions: Vec<Vec3<T>>,
        dims: Vec<usize>,
        plane: Option<Vec3<T>>,
    ) -> Self {
        let mut blocks = Self {
            dims,
            axes,
            directions,
            ..Self::empty()
        };
        blocks.fill(mechanism, plane);
        blocks
    }

    /// Fill everything the axes, directions and dims determine — responses, K, v⁰, the
    /// offsets, μ and the points — in place, and the plane.
    fn fill<M: Mechanism<T, Screw = S>>(&mut self, mechanism: &M, plane: Option<Vec3<T>>) {
        self.responses.clear();
        self.responses
            .extend(self.axes.iter().map(|a| mechanism.response(a)));
        let len = self.axes.len();
        self.k.clear();
        self.k.reserve(len * len);
        for a in &self.axes {
            for r in &self.responses {
                self.k.push(a.reciprocal(r));
            }
        }
        self.v0.clear();
        self.v0
            .extend(self.axes.iter().map(|a| a.reciprocal(mechanism.velocity())));
        self.offset.clear();
        self.offset.reserve(self.dims.len());
        let mut at = 0;
        for d in &self.dims {
            self.offset.push(at);
            at += 1 + d;
        }
        let contacts: &[Contact<T>] = mechanism.contacts();
        self.mu.clear();
        self.mu.extend(contacts.iter().map(|c| c.mu.clone()));
        self.points.clear();
        self.points.extend(contacts.iter().map(|c| c.point.clone()));
        self.plane = plane;
    }

    /// −K x: the velocity change along every axis for the impulse increments `x`.
    pub fn velocity_change(&self, x: &[T], out: &mut Vec<T>) {
        let n = self.len();
        out.clear();
        out.reserve(n);
        for row in self.k.chunks_exact(n.max(1)).take(n) {
            let mut s = T::zero();
            for (kr, xr) in row.iter().zip(x) {
                if !xr.is_zero() {
                    s += kr.clone() * xr;
                }
            }
            out.push(-s);
        }
    }

    /// Entry `q` of −K x alone: [`Blocks::velocity_change`]'s entry `q`, bit for bit (the same
    /// terms in the same order).
    pub fn velocity_change_at(&self, x: &[T], q: usize) -> T {
        let n = self.len();
        let mut s = T::zero();
        for (kr, xr) in self.k[q * n..(q + 1) * n].iter().zip(x) {
            if !xr.is_zero() {
                s += kr.clone() * xr;
            }
        }
        -s
    }

    /// The twist {v⁰} − Σ_q Λ_q W{E_q} after the impulses Λ (eq. 142).
    pub fn twist_after(&self, velocity: &S, lambda: &[T]) -> S {
        let mut v = velocity.clone();
        for (l, r) in lambda.iter().zip(&self.responses) {
            if !l.is_zero() {
                v.add_scaled(&-l.clone(), r);
            }
        }
        v
    }
}

/// The coordinate planes' unit normals, z, y, x: every scene written in principal axes.
fn coordinate_planes<T: Scalar>() -> [Vec3<T>; 3] {
    [2, 1, 0].map(|k| {
        let mut unit = Vec3::zeros();
        unit[k] = T::one();
        unit
    })
}

/// The unit normals e = d/|d| of the planes a planar scene in other than coordinate axes may
/// lie in: d from the scene's vectors (see the module docs) — n_a × n_b for two frictional
/// normals of `contacts` that are not parallel; otherwise each of `spins` (angular velocities,
/// along e in a planar motion), then n × w for each of `vectors` (vectors of the plane:
/// points, normals, velocities) — kept when d ≠ 0, d ⊥ every frictional normal and |d|² is the
/// square of a rational; each plane once, coordinate planes (tried first) left out.
pub fn plane_normals<T: Scalar>(
    contacts: &[Contact<T>],
    spins: &[Vec3<T>],
    vectors: &[Vec3<T>],
) -> Vec<Vec3<T>> {
    let rough: Vec<&Vec3<T>> = contacts
        .iter()
        .filter(|c| !c.mu.is_zero())
        .map(|c| &c.normal)
        .collect();
    let Some(&n) = rough.first() else {
        return Vec::new();
    };
    let crossing = rough.iter().map(|m| n.cross(m)).find(|d| !is_zero(d));
    let directions: Vec<Vec3<T>> = match crossing {
        Some(d) => vec![d],
        None => spins
            .iter()
            .cloned()
            .chain(vectors.iter().map(|w| n.cross(w)))
            .collect(),
    };
    let mut normals: Vec<Vec3<T>> = Vec::new();
    for d in directions {
        if is_zero(&d) || !rough.iter().all(|m| dot(&d, m).is_zero()) {
            continue;
        }
        let Some(length) = norm2(&d)
            .to_rational()
            .and_then(|q| q.sqrt_exact())
            .map(|q| T::from_rational(&q))
        else {
            continue;
        };
        let e = d / length;
        let coordinate = e.iter().filter(|x| x.is_zero()).count() == 2;
        let seen = normals.iter().any(|f| is_zero(&f.cross(&e)));
        if !coordinate && !seen {
            normals.push(e);
        }
    }
    normals
}

fn is_zero<T: Scalar>(v: &Vec3<T>) -> bool {
    v.iter().all(T::is_zero)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::problem::Problem;
    use crate::mechanics::body::RigidBody;
    use crate::mechanics::contact::Contact;
    use crate::scalar::{Exact, int, ratio};

    fn v(x: i64, y: i64, z: i64) -> Vec3<Exact> {
        Vec3::new(int(x), int(y), int(z))
    }

    fn bar(mu: Exact, omega_x: i64) -> Problem<Exact> {
        // Example 3's bar: points on Cy, normals along x, motion in the xy-plane.
        let c =
            |y: i64, k: Exact| Contact::new(v(0, y, 0), v(1, 0, 0), k).with_friction(mu.clone());
        Problem::new(
            RigidBody::principal(int(1), Vec3::new(int(12), ratio(8, 5), int(12))),
            Screw::new(Vec3::new(int(omega_x), int(0), ratio(2, 5)), v(3, 2, 0)),
            vec![c(-2, ratio(3, 10)), c(4, ratio(1, 5))],
        )
        .unwrap()
    }

    #[test]
    fn example_3_is_planar_in_the_xy_plane() {
        let b = Blocks::planar(&bar(ratio(1, 2), 0)).unwrap();
        assert_eq!(b.plane, Some(v(0, 0, 1)));
        assert_eq!(b.dims, vec![1, 1]);
        // The normal-normal blocks are the paper's g_ij (eq. 17, 19): 4/3, 1/3, 7/3.
        assert_eq!(b.at(0, 0), &ratio(4, 3));
        assert_eq!(b.at(0, 2), &ratio(1, 3));
        assert_eq!(b.at(2, 2), &ratio(7, 3));
        // t_i = e_z × e_x = e_y: the bar's own line; the slip velocity is v_Cy = 2.
        assert_eq!(b.v0[1], int(2));
        assert_eq!(b.v0[3], int(2));
    }

    #[test]
    fn a_spin_out_of_the_plane_is_not_planar() {
        assert!(Blocks::planar(&bar(ratio(1, 2), 1)).is_none());
    }
}
