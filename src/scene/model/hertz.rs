//! Hertz's contact stiffness from the shapes and materials that touch: a contact's
//! `stiffness = "hertz"` under the LZB law (issue 25; Johnson, *Contact Mechanics*, 1985, §4.2).
//!
//! Two elastic bodies touching at a point, with radii of curvature R₁, R₂ there (a plane's is
//! infinite) and materials (E₁, ν₁), (E₂, ν₂), press with the force
//!
//! ```text
//! F = K δ^(3/2),   K = (4/3) E* √R*,   1/E* = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂,   1/R* = 1/R₁ + 1/R₂
//! ```
//!
//! (Johnson eq. 4.22–4.23), so η = 3/2. Two equal spheres of one material give Siconos'
//! `ChainOfBalls` stiffness √(R/2) · (2/3) E/(1 − ν²). A sphere on a plane: R* = R.
//!
//! The curvature of a surface at the contact comes from the shape: a sphere's 1/R, an
//! obstacle plane's or a box face's 0. A box's edge or corner has no finite curvature (Hertz's
//! law does not hold there), a body without a shape has none known, and two planes touch over
//! an area: each is refused with the key that asked for Hertz. The materials are each body's and
//! each obstacle's `material = { young = E, poisson = ν }` (E in Pa, ν in (−1, 1/2]).

use toml_edit::Table;

use crate::number::{Number, parse_number};
use crate::scene::SceneError;
use crate::scene::read::short;

use super::Reader;
use super::shape::Shape;

/// An isotropic linear-elastic material.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Material {
    /// Young's modulus E (Pa).
    pub(crate) young: f64,
    /// Poisson's ratio ν.
    pub(crate) poisson: f64,
}

/// A surface at a contact point, as Hertz's law sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Surface {
    /// Curved with radius R (a sphere).
    Sphere(f64),
    /// Flat (an obstacle plane, inside a box face).
    Flat,
    /// No curvature Hertz's law can use, and why.
    Unknown(&'static str),
}

/// K = (4/3) E* √R* (module docs), or why not.
pub(crate) fn hertz_stiffness(
    (s1, m1): (Surface, Material),
    (s2, m2): (Surface, Material),
) -> Result<f64, String> {
    let curvature = |s: Surface| match s {
        Surface::Sphere(r) => Ok(1.0 / r),
        Surface::Flat => Ok(0.0),
        Surface::Unknown(why) => Err(why.to_string()),
    };
    let k = curvature(s1)? + curvature(s2)?;
    if k <= 0.0 {
        return Err("two flat surfaces touch over an area, not at a point".to_string());
    }
    let compliance =
        (1.0 - m1.poisson * m1.poisson) / m1.young + (1.0 - m2.poisson * m2.poisson) / m2.young;
    let stiffness = (4.0 / 3.0) / compliance * (1.0 / k).sqrt();
    if stiffness.is_finite() && stiffness > 0.0 {
        Ok(stiffness)
    } else {
        Err(format!(
            "the stiffness is not a finite positive number ({stiffness})"
        ))
    }
}

impl Reader<'_> {
    /// `material = { young = E, poisson = ν }` of the table at `at`, if given.
    pub(super) fn material(&self, t: &Table, at: &str) -> Result<Option<Material>, SceneError> {
        let Some(item) = t.get("material") else {
            return Ok(None);
        };
        let key = format!("{at}.material");
        let m = item.as_table_like().ok_or_else(|| {
            self.err(
                &key,
                Some(short(item)),
                "must be a table: material = { young = 2.1e11, poisson = 0.3 } (Pa, and a ratio)",
            )
        })?;
        let value = |name: &str, rule: &str, ok: &dyn Fn(f64) -> bool| -> Result<f64, SceneError> {
            let path = format!("{key}.{name}");
            let item = m
                .get(name)
                .ok_or_else(|| self.err(&path, None, format!("missing: {rule}")))?;
            let n = self.number(item, &path)?;
            if n.symbols.is_empty() && ok(n.approx) {
                Ok(n.approx)
            } else {
                Err(self.err(&path, Some(n.text), rule))
            }
        };
        for (name, _) in m.iter() {
            if name != "young" && name != "poisson" {
                return Err(self.err(
                    &format!("{key}.{name}"),
                    None,
                    "unknown key: a material has `young` (E, Pa) and `poisson` (ν)",
                ));
            }
        }
        Ok(Some(Material {
            young: value(
                "young",
                "Young's modulus E must be a number > 0 (Pa)",
                &|x| x.is_finite() && x > 0.0,
            )?,
            poisson: value(
                "poisson",
                "Poisson's ratio ν must be a number in (−1, 1/2]",
                &|x| x > -1.0 && x <= 0.5,
            )?,
        }))
    }

    /// What Hertz's law sees of `shape` at a contact point: a sphere's radius; a box is flat
    /// where the point is inside one face (`box_faces` = the number of faces it is on, `None`
    /// for a corner) and refused on an edge or a corner.
    pub(super) fn hertz_surface(&self, shape: Option<&Shape>, box_faces: Option<usize>) -> Surface {
        match (shape, box_faces) {
            (Some(Shape::Sphere(r)), _) => Surface::Sphere(self.magnitude(r)),
            (Some(Shape::Box(_)), Some(1)) => Surface::Flat,
            (Some(Shape::Box(_)), _) => Surface::Unknown(
                "the box touches at an edge or a corner, where its curvature is not finite",
            ),
            _ => Surface::Unknown("a body without a sphere or box `shape` has no known curvature"),
        }
    }

    /// Set contact `at`'s LZB stiffness to Hertz's from the two sides' surfaces and materials
    /// (`None`: that side gave no `material`, named by `whose`), and its exponent to 3/2.
    pub(super) fn set_hertz(
        &self,
        at: &str,
        stiffness: &mut Option<Number>,
        exponent: &mut Option<Number>,
        sides: [(Surface, Option<Material>, &str); 2],
    ) -> Result<(), SceneError> {
        let key = format!("{at}.stiffness");
        let value = Some("\"hertz\"".to_string());
        for (surface, _, whose) in &sides {
            if let Surface::Unknown(why) = surface {
                return Err(self.err(
                    &key,
                    value.clone(),
                    format!(
                        "Hertz's law does not apply at {whose}: {why}; give `stiffness` as a \
                         number"
                    ),
                ));
            }
        }
        let mut materials = [None; 2];
        for (k, (_, m, whose)) in sides.iter().enumerate() {
            materials[k] = Some(m.ok_or_else(|| {
                self.err(
                    &key,
                    value.clone(),
                    format!(
                        "Hertz's stiffness needs the material of {whose}: give it \
                         `material = {{ young = E, poisson = ν }}`"
                    ),
                )
            })?);
        }
        let [m1, m2] = materials.map(|m| m.expect("set above"));
        let k = hertz_stiffness((sides[0].0, m1), (sides[1].0, m2)).map_err(|why| {
            self.err(
                &key,
                value.clone(),
                format!("Hertz's law does not apply here: {why}; give `stiffness` as a number"),
            )
        })?;
        if let Some(e) = exponent
            && (e.approx != 1.5 || !e.symbols.is_empty())
        {
            return Err(self.err(
                &format!("{at}.exponent"),
                Some(e.text.clone()),
                "Hertz's stiffness goes with the exponent 3/2: drop `exponent`, or give `stiffness` \
                 as a number",
            ));
        }
        *stiffness = Some(parse_number(&format!("{k:e}")).expect("a float's text is a number"));
        *exponent = Some(parse_number("1.5").expect("1.5 is a number"));
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const STEEL: Material = Material {
        young: 203.0e9,
        poisson: 0.3,
    };

    #[test]
    fn two_equal_spheres_give_siconos_chain_stiffness() {
        let r = 0.01;
        let k =
            hertz_stiffness((Surface::Sphere(r), STEEL), (Surface::Sphere(r), STEEL)).expect("k");
        let siconos = (r / 2.0_f64).sqrt() * (2.0 / 3.0) * STEEL.young / (1.0 - 0.09);
        assert!(
            (k - siconos).abs() <= 4.0 * f64::EPSILON * siconos,
            "{k} vs {siconos}"
        );
    }

    #[test]
    fn a_sphere_on_a_plane_and_what_is_refused() {
        let k = hertz_stiffness((Surface::Sphere(0.02), STEEL), (Surface::Flat, STEEL)).expect("k");
        let e_star = STEEL.young / (2.0 * (1.0 - 0.09));
        assert!((k - 4.0 / 3.0 * e_star * 0.02_f64.sqrt()).abs() <= 1e-15 * k);
        assert!(hertz_stiffness((Surface::Flat, STEEL), (Surface::Flat, STEEL)).is_err());
        let corner = Surface::Unknown("a box's corner");
        assert!(hertz_stiffness((corner, STEEL), (Surface::Flat, STEEL)).is_err());
    }
}
