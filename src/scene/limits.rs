//! The sizes beyond which a scene is refused at once, rather than worked on for minutes or
//! allocated beyond memory: each limit names what grows faster than the scene.
//!
//! - **Exact arithmetic**, [`MAX_EXACT_CONTACTS`]: `solve` and `analyze` take O(N) rational
//!   operations (the contact wrenches reduced to rank G ≤ 6 independent ones,
//!   [`crate::analysis::wrench_space`]), but the numbers and the report grow with N.
//! - **Friction**, [`MAX_FRICTION_CONTACTS`]: the integration in impulse space works on the
//!   3N×3N matrix of the contacts' inertances ([`crate::impact::friction`]), O(N²) memory —
//!   2000 contacts took 1.5 GB, 60,000 would take 1.4 TB.
//! - **Closed forms**, [`MAX_DERIVE_CONTACTS`]: `derive` prints the N² inertances and factors
//!   G over rational functions in the symbols: 60 contacts took 0.4 s, 300 took 11 s.
//!
//! The simultaneous law itself needs no limit: beyond rank G contacts, G is singular whatever
//! the numbers, and `solve` says so from the wrenches in O(N) ([`super::pipeline`]). The
//! unilateral law's limit is Lemke's (N×N tableau), [`crate::impact::unilateral`]; `analyze`'s
//! in floats bounds its report ([`crate::tools::analyze`]).

use super::{Scene, SceneError};

/// The most contacts a scene may have in exact arithmetic (rationals or symbols), for `solve`,
/// `analyze` and `sweep` alike: 1000 contacts of a fuzzed scene take about a second (release
/// build).
pub const MAX_EXACT_CONTACTS: usize = 1000;

/// The most contacts with friction (or an energetic law) the integration in impulse space
/// takes, in any arithmetic: about 100 MB of matrices at the limit.
pub const MAX_FRICTION_CONTACTS: usize = 500;

/// The most contacts `derive` takes.
pub const MAX_DERIVE_CONTACTS: usize = 64;

/// The refusal of `scene`, whose contacts number more than `limit` for `what` (e.g.
/// "`analyze --exact`"), because `why`; `instead` says what to do (e.g. "; `analyze` without
/// --exact takes up to 1000000"). Key `contact`, the count as the value.
pub fn too_many(scene: &Scene, limit: usize, what: &str, why: &str, instead: &str) -> SceneError {
    SceneError {
        file: scene.file.clone(),
        key: "contact".into(),
        value: Some(format!("{} contacts", scene.contacts.len())),
        message: format!("{what} takes at most {limit} contacts: {why}{instead}"),
    }
}

/// The refusal of a frictional `scene` with more than [`MAX_FRICTION_CONTACTS`] contacts;
/// `None` within the limit.
pub fn friction_limit(scene: &Scene) -> Option<SceneError> {
    (scene.contacts.len() > MAX_FRICTION_CONTACTS).then(|| {
        too_many(
            scene,
            MAX_FRICTION_CONTACTS,
            "the integration with friction",
            "it works on the 3N×3N matrix of the contacts' inertances",
            "; without `mu` (and `[solve] restitution`) the simultaneous law takes any number",
        )
    })
}

/// The refusal of a solve of `scene` in exact arithmetic (`solve`, `sweep` or the Python
/// `solve` with `--exact`) beyond [`MAX_EXACT_CONTACTS`]; `None` within the limit.
pub fn exact_limit(scene: &Scene) -> Option<SceneError> {
    (scene.contacts.len() > MAX_EXACT_CONTACTS).then(|| {
        too_many(
            scene,
            MAX_EXACT_CONTACTS,
            "exact arithmetic (`--exact`)",
            "its work is linear in N but the numbers and the report grow with it",
            "; without --exact, `solve` and `sweep` take any number",
        )
    })
}

/// The refusal of `derive` on `scene` beyond [`MAX_DERIVE_CONTACTS`]; `None` within it.
pub fn derive_limit(scene: &Scene) -> Option<SceneError> {
    (scene.contacts.len() > MAX_DERIVE_CONTACTS).then(|| {
        too_many(
            scene,
            MAX_DERIVE_CONTACTS,
            "`derive`",
            "its closed forms are the N² inertances and G factored over rational functions",
            "; `analyze --exact` reports the rank, the family and the energies of a rational scene",
        )
    })
}
