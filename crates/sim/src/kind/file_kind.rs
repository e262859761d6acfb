//! The kinds of slipload input file and what a command expects, each kind recognised by
//! a JSON file's top-level keys (listed in the `kind` module's docs). Plain data with no
//! error of its own: `SimError::WrongKind` names these types, so the error enum sits
//! above this file.

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
}
