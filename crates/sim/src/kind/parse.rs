//! Parsing a JSON input of an expected kind: serde's error for a file of that kind, and
//! for a file that is recognisably another kind, [`SimError::WrongKind`] with what to run
//! instead.

use super::file_kind::{Expected, FileKind};
use crate::error::SimError;
use serde::de::DeserializeOwned;
use std::path::Path;

/// The wrong-kind error for `text` at `path` when it is recognisably another kind than
/// `expected` (`None` when it is of the expected kind or not recognised).
pub fn wrong_kind(text: &str, path: &Path, expected: Expected) -> Option<SimError> {
    let found = FileKind::of_json(text)?;
    (!expected.accepts(found)).then(|| SimError::WrongKind {
        path: path.to_path_buf(),
        found,
        expected,
    })
}

/// Parses `text` as `T`, a file of the `expected` kind. When it does not fit and is
/// recognisably another kind of file, the error says which and what to run instead;
/// otherwise it is serde's (field, line and column).
pub fn parse<T: DeserializeOwned>(
    text: &str,
    path: &Path,
    expected: Expected,
) -> Result<T, SimError> {
    serde_json::from_str(text).map_err(|source| {
        wrong_kind(text, path, expected).unwrap_or_else(|| SimError::Json {
            path: path.to_path_buf(),
            source,
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_names_the_kind_found() {
        #[derive(Debug, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        #[allow(dead_code)]
        struct Scene {
            building: String,
        }
        let study = r#"{"building": "b.json", "suites": [], "space": {}, "objective": {}}"#;
        let e = parse::<Scene>(study, Path::new("s.json"), Expected::SceneOrBuilding)
            .expect_err("a study is not a scene");
        let msg = e.to_string();
        assert!(msg.contains("s.json is a study"), "{msg}");
        assert!(msg.contains("slipload optimize s.json"), "{msg}");
        // A scene with a misspelt field keeps serde's message.
        let e = parse::<Scene>(
            r#"{"building": "b", "excitatoin": {}}"#,
            Path::new("t.json"),
            Expected::SceneOrBuilding,
        )
        .expect_err("unknown field");
        assert!(e.to_string().contains("excitatoin"), "{e}");
    }
}
