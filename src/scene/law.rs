//! Which impact law a scene is solved under, and the combinations that are refused rather
//! than answered under another law's name.
//!
//! The frictional integration (§14, [`crate::impact::friction`]) runs the unilateral law too
//! ([`crate::impact::friction::Hypothesis::Unilateral`]: a contact that would pull is released,
//! and re-engages when its gap closes), under Newton's, Poisson's and the energetic
//! restitution, in planar scenes exactly and in spatial ones by the adaptive integrator.
//!
//! The LZB law ([`crate::impact::multiple`]) is integrated in f64, with Coulomb friction, by its
//! own paths ([`super::lzb`]: `solve`, `sweep`, `analyze`, `bench --scene`, Python's `solve`):
//! an impulse-space restitution law with it is refused here, and the simultaneous solvers
//! refuse the law itself ([`Scene::law_applies`]) rather than answer under another law's name.

use crate::impact::friction::Restitution;
use crate::impact::unilateral::Law;

use super::{Scene, SceneError};

/// Refuse the LZB law with a `[solve] restitution` (the LZB law has its own restitution: each
/// contact's energetic coefficient); friction it integrates.
pub(super) fn lzb_allowed(
    file: &str,
    restitution: Option<Restitution>,
    how: &str,
) -> Result<(), SceneError> {
    let Some(r) = restitution else {
        return Ok(());
    };
    Err(SceneError {
        file: file.to_string(),
        key: "solve.restitution".to_string(),
        value: Some(r.name().to_string()),
        message: format!(
            "{how} has its own restitution law (each contact's energetic coefficient: \
             `k_energetic`, else `k`): drop `[solve] restitution`"
        ),
    })
}

impl Scene {
    /// The first contact with friction (μ ≠ 0, or not known to be 0), if any.
    pub fn first_rough_contact(&self) -> Option<usize> {
        self.contacts.iter().position(|c| match &c.mu.exact {
            Ok(q) => !num_traits::Zero::is_zero(q) || c.mu.tangent != 0.0,
            Err(_) => true,
        })
    }

    /// Solve the scene under `law` instead of its own (`--law`, Python's `law=`), refused
    /// where the law cannot be applied as named (the LZB law with a `[solve] restitution`).
    ///
    /// # Errors
    /// A [`SceneError`] naming `solve.restitution`, or the first rough contact's `mu`.
    pub fn set_law(&mut self, law: Law, how: &str) -> Result<(), SceneError> {
        match law {
            Law::Lzb => lzb_allowed(&self.file, self.restitution, how)?,
            Law::Simultaneous | Law::Unilateral => {}
        }
        self.law = law;
        Ok(())
    }

    /// Whether the scene's law can be applied as named; every solve checks it, whichever way
    /// the law was set.
    ///
    /// # Errors
    /// As [`Scene::set_law`].
    pub fn law_applies(&self) -> Result<(), SceneError> {
        match self.law {
            Law::Simultaneous | Law::Unilateral => Ok(()),
            Law::Lzb => Err(SceneError {
                file: self.file.clone(),
                key: "solve.law".to_string(),
                value: Some("lzb".to_string()),
                message: "the LZB law is run in f64 by `inertance solve`, `sweep`, `analyze` \
                          (against the simultaneous law), `bench --scene` and Python's `solve`; \
                          this path (the simultaneous solvers: `derive`, `check`, the batch \
                          API) does not run it: use one of those, or choose another law"
                    .to_string(),
            }),
        }
    }
}
