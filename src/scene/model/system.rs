//! Reading a scene of several bodies: `[[body]]` tables with a `name`, contacts that name the
//! bodies they join, and `[[joint]]` tables ([`crate::mechanics::system`]).
//!
//! Every body is read as a modelled body is (`shape` or the mass properties, `pose`,
//! `position`, `velocity` and `angular_velocity` in the world frame), its keys at
//! `body[i].…`, and kept in **world axes about its own centre of mass**: m_b, J_b = R J_C Rᵀ,
//! C_b = position + R c, [ω_b; v_Cb]. A contact names its bodies — `bodies = ["a", "b"]`, the
//! normal pointing out of `a` toward `b`, or `body = "a"` with an `obstacle` (the normal −N) —
//! and is placed by a world `point`, a `corner` of the first body's box or a `body_point` in
//! its axes. A box touching an obstacle along an edge or a face must name every touching
//! corner, as for one body; a contact between two spheres or boxes must lie on both surfaces,
//! with its normal the surfaces' normal there (where a point lies on both surfaces with
//! different normals the bodies cross each other), and a box resting on another body along an
//! edge or a face must name every corner of it that touches the other body.
//! A `[[joint]]` has a `kind` (`revolute`, `prismatic`, `cylindrical`, `spherical`, `planar`,
//! `fixed`), the `bodies` it joins (one name: to the ground), an `anchor` (world) and an `axis`
//! (the plane's normal for `planar`), as its kind needs.

use toml_edit::{Item, Table};

use super::super::SceneError;
use super::super::read::{Reader, short};
use super::super::schema::ContactSpec;
use super::obstacle::{Obstacle, world};
use super::shape::Shape;
use super::term::{Mat3, Term, Vec3, apply, cross, dot, product, sub, transpose, zero};
use super::{Axes, Frame};
use crate::mechanics::system::Pair;
use crate::number::Number;

/// One body of a system scene, as read: world axes, about its centre of mass.
#[derive(Clone, Debug, PartialEq)]
pub struct BodySpec {
    /// Its `name`.
    pub name: String,
    /// m.
    pub mass: Number,
    /// J in world axes: (J_xx, J_yy, J_zz).
    pub inertia: [Number; 3],
    /// (J_xy, J_xz, J_yz), when not all zero.
    pub inertia_products: Option<[Number; 3]>,
    /// C, in the world.
    pub centre: [Number; 3],
    /// v_C before impact.
    pub velocity: [Number; 3],
    /// ω before impact.
    pub angular_velocity: [Number; 3],
}

/// The kinds of joint between bodies (`[[joint]] kind`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SystemJointKind {
    /// `revolute`: `anchor`, `axis`.
    Revolute,
    /// `prismatic`: `axis`.
    Prismatic,
    /// `cylindrical`: `anchor`, `axis`.
    Cylindrical,
    /// `spherical`: `anchor`.
    Spherical,
    /// `planar`: `axis`, the plane's normal.
    Planar,
    /// `fixed`: `anchor`, where its reaction is reported.
    Fixed,
}

impl SystemJointKind {
    /// The joint of this kind through `point` along `axis` (the keys its kind reads; a planar
    /// joint's `axis` is its plane's normal).
    pub fn joint<T: crate::scalar::Scalar>(
        self,
        point: crate::mechanics::screw::Vec3<T>,
        axis: crate::mechanics::screw::Vec3<T>,
    ) -> crate::mechanics::constraint::Joint<T> {
        use crate::mechanics::constraint::Joint;
        match self {
            SystemJointKind::Revolute => Joint::Revolute { point, axis },
            SystemJointKind::Prismatic => Joint::Prismatic { axis },
            SystemJointKind::Cylindrical => Joint::Cylindrical { point, axis },
            SystemJointKind::Spherical => Joint::Spherical { point },
            SystemJointKind::Planar => Joint::Planar { normal: axis },
            SystemJointKind::Fixed => Joint::Fixed { point },
        }
    }

    const NAMES: [(&'static str, SystemJointKind); 6] = [
        ("revolute", SystemJointKind::Revolute),
        ("prismatic", SystemJointKind::Prismatic),
        ("cylindrical", SystemJointKind::Cylindrical),
        ("spherical", SystemJointKind::Spherical),
        ("planar", SystemJointKind::Planar),
        ("fixed", SystemJointKind::Fixed),
    ];

    /// (needs `anchor`, needs `axis`).
    fn needs(self) -> (bool, bool) {
        match self {
            SystemJointKind::Revolute | SystemJointKind::Cylindrical => (true, true),
            SystemJointKind::Prismatic | SystemJointKind::Planar => (false, true),
            SystemJointKind::Spherical | SystemJointKind::Fixed => (true, false),
        }
    }
}

/// One `[[joint]]`, as read (world).
#[derive(Clone, Debug, PartialEq)]
pub struct SystemJointSpec {
    /// Its kind.
    pub kind: SystemJointKind,
    /// The bodies it joins (the second `None`: the ground).
    pub pair: Pair,
    /// Its anchor, when its kind has one.
    pub anchor: Option<[Number; 3]>,
    /// Its axis (a planar joint's normal), when its kind has one.
    pub axis: Option<[Number; 3]>,
}

/// A system scene's bodies, what each contact joins, and its joints.
#[derive(Clone, Debug, PartialEq)]
pub struct SystemSpec {
    /// The bodies, in order.
    pub bodies: Vec<BodySpec>,
    /// Per contact, the bodies it joins.
    pub pairs: Vec<Pair>,
    /// Per contact against an obstacle, how the report names it: its `name`, or
    /// `obstacle[i]` when it has none; `None` for a contact between bodies or with a
    /// written normal.
    pub obstacles: Vec<Option<String>>,
    /// The joints.
    pub joints: Vec<SystemJointSpec>,
    /// Per contact, its lever arms A − C_a on its first body and A − C_b on its second
    /// (`None`: an obstacle), computed exactly from the scene's numbers, so that a float solve
    /// rounds each once, as a `[body]` scene's ([`crate::mechanics::system::System::with_lever_arms`]).
    pub levers: Vec<Lever>,
}

/// A contact's lever arms A − C_a and A − C_b (`None`: an obstacle), world axes.
pub type Lever = ([Number; 3], Option<[Number; 3]>);

impl SystemSpec {
    /// Every number of the bodies and joints, with its key.
    pub fn numbers(&self) -> Vec<(String, &Number)> {
        let mut v: Vec<(String, &Number)> = Vec::new();
        for (b, body) in self.bodies.iter().enumerate() {
            v.push((format!("body[{b}].mass"), &body.mass));
            let triples = [
                ("inertia", Some(&body.inertia)),
                ("inertia_products", body.inertia_products.as_ref()),
                ("centre", Some(&body.centre)),
                ("velocity", Some(&body.velocity)),
                ("angular_velocity", Some(&body.angular_velocity)),
            ];
            for (key, t) in triples {
                for (k, n) in t.into_iter().flatten().enumerate() {
                    v.push((format!("body[{b}].{key}[{k}]"), n));
                }
            }
        }
        for (j, joint) in self.joints.iter().enumerate() {
            for (key, t) in [("anchor", &joint.anchor), ("axis", &joint.axis)] {
                for (k, n) in t.iter().flatten().enumerate() {
                    v.push((format!("joint[{j}].{key}[{k}]"), n));
                }
            }
        }
        v
    }
}

/// Keys a `[[body]]` of a system may have.
const BODY_KEYS: [&str; 12] = [
    "name",
    "material",
    "shape",
    "mass",
    "density",
    "inertia",
    "inertia_about",
    "centre_of_mass",
    "pose",
    "position",
    "velocity",
    "angular_velocity",
];

/// Whether the document is a system of bodies: `[[body]]` tables.
pub(crate) fn declared(root: &Table) -> bool {
    matches!(root.get("body"), Some(Item::ArrayOfTables(_)))
}

/// A body read, in the world, with what its contacts need.
struct Placed {
    frame: Frame,
    shape: Option<Shape>,
    /// `material`, for Hertz's stiffness.
    material: Option<super::hertz::Material>,
}

impl Reader<'_> {
    /// Read a system scene's bodies and joints, and place its contacts (world points, normals
    /// out of their first body).
    pub(crate) fn system(
        &self,
        root: &Table,
        contacts: &mut [ContactSpec],
    ) -> Result<SystemSpec, SceneError> {
        for key in ["constraints", "surface"] {
            if root.contains_key(key) {
                return Err(self.err(
                    key,
                    None,
                    format!(
                        "a scene of several bodies takes [[joint]] tables for its joints; `[{key}]` \
                         is the one-body form"
                    ),
                ));
            }
        }
        let Some(Item::ArrayOfTables(tables)) = root.get("body") else {
            return Err(self.err("body", None, "must be [[body]] tables"));
        };
        let mut names: Vec<String> = Vec::new();
        let mut bodies = Vec::new();
        let mut placed = Vec::new();
        for (i, t) in tables.iter().enumerate() {
            let (spec, p) = self.system_body(t, i, &names)?;
            names.push(spec.name.clone());
            bodies.push(spec);
            placed.push(p);
        }
        let obstacles = self.obstacles(root)?;
        let (pairs, against) =
            self.place_system_contacts(root, contacts, &names, &placed, &obstacles)?;
        let mut levers = Vec::with_capacity(pairs.len());
        for (i, (contact, pair)) in contacts.iter().zip(&pairs).enumerate() {
            let point = contact.point.each_ref().map(Term::of);
            let key = format!("contact[{i}].point");
            let arm = |b: usize| self.numbers3(&sub(&point, &placed[b].frame.centre), &key);
            levers.push((arm(pair.first)?, pair.second.map(arm).transpose()?));
        }
        let joints = self.joints(root, &names)?;
        Ok(SystemSpec {
            bodies,
            pairs,
            obstacles: against,
            joints,
            levers,
        })
    }

    /// `body[i]`: its numbers in world axes about its centre.
    fn system_body(
        &self,
        t: &Table,
        i: usize,
        taken: &[String],
    ) -> Result<(BodySpec, Placed), SceneError> {
        let at = format!("body[{i}]");
        self.only_keys(t, &at, &BODY_KEYS)?;
        let name = self.string(self.get(t, "name", &at)?, &format!("{at}.name"))?;
        if taken.contains(&name) {
            return Err(self.err(
                &format!("{at}.name"),
                Some(format!("\"{name}\"")),
                "two bodies have this name",
            ));
        }
        let (mut props, shape) = self.mass_properties(t, &at)?;
        if self.degenerate(&mut props, shape.as_ref(), &at)?.is_some() {
            return Err(self.err(
                &format!("{at}.shape"),
                None,
                "a body of a system needs a moment of inertia about every axis: a thin rod or \
                 point masses on a line are not taken yet (give it a solid shape, or its inertia)",
            ));
        }
        let r = self.pose(t.get("pose"), &at)?;
        let position = match t.get("position") {
            None => zero(),
            Some(p) => self
                .triple(p, &format!("{at}.position"))?
                .each_ref()
                .map(Term::of),
        };
        let centre = world(&position, &r, &props.centre);
        let j: Mat3 = product(&product(&r, &props.inertia), &transpose(&r));
        let mass = self.term_number(&props.mass, &format!("{at}.mass"))?;
        self.positive(&mass, &format!("{at}.mass"), "a mass must be positive")?;
        let inertia = [
            self.term_number(&j[0][0], &format!("{at}.inertia[0]"))?,
            self.term_number(&j[1][1], &format!("{at}.inertia[1]"))?,
            self.term_number(&j[2][2], &format!("{at}.inertia[2]"))?,
        ];
        let off = [&j[0][1], &j[0][2], &j[1][2]];
        let inertia_products = if off.iter().all(|t| t.is_zero()) {
            None
        } else {
            Some([
                self.term_number(off[0], &format!("{at}.inertia[0][1]"))?,
                self.term_number(off[1], &format!("{at}.inertia[0][2]"))?,
                self.term_number(off[2], &format!("{at}.inertia[1][2]"))?,
            ])
        };
        let velocity = self.triple(self.get(t, "velocity", &at)?, &format!("{at}.velocity"))?;
        let angular_velocity = self.triple(
            self.get(t, "angular_velocity", &at)?,
            &format!("{at}.angular_velocity"),
        )?;
        let spec = BodySpec {
            name,
            mass,
            inertia,
            inertia_products,
            centre: self.numbers3(&centre, &format!("{at}.centre"))?,
            velocity,
            angular_velocity,
        };
        let frame = Frame {
            r,
            position,
            centre_body: props.centre.clone(),
            centre,
            axes: Axes::World,
        };
        let material = self.material(t, &at)?;
        Ok((
            spec,
            Placed {
                frame,
                shape,
                material,
            },
        ))
    }

    /// The body named by `item` at `key`.
    fn body_ref(&self, item: &Item, key: &str, names: &[String]) -> Result<usize, SceneError> {
        let name = self.string(item, key)?;
        names.iter().position(|n| *n == name).ok_or_else(|| {
            self.err(
                key,
                Some(format!("\"{name}\"")),
                format!("no such body; the scene has: {}", names.join(", ")),
            )
        })
    }

    /// `bodies = ["a", "b"]` (or `["a"]` where one is allowed) at `key`.
    fn body_list(
        &self,
        item: &Item,
        key: &str,
        names: &[String],
        one: bool,
    ) -> Result<Pair, SceneError> {
        let list = item
            .as_array()
            .filter(|a| a.len() == 2 || (one && a.len() == 1));
        let Some(list) = list else {
            return Err(self.err(
                key,
                Some(short(item)),
                if one {
                    "must name one body (joined to the ground) or two: [\"a\", \"b\"]"
                } else {
                    "must name two bodies, [\"a\", \"b\"] (the normal out of a); for a body \
                     against an obstacle write `body` and `obstacle`"
                },
            ));
        };
        let refs: Vec<usize> = list
            .iter()
            .enumerate()
            .map(|(k, v)| self.body_ref(&Item::Value(v.clone()), &format!("{key}[{k}]"), names))
            .collect::<Result<_, _>>()?;
        if refs.len() == 2 && refs[0] == refs[1] {
            return Err(self.err(
                key,
                Some(short(item)),
                "joins a body to itself: name two different bodies",
            ));
        }
        Ok(Pair {
            first: refs[0],
            second: refs.get(1).copied(),
        })
    }

    /// Each contact's bodies, world point and normal (out of its first body); with the name
    /// of the obstacle it touches ([`SystemSpec::obstacles`]).
    fn place_system_contacts(
        &self,
        root: &Table,
        contacts: &mut [ContactSpec],
        names: &[String],
        placed: &[Placed],
        obstacles: &[Obstacle],
    ) -> Result<(Vec<Pair>, Vec<Option<String>>), SceneError> {
        let Some(Item::ArrayOfTables(tables)) = root.get("contact") else {
            return Ok((Vec::new(), Vec::new()));
        };
        let mut pairs = Vec::with_capacity(contacts.len());
        let mut against = Vec::with_capacity(contacts.len());
        let mut on_obstacles: Vec<Vec<(usize, usize, Vec3)>> = vec![Vec::new(); placed.len()];
        let mut between: Vec<(usize, Pair, Vec3, Vec3)> = Vec::new();
        for (i, (t, spec)) in tables.iter().zip(contacts.iter_mut()).enumerate() {
            let at = format!("contact[{i}]");
            let obstacle = match t.get("obstacle") {
                None => None,
                Some(o) => Some(self.obstacle_ref(o, &format!("{at}.obstacle"), obstacles)?),
            };
            let pair = match (t.get("bodies"), t.get("body"), obstacle) {
                (Some(b), None, None) => {
                    self.body_list(b, &format!("{at}.bodies"), names, false)?
                }
                (None, Some(b), Some(_)) => Pair {
                    first: self.body_ref(b, &format!("{at}.body"), names)?,
                    second: None,
                },
                (Some(_), _, Some(_)) => {
                    return Err(self.err(
                        &format!("{at}.obstacle"),
                        None,
                        "a contact is between two bodies (`bodies`) or between a body and an \
                         obstacle (`body` and `obstacle`), not both",
                    ));
                }
                _ => {
                    return Err(self.err(
                        &format!("{at}.bodies"),
                        None,
                        "missing: name the two bodies it joins, `bodies = [\"a\", \"b\"]` (the \
                         normal out of a), or `body` and `obstacle`",
                    ));
                }
            };
            let first = &placed[pair.first];
            let given: Vec<&str> = ["point", "body_point", "corner"]
                .into_iter()
                .filter(|k| t.contains_key(k))
                .collect();
            let (point, body_point): (Vec3, Option<Vec3>) = match given.as_slice() {
                ["point"] => (spec.point.each_ref().map(Term::of), None),
                ["body_point"] => {
                    let p = self.triple(
                        t.get("body_point").unwrap_or(&Item::None),
                        &format!("{at}.body_point"),
                    )?;
                    let p = p.each_ref().map(Term::of);
                    (world(&first.frame.position, &first.frame.r, &p), Some(p))
                }
                [_] => {
                    let p = self.corner(
                        t.get("corner").unwrap_or(&Item::None),
                        &format!("{at}.corner"),
                        first.shape.as_ref(),
                    )?;
                    (world(&first.frame.position, &first.frame.r, &p), Some(p))
                }
                [] => {
                    return Err(self.err(
                        &format!("{at}.point"),
                        None,
                        "missing: give `point` (world), `body_point` (the first body's axes) or \
                         `corner` (of the first body's box)",
                    ));
                }
                [a, b, ..] => {
                    return Err(self.err(
                        &format!("{at}.{b}"),
                        None,
                        format!(
                            "give one of `point`, `body_point` or `corner`, not `{a}` and `{b}`"
                        ),
                    ));
                }
            };
            spec.point = self.numbers3(&point, &format!("{at}.point"))?;
            match obstacle {
                Some(o) => {
                    if let Some(n) = t.get("normal") {
                        return Err(self.err(
                            &format!("{at}.normal"),
                            Some(short(n)),
                            "the contact names an obstacle, whose normal gives the body's (n = −N); drop `normal`",
                        ));
                    }
                    let ob = &obstacles[o];
                    let n = ob.normal.each_ref().map(|x| -x);
                    spec.normal = Some(self.numbers3(&n, &format!("{at}.normal"))?);
                    self.check_obstacle(
                        ob,
                        o,
                        &point,
                        body_point.as_ref(),
                        &first.frame,
                        first.shape.as_ref(),
                        &at,
                    )?;
                    on_obstacles[pair.first].push((i, o, point.clone()));
                    if spec.hertz {
                        let faces = self.box_faces(first, &point, &at)?;
                        let body = format!("body \"{}\"", names[pair.first]);
                        self.set_hertz(
                            &at,
                            &mut spec.stiffness,
                            &mut spec.exponent,
                            [
                                (
                                    self.hertz_surface(first.shape.as_ref(), faces),
                                    first.material,
                                    &body,
                                ),
                                (super::hertz::Surface::Flat, ob.material, &ob.label(o)),
                            ],
                        )?;
                    }
                }
                None => {
                    let Some(normal) = &spec.normal else {
                        return Err(self.err(
                            &format!("{at}.normal"),
                            None,
                            "missing: give the normal at the contact, pointing out of the first \
                             body toward the second",
                        ));
                    };
                    between.push((i, pair, point.clone(), normal.each_ref().map(Term::of)));
                    // The key the point was written at, and its value, for the messages.
                    let written = given[0];
                    let item = t.get(written).map(short);
                    for body in std::iter::once(pair.first).chain(pair.second) {
                        self.on_surface(
                            &placed[body],
                            &point,
                            (&names[body], body),
                            (&format!("{at}.{written}"), item.clone()),
                        )?;
                    }
                    if spec.hertz {
                        let mut sides = Vec::with_capacity(2);
                        for body in std::iter::once(pair.first).chain(pair.second) {
                            let faces = self.box_faces(&placed[body], &point, &at)?;
                            sides.push((
                                self.hertz_surface(placed[body].shape.as_ref(), faces),
                                placed[body].material,
                                format!("body \"{}\"", names[body]),
                            ));
                        }
                        let [a, b] = &sides[..] else {
                            unreachable!("a contact between bodies has two")
                        };
                        self.set_hertz(
                            &at,
                            &mut spec.stiffness,
                            &mut spec.exponent,
                            [(a.0, a.1, &a.2), (b.0, b.1, &b.2)],
                        )?;
                    }
                    let n = normal.each_ref().map(Term::of);
                    let shown = t.get("normal").map(short);
                    for (body, out) in [(pair.first, true)]
                        .into_iter()
                        .chain(pair.second.map(|b| (b, false)))
                    {
                        self.along_surface_normal(
                            &placed[body],
                            &point,
                            &n,
                            out,
                            &names[body],
                            (&format!("{at}.normal"), shown.clone()),
                        )?;
                    }
                }
            }
            pairs.push(pair);
            against.push(obstacle.map(|o| {
                obstacles[o]
                    .name
                    .clone()
                    .unwrap_or_else(|| format!("obstacle[{o}]"))
            }));
        }
        self.every_corner_on_a_body_named(&between, placed, names)?;
        for (p, named) in placed.iter().zip(&on_obstacles) {
            if let Some(Shape::Box(dims)) = &p.shape {
                self.every_touching_corner_named(named, obstacles, &p.frame, dims)?;
            }
        }
        Ok((pairs, against))
    }

    /// A contact between two bodies must lie on each one's surface, where the shape says what
    /// that is (a sphere, a box): two bodies cannot touch at a point inside one of them. The
    /// error is at the key the point was written at (`key`, with its value), and says where the
    /// point is relative to the body (`body`: its name and index).
    fn on_surface(
        &self,
        placed: &Placed,
        point: &Vec3,
        (name, index): (&str, usize),
        (key, value): (&str, Option<String>),
    ) -> Result<(), SceneError> {
        let Some(what) = self.off_surface(placed, point, key)? else {
            return Ok(());
        };
        let at = |x: &Term| self.approx(x);
        Err(self.err(
            key,
            value,
            format!(
                "the contact point ({}, {}, {}) is not on the surface of body \"{name}\": {what}. \
                 Two bodies touch where both their surfaces are: move the point there, or the \
                 bodies (`body[{index}].position`) so that they touch at it",
                at(&point[0]),
                at(&point[1]),
                at(&point[2]),
            ),
        ))
    }

    /// Where `point` is, when it is not on the surface of the body `placed` (a sphere or a
    /// box; any point is on the surface of a body without a shape); `None` when it is on it.
    fn off_surface(
        &self,
        placed: &Placed,
        point: &Vec3,
        key: &str,
    ) -> Result<Option<String>, SceneError> {
        // The point in the body's axes, from its centre.
        let local = apply(
            &transpose(&placed.frame.r),
            &sub(point, &placed.frame.centre),
        );
        let scale = local
            .iter()
            .map(|x| self.magnitude(x))
            .fold(0.0, f64::max)
            .max(1e-300);
        let at = |x: &Term| self.approx(x);
        match &placed.shape {
            Some(Shape::Sphere(r)) => {
                let d = &dot(&local, &local) - &(r * r);
                if self.sign_at(&d, scale * scale, key)? != Some(0) {
                    let distance = self.magnitude(&dot(&local, &local)).sqrt();
                    return Ok(Some(format!(
                        "it is {distance:.6} m from the sphere's centre, whose radius is {} m",
                        at(r)
                    )));
                }
            }
            Some(Shape::Box(dims)) => {
                let half = |k: usize| &dims[k] / &Term::int(2);
                let mut on_face = false;
                let mut outside = false;
                for k in 0..3 {
                    let slack = &(&half(k) * &half(k)) - &(&local[k] * &local[k]);
                    match self.sign_at(&slack, scale * scale, key)? {
                        Some(s) if s < 0 => outside = true,
                        Some(0) => on_face = true,
                        _ => {}
                    }
                }
                if outside || !on_face {
                    return Ok(Some(format!(
                        "in the box's axes, from its centre, it is at ({}, {}, {}), {} the faces \
                         at ±({}, {}, {})",
                        at(&local[0]),
                        at(&local[1]),
                        at(&local[2]),
                        if outside {
                            "outside"
                        } else {
                            "inside, between"
                        },
                        at(&half(0)),
                        at(&half(1)),
                        at(&half(2)),
                    )));
                }
            }
            _ => {}
        }
        Ok(None)
    }

    /// Where a contact between two bodies is on a sphere or inside a face of a box, that
    /// surface has one normal there, and the contact's normal must be along it: out of the
    /// first body (`out`), into the second. Where two surfaces share a point with different
    /// normals the bodies cross each other (two spheres closer than their radii meet on a
    /// circle). On a box's edge or corner any normal of the other body's surface fits.
    fn along_surface_normal(
        &self,
        placed: &Placed,
        point: &Vec3,
        n: &Vec3,
        out: bool,
        name: &str,
        (key, value): (&str, Option<String>),
    ) -> Result<(), SceneError> {
        let local = apply(
            &transpose(&placed.frame.r),
            &sub(point, &placed.frame.centre),
        );
        // The outward normal of the surface at the point, in the world.
        let outward: Vec3 = match &placed.shape {
            Some(Shape::Sphere(_)) => sub(point, &placed.frame.centre),
            Some(Shape::Box(dims)) => {
                let scale = local
                    .iter()
                    .map(|x| self.magnitude(x))
                    .fold(0.0, f64::max)
                    .max(1e-300);
                let faces = self.faces_at(dims, &local, key)?;
                let [k] = faces[..] else {
                    return Ok(());
                };
                let mut e: Vec3 = zero();
                e[k] = match self.sign_at(&local[k], scale, key)? {
                    Some(s) if s < 0 => Term::int(-1),
                    _ => Term::int(1),
                };
                apply(&placed.frame.r, &e)
            }
            _ => return Ok(()),
        };
        let across = cross(n, &outward);
        let scale = n
            .iter()
            .chain(outward.iter())
            .map(|x| self.magnitude(x))
            .fold(0.0, f64::max)
            .max(1e-300);
        let mut parallel = true;
        for c in &across {
            parallel &= self.sign_at(c, scale * scale, key)? == Some(0);
        }
        let facing = self.sign_at(&dot(n, &outward), scale * scale, key)?;
        let right = if out { Some(1) } else { Some(-1) };
        if parallel && facing == right {
            return Ok(());
        }
        let at = |x: &Term| self.approx(x);
        let show = |v: &Vec3| format!("({}, {}, {})", at(&v[0]), at(&v[1]), at(&v[2]));
        Err(self.err(
            key,
            value,
            format!(
                "the normal is not the surface normal of body \"{name}\" at the contact point {}: \
                 its surface there faces {} ({}), and the contact's normal points out of the first \
                 body into the second. Two bodies that touch share their surface normal there; \
                 where a point lies on both surfaces with different normals, the bodies cross \
                 each other — move them apart so that they only touch",
                show(point),
                show(&outward),
                match &placed.shape {
                    Some(Shape::Sphere(_)) => "from its centre through the point",
                    _ => "across the face the point is on",
                },
            ),
        ))
    }

    /// The faces of a box (of sides `dims`) that the point `local` (box axes, from its centre)
    /// lies on: one inside a face, two on an edge, three at a corner.
    fn faces_at(&self, dims: &Vec3, local: &Vec3, key: &str) -> Result<Vec<usize>, SceneError> {
        let scale = local
            .iter()
            .map(|x| self.magnitude(x))
            .fold(0.0, f64::max)
            .max(1e-300);
        let mut faces = Vec::new();
        for k in 0..3 {
            let half = &dims[k] / &Term::int(2);
            let slack = &(&half * &half) - &(&local[k] * &local[k]);
            if self.sign_at(&slack, scale * scale, key)? == Some(0) {
                faces.push(k);
            }
        }
        Ok(faces)
    }

    /// For a box-shaped body, how many of its faces the world point is on; `None` otherwise.
    fn box_faces(
        &self,
        placed: &Placed,
        point: &Vec3,
        key: &str,
    ) -> Result<Option<usize>, SceneError> {
        let Some(Shape::Box(dims)) = &placed.shape else {
            return Ok(None);
        };
        let local = apply(
            &transpose(&placed.frame.r),
            &sub(point, &placed.frame.centre),
        );
        Ok(Some(self.faces_at(dims, &local, key)?.len()))
    }

    /// Whether two points are the same (see [`Reader::sign_at`]).
    fn same_point(&self, p: &Vec3, q: &Vec3, key: &str) -> Result<bool, SceneError> {
        let scale = p
            .iter()
            .chain(q.iter())
            .map(|x| self.magnitude(x))
            .fold(0.0, f64::max)
            .max(1e-300);
        for (a, b) in p.iter().zip(q) {
            if self.sign_of_difference(a, b, scale, key)? != Some(0) {
                return Ok(false);
            }
        }
        Ok(true)
    }

    /// A box resting on another body along an edge or a face, as against an obstacle: when a
    /// contact between two bodies is at a corner of the first body's box, every corner of that
    /// box as far along the contact's normal that lies on the second body's surface touches it
    /// too, and must be a contact between the two — else the box would pass through the other
    /// body there. `between`: (index, pair, point, normal) of each contact between two bodies.
    fn every_corner_on_a_body_named(
        &self,
        between: &[(usize, Pair, Vec3, Vec3)],
        placed: &[Placed],
        names: &[String],
    ) -> Result<(), SceneError> {
        for (i, pair, point, n) in between {
            let (a, Some(b)) = (pair.first, pair.second) else {
                continue;
            };
            let (Some(Shape::Box(dims)), Some(_)) = (&placed[a].shape, &placed[b].shape) else {
                continue;
            };
            let at = format!("contact[{i}]");
            let frame = &placed[a].frame;
            let down: Vec3 = n.each_ref().map(|x| -x);
            let Some(extreme) = self.touching(dims, frame, &down, &at)? else {
                continue;
            };
            let mut corners = Vec::with_capacity(extreme.len());
            let mut at_a_corner = false;
            for s in &extreme {
                let c = world(&frame.position, &frame.r, &Shape::corner(dims, *s));
                at_a_corner |= self.same_point(&c, point, &at)?;
                corners.push((*s, c));
            }
            if extreme.len() < 2 || !at_a_corner {
                continue;
            }
            let mut touching = Vec::new();
            let mut missing = Vec::new();
            for (s, c) in &corners {
                if self.off_surface(&placed[b], c, &at)?.is_some() {
                    continue;
                }
                touching.push(*s);
                let mut named = false;
                for (_, other, p, _) in between {
                    let same_pair = (other.first, other.second) == (a, Some(b))
                        || (other.first, other.second) == (b, Some(a));
                    named |= same_pair && self.same_point(p, c, &at)?;
                }
                if !named {
                    missing.push(*s);
                }
            }
            if let Some(first) = missing.first() {
                let list = |v: &[[i64; 3]]| {
                    v.iter()
                        .map(|s| format!("{s:?}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                };
                return Err(self.err(
                    &at,
                    None,
                    format!(
                        "the box \"{}\" touches \"{}\" at {} corners in this pose ({}), but the \
                         contacts between them name {} of them: at the others ({}) it would pass \
                         through \"{}\". Add a contact for each (`bodies = [\"{}\", \"{}\"]`, \
                         `corner = {first:?}`, the same normal)",
                        names[a],
                        names[b],
                        touching.len(),
                        list(&touching),
                        touching.len() - missing.len(),
                        list(&missing),
                        names[b],
                        names[a],
                        names[b],
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The `[[joint]]` tables (a simulated system's too: [`super::simulated_system`]).
    pub(crate) fn joints(
        &self,
        root: &Table,
        names: &[String],
    ) -> Result<Vec<SystemJointSpec>, SceneError> {
        let tables = match root.get("joint") {
            None => return Ok(Vec::new()),
            Some(Item::ArrayOfTables(a)) => a,
            Some(other) => {
                return Err(self.err(
                    "joint",
                    Some(short(other)),
                    "must be [[joint]] tables (kind, bodies, anchor, axis)",
                ));
            }
        };
        let mut out = Vec::with_capacity(tables.len());
        for (j, t) in tables.iter().enumerate() {
            let at = format!("joint[{j}]");
            self.only_keys(t, &at, &["kind", "bodies", "anchor", "axis"])?;
            let kind_item = self.get(t, "kind", &at)?;
            let kind_name = self.string(kind_item, &format!("{at}.kind"))?;
            let kind = SystemJointKind::NAMES
                .iter()
                .find(|(n, _)| *n == kind_name)
                .map(|(_, k)| *k)
                .ok_or_else(|| {
                    self.err(
                        &format!("{at}.kind"),
                        Some(format!("\"{kind_name}\"")),
                        "expected one of revolute, prismatic, cylindrical, spherical, planar, fixed",
                    )
                })?;
            let pair = self.body_list(
                self.get(t, "bodies", &at)?,
                &format!("{at}.bodies"),
                names,
                true,
            )?;
            let (anchor_needed, axis_needed) = kind.needs();
            let vector = |key: &str, needed: bool| -> Result<Option<[Number; 3]>, SceneError> {
                match (t.get(key), needed) {
                    (Some(item), true) => {
                        let v = self.triple(item, &format!("{at}.{key}"))?;
                        if key == "axis" {
                            self.nonzero(&v, &format!("{at}.axis"), "an axis")?;
                        }
                        Ok(Some(v))
                    }
                    (None, true) => Err(self.err(
                        &format!("{at}.{key}"),
                        None,
                        format!("missing (required for a {kind_name} joint)"),
                    )),
                    (Some(item), false) => Err(self.err(
                        &format!("{at}.{key}"),
                        Some(short(item)),
                        format!("a {kind_name} joint has no {key}; drop it"),
                    )),
                    (None, false) => Ok(None),
                }
            };
            out.push(SystemJointSpec {
                kind,
                pair,
                anchor: vector("anchor", anchor_needed)?,
                axis: vector("axis", axis_needed)?,
            });
        }
        Ok(out)
    }
}
