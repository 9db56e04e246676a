//! Varied numbers set straight into a validated scene: most sweeps vary a mass, a moment, a
//! velocity, a point or a coefficient, and re-reading the document at every point would cost
//! more than the solve.

use num_rational::BigRational;
use num_traits::Zero;

use super::text::text;
use crate::mechanics::contact::Contact;
use crate::number::{Number, rational_to_f64};
use crate::scalar::Scalar;
use crate::scene::Scene;

/// A varied number that can be set in a validated [`Scene`] directly, without re-reading the
/// document: the numbers whose validity is convex (a value between two valid ones is valid:
/// m, J > 0, k ∈ [0, 1], μ ≥ 0, no condition on velocities or points), so checking START and STOP
/// covers the whole range. Normals, tangents and constraints (which must not be zero vectors)
/// go through [`set_value`] and [`Scene::from_document`] at every point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Slot {
    Mass,
    Inertia(usize),
    Velocity(usize),
    AngularVelocity(usize),
    Point(usize, usize),
    K(usize),
    KNewton(usize),
    KPoisson(usize),
    Mu(usize),
}

impl Slot {
    /// The slots of the varied `paths` in `scene` when every one is directly settable, else
    /// `None` and each point re-reads the document: when `reread` (a path names a parameter,
    /// which may feed many numbers, or the caller wants the reader's own messages), for a
    /// system (its body numbers feed its shapes' moments and its contacts' points), and for a
    /// modelled scene unless every path is one it keeps [as written](Slot::as_written).
    pub(super) fn all<'a>(
        paths: impl Iterator<Item = &'a str>,
        scene: &Scene,
        reread: bool,
    ) -> Option<Vec<Slot>> {
        if reread || scene.system.is_some() {
            return None;
        }
        let slots: Option<Vec<Slot>> = paths.map(|p| Slot::find(p, scene)).collect();
        slots.filter(|s| match scene.axes {
            None => true,
            Some(axes) => s.iter().all(|s| s.as_written(axes)),
        })
    }

    /// The slot of `path` in `scene`, if it is one of the directly settable numbers.
    pub(super) fn find(path: &str, scene: &Scene) -> Option<Slot> {
        let index = |s: &str, limit: usize| -> Option<usize> {
            let i: usize = s.strip_prefix('[')?.strip_suffix(']')?.parse().ok()?;
            (i < limit).then_some(i)
        };
        if let Some(rest) = path.strip_prefix("body.") {
            if rest == "mass" {
                return Some(Slot::Mass);
            }
            let (key, idx) = rest.split_at(rest.find('[')?);
            let i = index(idx, 3)?;
            return match key {
                "inertia" => Some(Slot::Inertia(i)),
                "velocity" => Some(Slot::Velocity(i)),
                "angular_velocity" => Some(Slot::AngularVelocity(i)),
                _ => None,
            };
        }
        let rest = path.strip_prefix("contact")?;
        let (idx, key) = rest.split_once('.')?;
        let c = index(idx, scene.contacts.len())?;
        match key {
            "k" => Some(Slot::K(c)),
            "k_newton" => Some(Slot::KNewton(c)),
            "k_poisson" => Some(Slot::KPoisson(c)),
            "mu" => Some(Slot::Mu(c)),
            _ => {
                let i = index(key.strip_prefix("point")?, 3)?;
                Some(Slot::Point(c, i))
            }
        }
    }

    /// Whether a modelled scene (world frame, pose, shape: [`crate::scene::model`]) solved in
    /// `axes` keeps the number as written: a contact's coefficients (k, μ) are read as in the
    /// paper's form and never brought to the solver's frame; the body's velocity v_C and
    /// angular velocity ω are written in the world frame and, solved in world axes (the
    /// default), reach the solver unchanged (Q = I in the frame change of
    /// [`crate::scene::model`]) and feed nothing else the lowering computes. Its points, the
    /// body's mass and moments (and, in body axes, Rᵀ v_C and Rᵀ ω) are computed from the pose
    /// and the shape, so varying those re-reads the document.
    pub(super) fn as_written(self, axes: crate::scene::model::Axes) -> bool {
        match self {
            Slot::K(_) | Slot::KNewton(_) | Slot::KPoisson(_) | Slot::Mu(_) => true,
            Slot::Velocity(_) | Slot::AngularVelocity(_) => {
                axes == crate::scene::model::Axes::World
            }
            Slot::Mass | Slot::Inertia(_) | Slot::Point(..) => false,
        }
    }

    /// Whether the number is a coefficient of restitution (`k`, `k_newton`, `k_poisson`): a
    /// dimensionless number that the scaling of [`crate::scene::scale`] neither changes nor
    /// reads and that the solve reads from one contact only, so a problem prepared once can
    /// take it directly ([`super::coefficients`]).
    pub(super) fn restitution(self) -> bool {
        matches!(self, Slot::K(_) | Slot::KNewton(_) | Slot::KPoisson(_))
    }

    /// Set a coefficient of restitution to q in a prepared problem's `contacts`, as
    /// [`Scene::contact`] reads it from the scene with [`Slot::set`] applied: Stronge's k_E
    /// follows k_P where the scene does not write `k_energetic`. Other slots are left alone
    /// ([`Slot::restitution`] says which are set). `None` where the reader refuses q: a
    /// nonzero q that `T` rounds to zero (below 2⁻¹⁰⁷⁴ in f64) is out of its range, not 0.
    pub(super) fn set_restitution<T: Scalar>(
        self,
        contacts: &mut [Contact<T>],
        scene: &Scene,
        q: &BigRational,
    ) -> Option<()> {
        let (c, newton, poisson) = match self {
            Slot::K(c) => (c, true, true),
            Slot::KNewton(c) => (c, true, false),
            Slot::KPoisson(c) => (c, false, true),
            _ => return Some(()),
        };
        let x = T::from_rational(q);
        if !q.is_zero() && (x.is_zero() || !x.is_finite()) {
            return None;
        }
        let contact = &mut contacts[c];
        if poisson && scene.contacts[c].k_energetic.is_none() {
            contact.k_energetic = x.clone();
        }
        if poisson {
            contact.k_poisson = x.clone();
        }
        if newton {
            contact.k_newton = x;
        }
        Some(())
    }

    /// Set the number to q, as [`set_value`] and [`Scene::from_document`] would: a modelled
    /// scene's velocities are read back from their terms, whose text is the fraction
    /// (`7/100`, where the document's own number reads `0.07`).
    pub(super) fn set(self, scene: &mut Scene, q: &BigRational) {
        let read_back =
            scene.axes.is_some() && matches!(self, Slot::Velocity(_) | Slot::AngularVelocity(_));
        let n = Number {
            text: if read_back {
                crate::number::format_rational(q)
            } else {
                text(q)
            },
            exact: Ok(q.clone()),
            approx: rational_to_f64(q),
            symbols: Vec::new(),
            tangent: 0.0,
            source: None,
        };
        match self {
            Slot::Mass => scene.mass = n,
            Slot::Inertia(i) => scene.inertia[i] = n,
            Slot::Velocity(i) => scene.velocity[i] = n,
            Slot::AngularVelocity(i) => scene.angular_velocity[i] = n,
            Slot::Point(c, i) => scene.contacts[c].point[i] = n,
            Slot::K(c) => {
                scene.contacts[c].k_newton = n.clone();
                scene.contacts[c].k_poisson = n;
            }
            Slot::KNewton(c) => scene.contacts[c].k_newton = n,
            Slot::KPoisson(c) => scene.contacts[c].k_poisson = n,
            Slot::Mu(c) => scene.contacts[c].mu = n,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::text::toml_text;
    use super::*;
    use crate::scene::{parse_document, set_value};
    use crate::tools::sweep::q;

    const SCENE: &str = r#"
        [body]
        mass = 1
        inertia = [12, 1.6, 12]
        velocity = [3, 2, 0]
        angular_velocity = [0, 0, 0.4]
        [[contact]]
        point = [0, -2, 0]
        normal = [1, 0, 0]
        k = 0.3
        [[contact]]
        point = [0, 4, 0]
        normal = [1, 0, 0]
        k_newton = 0.2
        k_poisson = "1/7"
    "#;

    #[test]
    fn direct_slots_agree_with_rereading_the_document() {
        let doc = parse_document(SCENE, "s.toml").unwrap();
        let base = Scene::from_document(&doc, "s.toml").unwrap();
        let paths = [
            "body.mass",
            "body.inertia[2]",
            "body.velocity[0]",
            "body.angular_velocity[1]",
            "contact[0].point[1]",
            "contact[1].point[2]",
            "contact[0].k",
            "contact[1].k",
            "contact[0].k_newton",
            "contact[1].k_poisson",
            "contact[0].mu",
        ];
        for path in paths {
            let slot = Slot::find(path, &base).unwrap_or_else(|| panic!("{path}"));
            for x in [q(1, 3), q(1, 100), q(1, 1), q(5, 8), q(3, 7)] {
                let mut d = doc.clone();
                set_value(&mut d, path, &toml_text(&x)).unwrap();
                let reread = Scene::from_document(&d, "s.toml").unwrap();
                let mut direct = base.clone();
                slot.set(&mut direct, &x);
                assert_eq!(direct, reread, "{path} = {x}");
            }
        }
        for path in [
            "contact[0].normal[0]",
            "contact[2].k",
            "contact[0].tangent[0]",
            "body.inertia[3]",
            "body.inertia",
            "contact[0].point",
            "name",
        ] {
            assert_eq!(Slot::find(path, &base), None, "{path}");
        }
    }

    /// A modelled scene (world frame, shape, pose, obstacles) keeps a contact's coefficients as
    /// written: setting them in the scene read once is re-reading the document with them set.
    #[test]
    fn coefficients_of_modelled_scenes_agree_with_rereading_the_document() {
        let scenes = [
            (
                "tilted-box.toml",
                include_str!("../../../examples/tilted-box.toml"),
            ),
            (
                "flat-box.toml",
                include_str!("../../../examples/flat-box.toml"),
            ),
            (
                "rocking-block.toml",
                include_str!("../../../examples/rocking-block.toml"),
            ),
            (
                "ball-in-corner.toml",
                include_str!("../../../examples/ball-in-corner.toml"),
            ),
        ];
        for (file, text) in scenes {
            let doc = parse_document(text, file).unwrap();
            let base = Scene::from_document(&doc, file).unwrap();
            assert!(base.axes.is_some(), "{file} is modelled");
            for c in 0..base.contacts.len().min(3) {
                for key in ["k", "k_newton", "k_poisson", "mu"] {
                    let path = format!("contact[{c}].{key}");
                    let slots = Slot::all([path.as_str()].into_iter(), &base, false)
                        .unwrap_or_else(|| panic!("{file}: {path}"));
                    for x in [q(0, 1), q(1, 3), q(1, 100), q(1, 1), q(5, 8)] {
                        let mut d = doc.clone();
                        set_value(&mut d, &path, &toml_text(&x)).unwrap();
                        let reread = Scene::from_document(&d, file).unwrap();
                        let mut direct = base.clone();
                        slots[0].set(&mut direct, &x);
                        assert_eq!(direct, reread, "{file}: {path} = {x}");
                    }
                }
            }
            // In world axes the velocities reach the solver as written.
            for path in [
                "body.velocity[0]",
                "body.velocity[2]",
                "body.angular_velocity[1]",
            ] {
                let slots = Slot::all([path, "contact[0].k"].into_iter(), &base, false)
                    .unwrap_or_else(|| panic!("{file}: {path}"));
                for x in [q(0, 1), q(-1, 3), q(7, 100), q(-5, 1)] {
                    let mut d = doc.clone();
                    set_value(&mut d, path, &toml_text(&x)).unwrap();
                    let reread = Scene::from_document(&d, file).unwrap();
                    let mut direct = base.clone();
                    slots[0].set(&mut direct, &x);
                    assert_eq!(direct, reread, "{file}: {path} = {x}");
                }
            }
            // Numbers the lowering computes from the pose and the shape are re-read.
            for path in ["body.mass", "contact[0].point[0]"] {
                assert_eq!(
                    Slot::all([path].into_iter(), &base, false),
                    None,
                    "{file}: {path}"
                );
                assert_eq!(
                    Slot::all(["contact[0].k", path].into_iter(), &base, false),
                    None,
                    "{file}: {path}"
                );
            }
            assert_eq!(Slot::all(["contact[0].k"].into_iter(), &base, true), None);
            // Solved in body axes, the velocities are turned by Rᵀ: re-read.
            if !text.contains("[solve]") {
                let body_axes = format!("{text}\n[solve]\naxes = \"body\"\n");
                let doc = parse_document(&body_axes, file).unwrap();
                let base = Scene::from_document(&doc, file).unwrap();
                for path in ["body.velocity[0]", "body.angular_velocity[2]"] {
                    assert_eq!(
                        Slot::all([path].into_iter(), &base, false),
                        None,
                        "{file} in body axes: {path}"
                    );
                }
            }
        }
    }
}
