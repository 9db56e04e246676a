//! A scene to simulate (`inertance simulate`): the body (shape, mass, pose, position, velocity
//! and angular velocity, as in any world-frame scene), the obstacle planes, and `[simulate]`.
//! It names no contacts: the simulation finds them, every feature of the shape against every
//! obstacle, and gives each the law of its obstacle.
//!
//! ```toml
//! [simulate]
//! gravity = [0, 0, -9.81]    # m/s², world (default)
//! duration = 5               # s (required)
//! impacts = 1000             # the most impacts (default 10 000)
//! output_step = 0.01         # trajectory spacing, s (default duration / 500)
//! simultaneity = 1e-9        # contacts this close in time strike as one impact, s (default 0)
//! tolerance = 1e-10          # relative, of the integration and the integrated laws
//! rest_speed = 1e-6          # m/s: slower after an impact, a contact persists (default 10⁻⁶ √(g L))
//! law = "simultaneous"       # or "unilateral", "lzb"
//! restitution = "newton"     # or "poisson", "energetic" (not with lzb)
//! plane = [0, 1, 0]          # a planar motion: a box's corners become its edges' midpoints
//! contact = { k = 0.5, mu = 0 }    # every obstacle's contacts: k, mu, k_energetic, stiffness, exponent
//! [simulate.obstacle.floor]        # one obstacle's, overriding
//! mu = 0.6
//! ```
//!
//! The shapes it moves: a box (its eight corners, or in a planar motion its four edges), a
//! sphere, a rod (its two ends). Every number is read as any scene number and used in f64.
//! A scene of several `[[body]]` spheres is a system ([`super::simulated_system`]), read with the
//! same `[simulate]` options and law ([`Reader::simulate_options`]).

use nalgebra::{Matrix3, Rotation3, UnitQuaternion};
use toml_edit::Table;

use super::super::SceneError;
use super::super::read::{Reader, short};
use super::shape::Shape;
use super::term::Term;
use crate::impact::friction::Restitution;
use crate::simulate::body::{Body, Shape as SimShape, State, V3};
use crate::simulate::impact::Law;
use crate::simulate::run::{Options, Setup};
use crate::simulate::world::{ContactLaw, Plane, gap};

/// The keys of `[simulate]` for one body.
pub(super) const SIMULATE_KEYS: &[&str] = &[
    "gravity",
    "duration",
    "impacts",
    "output_step",
    "simultaneity",
    "tolerance",
    "rest_speed",
    "law",
    "restitution",
    "plane",
    "contact",
    "obstacle",
];
const CONTACT_KEYS: &[&str] = &["k", "mu", "k_energetic", "stiffness", "exponent"];

fn v3(t: &[Term; 3]) -> V3 {
    V3::new(t[0].approx(), t[1].approx(), t[2].approx())
}

impl Reader<'_> {
    /// The simulation a document describes.
    pub(crate) fn simulation(&self, root: &Table) -> Result<Setup, SceneError> {
        if let Some(c) = root.get("contact") {
            return Err(self.err(
                "contact",
                Some(short(c)),
                "a scene to simulate names no contacts: every feature of the shape is tried \
                 against every [[obstacle]]; give the contacts' law in [simulate] contact",
            ));
        }
        for key in ["solve", "constraints", "surface"] {
            if let Some(item) = root.get(key) {
                return Err(self.err(
                    key,
                    Some(short(item)),
                    "`simulate` reads its law and options from [simulate]; constraints and \
                     surfaces are not simulated yet",
                ));
            }
        }
        let body = self.table(root, "body", "")?;
        self.only_keys(
            body,
            "body",
            &[
                "shape",
                "mass",
                "density",
                "pose",
                "position",
                "velocity",
                "angular_velocity",
                "material",
            ],
        )?;
        let Some(shape_item) = body.get("shape") else {
            return Err(self.err(
                "body.shape",
                None,
                "a body to simulate needs a shape: { box = [a, b, c] }, { sphere = r }, { rod = L } \
                 or { cylinder = [r, h] }",
            ));
        };
        let (props, shape) = self.mass_properties(body, "body")?;
        let shape = match shape {
            Some(Shape::Box(d)) => SimShape::Box { half: v3(&d) / 2.0 },
            Some(Shape::Sphere(r)) => SimShape::Sphere { radius: r.approx() },
            Some(Shape::Rod(l)) => SimShape::Rod {
                half_length: l.approx() / 2.0,
            },
            Some(Shape::Cylinder(r, h)) => SimShape::Cylinder {
                radius: r.approx(),
                half_height: h.approx() / 2.0,
            },
            _ => {
                return Err(self.err(
                    "body.shape",
                    Some(short(shape_item)),
                    "`simulate` moves a box, a sphere, a rod or a cylinder (point masses are \
                     not simulated yet)",
                ));
            }
        };
        let r = self.pose(body.get("pose"), "body")?;
        let rm = Matrix3::from_fn(|i, j| r[i][j].approx());
        let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(rm));
        let position = match body.get("position") {
            None => V3::zeros(),
            Some(p) => v3(&self.triple(p, "body.position")?.each_ref().map(Term::of)),
        };
        let mut inertia = Matrix3::from_fn(|i, j| props.inertia[i][j].approx());
        if let SimShape::Rod { .. } = shape {
            // no moment about the axis: completed as the impact scenes do (any c > 0 gives the
            // same motion of the ends, which have no moment about it)
            inertia[(2, 2)] = inertia[(0, 0)];
        }
        let mass = props.mass.approx();
        let velocity = v3(&self
            .triple(self.get(body, "velocity", "body")?, "body.velocity")?
            .each_ref()
            .map(Term::of));
        let omega = v3(&self
            .triple(
                self.get(body, "angular_velocity", "body")?,
                "body.angular_velocity",
            )?
            .each_ref()
            .map(Term::of));
        let sim = self.table(root, "simulate", "")?;
        self.only_keys(sim, "simulate", SIMULATE_KEYS)?;
        let mut world_plane = None;
        let plane_normal = match sim.get("plane") {
            None => None,
            Some(p) => {
                let n = self.triple(p, "simulate.plane")?;
                self.nonzero(&n, "simulate.plane", "the normal of the plane of motion")?;
                let n = v3(&n.each_ref().map(Term::of)).normalize();
                if velocity.dot(&n).abs() > 1e-12 * velocity.norm().max(1.0)
                    || omega.cross(&n).norm() > 1e-12 * omega.norm().max(1.0)
                {
                    return Err(self.err(
                        "simulate.plane",
                        Some(short(p)),
                        "the motion is not planar: v must lie in the plane and ω along its normal",
                    ));
                }
                world_plane = Some(n);
                // in body axes: the planar model reduces the box along it
                Some(rm.transpose() * n)
            }
        };
        let Some(body_model) = Body::new(mass, inertia, shape, plane_normal) else {
            return Err(self.err("body", None, "the inertia tensor is singular"));
        };
        let (gravity, mut options, law) = self.simulate_options(sim)?;
        if let Some(n) = plane_normal {
            if gravity.dot(&(rm * n)).abs() > 1e-12 * gravity.norm() {
                return Err(self.err(
                    "simulate.gravity",
                    None,
                    "gravity must lie in the plane of motion (`simulate.plane`)",
                ));
            }
        }
        let obstacles = self.obstacles(root)?;
        if obstacles.is_empty() {
            return Err(self.err(
                "obstacle",
                None,
                "a scene to simulate needs at least one [[obstacle]] plane",
            ));
        }
        let defaults = match sim.get("contact") {
            None => None,
            Some(item) => Some(item.as_table_like().ok_or_else(|| {
                self.err(
                    "simulate.contact",
                    Some(short(item)),
                    "a table: { k = …, mu = … }",
                )
            })?),
        };
        let base = self.contact_law(defaults, "simulate.contact", None)?;
        let overrides = match sim.get("obstacle") {
            None => None,
            Some(item) => Some(item.as_table_like().ok_or_else(|| {
                self.err(
                    "simulate.obstacle",
                    Some(short(item)),
                    "tables [simulate.obstacle.NAME]",
                )
            })?),
        };
        let names: Vec<String> = obstacles
            .iter()
            .enumerate()
            .map(|(i, o)| o.name.clone().unwrap_or_else(|| format!("obstacle[{i}]")))
            .collect();
        self.known_obstacles(overrides, &names)?;
        let mut planes = Vec::with_capacity(obstacles.len());
        for (i, o) in obstacles.iter().enumerate() {
            let normal = v3(&o.normal).normalize();
            let point = o.point.as_ref().map_or_else(V3::zeros, v3);
            let own = overrides.and_then(|t| t.get(&names[i])).map(|item| {
                item.as_table_like().ok_or_else(|| {
                    self.err(
                        &format!("simulate.obstacle.{}", names[i]),
                        Some(short(item)),
                        "a table of k, mu, …",
                    )
                })
            });
            let law = match own {
                None => base.clone(),
                Some(t) => self.contact_law(
                    Some(t?),
                    &format!("simulate.obstacle.{}", names[i]),
                    Some(&base),
                )?,
            };
            planes.push(Plane {
                name: names[i].clone(),
                normal,
                point,
                law,
            });
        }
        let start = State {
            x: position + rm * v3(&props.centre),
            q,
            v: velocity,
            w: omega,
        };
        let length = body_model
            .reach()
            .max(start.x.norm())
            .max(f64::MIN_POSITIVE);
        for f in &body_model.features {
            for p in &planes {
                let g = gap(f, p, &start);
                if g.gap < -1e-9 * length {
                    return Err(self.err(
                        "body.position",
                        None,
                        format!(
                            "the body starts inside obstacle \"{}\": its {} is {:.6e} m beyond the plane",
                            p.name,
                            f.label(),
                            -g.gap
                        ),
                    ));
                }
            }
        }
        options.rest_speed = self.rest_speed(sim, &gravity, length, velocity.norm())?;
        Ok(Setup {
            body: body_model,
            planes,
            law,
            start,
            options,
            plane: world_plane,
        })
    }

    /// Every `[simulate.obstacle.NAME]` names an obstacle of `names`.
    pub(super) fn known_obstacles(
        &self,
        overrides: Option<&dyn toml_edit::TableLike>,
        names: &[String],
    ) -> Result<(), SceneError> {
        for (name, _) in overrides.into_iter().flat_map(|t| t.iter()) {
            if !names.iter().any(|n| n == name) {
                return Err(self.err(
                    &format!("simulate.obstacle.{name}"),
                    None,
                    format!("no such obstacle; the scene has: {}", names.join(", ")),
                ));
            }
        }
        Ok(())
    }

    /// `[simulate]`'s gravity, options and law, shared by one body and a system of spheres
    /// (`rest_speed` left 0: [`Reader::rest_speed`] sets it once the scene's scales are known).
    pub(super) fn simulate_options(&self, sim: &Table) -> Result<(V3, Options, Law), SceneError> {
        let gravity = match sim.get("gravity") {
            None => V3::new(0.0, 0.0, -9.81),
            Some(g) => v3(&self.triple(g, "simulate.gravity")?.each_ref().map(Term::of)),
        };
        let positive = |key: &str| -> Result<Option<f64>, SceneError> {
            match sim.get(key) {
                None => Ok(None),
                Some(item) => {
                    let n = self.number(item, &format!("simulate.{key}"))?;
                    self.positive(&n, &format!("simulate.{key}"), "must be positive")?;
                    Ok(Some(n.approx))
                }
            }
        };
        let Some(duration) = positive("duration")? else {
            return Err(self.err(
                "simulate.duration",
                None,
                "how long to simulate, in seconds",
            ));
        };
        let impacts = match sim.get("impacts") {
            None => 10_000,
            Some(item) => match item.as_integer() {
                Some(n) if n > 0 => n as usize,
                _ => {
                    return Err(self.err(
                        "simulate.impacts",
                        Some(short(item)),
                        "the most impacts: a positive integer",
                    ));
                }
            },
        };
        let output_step = positive("output_step")?.unwrap_or(duration / 500.0);
        let simultaneity = match sim.get("simultaneity") {
            None => 0.0,
            Some(item) => {
                let n = self.number(item, "simulate.simultaneity")?;
                if !(n.approx >= 0.0 && n.approx.is_finite()) {
                    return Err(self.err(
                        "simulate.simultaneity",
                        Some(short(item)),
                        "a time ≥ 0, in seconds",
                    ));
                }
                n.approx
            }
        };
        let tolerance = positive("tolerance")?.unwrap_or(1e-10);
        if tolerance >= 1.0 {
            return Err(self.err("simulate.tolerance", None, "a relative tolerance in (0, 1)"));
        }
        let law_name = match sim.get("law") {
            None => "simultaneous".to_string(),
            Some(item) => self.string(item, "simulate.law")?,
        };
        let restitution = match sim.get("restitution") {
            None => None,
            Some(item) => {
                let name = self.string(item, "simulate.restitution")?;
                Some(
                    Restitution::ALL
                        .into_iter()
                        .find(|r| r.name() == name)
                        .ok_or_else(|| {
                            self.err(
                                "simulate.restitution",
                                Some(short(item)),
                                "one of \"newton\", \"poisson\", \"energetic\"",
                            )
                        })?,
                )
            }
        };
        let law = match (law_name.as_str(), restitution) {
            ("simultaneous", r) => Law::Simultaneous(r.unwrap_or(Restitution::Newton)),
            ("unilateral", Some(Restitution::Energetic)) => {
                return Err(self.err(
                    "simulate.restitution",
                    Some("\"energetic\"".into()),
                    "the unilateral law is integrated with Newton's and Poisson's restitution",
                ));
            }
            ("unilateral", r) => Law::Unilateral(r.unwrap_or(Restitution::Newton)),
            ("lzb", None) => Law::Lzb,
            ("lzb", Some(r)) => {
                return Err(self.err(
                    "simulate.restitution",
                    Some(format!("\"{}\"", r.name())),
                    "the LZB law has its own restitution (each contact's k_energetic, else k): drop it",
                ));
            }
            (other, _) => {
                return Err(self.err(
                    "simulate.law",
                    Some(format!("\"{other}\"")),
                    "one of \"simultaneous\", \"unilateral\", \"lzb\"",
                ));
            }
        };
        Ok((
            gravity,
            Options {
                gravity,
                duration,
                max_impacts: impacts,
                output_step,
                simultaneity,
                tolerance,
                rest_speed: 0.0,
            },
            law,
        ))
    }

    /// `[simulate] rest_speed`, by default 10⁻⁶ of the larger of √(|g| L) and the fastest
    /// initial speed.
    pub(super) fn rest_speed(
        &self,
        sim: &Table,
        gravity: &V3,
        length: f64,
        fastest: f64,
    ) -> Result<f64, SceneError> {
        match sim.get("rest_speed") {
            Some(item) => {
                let n = self.number(item, "simulate.rest_speed")?;
                self.positive(&n, "simulate.rest_speed", "must be positive")?;
                Ok(n.approx)
            }
            None => Ok(1e-6
                * (gravity.norm() * length)
                    .sqrt()
                    .max(fastest)
                    .max(f64::MIN_POSITIVE)),
        }
    }

    /// A contact law table (`k`, `mu`, `k_energetic`, `stiffness`, `exponent`) over `base`.
    pub(super) fn contact_law(
        &self,
        t: Option<&dyn toml_edit::TableLike>,
        at: &str,
        base: Option<&ContactLaw>,
    ) -> Result<ContactLaw, SceneError> {
        let mut law = base.cloned().unwrap_or(ContactLaw {
            k: 1.0,
            k_energetic: 1.0,
            mu: 0.0,
            stiffness: 1.0,
            exponent: 1.5,
        });
        let Some(t) = t else {
            return Ok(law);
        };
        self.only_keys(t, at, CONTACT_KEYS)?;
        let mut energetic_given = false;
        for (key, item) in t.iter() {
            let k = format!("{at}.{key}");
            let n = self.number(item, &k)?;
            match key {
                "k" | "k_energetic" => {
                    let n = self.coefficient(n, &k)?;
                    if key == "k" {
                        law.k = n.approx;
                    } else {
                        law.k_energetic = n.approx;
                        energetic_given = true;
                    }
                }
                "mu" => law.mu = self.friction(n, &k)?.approx,
                _ => {
                    self.positive(&n, &k, "must be positive")?;
                    if key == "stiffness" {
                        law.stiffness = n.approx;
                    } else {
                        law.exponent = n.approx;
                    }
                }
            }
        }
        if !energetic_given && t.get("k").is_some() {
            law.k_energetic = law.k;
        }
        Ok(law)
    }
}
