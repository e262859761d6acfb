//! A study's suites, loaded: record files and patterns, pairs and how they run, each
//! suite's scaling, into the study's records (suite after suite), the orientations of a
//! pair run `worst`, and each suite's [`SuiteInfo`].

use crate::base::error::OptError;
use crate::model::code_scaling::{CodeScaling, ScalingBasis, scale_to_code};
use crate::model::config::{MIN_STUDY_PGA_G, RecordEntry, ScaleConfig, StudyConfig};
use crate::model::orientation::PairRun;
use serde::{Deserialize, Serialize};
use slipload_motion::{G, Record, RecordPair, SuiteTarget, Synthetic, Units};
use slipload_sim::Building;
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

/// A suite, resolved: its name and the range of its records in [`crate::Study::records`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SuiteInfo {
    /// Name.
    pub name: String,
    /// Indices into the study's records.
    pub range: Range<usize>,
    /// How the suite was scaled to a code spectrum, when it was
    /// ([`crate::model::config::ScaleConfig::CodeSpectrum`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub code_scaling: Option<CodeScaling>,
    /// Seconds of rest after each of its records (`free_vibration_s`; 0: none).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub free_vibration_s: f64,
    /// How its pairs ran, as the report says it, when the study said (`pairs`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pair_run: Option<String>,
    /// Its number of pairs, when they ran rotated (each pair one ground motion).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub pairs: Option<usize>,
}

impl SuiteInfo {
    /// Its number of ground motions: pairs count once, whether they ran as components,
    /// orientations or their envelope.
    pub fn motions(&self) -> usize {
        self.pairs
            .or(self.code_scaling.as_ref().and_then(|c| c.pairs))
            .unwrap_or(self.range.len())
    }
}

/// A pair's name from its components' file names: `FIRST+SECOND`.
fn pair_name(a: &Record, b: &Record) -> String {
    let stem = |r: &Record| {
        Path::new(r.name()).file_name().map_or_else(
            || r.name().to_string(),
            |n| n.to_string_lossy().into_owned(),
        )
    };
    format!("{}+{}", stem(a), stem(b))
}

/// Appends a pair's runs to the study's records, the orientations of a `worst` pair
/// beside its one run.
fn push_runs(
    records: &mut Vec<Arc<Record>>,
    orientations: &mut Vec<Vec<Arc<Record>>>,
    runs: Vec<Record>,
    further: Vec<Record>,
) {
    orientations.resize(records.len(), Vec::new());
    records.extend(runs.into_iter().map(Arc::new));
    orientations.resize(records.len(), Vec::new());
    // (only a `worst` pair has orientations, and it is one run)
    if !further.is_empty()
        && let Some(last) = orientations.last_mut()
    {
        *last = further.into_iter().map(Arc::new).collect();
    }
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// `*` matching of one file name (no other wildcards); a pattern's extension matches in
/// any case (`*.AT2` takes `x.at2`: PEER files come with either).
fn wildcard(pattern: &str, name: &str) -> bool {
    if let (Some((pstem, pext)), Some((nstem, next))) =
        (pattern.rsplit_once('.'), name.rsplit_once('.'))
        && !pext.contains('*')
    {
        return pext.eq_ignore_ascii_case(next) && wildcard_exact(pstem, nstem);
    }
    wildcard_exact(pattern, name)
}

/// `*` matching of one file name, case as written.
fn wildcard_exact(pattern: &str, name: &str) -> bool {
    let parts: Vec<&str> = pattern.split('*').collect();
    if parts.len() == 1 {
        return pattern == name;
    }
    let (first, last) = (parts[0], parts[parts.len() - 1]);
    if !name.starts_with(first) || name.len() < first.len() + last.len() || !name.ends_with(last) {
        return false;
    }
    let mut rest = &name[first.len()..name.len() - last.len()];
    for mid in &parts[1..parts.len() - 1] {
        match rest.find(mid) {
            Some(i) => rest = &rest[i + mid.len()..],
            None => return false,
        }
    }
    true
}

/// Files of one record entry: the file itself, or the sorted matches of a `*` pattern
/// (whose extension matches in any case: [`wildcard`]).
fn expand(base: &Path, entry: &str, path: &Path, field: &str) -> Result<Vec<PathBuf>, OptError> {
    let full = base.join(entry);
    let name = full
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    if !name.contains('*') {
        if !full.is_file() {
            let what = if full.is_dir() {
                "is a folder, not a record file (name the files, or a pattern such as folder/*.AT2, which takes .at2 too)"
            } else if full.exists() {
                "is not a regular file"
            } else {
                "does not exist"
            };
            return Err(OptError::invalid(
                path,
                field,
                format!("record file {} {what}", full.display()),
            ));
        }
        return Ok(vec![full]);
    }
    let dir = full.parent().unwrap_or(Path::new("."));
    if dir.to_string_lossy().contains('*') {
        return Err(OptError::invalid(
            path,
            field,
            "`*` is allowed in the file name only, not in folder names",
        ));
    }
    let listing = std::fs::read_dir(dir).map_err(|source| OptError::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let mut found: Vec<PathBuf> = listing
        .filter_map(|e| e.ok())
        .filter(|e| e.path().is_file() && wildcard(&name, &e.file_name().to_string_lossy()))
        .map(|e| e.path())
        .collect();
    found.sort();
    if found.is_empty() {
        return Err(OptError::invalid(
            path,
            field,
            format!("pattern {} matches no file", full.display()),
        ));
    }
    Ok(found)
}

/// The records of every suite of `cfg` (paths relative to `base`; errors name `path`):
/// the records, suite after suite; per record its orientations (empty unless a `worst`
/// pair's); the suites.
#[allow(clippy::type_complexity)]
pub(crate) fn load_suites(
    cfg: &StudyConfig,
    building: &Building,
    base: &Path,
    path: &Path,
) -> Result<(Vec<Arc<Record>>, Vec<Vec<Arc<Record>>>, Vec<SuiteInfo>), OptError> {
    let t1 = building.t1();
    let mut records = Vec::new();
    let mut orientations: Vec<Vec<Arc<Record>>> = Vec::new();
    let mut suites = Vec::new();
    for (i, s) in cfg.suites.iter().enumerate() {
        let start = records.len();
        let mut code_scaling = None;
        let pair_run = match &s.pairs {
            Some(p) => p.resolve(path, i)?,
            None => PairRun::Components,
        };
        let mut pair_runs = 0;
        if let Some(syn) = &s.synthetic {
            let params = Synthetic {
                duration_s: syn.duration_s,
                ..Synthetic::default()
            };
            let rs = slipload_motion::synthetic_suite(
                &params,
                syn.count,
                syn.seed,
                SuiteTarget::Pga {
                    pga_m_s2: syn.pga_g * G,
                },
            )?;
            records.extend(rs.into_iter().map(Arc::new));
        } else {
            let units = match &s.units {
                Some(u) => Some(u.parse::<Units>().map_err(|e| {
                    OptError::invalid(path, format!("suites[{i}].units"), e.to_string())
                })?),
                None => None,
            };
            // one file twice in a suite would count its record twice in every statistic
            let mut seen: Vec<(PathBuf, usize)> = Vec::new();
            // a suite scaled to a code spectrum: read whole, then one factor for all
            let mut unscaled: Vec<Record> = Vec::new();
            // pairs of components, when the suite is scaled to a code spectrum
            let mut pairs: Vec<RecordPair> = Vec::new();
            let code = matches!(&s.scale, Some(ScaleConfig::CodeSpectrum(_)));
            for (j, entry) in s.records.iter().enumerate() {
                let field = format!("suites[{i}].records[{j}]");
                let (files, is_pair) = match entry {
                    RecordEntry::File(e) => (expand(base, e, path, &field)?, false),
                    RecordEntry::Pair(two) => {
                        let mut files = Vec::with_capacity(2);
                        for (c, e) in two.iter().enumerate() {
                            let f = format!("{field}[{c}]");
                            if e.contains('*') {
                                return Err(OptError::invalid(
                                    path,
                                    f,
                                    format!(
                                        "{e:?}: a pair names the two component files of one event, not a `*` pattern"
                                    ),
                                ));
                            }
                            files.extend(expand(base, e, path, &f)?);
                        }
                        (files, true)
                    }
                };
                let mut components: Vec<Record> = Vec::new();
                pair_runs += usize::from(is_pair);
                for file in files {
                    let key = std::fs::canonicalize(&file).unwrap_or_else(|_| file.clone());
                    if let Some((_, k)) = seen.iter().find(|(f, _)| *f == key) {
                        return Err(OptError::invalid(
                            path,
                            field,
                            format!(
                                "{} is already in this suite (suites[{i}].records[{k}]): a record counts once in a suite's statistics; name it once",
                                file.display()
                            ),
                        ));
                    }
                    seen.push((key, j));
                    let r = slipload_motion::read_record(&file, units, s.dt_s)?;
                    let r = match &s.scale {
                        Some(ScaleConfig::CodeSpectrum(_)) => {
                            if is_pair {
                                components.push(r);
                            } else {
                                unscaled.push(r);
                            }
                            continue;
                        }
                        // a pair rotated is scaled by one factor for both components
                        Some(ScaleConfig::PgaG(_) | ScaleConfig::SaT1G(_))
                            if is_pair && pair_run != PairRun::Components =>
                        {
                            return Err(OptError::invalid(
                                path,
                                format!("suites[{i}].scale"),
                                "a pair rotated over orientations (`pairs.run` angles or worst) is scaled by one factor for both components: give `factor` or `code_spectrum`, not a PGA or Sa(T₁) per component",
                            ));
                        }
                        None => r,
                        Some(ScaleConfig::Factor(f)) => {
                            let r = r.try_scaled(*f)?;
                            let pga_g = r.pga() / G;
                            if pga_g < MIN_STUDY_PGA_G {
                                return Err(OptError::invalid(
                                    path,
                                    format!("suites[{i}].scale.factor"),
                                    format!(
                                        "scales {} to a PGA of {pga_g:.3e} g, below {MIN_STUDY_PGA_G} g: no dissipator slips and every design is the bare frame (give scale.pga_g, or check the factor)",
                                        file.display()
                                    ),
                                ));
                            }
                            r
                        }
                        Some(ScaleConfig::PgaG(p)) => r.scaled_to_pga(*p * G)?,
                        Some(ScaleConfig::SaT1G(sa)) => {
                            slipload_motion::scale_to_spectral_acceleration(
                                std::slice::from_ref(&r),
                                t1,
                                0.05,
                                sa * G,
                            )?
                            .records
                            .remove(0)
                        }
                    };
                    if is_pair && pair_run != PairRun::Components {
                        components.push(r);
                    } else {
                        records.push(Arc::new(r));
                    }
                }
                if is_pair && !code && pair_run != PairRun::Components {
                    let mut two = components.into_iter();
                    if let (Some(a), Some(b)) = (two.next(), two.next()) {
                        let pair = RecordPair::new(pair_name(&a, &b), a, b)
                            .map_err(|e| OptError::invalid(path, &field, e.to_string()))?;
                        let (runs, further) = pair_run.runs_of(&pair)?;
                        push_runs(&mut records, &mut orientations, runs, further);
                    }
                } else if code && is_pair {
                    let mut two = components.into_iter();
                    if let (Some(a), Some(b)) = (two.next(), two.next()) {
                        let pair = RecordPair::new(pair_name(&a, &b), a, b)
                            .map_err(|e| OptError::invalid(path, &field, e.to_string()))?;
                        pairs.push(pair);
                    }
                }
            }
            if let Some(ScaleConfig::CodeSpectrum(c)) = &s.scale {
                let (scaled, scaling) = scale_to_code(
                    &unscaled,
                    &pairs,
                    c,
                    s.limits.as_ref(),
                    &ScalingBasis::of(building),
                    path,
                    i,
                )?;
                if pairs.is_empty() || pair_run == PairRun::Components {
                    records.extend(scaled.into_iter().map(Arc::new));
                } else {
                    // the scaled components, pair by pair, rotated as the suite asks
                    let mut it = scaled.into_iter();
                    for p in &pairs {
                        if let (Some(a), Some(b)) = (it.next(), it.next()) {
                            let pair = RecordPair::new(p.name(), a, b).map_err(|e| {
                                OptError::invalid(path, format!("suites[{i}]"), e.to_string())
                            })?;
                            let (runs, further) = pair_run.runs_of(&pair)?;
                            push_runs(&mut records, &mut orientations, runs, further);
                        }
                    }
                }
                code_scaling = Some(scaling);
            }
        }
        orientations.resize(records.len(), Vec::new());
        if s.pairs.is_some() && pair_runs == 0 {
            return Err(OptError::invalid(
                path,
                format!("suites[{i}].pairs"),
                "says how pairs run, but the suite names no pair (`[first, second]` in its records)",
            ));
        }
        suites.push(SuiteInfo {
            pair_run: s.pairs.as_ref().map(|_| pair_run.describe()),
            pairs: (pair_run != PairRun::Components).then_some(pair_runs),
            name: s.name.clone(),
            range: start..records.len(),
            code_scaling: code_scaling.take(),
            free_vibration_s: s.free_vibration_s.unwrap_or(0.0),
        });
    }
    Ok((records, orientations, suites))
}

#[cfg(test)]
mod tests {
    use super::wildcard;

    #[test]
    fn wildcard_matches_like_a_shell() {
        assert!(wildcard("*.AT2", "RSN6.AT2"));
        assert!(wildcard("RSN*_*.AT2", "RSN6_IMPVALL.AT2"));
        assert!(!wildcard("RSN*.AT2", "ELC.AT2"));
        // the extension in any case, the rest as written
        assert!(wildcard("*.AT2", "x.at2"));
        assert!(wildcard("RSN*.at2", "RSN6.AT2"));
        assert!(!wildcard("RSN*.AT2", "rsn6.AT2"));
        assert!(!wildcard("*.AT2", "x.AT2.bak"));
        assert!(wildcard("a*a", "aa"));
        assert!(!wildcard("a*a", "a"));
    }
}
