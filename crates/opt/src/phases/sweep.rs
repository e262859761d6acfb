//! The sweep: a sample of designs × every record as independent tasks, journalled,
//! shardable, and written as `manifest.json`, `responses.csv` and `designs.csv` built
//! from the journal sorted by (design, record) — so the bytes do not depend on thread
//! count, shard split or interruptions.
//!
//! Design 0 is always the bare frame (every slip load 0: the reference of reductions and
//! of the relative performance index), design 1 the slip loads of the building file,
//! then the sample.

use crate::base::collapse::{COLLAPSED, objective_text, reduction, reduction_text};
use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::base::shard::Shard;
use crate::eval::evaluate::{Task, run_tasks};
use crate::model::check::{Checks, DesignCheck};
use crate::model::fidelity::Fidelity;
use crate::model::fingerprint::Fingerprint;
use crate::model::objective::Objective;
use crate::model::sampler;
use crate::model::sampler::Design;
use crate::model::study::{Study, SuiteInfo};
use crate::store::folder::StudyFolder;
use crate::store::journal::{Entry, Journal};
use serde::{Deserialize, Serialize};
use slipload_sim::scene::MethodName;
use std::fmt::Write as _;
use std::path::Path;

/// Everything the output files depend on: written by every run and every shard
/// (identically), read by `merge`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Manifest {
    /// Study name.
    pub study: String,
    /// Objective.
    pub objective: Objective,
    /// Sweep method name.
    pub method: MethodName,
    /// Why the sweep runs that method ([`crate::eval::probe::choose_sweep_method`]).
    #[serde(default)]
    pub method_reason: String,
    /// Sweep time step, s (`null`: sim's default per record).
    pub dt_s: Option<f64>,
    /// Energies accumulated.
    pub energies: bool,
    /// Floors (from 1) of the dissipators.
    pub damper_floors: Vec<usize>,
    /// Number of storeys.
    pub storeys: usize,
    /// Suites.
    pub suites: Vec<SuiteInfo>,
    /// Run names: the records, then (with property bounds) the records at the lower and
    /// the upper bound ([`Study::run_name`]).
    pub records: Vec<String>,
    /// The property bounds and limits (absent: none).
    #[serde(default, skip_serializing_if = "Checks::is_empty")]
    pub checks: Checks,
    /// Designs.
    pub designs: Vec<Design>,
    /// The study's fingerprint: every journal of the folder must carry the same
    /// ([`crate::model::fingerprint`]).
    pub fingerprint: Fingerprint,
}

impl Manifest {
    /// The sweep of a study.
    pub fn of(study: &Study) -> Manifest {
        let m = study.space.dampers.len();
        let mut designs = vec![
            Design {
                label: "bare".into(),
                slip_loads_n: vec![0.0; m],
                z: None,
                friction_n: None,
            },
            Design {
                label: "file".into(),
                slip_loads_n: study.file_slip_loads(),
                z: None,
                friction_n: study.file_friction(),
            },
        ];
        for (i, z) in sampler::sample(&study.space, &study.config.sweep)
            .into_iter()
            .enumerate()
        {
            designs.push(Design {
                label: format!("s{:04}", i + 1),
                slip_loads_n: study.space.slip_loads(&z),
                z: Some(z),
                friction_n: None,
            });
        }
        let fid = Fidelity::sweep(study);
        let fingerprint = crate::model::fingerprint::of_study(study, &designs);
        Manifest {
            study: study.name.clone(),
            objective: study.objective.clone(),
            method: fid.method,
            method_reason: study.sweep_method.reason.clone(),
            dt_s: fid.dt_s,
            energies: fid.energies,
            damper_floors: study.space.dampers.iter().map(|f| f + 1).collect(),
            storeys: study.building.floors(),
            suites: study.suites.clone(),
            records: study.run_names(),
            checks: study.checks.clone(),
            designs,
            fingerprint,
        }
    }

    /// Reads a folder's `manifest.json` (`path`), size-bounded, naming it in errors.
    pub fn read(path: &Path) -> Result<Manifest, OptError> {
        let text = slipload_motion::limits::read_input_text(
            path,
            "sweep manifest",
            slipload_motion::limits::MAX_CONFIG_BYTES,
        )?;
        serde_json::from_str(&text).map_err(|source| OptError::Json {
            path: path.to_path_buf(),
            source,
        })
    }

    /// Number of tasks (designs × records); task k = design · records + record.
    pub fn tasks(&self) -> usize {
        self.designs.len() * self.records.len()
    }

    /// (design, record) of task k.
    pub fn task(&self, k: usize) -> (usize, usize) {
        (k / self.records.len(), k % self.records.len())
    }

    /// Checks a journal entry against this manifest.
    /// `line` is the entry's line in the journal (from 1), for the error message.
    pub fn check(&self, e: &Entry, path: &Path, line: usize) -> Result<(), OptError> {
        let bad = |message: String| OptError::Journal {
            path: path.to_path_buf(),
            line,
            message,
        };
        let d = self.designs.get(e.design).ok_or_else(|| {
            bad(format!(
                "design {} is not in this study (it has {}): the study changed; use a fresh --out",
                e.design,
                self.designs.len()
            ))
        })?;
        let name = self.records.get(e.record).ok_or_else(|| {
            bad(format!(
                "record {} is not in this study: the study changed; use a fresh --out",
                e.record
            ))
        })?;
        if *name != e.record_name {
            return Err(bad(format!(
                "record {} is {:?} here but {:?} in the journal: the study changed; use a fresh --out",
                e.record, name, e.record_name
            )));
        }
        let same = d.slip_loads_n.len() == e.slip_loads_n.len()
            && d.slip_loads_n
                .iter()
                .zip(&e.slip_loads_n)
                .all(|(a, b)| a.to_bits() == b.to_bits());
        if !same {
            return Err(bad(format!(
                "design {} ({}) has other slip loads in the journal: the study changed; use a fresh --out",
                e.design, d.label
            )));
        }
        Ok(())
    }

    /// `responses.csv`: every (design, record), sorted by key. `None` if a task is missing.
    pub fn responses_csv(&self, rows: &[Option<RecordMetrics>]) -> String {
        let n = self.storeys;
        let mut s = String::from("design,label,record,suite");
        for f in &self.damper_floors {
            let _ = write!(s, ",slip_load_kN_{f}");
        }
        for i in 1..=n {
            let _ = write!(s, ",drift_ratio_{i}");
        }
        for i in 1..=n {
            let _ = write!(s, ",residual_drift_ratio_{i}");
        }
        s.push_str(",peak_floor_acceleration_m_s2,peak_base_shear_N,peak_displacement_m");
        for i in 1..=n {
            let _ = write!(s, ",stroke_m_{i}");
        }
        s.push_str(",energy_input_J,energy_friction_J,strain_energy_area_J_s");
        // A yielding frame's ductility, hysteretic energy and collapse (absent otherwise,
        // so an elastic study's file is as before).
        let nonlinear = rows
            .iter()
            .flatten()
            .any(|m| m.ductility.is_some() || m.energy_plastic.is_some() || m.collapsed());
        if nonlinear {
            for i in 1..=n {
                let _ = write!(s, ",ductility_{i}");
            }
            s.push_str(",energy_plastic_J,collapse_storey,collapse_time_s");
        }
        s.push('\n');
        let opt = |o: Option<f64>| o.map(|v| v.to_string()).unwrap_or_default();
        for (k, row) in rows.iter().enumerate() {
            let Some(m) = row else { continue };
            let (d, r) = self.task(k);
            let design = &self.designs[d];
            let record = r % self.record_count();
            let suite = self
                .suites
                .iter()
                .find(|su| su.range.contains(&record))
                .map(|su| su.name.as_str())
                .unwrap_or("");
            let _ = write!(s, "{d},{},{},{suite}", design.label, self.records[r]);
            write_slip_loads_kn(&mut s, design);
            for v in &m.drift_ratio {
                let _ = write!(s, ",{v}");
            }
            // a run that stopped on the collapse limit has no residual drift: left empty
            for v in &m.residual_drift_ratio {
                if m.collapsed() {
                    s.push(',');
                } else {
                    let _ = write!(s, ",{v}");
                }
            }
            let _ = write!(
                s,
                ",{},{},{}",
                m.peak_floor_acceleration, m.peak_base_shear, m.peak_displacement
            );
            for v in &m.stroke {
                let _ = write!(s, ",{v}");
            }
            let _ = write!(
                s,
                ",{},{},{}",
                opt(m.energy_input),
                opt(m.energy_friction),
                opt(m.strain_energy_area)
            );
            if nonlinear {
                match &m.ductility {
                    Some(mu) => mu.iter().for_each(|v| {
                        let _ = write!(s, ",{v}");
                    }),
                    None => (0..n).for_each(|_| s.push(',')),
                }
                let (storey, time) = m
                    .collapse
                    .map_or((String::new(), String::new()), |(st, t)| {
                        (st.to_string(), t.to_string())
                    });
                let _ = write!(s, ",{},{storey},{time}", opt(m.energy_plastic));
            }
            s.push('\n');
        }
        s
    }

    /// The number of records (the runs of one property case).
    pub fn record_count(&self) -> usize {
        self.records.len() / self.checks.cases().len()
    }

    /// Objective of every design (`rows[d · runs + r]` complete), and of its terms, at
    /// the case the objective reads.
    pub fn objectives(&self, rows: &[RecordMetrics]) -> Result<Vec<(f64, Vec<f64>)>, OptError> {
        let nr = self.records.len();
        let records = self.record_count();
        let ranges: Vec<_> = self.suites.iter().map(|s| s.range.clone()).collect();
        let bare = &rows[0..nr];
        (0..self.designs.len())
            .map(|d| {
                let rec = &rows[d * nr..(d + 1) * nr];
                let terms =
                    self.checks
                        .terms(&self.objective, rec, Some(bare), &ranges, records)?;
                let f = self
                    .checks
                    .objective(
                        &self.objective,
                        rec,
                        Some(bare),
                        &ranges,
                        records,
                        &self.designs[d].slip_loads_n,
                    )
                    .map_err(|e| match e {
                        OptError::NonFinite { quantity, .. } => OptError::NonFinite {
                            design: format!("{d} ({})", self.designs[d].label),
                            record: format!("the {nr} runs of the study"),
                            quantity,
                        },
                        e => e,
                    })?;
                Ok((f, terms))
            })
            .collect()
    }

    /// The check of every design against the study's limits (`None`: the study has no
    /// limits).
    pub fn checks_of(&self, rows: &[RecordMetrics]) -> Result<Option<Vec<DesignCheck>>, OptError> {
        if !self.checks.has_limits() {
            return Ok(None);
        }
        let nr = self.records.len();
        let suites: Vec<(&str, std::ops::Range<usize>)> = self
            .suites
            .iter()
            .map(|s| (s.name.as_str(), s.range.clone()))
            .collect();
        (0..self.designs.len())
            .map(|d| {
                self.checks
                    .check(&rows[d * nr..(d + 1) * nr], &suites, self.record_count())
            })
            .collect::<Result<Vec<_>, _>>()
            .map(Some)
    }

    /// `designs.csv`: per design its slip loads, objective, terms, reduction against the
    /// bare frame (1 − f/f_bare) and rank (1 = best; bare and file designs included).
    pub fn designs_csv(&self, rows: &[RecordMetrics]) -> Result<String, OptError> {
        let obj = self.objectives(rows)?;
        let checks = self.checks_of(rows)?;
        // with limits, a design that passes ranks before every design that does not
        let failed = |d: usize| checks.as_ref().is_some_and(|c| !c[d].passes());
        let mut order: Vec<usize> = (0..obj.len()).collect();
        order.sort_by(|&a, &b| {
            failed(a)
                .cmp(&failed(b))
                .then(obj[a].0.total_cmp(&obj[b].0))
                .then(a.cmp(&b))
        });
        let mut rank = vec![0; obj.len()];
        for (i, &d) in order.iter().enumerate() {
            rank[d] = i + 1;
        }
        let mut s = String::from("design,label");
        for f in &self.damper_floors {
            let _ = write!(s, ",slip_load_kN_{f}");
        }
        s.push_str(",objective");
        for t in &self.objective.terms {
            let _ = write!(s, ",{}_{}", t.statistic.as_str(), t.metric.as_str());
        }
        if checks.is_some() {
            s.push_str(",check,governing_ratio,governing");
        }
        s.push_str(",reduction_vs_bare,rank\n");
        let f0 = obj[0].0;
        for (d, design) in self.designs.iter().enumerate() {
            let _ = write!(s, "{d},{}", design.label);
            write_slip_loads_kn(&mut s, design);
            // a design that collapses on a record has no objective, nor terms: it failed
            let collapsed = !obj[d].0.is_finite();
            let _ = write!(s, ",{}", objective_text(obj[d].0, None));
            for v in &obj[d].1 {
                let cell = if collapsed {
                    COLLAPSED.to_string()
                } else {
                    v.to_string()
                };
                let _ = write!(s, ",{cell}");
            }
            if let Some(c) = &checks {
                let c = &c[d];
                let (ratio, what) = c.governing().map_or((String::new(), String::new()), |g| {
                    (
                        g.ratio.to_string(),
                        format!("{} {} {}", g.suite, g.case.as_str(), g.criterion),
                    )
                });
                let verdict = if c.passes() { "pass" } else { "fail" };
                let _ = write!(s, ",{verdict},{ratio},{what}");
            }
            let red = reduction_text(reduction(obj[d].0, f0), None);
            let _ = writeln!(s, ",{red},{}", rank[d]);
        }
        Ok(s)
    }

    /// The manifest as pretty JSON with a final newline.
    pub fn to_json(&self) -> String {
        let mut s = serde_json::to_string_pretty(self).expect("a manifest serialises");
        s.push('\n');
        s
    }
}

/// The slip-load cells (kN) of one design's CSV row: the slip loads, or the friction law
/// where the design has one (`locked`, `F⁻..F⁺`).
fn write_slip_loads_kn(s: &mut String, design: &Design) {
    match &design.friction_n {
        Some(laws) => laws.iter().for_each(|l| {
            let _ = write!(s, ",{}", l.text(1e3));
        }),
        None => design.slip_loads_n.iter().for_each(|v| {
            let _ = write!(s, ",{}", v / 1e3);
        }),
    }
}

/// What a sweep run did.
#[derive(Debug, Clone)]
pub struct SweepReport {
    /// The manifest.
    pub manifest: Manifest,
    /// Tasks of this shard.
    pub shard_tasks: usize,
    /// Of which taken from the journal.
    pub resumed: usize,
    /// Of which run now.
    pub ran: usize,
    /// Journal lines not trusted (checksum failed or missing): their tasks ran again.
    pub distrusted: usize,
    /// All rows (when this run covers every task), sorted by key.
    pub rows: Option<Vec<RecordMetrics>>,
}

/// Places journal entries by task key, checking each against the manifest; later
/// duplicates of a key must agree (they come from the same deterministic task).
fn place(
    manifest: &Manifest,
    entries: Vec<Entry>,
    path: &Path,
    rows: &mut [Option<RecordMetrics>],
) -> Result<(), OptError> {
    for (i, e) in entries.into_iter().enumerate() {
        // read() keeps every complete line, so entry i is line i + 1
        manifest.check(&e, path, i + 1)?;
        let k = e.design * manifest.records.len() + e.record;
        if rows[k].is_none() {
            rows[k] = Some(e.metrics);
        }
    }
    Ok(())
}

/// Writes `manifest.json`, and when every task is done `responses.csv` and
/// `designs.csv`, into `out`.
pub fn write_outputs(
    folder: &StudyFolder,
    manifest: &Manifest,
    rows: &[Option<RecordMetrics>],
) -> Result<Option<Vec<RecordMetrics>>, OptError> {
    folder.write("manifest.json", manifest.to_json().as_bytes())?;
    if rows.iter().any(Option::is_none) {
        return Ok(None);
    }
    let full: Vec<RecordMetrics> = rows.iter().flatten().cloned().collect();
    folder.write("responses.csv", manifest.responses_csv(rows).as_bytes())?;
    folder.write("designs.csv", manifest.designs_csv(&full)?.as_bytes())?;
    Ok(Some(full))
}

/// Runs (the shard's slice of) a study's sweep into `out`, journalled; `tick` is called
/// after every task run now.
pub fn run(
    study: &Study,
    folder: &StudyFolder,
    shard: Shard,
    resume: bool,
    tick: &(dyn Fn() + Sync),
) -> Result<SweepReport, OptError> {
    let manifest = Manifest::of(study);
    let jpath = folder.journal("journal.jsonl")?;
    let (journal, entries) = Journal::open(&jpath, &manifest.fingerprint, resume)?;
    let distrusted = journal.distrusted();
    let total = manifest.tasks();
    let mut rows: Vec<Option<RecordMetrics>> = vec![None; total];
    place(&manifest, entries, &jpath, &mut rows)?;
    let mine: Vec<usize> = (0..total).filter(|&k| shard.owns(k)).collect();
    let resumed = mine.iter().filter(|&&k| rows[k].is_some()).count();
    let todo: Vec<usize> = mine
        .iter()
        .copied()
        .filter(|&k| rows[k].is_none())
        .collect();
    let tasks: Vec<Task> = todo
        .iter()
        .map(|&k| {
            let (d, r) = manifest.task(k);
            Task {
                label: manifest.designs[d].label.clone(),
                slip_loads: manifest.designs[d].slip_loads_n.clone(),
                friction: manifest.designs[d].friction_n.clone(),
                record: r,
            }
        })
        .collect();
    let fid = Fidelity::sweep(study);
    run_tasks(study, &tasks, &fid, &|i, m| {
        let (d, r) = manifest.task(todo[i]);
        journal.append(&Entry {
            design: d,
            record: r,
            record_name: manifest.records[r].clone(),
            slip_loads_n: manifest.designs[d].slip_loads_n.clone(),
            metrics: m.clone(),
        })?;
        tick();
        Ok(())
    })?;
    drop(journal);
    // Outputs come from the journal as written, never from memory: a resumed run and a
    // fresh one read the same lines.
    let (entries, _) = crate::store::journal::read(&jpath)?;
    let mut rows: Vec<Option<RecordMetrics>> = vec![None; total];
    place(&manifest, entries, &jpath, &mut rows)?;
    let keep: Vec<Option<RecordMetrics>> = if shard.count == 1 {
        rows
    } else {
        // a shard writes only the manifest: merge builds the tables
        vec![None; total]
    };
    let full = write_outputs(folder, &manifest, &keep)?;
    Ok(SweepReport {
        manifest,
        shard_tasks: mine.len(),
        resumed,
        ran: todo.len(),
        distrusted,
        rows: full,
    })
}

/// The absolute, symlink-free form of `p`, as far as it exists (a missing tail is kept
/// as written), so that two spellings of one folder compare equal.
fn resolved(p: &Path) -> std::path::PathBuf {
    let abs = if p.is_absolute() {
        p.to_path_buf()
    } else {
        std::env::current_dir().unwrap_or_default().join(p)
    };
    let mut head = abs.clone();
    let mut tail = Vec::new();
    loop {
        if let Ok(c) = std::fs::canonicalize(&head) {
            let mut out = c;
            for t in tail.iter().rev() {
                out.push(t);
            }
            return out;
        }
        match (head.file_name().map(|n| n.to_os_string()), head.parent()) {
            (Some(n), Some(parent)) => {
                tail.push(n);
                head = parent.to_path_buf();
            }
            _ => return abs,
        }
    }
}

/// Refuses a merge whose output folder is one of its shard folders, lies inside one, or
/// holds one: the merged files would overwrite or mix with a shard's own (and a shard
/// merged into itself keeps a partial journal beside complete tables).
///
/// A shard folder named twice (or through a link) is refused too: it would be counted as
/// two shards.
pub fn check_merge_folders(dirs: &[&Path], out: &Path) -> Result<(), OptError> {
    let mut seen: Vec<(std::path::PathBuf, &Path)> = Vec::new();
    for d in dirs {
        let key = std::fs::canonicalize(d).unwrap_or_else(|_| d.to_path_buf());
        if let Some((_, first)) = seen.iter().find(|(k, _)| *k == key) {
            return Err(OptError::Argument(format!(
                "shard folder {} is named twice (first as {}): name each shard folder once",
                d.display(),
                first.display()
            )));
        }
        seen.push((key, d));
    }
    let o = resolved(out);
    for d in dirs {
        let r = resolved(d);
        let why = if r == o {
            "is the output folder itself"
        } else if o.starts_with(&r) {
            "holds the output folder"
        } else if r.starts_with(&o) {
            "lies inside the output folder"
        } else {
            continue;
        };
        return Err(OptError::Shard(format!(
            "shard folder {} {why} ({}): merge writes into a folder of its own; give an --out outside every shard folder",
            d.display(),
            out.display()
        )));
    }
    Ok(())
}

/// Refuses an output folder of `merge` that holds another study's sweep (its
/// `manifest.json` or a journal of another fingerprint): merging over it would mix two
/// studies' files.
fn check_merge_output(folder: &StudyFolder, manifest: &Manifest) -> Result<(), OptError> {
    let out = folder.dir();
    let path = folder.path("manifest.json");
    // read through the bounded reader: a FIFO or device under that name is refused by
    // kind instead of blocking the merge
    let existing = match std::fs::symlink_metadata(&path) {
        Ok(_) => Some(slipload_motion::limits::read_input_text(
            &path,
            "sweep manifest",
            slipload_motion::limits::MAX_CONFIG_BYTES,
        )?),
        Err(_) => None,
    };
    if let Some(text) = existing {
        let theirs = serde_json::from_str::<Manifest>(&text).ok();
        if theirs
            .as_ref()
            .is_none_or(|m| m.fingerprint != manifest.fingerprint)
        {
            return Err(OptError::Shard(format!(
                "{} holds {}: merge into an empty folder or one holding this study's sweep (fingerprint {})",
                out.display(),
                match &theirs {
                    Some(m) => format!(
                        "the sweep of another study ({}, fingerprint {}; changed: {})",
                        m.study,
                        m.fingerprint.hash,
                        manifest.fingerprint.describe_changes(&m.fingerprint)
                    ),
                    None => format!("a {} that is not a sweep manifest", path.display()),
                },
                manifest.fingerprint.hash
            )));
        }
    }
    folder.check_journals(&manifest.fingerprint)
}

/// Joins the journals of shard folders into `out`: the bytes a single run writes.
/// Every folder must hold the same `manifest.json`; every task must be present. Returns
/// the manifest and the rows (task order), from which the caller draws the figures a
/// single run draws.
pub fn merge(
    dirs: &[&Path],
    folder: &StudyFolder,
) -> Result<(Manifest, Vec<RecordMetrics>), OptError> {
    let out = folder.dir();
    let mut manifest: Option<(Manifest, &Path)> = None;
    for dir in dirs {
        // a shard still being written would be merged half done
        crate::store::folder::check_idle(dir)?;
        let m = Manifest::read(&dir.join("manifest.json"))?;
        match &manifest {
            None => manifest = Some((m, dir)),
            Some((first, fd)) if first.fingerprint != m.fingerprint => {
                return Err(OptError::Shard(format!(
                    "{} and {} hold sweeps of different studies (fingerprints {} and {}; changed: {}): merge only shards of one study",
                    fd.display(),
                    dir.display(),
                    first.fingerprint.hash,
                    m.fingerprint.hash,
                    m.fingerprint.describe_changes(&first.fingerprint)
                )));
            }
            Some((first, fd)) if *first != m => {
                return Err(OptError::Shard(format!(
                    "{} and {} hold sweeps of different studies",
                    fd.display(),
                    dir.display()
                )));
            }
            Some(_) => {}
        }
    }
    let (manifest, _) = manifest.ok_or_else(|| OptError::Shard("no folders to merge".into()))?;
    check_merge_folders(dirs, out)?;
    check_merge_output(folder, &manifest)?;
    let mut rows: Vec<Option<RecordMetrics>> = vec![None; manifest.tasks()];
    for dir in dirs {
        let jpath = dir.join("journal.jsonl");
        let Some((header, entries, _)) = crate::store::journal::read_journal::<Entry>(&jpath)?
        else {
            continue;
        };
        if header.journal != "sweep" || header.fingerprint != manifest.fingerprint {
            return Err(OptError::Journal {
                path: jpath.clone(),
                line: 1,
                message: format!(
                    "was written for another study than the shards' manifest (changed: {}): merge only shards of one study",
                    manifest.fingerprint.describe_changes(&header.fingerprint)
                ),
            });
        }
        place(&manifest, entries, &jpath, &mut rows)?;
    }
    let missing = rows.iter().filter(|r| r.is_none()).count();
    if missing > 0 {
        let first = rows.iter().position(Option::is_none).unwrap_or(0);
        let (d, r) = manifest.task(first);
        return Err(OptError::Shard(format!(
            "{missing} of {} tasks are in no journal (first: design {d}, record {r}); run the missing shards (with --resume) first",
            manifest.tasks()
        )));
    }
    // the merged journal, sorted by key: `--resume` in `out` finds every task done
    let mut entries = Vec::with_capacity(rows.len());
    for (k, m) in rows.iter().enumerate() {
        let (d, r) = manifest.task(k);
        entries.push(Entry {
            design: d,
            record: r,
            record_name: manifest.records[r].clone(),
            slip_loads_n: manifest.designs[d].slip_loads_n.clone(),
            metrics: m.clone().expect("checked complete above"),
        });
    }
    let journal_text =
        crate::store::journal::journal_text("sweep", &manifest.fingerprint, &entries);
    // the journal first: the tables are never newer than the tasks they come from
    folder.write("journal.jsonl", journal_text.as_bytes())?;
    let full = write_outputs(folder, &manifest, &rows)?.expect("checked complete above");
    Ok((manifest, full))
}
