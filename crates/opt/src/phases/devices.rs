//! The device specification of the recommended design: per damper, what the device must
//! be bought and prototype-tested for — its slip load and the range the property bounds
//! give it, the largest friction force, the design stroke each way, the largest slip
//! velocity, the cumulative travel, the slip cycles and the energy it dissipates, each the
//! largest over every record and property case of the check — and, when the study gives
//! the brace angle, the brace's axial force and stiffness. Written as
//! `device-table.{csv,md,json}` beside the code check.
//!
//! The building gives each brace as a storey-level (horizontal) spring k′ in series with
//! its slider; a diagonal brace at θ to the horizontal of axial stiffness k_axial gives
//! k′ = k_axial cos²θ, and a horizontal force F is an axial force F / cos θ in it.

use crate::base::error::OptError;
use crate::base::metrics::RecordMetrics;
use crate::model::check::{CaseName, md_text, short};
use crate::model::devices_config::RedundancyConfig;
use crate::model::study::Study;
use crate::phases::protocol::TestProtocol;
use crate::store::folder::StudyFolder;
use serde::Serialize;
use std::fmt::Write as _;

/// One suite's stroke of one damper (the larger of the two ways, per record).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SuiteStroke {
    /// The suite.
    pub suite: String,
    /// The mean over the suite's records, the largest over the property cases, mm.
    pub mean_mm: f64,
    /// The property case of that largest mean (the lower bound, where the slip loads are
    /// least, as a rule).
    pub mean_case: CaseName,
    /// The largest over the records and cases, mm.
    pub max_mm: f64,
}

/// What one damper must be specified for.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DeviceRow {
    /// Floor (from 1).
    pub floor: usize,
    /// Nominal slip load, kN.
    pub slip_load_kn: f64,
    /// Slip load at the lower and the upper bound, kN.
    pub slip_load_range_kn: [f64; 2],
    /// Largest |friction force| over every run, kN.
    pub peak_force_kn: f64,
    /// Largest slip displacement each way over every run, mm (positive, negative).
    pub stroke_mm: [f64; 2],
    /// The stroke per suite (hazard level).
    pub stroke_by_suite: Vec<SuiteStroke>,
    /// Largest |slip velocity| over every run, mm/s.
    pub peak_velocity_mm_s: f64,
    /// Largest cumulative slip travel of one run, m.
    pub cumulative_travel_m: f64,
    /// Largest number of slip excursions of one run.
    pub slip_excursions: u64,
    /// Largest number of full slip cycles of one run.
    pub cycles: f64,
    /// Largest energy dissipated in one run, kJ.
    pub energy_kj: f64,
    /// The brace's axial force at the largest friction force, kN (with the brace angle).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub brace_axial_force_kn: Option<f64>,
    /// The brace's axial stiffness, k′ / cos²θ, MN/m (with the brace angle).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub brace_axial_stiffness_mn_m: Option<f64>,
    /// Whether the damper never slipped on any record at any case: it acts as a rigid
    /// brace at this slip load.
    pub never_slips: bool,
}

/// The device table of one design.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DeviceTable {
    /// The study.
    pub study: String,
    /// The fidelity the runs were at.
    pub fidelity: String,
    /// Runs the maxima are taken over (records × property cases).
    pub runs: usize,
    /// The brace angle to the horizontal, degrees, when the study gives it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub brace_angle_deg: Option<f64>,
    /// Braces sharing each damper's force, when the study gives it (the brace columns are
    /// per brace).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub braces_per_damper: Option<usize>,
    /// The devices' stroke capacity each way, mm, when the study gives it
    /// (`devices.stroke_capacity_mm`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stroke_capacity_mm: Option<f64>,
    /// One row per damper, bottom to top.
    pub dampers: Vec<DeviceRow>,
    /// The device tests, when the study gives `devices.test_protocol`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub test_protocol: Option<TestProtocol>,
    /// Each device's design values under the redundancy rule, when the study gives
    /// `devices.redundancy`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub redundancy: Option<RedundancyDesign>,
}

/// The devices' design values under the redundancy rule (`devices.redundancy`): each
/// storey's damper stands for `devices_per_storey` devices, which share its force and
/// each take its stroke; with fewer devices than the rule's minimum their design
/// displacement and velocity are × `factor`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RedundancyDesign {
    /// Devices per storey.
    pub devices_per_storey: u32,
    /// Devices on the fewer side of the centre of rigidity, when stated.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub devices_per_side: Option<u32>,
    /// Whether the rule raises the design values.
    pub applies: bool,
    /// Why (or why not), in words.
    pub why: String,
    /// The factor on the design displacement and velocity (1 when the rule does not
    /// apply).
    pub factor: f64,
    /// One row per damper, bottom to top.
    pub devices: Vec<DeviceDesign>,
}

/// One device's design values.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DeviceDesign {
    /// Floor (from 1).
    pub floor: usize,
    /// Each device's slip load at the upper property bound (the storey's over its
    /// devices), kN: the force it and its connections are designed for.
    pub device_force_kn: f64,
    /// Per suite, the design displacement: the suite's mean stroke at its governing case
    /// × the factor, mm.
    pub design_stroke_mm: Vec<f64>,
    /// The design velocity: the largest slip velocity × the factor, mm/s.
    pub design_velocity_mm_s: f64,
}

impl DeviceTable {
    /// The files [`DeviceTable::write_files`] writes.
    pub const FILES: [&str; 3] = ["device-table.csv", "device-table.md", "device-table.json"];

    /// The table of the design `slip_loads_n` (N per damper) from its runs (every run of
    /// `study`, with the per-damper demands the check fidelity records).
    pub fn of(
        study: &Study,
        slip_loads_n: &[f64],
        runs: &[RecordMetrics],
        fidelity: String,
    ) -> Result<DeviceTable, OptError> {
        let cases = study.checks.cases();
        let (lo, hi) = study.checks.slip_load_range();
        let n = study.records.len();
        let angle = study
            .config
            .devices
            .as_ref()
            .and_then(|d| d.brace_angle_deg);
        let braces = study
            .config
            .devices
            .as_ref()
            .and_then(|d| d.braces_per_damper);
        // n braces at θ share the storey-level force and stiffness: each carries
        // F/(n cos θ) axially and has k′/(n cos²θ)
        let per_brace = braces.unwrap_or(1) as f64;
        let cos = angle.map(|t| t.to_radians().cos());
        let mut rows = Vec::new();
        for (k, &floor) in study.space.dampers.iter().enumerate() {
            let demand = |m: &RecordMetrics| {
                m.dampers
                    .as_ref()
                    .and_then(|d| d.get(floor).copied())
                    .ok_or_else(|| {
                        OptError::Missing(format!(
                            "the device table needs the per-damper demands of floor {} (outputs.dampers at the check fidelity)",
                            floor + 1
                        ))
                    })
            };
            let all = runs.iter().map(demand).collect::<Result<Vec<_>, _>>()?;
            let max = |f: &dyn Fn(&slipload_sim::response::DamperDemand) -> f64| {
                all.iter().map(f).fold(0.0, f64::max)
            };
            let peak_force = max(&|d| d.peak_force_n);
            let stroke_by_suite = study
                .suites
                .iter()
                .map(|s| {
                    let mut mean = 0.0f64;
                    let mut mean_case = CaseName::Nominal;
                    let mut top = 0.0f64;
                    for c in 0..cases.len() {
                        let strokes: Vec<f64> = s
                            .range
                            .clone()
                            .map(|r| {
                                let d = &all[c * n + r];
                                d.slip_max_pos_m.max(d.slip_max_neg_m)
                            })
                            .collect();
                        let m = strokes.iter().sum::<f64>() / strokes.len().max(1) as f64;
                        if m > mean {
                            (mean, mean_case) = (m, cases[c].name);
                        }
                        top = strokes.iter().copied().fold(top, f64::max);
                    }
                    SuiteStroke {
                        suite: s.name.clone(),
                        mean_mm: 1e3 * mean,
                        mean_case,
                        max_mm: 1e3 * top,
                    }
                })
                .collect();
            let brace = study.building.dissipators[floor]
                .as_ref()
                .map(|d| d.brace_stiffness);
            let travel = max(&|d| d.cumulative_travel_m);
            let excursions = all.iter().map(|d| d.slip_excursions).max().unwrap_or(0);
            rows.push(DeviceRow {
                floor: floor + 1,
                slip_load_kn: slip_loads_n[k] / 1e3,
                slip_load_range_kn: [lo * slip_loads_n[k] / 1e3, hi * slip_loads_n[k] / 1e3],
                peak_force_kn: peak_force / 1e3,
                stroke_mm: [
                    1e3 * max(&|d| d.slip_max_pos_m),
                    1e3 * max(&|d| d.slip_max_neg_m),
                ],
                stroke_by_suite,
                peak_velocity_mm_s: 1e3 * max(&|d| d.peak_slip_velocity_m_s),
                cumulative_travel_m: travel,
                slip_excursions: excursions,
                cycles: max(&|d| d.cycles),
                energy_kj: max(&|d| d.energy_j) / 1e3,
                brace_axial_force_kn: cos.map(|c| peak_force / (per_brace * c) / 1e3),
                brace_axial_stiffness_mn_m: cos
                    .zip(brace)
                    .map(|(c, k)| k / (per_brace * c * c) / 1e6),
                never_slips: excursions == 0,
            });
        }
        let redundancy = study
            .config
            .devices
            .as_ref()
            .and_then(|d| d.redundancy)
            .map(|r| {
                let (applies, why) = r.applies();
                let factor = if applies {
                    r.factor.unwrap_or(RedundancyConfig::FACTOR)
                } else {
                    1.0
                };
                let per = f64::from(r.devices_per_storey);
                RedundancyDesign {
                    devices_per_storey: r.devices_per_storey,
                    devices_per_side: r.devices_per_side,
                    applies,
                    why,
                    factor,
                    devices: rows
                        .iter()
                        .map(|row| DeviceDesign {
                            floor: row.floor,
                            device_force_kn: row.slip_load_range_kn[1] / per,
                            design_stroke_mm: row
                                .stroke_by_suite
                                .iter()
                                .map(|s| factor * s.mean_mm)
                                .collect(),
                            design_velocity_mm_s: factor * row.peak_velocity_mm_s,
                        })
                        .collect(),
                }
            });
        // the tests' amplitudes are the design displacements: × the redundancy factor
        let raised = redundancy.as_ref().map_or(1.0, |r| r.factor);
        let test_protocol = study
            .config
            .devices
            .as_ref()
            .and_then(|d| d.test_protocol)
            .map(|config| {
                let strokes: Vec<Vec<f64>> = rows
                    .iter()
                    .map(|r| {
                        r.stroke_by_suite
                            .iter()
                            .map(|s| raised * s.mean_mm)
                            .collect()
                    })
                    .collect();
                TestProtocol::of(study, config, slip_loads_n, runs, &strokes)
            });
        Ok(DeviceTable {
            study: study.name.clone(),
            fidelity,
            runs: runs.len(),
            brace_angle_deg: angle,
            braces_per_damper: braces,
            stroke_capacity_mm: study
                .config
                .devices
                .as_ref()
                .and_then(|d| d.stroke_capacity_mm),
            dampers: rows,
            test_protocol,
            redundancy,
        })
    }

    /// The floors whose damper never slipped.
    pub fn rigid_floors(&self) -> Vec<usize> {
        self.dampers
            .iter()
            .filter(|r| r.never_slips)
            .map(|r| r.floor)
            .collect()
    }

    /// `device-table.csv`: one line per damper (per-suite strokes as columns).
    pub fn to_csv(&self) -> String {
        let mut s = String::from(
            "floor,slip_load_kN,slip_load_lower_kN,slip_load_upper_kN,peak_force_kN,stroke_pos_mm,stroke_neg_mm",
        );
        if let Some(r) = self.dampers.first() {
            for st in &r.stroke_by_suite {
                let _ = write!(
                    s,
                    ",stroke_mean_mm_{0},stroke_mean_case_{0},stroke_max_mm_{0}",
                    st.suite
                );
            }
        }
        s.push_str(",peak_velocity_mm_s,cumulative_travel_m,slip_excursions,cycles,energy_kJ");
        if self.brace_angle_deg.is_some() {
            s.push_str(",brace_axial_force_kN,brace_axial_stiffness_MN_m");
        }
        s.push_str(",never_slips\n");
        for r in &self.dampers {
            let _ = write!(
                s,
                "{},{},{},{},{},{},{}",
                r.floor,
                r.slip_load_kn,
                r.slip_load_range_kn[0],
                r.slip_load_range_kn[1],
                r.peak_force_kn,
                r.stroke_mm[0],
                r.stroke_mm[1]
            );
            for st in &r.stroke_by_suite {
                let _ = write!(s, ",{},{},{}", st.mean_mm, st.mean_case.as_str(), st.max_mm);
            }
            let _ = write!(
                s,
                ",{},{},{},{},{}",
                r.peak_velocity_mm_s,
                r.cumulative_travel_m,
                r.slip_excursions,
                r.cycles,
                r.energy_kj
            );
            if let (Some(f), Some(k)) = (r.brace_axial_force_kn, r.brace_axial_stiffness_mn_m) {
                let _ = write!(s, ",{f},{k}");
            } else if self.brace_angle_deg.is_some() {
                s.push_str(",,");
            }
            let _ = writeln!(s, ",{}", r.never_slips);
        }
        s
    }

    /// `device-table.json`.
    pub fn to_json(&self) -> Result<String, OptError> {
        let mut s = serde_json::to_string_pretty(self).map_err(|source| OptError::Json {
            path: "device-table.json".into(),
            source,
        })?;
        s.push('\n');
        Ok(s)
    }

    /// `device-table.md`.
    pub fn to_markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(s, "# Device table: {}\n", self.study);
        let _ = writeln!(
            s,
            "What each damper must be specified and prototype-tested for: the largest of each quantity over {} runs (every record at every property case), {}. Stroke: the largest slip displacement each way; per suite, the mean over its records at the property case where it is largest (named) and the largest (the larger way per record).{}\n",
            self.runs,
            self.fidelity,
            match (self.brace_angle_deg, self.braces_per_damper) {
                (Some(t), None) => format!(
                    " Brace at {t}° to the horizontal: axial force F / cos θ, axial stiffness k′ / cos²θ."
                ),
                (Some(t), Some(n)) => format!(
                    " {n} brace(s) per damper{}, each at {t}° to the horizontal: each brace's axial force F / ({n} cos θ), axial stiffness k′ / ({n} cos²θ).",
                    if n == 2 { " (a chevron)" } else { "" }
                ),
                (None, _) => String::new(),
            }
        );
        if let Some(c) = self.stroke_capacity_mm {
            let largest = self
                .dampers
                .iter()
                .map(|r| r.stroke_mm[0].max(r.stroke_mm[1]))
                .fold(0.0, f64::max);
            let _ = writeln!(
                s,
                "Stroke capacity {} mm each way (`devices.stroke_capacity_mm`): a run in which a damper travels past it is an unacceptable response in the code check. The largest stroke here is {:.1} mm, {:.0} % of it.\n",
                short(c),
                largest,
                100.0 * largest / c
            );
        }
        let suites: Vec<String> = self
            .dampers
            .first()
            .map(|r| r.stroke_by_suite.iter().map(|s| s.suite.clone()).collect())
            .unwrap_or_default();
        s.push_str("| floor | slip load (kN) | range (kN) | peak force (kN) | stroke + / − (mm) |");
        for su in &suites {
            let _ = write!(s, " stroke {su} mean / max (mm) |");
        }
        s.push_str(" velocity (mm/s) | travel (m) | cycles | energy (kJ) |");
        if self.brace_angle_deg.is_some() {
            s.push_str(" brace force (kN) | brace k (MN/m) |");
        }
        s.push_str(" note |\n|---:|---:|---:|---:|---:|");
        for _ in &suites {
            s.push_str("---:|");
        }
        s.push_str("---:|---:|---:|---:|");
        if self.brace_angle_deg.is_some() {
            s.push_str("---:|---:|");
        }
        s.push_str("---|\n");
        for r in &self.dampers {
            let _ = write!(
                s,
                "| {} | {:.1} | {:.1}–{:.1} | {:.1} | {:.1} / {:.1} |",
                r.floor,
                r.slip_load_kn,
                r.slip_load_range_kn[0],
                r.slip_load_range_kn[1],
                r.peak_force_kn,
                r.stroke_mm[0],
                r.stroke_mm[1]
            );
            for st in &r.stroke_by_suite {
                let _ = write!(
                    s,
                    " {:.1} ({}) / {:.1} |",
                    st.mean_mm,
                    st.mean_case.as_str(),
                    st.max_mm
                );
            }
            let _ = write!(
                s,
                " {} | {} | {} | {} |",
                short(r.peak_velocity_mm_s),
                short(r.cumulative_travel_m),
                r.cycles,
                short(r.energy_kj)
            );
            if let (Some(f), Some(k)) = (r.brace_axial_force_kn, r.brace_axial_stiffness_mn_m) {
                let _ = write!(s, " {f:.1} | {} |", short(k));
            } else if self.brace_angle_deg.is_some() {
                s.push_str(" — | — |");
            }
            let past = self
                .stroke_capacity_mm
                .is_some_and(|c| r.stroke_mm[0].max(r.stroke_mm[1]) > c);
            let _ = writeln!(
                s,
                " {} |",
                match (r.never_slips, past) {
                    (true, _) => "never slips: acts as a rigid brace at this slip load",
                    (false, true) => "stroke past the capacity on some run",
                    (false, false) => "",
                }
            );
        }
        if let Some(r) = &self.redundancy {
            s.push('\n');
            s.push_str(&r.to_markdown(&suites));
        }
        if let Some(p) = &self.test_protocol {
            s.push('\n');
            s.push_str(&p.to_markdown());
        }
        s
    }

    /// Writes `device-table.{csv,md,json}` into the study folder.
    pub fn write_files(&self, folder: &StudyFolder) -> Result<(), OptError> {
        folder.write("device-table.csv", self.to_csv().as_bytes())?;
        folder.write("device-table.md", self.to_markdown().as_bytes())?;
        folder.write("device-table.json", self.to_json()?.as_bytes())?;
        Ok(())
    }
}

impl RedundancyDesign {
    /// The section of `device-table.md`; `suites` names the design displacements'
    /// columns.
    pub fn to_markdown(&self, suites: &[String]) -> String {
        let mut s = String::from(
            "## Devices and the redundancy rule

",
        );
        let _ = writeln!(
            s,
            "Each storey's damper is {} devices (`devices.redundancy`), which share its force and each take its stroke. {}: {}. The minimum counts (4 per storey, 2 on each side of the centre of rigidity) and the factor 1.3 are the project's reading of ASCE 7-16 Ch. 18's redundancy rule for damping devices, whose text was not available to check; the study can give its own.\n",
            self.devices_per_storey,
            if self.applies {
                format!(
                    "The rule raises the design displacement and velocity × {}",
                    short(self.factor)
                )
            } else {
                "The rule does not raise the design values".to_string()
            },
            self.why
        );
        s.push_str("| floor | device force at λ_max (kN) |");
        for su in suites {
            let _ = write!(s, " design stroke {} (mm) |", md_text(su));
        }
        s.push_str(" design velocity (mm/s) |\n|---:|---:|");
        for _ in suites {
            s.push_str("---:|");
        }
        s.push_str("---:|\n");
        for d in &self.devices {
            let _ = write!(s, "| {} | {:.1} |", d.floor, d.device_force_kn);
            for v in &d.design_stroke_mm {
                let _ = write!(s, " {v:.1} |");
            }
            let _ = writeln!(s, " {:.1} |", d.design_velocity_mm_s);
        }
        s
    }
}
