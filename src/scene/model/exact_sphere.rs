//! A scene to simulate read exactly ([`crate::simulate::exact`]): a frictionless sphere among
//! planes, every number as the exact value it was written as (`0.1` is 1/10, `sqrt(2)` a
//! radical), in the caller's exact type. The scene is first read and checked as any scene to
//! simulate ([`super::simulation`]); this reads again only what an exact run uses — the radius,
//! the position and velocity, gravity, the planes and each plane's coefficient (`k`, or
//! `k_energetic` under the LZB and energetic laws), the duration and the impact budget (20
//! unless `impacts` is given: exact numbers grow with every impact).

use toml_edit::Table;

use super::super::SceneError;
use super::super::read::{Reader, short};
use super::term::Term;
use crate::impact::friction::Restitution;
use crate::scalar::Scalar;
use crate::simulate::exact::{ExactPlane, ExactSphere, V};
use crate::simulate::{Law, Setup, Shape};

impl Reader<'_> {
    /// The exact sphere of a scene already read into `setup`.
    pub(crate) fn exact_sphere<T: Scalar>(
        &self,
        root: &Table,
        setup: &Setup,
    ) -> Result<ExactSphere<T>, SceneError> {
        if !matches!(setup.body.shape, Shape::Sphere { .. }) {
            return Err(self.err(
                "body.shape",
                None,
                "an exact run moves a sphere (its event times are roots of quadratics); a box, \
                 a rod or a turning body is integrated in f64",
            ));
        }
        if let Some(p) = setup.planes.iter().find(|p| p.law.mu > 0.0) {
            return Err(self.err(
                &format!("simulate.obstacle.{}", p.name),
                Some(format!("mu = {}", p.law.mu)),
                "an exact run is frictionless (friction couples the spin); drop mu or run in f64",
            ));
        }
        let energetic = matches!(
            setup.law,
            Law::Lzb | Law::Simultaneous(Restitution::Energetic)
        );
        let body = self.table(root, "body", "")?;
        let value = |n: &crate::number::Number, key: &str| -> Result<T, SceneError> {
            T::from_number(n).map_err(|e| self.err(key, Some(n.text.clone()), e))
        };
        let triple = |item: Option<&toml_edit::Item>, key: &str, default: [i64; 3]| match item {
            None => Ok(default
                .map(|d| T::from_rational(&num_rational::BigRational::from_integer(d.into())))),
            Some(item) => {
                let [a, b, c] = self.triple(item, key)?;
                Ok::<V<T>, SceneError>([value(&a, key)?, value(&b, key)?, value(&c, key)?])
            }
        };
        let shape = self.get(body, "shape", "body")?;
        let radius = shape
            .as_table_like()
            .and_then(|t| t.get("sphere"))
            .ok_or_else(|| self.err("body.shape", Some(short(shape)), "{ sphere = r }"))?;
        let radius = value(
            &self.number(radius, "body.shape.sphere")?,
            "body.shape.sphere",
        )?;
        let x = triple(body.get("position"), "body.position", [0, 0, 0])?;
        let v = triple(body.get("velocity"), "body.velocity", [0, 0, 0])?;
        let sim = self.table(root, "simulate", "")?;
        let gravity = match sim.get("gravity") {
            None => {
                let g = crate::number::parse_number("-9.81").expect("a number");
                [T::zero(), T::zero(), value(&g, "simulate.gravity")?]
            }
            Some(item) => triple(Some(item), "simulate.gravity", [0, 0, 0])?,
        };
        let duration = value(
            &self.number(self.get(sim, "duration", "simulate")?, "simulate.duration")?,
            "simulate.duration",
        )?;
        // each plane's coefficient: [simulate.obstacle.NAME], else [simulate] contact, else 1
        let key = if energetic { "k_energetic" } else { "k" };
        let coefficient =
            |t: Option<&toml_edit::Item>, at: &str| -> Result<Option<T>, SceneError> {
                let Some(t) = t.and_then(|t| t.as_table_like()) else {
                    return Ok(None);
                };
                // the energetic coefficient defaults to k, as the f64 reader takes it
                let item = t.get(key).or_else(|| t.get("k"));
                match item {
                    None => Ok(None),
                    Some(item) => {
                        let k = format!("{at}.{key}");
                        Ok(Some(value(&self.number(item, &k)?, &k)?))
                    }
                }
            };
        let base = coefficient(sim.get("contact"), "simulate.contact")?.unwrap_or_else(T::one);
        let obstacles = self.obstacles(root)?;
        let mut planes = Vec::with_capacity(obstacles.len());
        for (i, (o, p)) in obstacles.iter().zip(&setup.planes).enumerate() {
            let at = format!("obstacle[{i}]");
            let term = |t: &Term, key: &str| -> Result<T, SceneError> {
                match t {
                    Term::Rat(q) => Ok(T::from_rational(q)),
                    Term::Text(text, ..) => {
                        let n = crate::number::parse_number(text)
                            .map_err(|e| self.err(key, Some(text.clone()), e.to_string()))?;
                        value(&n, key)
                    }
                }
            };
            let n: V<T> = [
                term(&o.normal[0], &format!("{at}.normal"))?,
                term(&o.normal[1], &format!("{at}.normal"))?,
                term(&o.normal[2], &format!("{at}.normal"))?,
            ];
            let norm2 = n[0].clone() * &n[0] + n[1].clone() * &n[1] + n[2].clone() * &n[2];
            let norm = norm2.sqrt_exact().ok_or_else(|| {
                self.err(
                    &format!("{at}.normal"),
                    None,
                    "its length is not exact in this type (use --exact with radicals, or f64)",
                )
            })?;
            let normal = n.map(|c| c / norm.clone());
            let point = match &o.point {
                None => [T::zero(), T::zero(), T::zero()],
                Some(pt) => [
                    term(&pt[0], &format!("{at}.point"))?,
                    term(&pt[1], &format!("{at}.point"))?,
                    term(&pt[2], &format!("{at}.point"))?,
                ],
            };
            let own = sim
                .get("obstacle")
                .and_then(|t| t.as_table_like())
                .and_then(|t| t.get(&p.name));
            let k = match coefficient(own, &format!("simulate.obstacle.{}", p.name))? {
                Some(k) => k,
                None => base.clone(),
            };
            planes.push(ExactPlane {
                name: p.name.clone(),
                normal,
                point,
                k,
            });
        }
        Ok(ExactSphere {
            radius,
            x,
            v,
            gravity,
            planes,
            duration,
            // exact numbers grow with every impact (a Zeno sequence doubles its denominators):
            // an exact run lists 20 impacts unless [simulate] impacts says otherwise
            max_impacts: if sim.contains_key("impacts") {
                setup.options.max_impacts
            } else {
                20
            },
        })
    }
}
