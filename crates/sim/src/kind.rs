//! What kind of slipload input a JSON file is, recognised by its top-level keys — so that
//! a file given to the wrong command is answered with what to run instead of a schema
//! error about its first foreign field ([`SimError::WrongKind`]).
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

use crate::error::SimError;
use serde::de::DeserializeOwned;
use std::path::Path;

/// The kinds of input file slipload reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// A building (`simulate`, `explain`, `accuracy` take it as a scene without excitation).
    Building,
    /// A scene: building + excitation + outputs + method.
    Scene,
    /// A study: building + suites + design space + objective.
    Study,
    /// A list of named candidate designs (`rank --designs`).
    Designs,
}

const BUILDING_KEYS: &[&str] = &[
    "floor_masses",
    "mass_matrix",
    "storey_stiffness",
    "stiffness_matrix",
    "damping",
    "storey_heights",
    "dissipators",
];
const SCENE_KEYS: &[&str] = &["excitation", "duration", "method", "outputs", "reduce"];
const STUDY_KEYS: &[&str] = &[
    "suites",
    "space",
    "constraints",
    "objective",
    "fidelity",
    "sweep",
    "refine",
];

impl FileKind {
    /// The kind of a parsed JSON value, if it is recognisably one.
    pub fn of_value(value: &serde_json::Value) -> Option<FileKind> {
        if let Some(list) = value.as_array() {
            let designs = !list.is_empty()
                && list.iter().all(|d| {
                    d.as_object()
                        .is_some_and(|o| o.contains_key("slip_loads_kn"))
                });
            return designs.then_some(FileKind::Designs);
        }
        let obj = value.as_object()?;
        let count = |keys: &[&str]| keys.iter().filter(|k| obj.contains_key(**k)).count();
        let scores = [
            (FileKind::Building, count(BUILDING_KEYS)),
            (FileKind::Scene, count(SCENE_KEYS)),
            (FileKind::Study, count(STUDY_KEYS)),
        ];
        let best = scores.iter().map(|s| s.1).max().unwrap_or(0);
        if best == 0 {
            return obj.contains_key("building").then_some(FileKind::Scene);
        }
        let mut top = scores.iter().filter(|s| s.1 == best);
        match (top.next(), top.next()) {
            (Some(&(kind, _)), None) => Some(kind),
            _ => None,
        }
    }

    /// The kind of JSON `text`, if it parses and is recognisably one.
    pub fn of_json(text: &str) -> Option<FileKind> {
        serde_json::from_str::<serde_json::Value>(text)
            .ok()
            .as_ref()
            .and_then(Self::of_value)
    }

    /// "a building", "a scene", …
    pub fn article(self) -> &'static str {
        match self {
            FileKind::Building => "a building",
            FileKind::Scene => "a scene",
            FileKind::Study => "a study",
            FileKind::Designs => "a list of candidate designs",
        }
    }

    /// What to run with a file of this kind at `path`.
    pub fn advice(self, path: &Path) -> String {
        let p = path.display();
        match self {
            FileKind::Building | FileKind::Scene => format!(
                "run `slipload simulate {p}` (or `explain`, `accuracy`); a study names its building in its `building` field"
            ),
            FileKind::Study => format!("run `slipload optimize {p}` (or `sweep`, `rank`, `table`)"),
            FileKind::Designs => format!("pass it to `slipload rank STUDY --designs {p}`"),
        }
    }
}

/// What a command expects: the kinds it reads, as said in an error ("a scene or a building").
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Expected {
    /// A scene, or a building (a scene with no excitation).
    SceneOrBuilding,
    /// A building.
    Building,
    /// A study.
    Study,
}

impl Expected {
    /// Whether a file of `kind` is what is expected.
    pub fn accepts(self, kind: FileKind) -> bool {
        match self {
            Expected::SceneOrBuilding => matches!(kind, FileKind::Scene | FileKind::Building),
            Expected::Building => kind == FileKind::Building,
            Expected::Study => kind == FileKind::Study,
        }
    }

    /// "a scene or a building", "a building", "a study".
    pub fn describe(self) -> &'static str {
        match self {
            Expected::SceneOrBuilding => "a scene or a building",
            Expected::Building => "a building",
            Expected::Study => "a study",
        }
    }
}

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

    fn kind(json: &str) -> Option<FileKind> {
        FileKind::of_json(json)
    }

    #[test]
    fn kinds_by_their_keys() {
        assert_eq!(
            kind(r#"{"name": "b", "floor_masses": [1], "storey_stiffness": [1]}"#),
            Some(FileKind::Building)
        );
        assert_eq!(
            kind(r#"{"building": "b.json", "excitation": {}}"#),
            Some(FileKind::Scene)
        );
        assert_eq!(kind(r#"{"building": "b.json"}"#), Some(FileKind::Scene));
        assert_eq!(
            kind(r#"{"building": "b.json", "suites": [], "space": {}, "objective": {}}"#),
            Some(FileKind::Study)
        );
        assert_eq!(
            kind(r#"[{"name": "a", "slip_loads_kn": [1]}]"#),
            Some(FileKind::Designs)
        );
        assert_eq!(kind(r#"{"name": "x"}"#), None);
        assert_eq!(kind("[]"), None);
        assert_eq!(kind("not json"), None);
        // As many scene keys as study keys: not recognised.
        assert_eq!(kind(r#"{"method": {}, "suites": []}"#), None);
    }

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
