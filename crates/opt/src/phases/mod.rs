//! The phases of a study, above [`crate::eval`], each importing only the phases listed
//! before it: the sweep ([`sweep`]), the refiners ([`refine`]), the derivatives of a design's
//! objective and limits ([`gradient`]) and the refinement with its
//! checked finalists ([`refinement`]), the design table ([`table`]), the front search
//! ([`pareto`]), the ranking ([`rank`]), the design family ([`family`]) and the data of
//! the study figures ([`figures`]); beside them, the building as the study ran it
//! ([`building`]: the folder's `building.json` and `building.md`). A phase takes the
//! paths of its journals from the study folder and never opens the folder itself.

pub mod building;
pub mod check;
pub mod compliance;
pub mod devices;
pub mod family;
pub mod figures;
pub mod gradient;
pub mod nonstructural;
pub mod pareto;
pub mod protocol;
pub mod rank;
pub mod refine;
pub mod refinement;
pub mod strength;
pub mod sweep;
pub mod table;
pub mod tolerance;
