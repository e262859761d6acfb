//! What kind of slipload input a JSON file is, recognised by its top-level keys — so that
//! a file given to the wrong command is answered with what to run instead of a schema
//! error about its first foreign field ([`SimError::WrongKind`](crate::error::SimError::WrongKind)).
//!
//! The kinds and the keys that mark them (keys shared by several kinds, such as `name`
//! and `description`, and `building` — which scenes and studies both have — mark none):
//! - building: `floor_masses`, `mass_matrix`, `storey_stiffness`, `stiffness_matrix`,
//!   `damping`, `storey_heights`, `dissipators`;
//! - scene: `excitation`, `duration`, `method`, `outputs`, `reduce`;
//! - study: `suites`, `space`, `constraints`, `objective`, `fidelity`, `sweep`, `refine`;
//! - candidate designs (`optimize` writes `candidates.json`): a list of objects with
//!   `slip_loads_kn`.
//!
//! An object with `building` and no other marking key is a scene. A file matching no kind,
//! or two kinds equally, is not recognised (the schema error stands).

pub(crate) mod file_kind;
mod parse;

pub use file_kind::{Expected, FileKind};
pub use parse::{parse, wrong_kind};
