//! One measured figure of `slipload bench`, judged against its target (met, NOT MET or
//! withdrawn), and the table the figures print as for people; the same figures are the
//! JSON of `--format json`.

use serde::Serialize;

/// Where each target's status (met, NOT MET, withdrawn) is explained.
pub const TARGETS_EXPLAINED: &str = "results/performance/README.md";

/// One measured figure.
#[derive(Debug, Clone, Serialize)]
pub struct Figure {
    /// What was run.
    pub case: String,
    /// What was measured.
    pub metric: String,
    /// The measurement.
    pub value: f64,
    /// Its unit.
    pub unit: String,
    /// The target, e.g. ">= 5000" (`null`: reported, no target).
    pub target: Option<String>,
    /// Whether a target in force is met (`null` without a target, or when the target is
    /// withdrawn).
    pub met: Option<bool>,
    /// The target's status: `met`, `NOT MET` or `withdrawn`
    /// (`null` without a target).
    pub status: Option<String>,
    /// Where the status is explained, for every status but `met` (`null` otherwise).
    pub note: Option<String>,
}

impl Figure {
    pub(super) fn new(case: &str, metric: &str, value: f64, unit: &str) -> Figure {
        Figure {
            case: case.into(),
            metric: metric.into(),
            value,
            unit: unit.into(),
            target: None,
            met: None,
            status: None,
            note: None,
        }
    }
    /// A target in force: its status is `met` or `NOT MET` (with a pointer to why).
    pub(super) fn judged(mut self, target: String, met: bool) -> Figure {
        self.target = Some(target);
        self.met = Some(met);
        self.status = Some(if met { "met" } else { "NOT MET" }.into());
        self.note = (!met).then(|| format!("see {TARGETS_EXPLAINED}"));
        self
    }
    pub(super) fn at_least(self, t: f64) -> Figure {
        let met = self.value >= t;
        self.judged(format!(">= {}", fmt(t)), met)
    }
    pub(super) fn at_most(self, t: f64) -> Figure {
        let met = self.value <= t;
        self.judged(format!("<= {}", fmt(t)), met)
    }
    pub(super) fn between(self, lo: f64, hi: f64) -> Figure {
        let met = self.value >= lo && self.value <= hi;
        self.judged(format!("{} .. {}", fmt(lo), fmt(hi)), met)
    }
    /// The target no longer holds the figure: reported beside it, not judged.
    pub(super) fn withdrawn(mut self) -> Figure {
        self.met = None;
        self.status = Some("withdrawn".into());
        self.note = Some(format!("see {TARGETS_EXPLAINED}"));
        self
    }
}

/// A figure or a target for the table: scientific notation with three decimals from 1e5
/// on and below 1e-2, whole numbers as such, else four decimals without trailing zeros.
pub(super) fn fmt(v: f64) -> String {
    if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-2) {
        format!("{v:.3e}")
    } else if v.fract() == 0.0 {
        format!("{v:.0}")
    } else {
        // four decimals, without trailing zeros (a guard of 55.4 prints as 55.4)
        let s = format!("{v:.4}");
        s.trim_end_matches('0').to_string()
    }
}

/// Prints the figures as a table, one block per case, each figure beside its target and
/// status.
pub(super) fn print_table(figs: &[Figure], clock_note: &str) {
    outln!("slipload bench — single thread unless stated; times are {clock_note}, medians");
    outln!(
        "targets: met, NOT MET or withdrawn; what each status means and why: {TARGETS_EXPLAINED}"
    );
    let mut last = "";
    for f in figs {
        if f.case != last {
            outln!("\n{}", f.case);
            last = &f.case;
        }
        let target = f.target.as_deref().unwrap_or("");
        let status = match (&f.status, &f.note) {
            (Some(s), Some(n)) => format!("{s}: {n}"),
            (Some(s), None) => s.clone(),
            (None, _) => String::new(),
        };
        outln!(
            "  {:<52} {:>12} {:<4} {:>12} {}",
            f.metric,
            fmt(f.value),
            f.unit,
            target,
            status
        );
    }
}
