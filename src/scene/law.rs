//! Which impact law a scene is solved under, and the combinations that are refused rather
//! than answered under another law's name.
//!
//! The frictional integration (§14, [`crate::impact::friction`]) imposes the paper's
//! simultaneous hypothesis on every contact: each one keeps compressing until the restitution
//! law stops it, and none may separate with a zero impulse. Run under the name "unilateral" it
//! would print the simultaneous answer — a pulling impulse at a contact that should separate —
//! as the unilateral one. Until the unilateral law is integrated with friction, the
//! combination is refused, from the scene file and from every override alike.
//!
//! The LZB law ([`crate::impact::multiple`]) is integrated in f64, with Coulomb friction, by its
//! own paths ([`super::lzb`]: `solve`, `sweep`, `analyze`, `bench --scene`, Python's `solve`):
//! an impulse-space restitution law with it is refused here, and the simultaneous solvers
//! refuse the law itself ([`Scene::law_applies`]) rather than answer under another law's name.

use crate::impact::friction::Restitution;
use crate::impact::unilateral::Law;

use super::schema::ContactSpec;
use super::{Scene, SceneError};

/// The first contact with friction (μ ≠ 0, or not known to be 0), if any.
fn first_rough(contacts: &[ContactSpec]) -> Option<usize> {
    contacts.iter().position(|c| match &c.mu.exact {
        Ok(q) => !num_traits::Zero::is_zero(q) || c.mu.tangent != 0.0,
        Err(_) => true,
    })
}

/// Refuse the unilateral law for `contacts` when one of them has friction; `how` says how the
/// law was asked for (`` `[solve] law = "unilateral"` ``, `` `--law unilateral` ``).
/// An energetic restitution law (`[solve] restitution`) is integrated in impulse space too.
pub(super) fn unilateral_allowed(
    file: &str,
    contacts: &[ContactSpec],
    restitution: Option<Restitution>,
    how: &str,
) -> Result<(), SceneError> {
    let rough = first_rough(contacts);
    let (key, value, what) = match (rough, restitution) {
        (Some(i), _) => (
            format!("contact[{i}].mu"),
            contacts[i].mu.text.clone(),
            "with friction",
        ),
        (None, Some(r)) => (
            "solve.restitution".to_string(),
            r.name().to_string(),
            "with a restitution law integrated in impulse space",
        ),
        (None, None) => return Ok(()),
    };
    Err(SceneError {
        file: file.to_string(),
        key,
        value: Some(value),
        message: format!(
            "{how} cannot be applied {what}: that integration (§14) imposes the simultaneous \
             hypothesis on every contact (none may separate), so its answer would not be the \
             unilateral law's. Solve with the simultaneous law (drop the unilateral law), or \
             with the unilateral law frictionless (μ = 0 at every contact, no `[solve] \
             restitution`)"
        ),
    })
}

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
    /// Solve the scene under `law` instead of its own (`--law`, Python's `law=`), refused
    /// where the law cannot be applied as named (the unilateral law with friction).
    ///
    /// # Errors
    /// A [`SceneError`] naming the first rough contact's `mu`.
    pub fn set_law(&mut self, law: Law, how: &str) -> Result<(), SceneError> {
        match law {
            Law::Unilateral => {
                unilateral_allowed(&self.file, &self.contacts, self.restitution, how)?;
            }
            Law::Lzb => lzb_allowed(&self.file, self.restitution, how)?,
            Law::Simultaneous => {}
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
            Law::Unilateral => unilateral_allowed(
                &self.file,
                &self.contacts,
                self.restitution,
                "the unilateral law",
            ),
            Law::Simultaneous => Ok(()),
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
