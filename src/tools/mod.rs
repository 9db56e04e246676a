//! The toolkit's commands, each a library function the CLI calls: [`analyze`] (degenerate
//! cases of a scene, §8), [`check`] (the paper's worked examples and closed forms, checked),
//! [`derive`](mod@derive) (closed forms over symbols), [`bench`](mod@bench) (accuracy against time per scalar; [`friction_bench`] its frictional part;
//! [`accuracy`] the accuracy contract measured per output; [`system_bench`] its part on scenes
//! of several bodies, [`chain`] the planar chain it times) and
//! [`sweep`] (parameter sweeps); [`lzb_compare`] (the simultaneous law against the LZB law
//! over stiffness ratios, for `analyze`).

pub mod accuracy;
pub mod analyze;
pub mod ball_in_corner;
pub mod bench;
pub mod chain;
pub mod check;
pub mod corpus;
pub mod derive;
pub mod friction_bench;
pub mod goals;
pub mod lean_bench;
pub mod lzb_bench;
pub mod lzb_compare;
pub mod n_curve;
pub mod sweep;
pub mod system_bench;
