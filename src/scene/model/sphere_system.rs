//! A system of spheres to simulate (`inertance simulate` on a scene of several `[[body]]`):
//! each body a sphere (`shape = { sphere = r }`, a `mass` or `density`, `position`,
//! `velocity`, an optional `angular_velocity` — kept by frictionless contacts and not reported
//! — and an optional `material` for Hertz's stiffness), the obstacle planes (none is fine: a
//! cradle in space), and `[simulate]` as for one body. The simulation watches every sphere
//! against every obstacle and every pair of spheres against each other.
//!
//! ```toml
//! [simulate]
//! law = "lzb"
//! contact = { k = 1, stiffness = "hertz" }   # every contact (spheres and planes)
//! [simulate.obstacle.wall]                   # the contacts with one obstacle
//! k = 1
//! [[simulate.pair]]                          # the contact of two spheres
//! bodies = ["bead 1", "bead 2"]
//! stiffness = 1e9
//! ```
//!
//! `stiffness = "hertz"` takes K = (4/3) E* √R* from the two sides' radii and materials
//! ([`super::hertz`]; η = 3/2). Contacts are frictionless: `mu` > 0 is refused.

use toml_edit::{Item, Table, TableLike};

use super::super::SceneError;
use super::super::read::{Reader, short};
use super::hertz::{Material, Surface, hertz_stiffness};
use super::shape::Shape;
use super::simulation::SIMULATE_KEYS;
use super::term::Term;
use crate::simulate::body::V3;
use crate::simulate::system::gaps::gap;
use crate::simulate::system::{Sphere, SystemSetup, SystemState, Touch};
use crate::simulate::world::{ContactLaw, Plane};

fn v3(t: &[Term; 3]) -> V3 {
    V3::new(t[0].approx(), t[1].approx(), t[2].approx())
}

/// A contact law, and whether its stiffness is Hertz's.
type Law = (ContactLaw, bool);

impl Reader<'_> {
    /// The system of spheres a document of several `[[body]]` describes.
    pub(crate) fn sphere_system(&self, root: &Table) -> Result<SystemSetup, SceneError> {
        if let Some(c) = root.get("contact") {
            return Err(self.err(
                "contact",
                Some(short(c)),
                "a scene to simulate names no contacts: every pair of spheres and every sphere \
                 and [[obstacle]] are watched; give their law in [simulate] contact",
            ));
        }
        for key in ["solve", "joint", "constraints", "surface"] {
            if let Some(item) = root.get(key) {
                return Err(self.err(
                    key,
                    Some(short(item)),
                    "`simulate` reads its law and options from [simulate]; joints, constraints \
                     and surfaces are not simulated",
                ));
            }
        }
        let Some(Item::ArrayOfTables(bodies)) = root.get("body") else {
            return Err(self.err("body", None, "[[body]] tables"));
        };
        let mut spheres = Vec::new();
        let mut materials: Vec<Option<Material>> = Vec::new();
        let mut x = Vec::new();
        let mut v = Vec::new();
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
                    "velocity",
                    "angular_velocity",
                    "material",
                ],
            )?;
            let name = match body.get("name") {
                Some(n) => self.string(n, &format!("{at}.name"))?,
                None => at.clone(),
            };
            if spheres.iter().any(|s: &Sphere| s.name == name) {
                return Err(self.err(
                    &format!("{at}.name"),
                    Some(format!("\"{name}\"")),
                    "two bodies of one name: contacts are named by their bodies",
                ));
            }
            let (props, shape) = self.mass_properties(body, &at)?;
            let radius = match shape {
                Some(Shape::Sphere(r)) => r.approx(),
                _ => {
                    return Err(self.err(
                        &format!("{at}.shape"),
                        body.get("shape").map(short),
                        "a system to simulate is made of spheres: shape = { sphere = r } \
                         (other shapes move only alone)",
                    ));
                }
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
            if let Some(w) = body.get("angular_velocity") {
                self.triple(w, &format!("{at}.angular_velocity"))?;
            }
            materials.push(self.material(body, &at)?);
            spheres.push(Sphere {
                name,
                mass: props.mass.approx(),
                radius,
            });
            x.push(position + v3(&props.centre));
            v.push(velocity);
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
                            spheres.iter().position(|s| s.name == n)
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
                                spheres
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
        let start = SystemState { x, v };
        let mut failure: Option<SceneError> = None;
        let candidates = SystemSetup::candidates(spheres.len(), planes.len(), |touch| {
            let (l, hertz) = match *touch {
                Touch::Plane { plane, .. } => plane_laws[plane].clone(),
                Touch::Pair { a, b } => pair_laws
                    .iter()
                    .rev()
                    .find(|(p, _)| *p == (a, b))
                    .map_or_else(|| base.clone(), |(_, l)| l.clone()),
            };
            if !hertz {
                return l;
            }
            let (first, second, whose) = match *touch {
                Touch::Plane { body, plane } => (
                    (Surface::Sphere(spheres[body].radius), materials[body], body),
                    (Surface::Flat, obstacles[plane].material),
                    format!("obstacle \"{}\"", names[plane]),
                ),
                Touch::Pair { a, b } => (
                    (Surface::Sphere(spheres[a].radius), materials[a], a),
                    (Surface::Sphere(spheres[b].radius), materials[b]),
                    format!("body \"{}\"", spheres[b].name),
                ),
            };
            let (Some(m1), Some(m2)) = (first.1, second.1) else {
                let who = if first.1.is_none() {
                    format!("body \"{}\"", spheres[first.2].name)
                } else {
                    whose
                };
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
            match hertz_stiffness((first.0, m1), (second.0, m2)) {
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
        let reach = spheres.iter().map(|s| s.radius).fold(0.0, f64::max);
        let length = start
            .x
            .iter()
            .map(|p| p.norm())
            .fold(reach, f64::max)
            .max(f64::MIN_POSITIVE);
        for c in &candidates {
            let g = gap(&c.touch, &spheres, &planes, &start);
            if g.gap < -1e-9 * length {
                let (a, b) = c.touch.name(&spheres, &planes);
                return Err(self.err(
                    "body.position",
                    None,
                    format!(
                        "\"{a}\" starts inside \"{b}\": they overlap by {:.6e} m",
                        -g.gap
                    ),
                ));
            }
        }
        let fastest = start.v.iter().map(|p| p.norm()).fold(0.0, f64::max);
        options.rest_speed = self.rest_speed(sim, &gravity, length, fastest)?;
        Ok(SystemSetup {
            spheres,
            planes,
            candidates,
            law,
            start,
            options,
        })
    }

    /// A contact law table whose `stiffness` may be `"hertz"`, over `base`; friction refused.
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
        if law.mu != 0.0 {
            return Err(self.err(
                &format!("{at}.mu"),
                Some(law.mu.to_string()),
                "contacts between spheres are frictionless for now: drop mu",
            ));
        }
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
