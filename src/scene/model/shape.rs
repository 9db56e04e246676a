//! Shapes and their mass properties, in body axes: the mass m, the centre of mass c and the
//! central inertia tensor J_C, exact wherever the dimensions are.
//!
//! Solids are homogeneous and centred on the body origin, their edges or axis along the body
//! axes (axis of revolution: z):
//!
//! ```text
//! box [a, b, c]   V = abc          J_C = m/12 diag(b² + c², a² + c², a² + b²)
//! sphere r        V = 4/3 π r³     J_C = 2/5 m r² I
//! cylinder [r, h] V = π r² h       J_C = diag(m(3r² + h²)/12, m(3r² + h²)/12, m r²/2)
//! rod L           (thin)           J_C = diag(m L²/12, m L²/12, 0)
//! points          m = Σ mᵢ,  c = Σ mᵢ pᵢ / m,  J_C = Σ mᵢ (|dᵢ|² I − dᵢ dᵢᵀ),  dᵢ = pᵢ − c
//! ```
//!
//! A solid takes `mass` or `density` (m = ρV); point masses carry their own.

use toml_edit::{Item, Table};

use super::super::SceneError;
use super::super::read::{Reader, short};
use super::term::{Mat3, Term, Vec3, add, dot, scale, sub, zero};

/// A shape as read: its kind and dimensions (what corners and touching points need).
#[derive(Clone, Debug)]
pub(crate) enum Shape {
    /// Edge lengths (a, b, c) along body x, y, z.
    Box(Vec3),
    /// Radius.
    Sphere(Term),
    /// Radius and height; axis body z.
    Cylinder(Term, Term),
    /// Length; along body z.
    Rod(Term),
    /// Point masses (mᵢ, pᵢ).
    Points(Vec<(Term, Vec3)>),
}

/// Mass properties in body axes.
pub(crate) struct MassProperties {
    /// m.
    pub(crate) mass: Term,
    /// c, body axes.
    pub(crate) centre: Vec3,
    /// J_C, body axes.
    pub(crate) inertia: Mat3,
}

const KINDS: &str = "box = [a, b, c], sphere = r, cylinder = [r, h], rod = L, points = [{ mass = m, at = [x, y, z] }, …]";

impl Reader<'_> {
    /// `[body] shape`.
    pub(super) fn shape(&self, item: &Item, key: &str) -> Result<Shape, SceneError> {
        let t = item
            .as_table_like()
            .filter(|t| t.len() == 1)
            .ok_or_else(|| {
                self.err(
                    key,
                    Some(short(item)),
                    format!("must name one shape: {{ {KINDS} }}"),
                )
            })?;
        let (kind, value) = t.iter().next().expect("one entry");
        let at = format!("{key}.{kind}");
        let positive = |n: crate::number::Number, k: &str| -> Result<Term, SceneError> {
            self.positive(&n, k, "a dimension must be positive")?;
            Ok(Term::of(&n))
        };
        Ok(match kind {
            "box" => {
                let d = self.triple(value, &at)?;
                let mut out = Vec::with_capacity(3);
                for (i, n) in d.into_iter().enumerate() {
                    out.push(positive(n, &format!("{at}[{i}]"))?);
                }
                Shape::Box([out[0].clone(), out[1].clone(), out[2].clone()])
            }
            "sphere" => Shape::Sphere(positive(self.number(value, &at)?, &at)?),
            "rod" => Shape::Rod(positive(self.number(value, &at)?, &at)?),
            "cylinder" => {
                let arr = value
                    .as_array()
                    .filter(|a| a.len() == 2)
                    .ok_or_else(|| self.err(&at, Some(short(value)), "must be [radius, height]"))?;
                let r = positive(
                    self.number_value(&arr.get(0).expect("two").clone(), &format!("{at}[0]"))?,
                    &format!("{at}[0]"),
                )?;
                let h = positive(
                    self.number_value(&arr.get(1).expect("two").clone(), &format!("{at}[1]"))?,
                    &format!("{at}[1]"),
                )?;
                Shape::Cylinder(r, h)
            }
            "points" => {
                let list = match value {
                    Item::ArrayOfTables(a) => a.iter().cloned().collect::<Vec<Table>>(),
                    other => other
                        .as_array()
                        .map(|a| {
                            a.iter()
                                .filter_map(|v| v.as_inline_table().map(|t| t.clone().into_table()))
                                .collect::<Vec<Table>>()
                        })
                        .filter(|v| v.len() == other.as_array().map_or(0, |a| a.len()))
                        .ok_or_else(|| {
                            self.err(
                                &at,
                                Some(short(other)),
                                "must be a list of point masses [{ mass = m, at = [x, y, z] }, …]",
                            )
                        })?,
                };
                if list.is_empty() {
                    return Err(self.err(&at, Some("[]".into()), "list at least one point mass"));
                }
                let mut points = Vec::with_capacity(list.len());
                for (i, p) in list.iter().enumerate() {
                    let pk = format!("{at}[{i}]");
                    self.only_keys(p, &pk, &["mass", "at"])?;
                    let m = self.number(self.get(p, "mass", &pk)?, &format!("{pk}.mass"))?;
                    self.positive(&m, &format!("{pk}.mass"), "a mass must be positive")?;
                    let x = self.triple(self.get(p, "at", &pk)?, &format!("{pk}.at"))?;
                    points.push((Term::of(&m), x.each_ref().map(Term::of)));
                }
                Shape::Points(points)
            }
            other => {
                return Err(self.err(
                    &format!("{key}.{other}"),
                    Some(short(value)),
                    format!("unknown shape; expected one of: {KINDS}"),
                ));
            }
        })
    }
}

impl Shape {
    /// The volume of a solid (`None` for point masses).
    pub(crate) fn volume(&self) -> Option<Term> {
        let pi = Term::constant("pi");
        Some(match self {
            Shape::Box([a, b, c]) => &(a * b) * c,
            Shape::Sphere(r) => &(&Term::constant("4/3*pi") * &r.square()) * r,
            Shape::Cylinder(r, h) => &(&pi * &r.square()) * h,
            Shape::Rod(_) | Shape::Points(_) => return None,
        })
    }

    /// The mass properties for the mass `m` (ignored for point masses, which carry theirs).
    pub(crate) fn mass_properties(&self, m: &Term) -> MassProperties {
        let twelfth = |x: Term| &(m * &x) / &Term::int(12);
        let diag = |a: Term, b: Term, c: Term| -> Mat3 {
            [
                [a, Term::int(0), Term::int(0)],
                [Term::int(0), b, Term::int(0)],
                [Term::int(0), Term::int(0), c],
            ]
        };
        let solid = |inertia: Mat3| MassProperties {
            mass: m.clone(),
            centre: zero(),
            inertia,
        };
        match self {
            Shape::Box([a, b, c]) => {
                let (a2, b2, c2) = (a.square(), b.square(), c.square());
                solid(diag(
                    twelfth(&b2 + &c2),
                    twelfth(&a2 + &c2),
                    twelfth(&a2 + &b2),
                ))
            }
            Shape::Sphere(r) => {
                let j = &(&Term::constant("2/5") * m) * &r.square();
                solid(diag(j.clone(), j.clone(), j))
            }
            Shape::Cylinder(r, h) => {
                let side = twelfth(&(&Term::int(3) * &r.square()) + &h.square());
                let axial = &(m * &r.square()) / &Term::int(2);
                solid(diag(side.clone(), side, axial))
            }
            Shape::Rod(l) => {
                let side = twelfth(l.square());
                solid(diag(side.clone(), side, Term::int(0)))
            }
            Shape::Points(points) => {
                let mass = points.iter().fold(Term::int(0), |acc, (mi, _)| &acc + mi);
                let moment = points
                    .iter()
                    .fold(zero(), |acc, (mi, p)| add(&acc, &scale(mi, p)));
                let centre = moment.map(|x| &x / &mass);
                let mut inertia: Mat3 = std::array::from_fn(|_| zero());
                for (mi, p) in points {
                    let d = sub(p, &centre);
                    let d2 = dot(&d, &d);
                    for i in 0..3 {
                        for j in 0..3 {
                            let e = if i == j {
                                &d2 - &(&d[i] * &d[j])
                            } else {
                                -&(&d[i] * &d[j])
                            };
                            inertia[i][j] = &inertia[i][j] + &(mi * &e);
                        }
                    }
                }
                MassProperties {
                    mass,
                    centre,
                    inertia,
                }
            }
        }
    }

    /// A box's corner with the signs `s` (each ±1): (s₀a/2, s₁b/2, s₂c/2).
    pub(crate) fn corner(dims: &Vec3, s: [i64; 3]) -> Vec3 {
        std::array::from_fn(|i| {
            &dims[i] * &Term::Rat(num_rational::BigRational::new(s[i].into(), 2.into()))
        })
    }

    /// The eight sign patterns of a box's corners.
    pub(crate) fn corners() -> Vec<[i64; 3]> {
        let mut out = Vec::with_capacity(8);
        for x in [-1, 1] {
            for y in [-1, 1] {
                for z in [-1, 1] {
                    out.push([x, y, z]);
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::BigRational;

    fn int(n: i64) -> Term {
        Term::int(n)
    }

    #[test]
    fn a_box_has_the_textbook_moments() {
        let b = Shape::Box([int(2), int(4), int(6)]);
        let p = b.mass_properties(&int(3));
        // m/12 (b² + c²) = 3/12 · 52 = 13; (a² + c²): 10; (a² + b²): 5.
        assert_eq!(p.inertia[0][0], int(13));
        assert_eq!(p.inertia[1][1], int(10));
        assert_eq!(p.inertia[2][2], int(5));
        assert!(p.inertia[0][1].is_zero());
    }

    #[test]
    fn point_masses_give_the_centre_and_the_central_tensor() {
        // Two unit masses at (±1, 0, 0) and one of mass 2 at (0, 3, 0): m = 4, c = (0, 3/2, 0).
        let pts = Shape::Points(vec![
            (int(1), [int(1), int(0), int(0)]),
            (int(1), [int(-1), int(0), int(0)]),
            (int(2), [int(0), int(3), int(0)]),
        ]);
        let p = pts.mass_properties(&int(0));
        assert_eq!(p.mass, int(4));
        assert_eq!(p.centre[1], Term::Rat(BigRational::new(3.into(), 2.into())));
        // J_xx = Σ m (y² + z²) about c = 1·9/4 + 1·9/4 + 2·9/4 = 9.
        assert_eq!(p.inertia[0][0], int(9));
        // J_yy = Σ m (x² + z²) = 2; J_zz = 11; no products (symmetric about the y axis).
        assert_eq!(p.inertia[1][1], int(2));
        assert_eq!(p.inertia[2][2], int(11));
        assert!(p.inertia[0][1].is_zero());
    }
}
