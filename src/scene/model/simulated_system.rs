//! A system to simulate (`inertance simulate` on a scene of several `[[body]]`): each body a
//! sphere (`shape = { sphere = r }`), a box (`shape = { box = [a, b, c] }`) or a thin rod
//! (`shape = { rod = L }`, along its body z), with a `mass` or
//! `density`, `position`, `pose`, `velocity`, an optional `angular_velocity` and an optional
//! `material` for Hertz's stiffness (a sphere's pose and spin are reported, and its spin
//! integrated, when a rough contact can touch it; frictionless contacts keep them); the obstacle planes (none is fine: a cradle in
//! space), and `[simulate]` as for one body. The simulation watches every feature (a sphere, a
//! box's corners, a rod's ends) against every obstacle, every pair of spheres against each
//! other, every feature against every face of every other box, every edge (a box's, a rod's
//! segment) against every other member's edges, and every sphere against every edge and corner
//! ([`crate::simulate::system::gaps`]).
//!
//! ```toml
//! [simulate]
//! law = "lzb"
//! contact = { k = 1, stiffness = "hertz" }   # every contact (bodies and planes)
//! [simulate.obstacle.wall]                   # the contacts with one obstacle
//! k = 1
//! [[simulate.pair]]                          # the contacts of two bodies
//! bodies = ["bead 1", "bead 2"]
//! stiffness = 1e9
//! ```
//!
//! `[[joint]]` tables hold bodies together (or one to the ground), read as an impact scene's
//! ([`super::system`]: `kind`, `bodies`, `anchor`, `axis`, in the world at t = 0) and carried by
//! their bodies from there ([`crate::simulate::system::joints`]); the velocities at t = 0 must be
//! ones each joint allows, no contact is watched between two bodies a joint holds, and a sphere
//! a joint holds turns (the joint's reaction has a moment about its centre).
//!
//! `stiffness = "hertz"` takes K = (4/3) E* √R* from the two sides' radii and materials
//! ([`super::hertz`]; η = 3/2) where both sides are curved or flat: a sphere on a sphere, a
//! plane or a box's face — a box's corner or edge and a rod have no radius, and their contacts
//! need a number.
//! `mu` sets Coulomb's friction of the contacts, as `k` does their restitution: in persistent
//! contact (stick and slip, [`crate::simulate::system::persist`]) and at impacts (the frictional
//! laws of [`crate::impact::friction`], or LZB's).

use toml_edit::{Item, Table, TableLike};

use super::super::SceneError;
use super::super::read::{Reader, short};
use super::hertz::{Material, Surface, hertz_stiffness};
use super::shape::Shape;
use super::simulation::SIMULATE_KEYS;
use super::term::Term;
use crate::mechanics::screw::Vec3;
use crate::number::Number;
use crate::simulate::body::{Body, Feature, Shape as SimShape, V3};
use crate::simulate::system::gaps::gap;
use crate::simulate::system::joints::rate as joint_rate;
use crate::simulate::system::overlap::deepest;
use crate::simulate::system::{Link, Member, SystemSetup, SystemState, Touch};
use crate::simulate::world::{ContactLaw, Plane};
use nalgebra::{Matrix3, Rotation3, UnitQuaternion};

fn v3(t: &[Term; 3]) -> V3 {
    V3::new(t[0].approx(), t[1].approx(), t[2].approx())
}

/// A contact law, and whether its stiffness is Hertz's.
type Law = (ContactLaw, bool);

impl Reader<'_> {
    /// The system a document of several `[[body]]` describes.
    pub(crate) fn simulated_system(&self, root: &Table) -> Result<SystemSetup, SceneError> {
        if let Some(c) = root.get("contact") {
            return Err(self.err(
                "contact",
                Some(short(c)),
                "a scene to simulate names no contacts: every body and [[obstacle]], and every \
                 pair of bodies, are watched; give their law in [simulate] contact",
            ));
        }
        for key in ["solve", "constraints", "surface"] {
            if let Some(item) = root.get(key) {
                return Err(self.err(
                    key,
                    Some(short(item)),
                    "`simulate` reads its law and options from [simulate]; a system's joints are \
                     [[joint]] tables, and one body's constraints and surfaces are not simulated",
                ));
            }
        }
        let Some(Item::ArrayOfTables(bodies)) = root.get("body") else {
            return Err(self.err("body", None, "[[body]] tables"));
        };
        let mut members: Vec<Member> = Vec::new();
        let mut materials: Vec<Option<Material>> = Vec::new();
        let (mut x, mut v, mut q, mut w) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (i, body) in bodies.iter().enumerate() {
            let at = format!("body[{i}]");
            self.only_keys(
                body,
                &at,
                &[
                    "name",
                    "shape",
                    "mass",
                    "density",
                    "position",
                    "pose",
                    "velocity",
                    "angular_velocity",
                    "material",
                ],
            )?;
            let name = match body.get("name") {
                Some(n) => self.string(n, &format!("{at}.name"))?,
                None => at.clone(),
            };
            if members.iter().any(|s| s.name == name) {
                return Err(self.err(
                    &format!("{at}.name"),
                    Some(format!("\"{name}\"")),
                    "two bodies of one name: contacts are named by their bodies",
                ));
            }
            let (props, shape) = self.mass_properties(body, &at)?;
            let shape = match shape {
                Some(Shape::Sphere(r)) => SimShape::Sphere { radius: r.approx() },
                Some(Shape::Box(d)) => SimShape::Box { half: v3(&d) / 2.0 },
                Some(Shape::Rod(l)) => SimShape::Rod {
                    half_length: l.approx() / 2.0,
                },
                _ => {
                    return Err(self.err(
                        &format!("{at}.shape"),
                        body.get("shape").map(short),
                        "a system to simulate is made of spheres, boxes and thin rods: shape = \
                         { sphere = r }, { box = [a, b, c] } or { rod = L } (cylinders move only \
                         alone)",
                    ));
                }
            };
            let r = self.pose(body.get("pose"), &at)?;
            let rm = Matrix3::from_fn(|i, j| r[i][j].approx());
            let mut inertia = Matrix3::from_fn(|i, j| props.inertia[i][j].approx());
            if let SimShape::Rod { .. } = shape {
                // no moment about the axis: completed as the single body's (every contact of a
                // thin rod is on its axis, so none has a moment about it, and any c > 0 gives
                // the same motion)
                inertia[(2, 2)] = inertia[(0, 0)];
            }
            let Some(model) = Body::new(props.mass.approx(), inertia, shape, None) else {
                return Err(self.err(&at, None, "the inertia tensor is singular"));
            };
            let position = match body.get("position") {
                None => V3::zeros(),
                Some(p) => v3(&self
                    .triple(p, &format!("{at}.position"))?
                    .each_ref()
                    .map(Term::of)),
            };
            let velocity = v3(&self
                .triple(self.get(body, "velocity", &at)?, &format!("{at}.velocity"))?
                .each_ref()
                .map(Term::of));
            let omega = match body.get("angular_velocity") {
                None => V3::zeros(),
                Some(item) => v3(&self
                    .triple(item, &format!("{at}.angular_velocity"))?
                    .each_ref()
                    .map(Term::of)),
            };
            materials.push(self.material(body, &at)?);
            members.push(Member {
                name,
                body: model,
                spins: false,
            });
            x.push(position + rm * v3(&props.centre));
            v.push(velocity);
            q.push(UnitQuaternion::from_rotation_matrix(
                &Rotation3::from_matrix_unchecked(rm),
            ));
            w.push(omega);
        }
        let sim = self.table(root, "simulate", "")?;
        // one body's keys, but `plane` (a planar motion of a box), and `pair`
        let keys: Vec<&str> = SIMULATE_KEYS
            .iter()
            .copied()
            .filter(|k| *k != "plane")
            .chain(["pair"])
            .collect();
        self.only_keys(sim, "simulate", &keys)?;
        let (gravity, mut options, law) = self.simulate_options(sim)?;
        let obstacles = self.obstacles(root)?;
        let names: Vec<String> = obstacles
            .iter()
            .enumerate()
            .map(|(i, o)| o.name.clone().unwrap_or_else(|| format!("obstacle[{i}]")))
            .collect();
        let base = self.sphere_law(
            table_at(self, sim, "contact", "simulate.contact")?,
            "simulate.contact",
            None,
        )?;
        let overrides = table_at(self, sim, "obstacle", "simulate.obstacle")?;
        self.known_obstacles(overrides, &names)?;
        let mut planes = Vec::with_capacity(obstacles.len());
        let mut plane_laws: Vec<Law> = Vec::new();
        for (i, o) in obstacles.iter().enumerate() {
            let at = format!("simulate.obstacle.{}", names[i]);
            let own = match overrides.and_then(|t| t.get(&names[i])) {
                None => None,
                Some(item) => Some(item.as_table_like().ok_or_else(|| {
                    self.err(&at, Some(short(item)), "a table of k, stiffness, …")
                })?),
            };
            let l = match own {
                None => base.clone(),
                Some(t) => self.sphere_law(Some(t), &at, Some(&base))?,
            };
            planes.push(Plane {
                name: names[i].clone(),
                normal: v3(&o.normal).normalize(),
                point: o.point.as_ref().map_or_else(V3::zeros, v3),
                law: l.0.clone(),
            });
            plane_laws.push(l);
        }
        // [[simulate.pair]]: bodies = [A, B] and a law.
        let mut pair_laws: Vec<((usize, usize), Law)> = Vec::new();
        if let Some(item) = sim.get("pair") {
            let Item::ArrayOfTables(arr) = item else {
                return Err(self.err(
                    "simulate.pair",
                    Some(short(item)),
                    "[[simulate.pair]] tables: bodies = [\"a\", \"b\"] and the law's keys",
                ));
            };
            for (i, t) in arr.iter().enumerate() {
                let at = format!("simulate.pair[{i}]");
                let item = self.get(t, "bodies", &at)?;
                let pair = item
                    .as_array()
                    .filter(|a| a.len() == 2)
                    .and_then(|a| {
                        let idx = |k: usize| {
                            let n = a.get(k)?.as_str()?;
                            members.iter().position(|s| s.name == n)
                        };
                        Some((idx(0)?, idx(1)?))
                    })
                    .filter(|(a, b)| a != b)
                    .ok_or_else(|| {
                        self.err(
                            &format!("{at}.bodies"),
                            Some(short(item)),
                            format!(
                                "two different bodies by name; the scene has: {}",
                                members
                                    .iter()
                                    .map(|s| s.name.as_str())
                                    .collect::<Vec<_>>()
                                    .join(", ")
                            ),
                        )
                    })?;
                let mut rest = t.clone();
                rest.remove("bodies");
                let l = self.sphere_law(Some(&rest), &at, Some(&base))?;
                pair_laws.push(((pair.0.min(pair.1), pair.0.max(pair.1)), l));
            }
        }
        let start = SystemState { x, v, q, w };
        let links = self.links(root, &mut members, &start)?;
        let mut failure: Option<SceneError> = None;
        // a side's surface for Hertz's law: a sphere's, or none (a box's corner)
        let surface = |m: usize, f: usize| match members[m].body.features[f] {
            Feature::Sphere { radius } => Some(Surface::Sphere(radius)),
            _ => None,
        };
        let candidates = SystemSetup::candidates(&members, planes.len(), |touch| {
            let key = |a: usize, b: usize| (a.min(b), a.max(b));
            let pair_law = |a: usize, b: usize| {
                pair_laws
                    .iter()
                    .rev()
                    .find(|(p, _)| *p == key(a, b))
                    .map_or_else(|| base.clone(), |(_, l)| l.clone())
            };
            let (l, hertz) = match *touch {
                Touch::Plane { plane, .. } => plane_laws[plane].clone(),
                Touch::Pair { a, b }
                | Touch::Face { a, b, .. }
                | Touch::Edges { a, b, .. }
                | Touch::OnEdge { a, b, .. }
                | Touch::OnCorner { a, b, .. } => pair_law(a, b),
            };
            if !hertz {
                return l;
            }
            // each side: its surface, its material, and who it is
            type HertzSide = (Option<Surface>, Option<Material>, String);
            let (first, second): (HertzSide, HertzSide) = match *touch {
                Touch::Plane {
                    body,
                    feature,
                    plane,
                } => (
                    (
                        surface(body, feature),
                        materials[body],
                        format!("body \"{}\"", members[body].name),
                    ),
                    (
                        Some(Surface::Flat),
                        obstacles[plane].material,
                        format!("obstacle \"{}\"", names[plane]),
                    ),
                ),
                Touch::Pair { a, b } => (
                    (
                        surface(a, 0),
                        materials[a],
                        format!("body \"{}\"", members[a].name),
                    ),
                    (
                        surface(b, 0),
                        materials[b],
                        format!("body \"{}\"", members[b].name),
                    ),
                ),
                Touch::Face { a, feature, b, .. } => (
                    (
                        surface(a, feature),
                        materials[a],
                        format!("body \"{}\"", members[a].name),
                    ),
                    (
                        Some(Surface::Flat),
                        materials[b],
                        format!("body \"{}\"", members[b].name),
                    ),
                ),
                // an edge, a corner or a rod's end has no radius
                Touch::Edges { a, b, .. }
                | Touch::OnEdge { a, b, .. }
                | Touch::OnCorner { a, b, .. } => (
                    (
                        surface(a, 0).filter(|_| members[a].radius().is_some()),
                        materials[a],
                        format!("body \"{}\"", members[a].name),
                    ),
                    (None, materials[b], format!("body \"{}\"", members[b].name)),
                ),
            };
            let (Some(s1), Some(s2)) = (first.0, second.0) else {
                let who = if first.0.is_none() {
                    &first.2
                } else {
                    &second.2
                };
                failure.get_or_insert_with(|| {
                    self.err(
                        "simulate.contact.stiffness",
                        Some("\"hertz\"".into()),
                        format!(
                            "Hertz's stiffness is for curved or flat surfaces, and the corners, \
                             edges and rod ends of {who} have no radius: give the stiffness of \
                             its contacts as a number ([[simulate.pair]] or \
                             [simulate.obstacle.NAME])"
                        ),
                    )
                });
                return l;
            };
            let (Some(m1), Some(m2)) = (first.1, second.1) else {
                let who = if first.1.is_none() { first.2 } else { second.2 };
                failure.get_or_insert_with(|| {
                    self.err(
                        "simulate.contact.stiffness",
                        Some("\"hertz\"".into()),
                        format!(
                            "Hertz's stiffness needs the material of {who}: give it \
                             `material = {{ young = E, poisson = ν }}`"
                        ),
                    )
                });
                return l;
            };
            match hertz_stiffness((s1, m1), (s2, m2)) {
                Ok(k) => ContactLaw {
                    stiffness: k,
                    exponent: 1.5,
                    ..l
                },
                Err(why) => {
                    failure.get_or_insert_with(|| {
                        self.err("simulate.contact.stiffness", Some("\"hertz\"".into()), why)
                    });
                    l
                }
            }
        });
        if let Some(e) = failure {
            return Err(e);
        }
        // no contact is watched between two members a joint holds together
        let joined = |a: usize, b: usize| links.iter().any(|l| l.joins(a, b));
        let mut candidates = candidates;
        candidates.retain(|c| match c.touch {
            Touch::Pair { a, b }
            | Touch::Face { a, b, .. }
            | Touch::Edges { a, b, .. }
            | Touch::OnEdge { a, b, .. }
            | Touch::OnCorner { a, b, .. } => !joined(a, b),
            Touch::Plane { .. } => true,
        });
        // a sphere a rough contact touches turns (its spin integrated)
        for c in candidates.iter().filter(|c| c.law.mu > 0.0) {
            for (b, _) in c.touch.bodies() {
                members[b].spins = true;
            }
        }
        let reach = members.iter().map(|m| m.body.reach()).fold(0.0, f64::max);
        let length = start
            .x
            .iter()
            .map(|p| p.norm())
            .fold(reach, f64::max)
            .max(f64::MIN_POSITIVE);
        let inside = |a: &str, b: &str, depth: f64| {
            self.err(
                "body.position",
                None,
                format!("\"{a}\" starts inside \"{b}\": they overlap by {depth:.6e} m"),
            )
        };
        for c in &candidates {
            let g = gap(&c.touch, &members, &planes, &start);
            if g.gap < -1e-9 * length {
                let (a, b) = c.touch.name(&members, &planes);
                return Err(inside(&a, &b, -g.gap));
            }
        }
        if let Some((a, b, depth)) = deepest(&members, &start, 1e-9 * length, joined) {
            return Err(inside(&members[a].name, &members[b].name, depth));
        }
        let fastest = (0..members.len())
            .map(|b| {
                let spin = if members[b].turns() {
                    start.w[b].norm() * members[b].body.reach()
                } else {
                    0.0
                };
                start.v[b].norm() + spin
            })
            .fold(0.0, f64::max);
        options.rest_speed = self.rest_speed(sim, &gravity, length, fastest)?;
        Ok(SystemSetup {
            members,
            planes,
            candidates,
            joints: links,
            law,
            start,
            options,
        })
    }

    /// The `[[joint]]` tables of a system to simulate, read as for one impact
    /// ([`Reader::joints`]; anchor and axis in the world at t = 0), each carried by its members
    /// from there; every member a joint holds turns (its spin integrated: the joint's reaction
    /// has a moment about its centre).
    ///
    /// # Errors
    /// As [`Reader::joints`]; and where the velocities at t = 0 move a joint's members along a
    /// motion it blocks (the rate beyond 10⁻⁹ of the fastest point's speed).
    fn links(
        &self,
        root: &Table,
        members: &mut [Member],
        start: &SystemState,
    ) -> Result<Vec<Link>, SceneError> {
        let names: Vec<String> = members.iter().map(|m| m.name.clone()).collect();
        let specs = self.joints(root, &names)?;
        let vector = |t: &Option<[Number; 3]>| {
            t.as_ref().map_or_else(Vec3::zeros, |t| {
                Vec3::new(t[0].approx, t[1].approx, t[2].approx)
            })
        };
        let mut links = Vec::with_capacity(specs.len());
        for spec in &specs {
            let (point, axis) = (vector(&spec.anchor), vector(&spec.axis));
            let joint = spec.kind.joint(point, axis);
            for b in std::iter::once(spec.pair.first).chain(spec.pair.second) {
                members[b].spins = true;
            }
            links.push(Link::new(joint, spec.pair, start));
        }
        let fastest = (0..members.len())
            .map(|b| start.v[b].norm() + start.w[b].norm() * members[b].body.reach())
            .fold(0.0, f64::max);
        for (j, l) in links.iter().enumerate() {
            let rate = joint_rate(std::slice::from_ref(l), members, start);
            if rate > 1e-9 * fastest {
                return Err(self.err(
                    &format!("joint[{j}]"),
                    None,
                    format!(
                        "the velocities at t = 0 move the members of this {} joint along a \
                         motion it blocks (at {rate:.6e} m/s): give each body the velocity and \
                         angular velocity the joint allows",
                        l.joint.name()
                    ),
                ));
            }
        }
        Ok(links)
    }

    /// A contact law table whose `stiffness` may be `"hertz"`, over `base`.
    fn sphere_law(
        &self,
        t: Option<&dyn TableLike>,
        at: &str,
        base: Option<&Law>,
    ) -> Result<Law, SceneError> {
        let mut hertz = base.is_some_and(|b| b.1);
        let mut plain = toml_edit::Table::new();
        if let Some(t) = t {
            for (key, item) in t.iter() {
                if key == "stiffness" && item.as_str().is_some() {
                    if item.as_str() != Some("hertz") {
                        return Err(self.err(
                            &format!("{at}.stiffness"),
                            Some(short(item)),
                            "a stiffness > 0, or \"hertz\" (from the radii and materials)",
                        ));
                    }
                    hertz = true;
                } else {
                    if key == "stiffness" {
                        hertz = false;
                    }
                    plain.insert(key, item.clone());
                }
            }
        }
        let law = self.contact_law(t.map(|_| &plain as &dyn TableLike), at, base.map(|b| &b.0))?;
        Ok((law, hertz))
    }
}

/// The table at `key` of `sim`, if given.
fn table_at<'t>(
    r: &Reader<'_>,
    sim: &'t Table,
    key: &str,
    at: &str,
) -> Result<Option<&'t dyn TableLike>, SceneError> {
    match sim.get(key) {
        None => Ok(None),
        Some(item) => item
            .as_table_like()
            .map(Some)
            .ok_or_else(|| r.err(at, Some(short(item)), "a table")),
    }
}
