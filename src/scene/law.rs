//! Which impact law a scene is solved under, and the combinations that are refused rather
//! than answered under another law's name.
//!
//! The frictional integration (§14, [`crate::impact::friction`]) runs the unilateral law too
//! ([`crate::impact::friction::Hypothesis::Unilateral`]: a contact that would pull is released,
//! and re-engages when its gap closes), under Newton's and Poisson's restitution, in planar
//! scenes (a spatial scene is refused by the integration itself, naming the law). With the
//! energetic restitution law it is not applied yet: that combination is refused here, from the
//! scene file and from every override alike, rather than answered under another law's name.
//!
//! The LZB law ([`crate::impact::multiple`]) is integrated frictionless, in f64, and only
//! `inertance solve` runs it ([`super::lzb`]): friction or an impulse-space restitution law
//! with it is refused here, and every other solve path refuses the law itself
//! ([`Scene::law_applies`]) rather than answer under another law's name.

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

/// Refuse the unilateral law with the energetic restitution law (`[solve] restitution =
/// "energetic"`), which it is not applied with yet; `how` says how the law was asked for
/// (`` `[solve] law = "unilateral"` ``, `` `--law unilateral` ``).
pub(super) fn unilateral_allowed(
    file: &str,
    restitution: Option<Restitution>,
    how: &str,
) -> Result<(), SceneError> {
    match restitution {
        Some(Restitution::Energetic) => Err(SceneError {
            file: file.to_string(),
            key: "solve.restitution".to_string(),
            value: Some("energetic".to_string()),
            message: format!(
                "{how} is not applied with the energetic restitution law yet (it is integrated \
                 with Newton's and Poisson's, with or without friction): choose `restitution = \
                 \"newton\"` or `\"poisson\"`, or solve with the simultaneous law"
            ),
        }),
        _ => Ok(()),
    }
}

/// Refuse the LZB law for `contacts` when one of them has friction, or with a `[solve]
/// restitution` (the LZB law has its own restitution: each contact's energetic coefficient).
pub(super) fn lzb_allowed(
    file: &str,
    contacts: &[ContactSpec],
    restitution: Option<Restitution>,
    how: &str,
) -> Result<(), SceneError> {
    let rough = first_rough(contacts);
    let (key, value, message) = match (rough, restitution) {
        (Some(i), _) => (
            format!("contact[{i}].mu"),
            contacts[i].mu.text.clone(),
            format!(
                "{how} is integrated without friction for now (friction with LZB, its Part II, \
                 is not implemented): set `mu = 0` at every contact, or solve with the \
                 simultaneous law"
            ),
        ),
        (None, Some(r)) => (
            "solve.restitution".to_string(),
            r.name().to_string(),
            format!(
                "{how} has its own restitution law (each contact's energetic coefficient: \
                 `k_energetic`, else `k`): drop `[solve] restitution`"
            ),
        ),
        (None, None) => return Ok(()),
    };
    Err(SceneError {
        file: file.to_string(),
        key,
        value: Some(value),
        message,
    })
}

impl Scene {
    /// Solve the scene under `law` instead of its own (`--law`, Python's `law=`), refused
    /// where the law cannot be applied as named (the unilateral law with the energetic
    /// restitution law; the LZB law with friction).
    ///
    /// # Errors
    /// A [`SceneError`] naming `solve.restitution`, or the first rough contact's `mu`.
    pub fn set_law(&mut self, law: Law, how: &str) -> Result<(), SceneError> {
        match law {
            Law::Unilateral => {
                unilateral_allowed(&self.file, self.restitution, how)?;
            }
            Law::Lzb => lzb_allowed(&self.file, &self.contacts, self.restitution, how)?,
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
            Law::Unilateral => {
                unilateral_allowed(&self.file, self.restitution, "the unilateral law")
            }
            Law::Simultaneous => Ok(()),
            Law::Lzb => Err(SceneError {
                file: self.file.clone(),
                key: "solve.law".to_string(),
                value: Some("lzb".to_string()),
                message: "the LZB law is solved by `inertance solve` only, in f64 (`analyze`, \
                          `sweep`, `bench`, `derive`, `check` and the batch and Python paths do \
                          not run it yet): run `inertance solve`, or choose another law"
                    .to_string(),
            }),
        }
    }
}
