//! The study folder, above [`crate::model`]: the journals (line format, checksums, the
//! fingerprint header) and the folder itself ([`folder::StudyFolder`]: its one-writer
//! lock, the list of files slipload wrote there, `fresh`, atomic writes).

pub mod folder;
pub mod journal;
