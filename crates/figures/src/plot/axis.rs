//! Axes: a linear or logarithmic coordinate with "nice" ticks, as one plotters coordinate
//! type (so every panel has the same chart type whatever its scales).

use plotters::coord::ranged1d::{KeyPointHint, NoDefaultFormatting, Ranged, ValueFormatter};
use std::ops::Range;

/// One axis of a panel, as the figure code describes it.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Label, "quantity (unit)", e.g. `"floor displacement (mm)"`.
    pub label: String,
    /// Logarithmic scale (non-positive values are left out of the plot).
    pub log: bool,
    /// Fixed range (min, max); `None` = fitted to the data with a small margin.
    pub range: Option<(f64, f64)>,
    /// Include zero in a fitted linear range (bars, energies, drift profiles).
    pub include_zero: bool,
    /// Ticks at whole numbers only (storeys, counts).
    pub integer: bool,
}

impl Axis {
    /// A linear axis labelled `label`, range fitted to the data.
    pub fn new(label: impl Into<String>) -> Self {
        Self {
            label: label.into(),
            log: false,
            range: None,
            include_zero: false,
            integer: false,
        }
    }

    /// The range this axis shows for data spanning `[lo, hi]` (finite, and > 0 on a log
    /// axis; `None` when there is no such datum).
    pub fn resolve(&self, data: Option<(f64, f64)>) -> (f64, f64) {
        if let Some(r) = self.range {
            return r;
        }
        if self.log {
            let (lo, hi) = data.unwrap_or((1.0, 10.0));
            let (lo, hi) = if hi > lo {
                (lo, hi)
            } else {
                (lo / 2.0, hi * 2.0)
            };
            // A 4 % margin in log space either side.
            let f = (hi / lo).powf(0.04);
            (lo / f, hi * f)
        } else {
            let (mut lo, mut hi) = data.unwrap_or((0.0, 1.0));
            if self.include_zero {
                lo = lo.min(0.0);
                hi = hi.max(0.0);
            }
            if hi <= lo {
                let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
                return (lo - d, hi + d);
            }
            let m = 0.04 * (hi - lo);
            // Zero stays on the edge when the data start there (energies, drifts).
            let lo = if lo == 0.0 && self.include_zero {
                0.0
            } else {
                lo - m
            };
            let hi = if hi == 0.0 && self.include_zero {
                0.0
            } else {
                hi + m
            };
            (lo, hi)
        }
    }
}

/// A resolved axis scale: the plotters coordinate of every panel axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scale {
    /// Shown range, data units.
    pub lo: f64,
    /// Shown range, data units.
    pub hi: f64,
    /// Logarithmic.
    pub log: bool,
    /// Labelled ticks wanted (at most; nice steps give between about half and all).
    pub ticks: usize,
    /// Ticks at whole numbers only (linear axes).
    pub integer: bool,
}

impl Scale {
    fn t(&self, v: f64) -> f64 {
        if self.log {
            (v.ln() - self.lo.ln()) / (self.hi.ln() - self.lo.ln())
        } else {
            (v - self.lo) / (self.hi - self.lo)
        }
    }

    /// Whether `v` can be placed on this axis (finite; positive on a log axis).
    pub fn accepts(&self, v: f64) -> bool {
        v.is_finite() && (!self.log || v > 0.0)
    }

    /// Major ticks, at most about `n`.
    pub fn major_ticks(&self, n: usize) -> Vec<f64> {
        if self.log {
            log_ticks(self.lo, self.hi, n).0
        } else {
            let (ticks, step) = linear_ticks(self.lo, self.hi, n);
            if self.integer && step < 1.0 {
                let (a, b) = (self.lo.ceil() as i64, self.hi.floor() as i64);
                (a..=b).map(|k| k as f64).collect()
            } else {
                ticks
            }
        }
    }

    fn minor_ticks(&self, n: usize) -> Vec<f64> {
        if self.log {
            log_ticks(self.lo, self.hi, n).1
        } else {
            // Linear axes: the major grid only.
            let _ = n;
            Vec::new()
        }
    }

    /// Tick label of `v` on this axis.
    pub fn format(&self, v: f64) -> String {
        if self.log {
            format_log(v)
        } else {
            let step = linear_ticks(self.lo, self.hi, self.ticks).1;
            format_linear(v, if self.integer { step.max(1.0) } else { step })
        }
    }
}

impl Ranged for Scale {
    type FormatOption = NoDefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        let t = self.t(*value);
        let p = f64::from(limit.0) + t * f64::from(limit.1 - limit.0);
        // Far outside points are clamped (plotters clips at the plotting area).
        p.clamp(-1e6, 1e6).round() as i32
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        let n = hint.max_num_points();
        if n == 0 {
            return Vec::new();
        }
        // The scale decides how many labels it wants (`ticks`), so labels and their
        // format agree; plotters' hint only caps it.
        let bold = self.ticks.min(hint.bold_points());
        if hint.weight().allow_light_points() && n > hint.bold_points() {
            self.minor_ticks(bold)
        } else {
            self.major_ticks(self.ticks.min(n))
        }
    }

    fn range(&self) -> Range<f64> {
        self.lo..self.hi
    }
}

impl ValueFormatter<f64> for Scale {
    fn format_ext(&self, value: &f64) -> String {
        self.format(*value)
    }
}

/// Nice linear ticks inside [lo, hi] (steps 1, 2, 5 × 10^k), at most about `n`;
/// returns (ticks, step).
pub fn linear_ticks(lo: f64, hi: f64, n: usize) -> (Vec<f64>, f64) {
    let span = hi - lo;
    if span.is_nan() || span <= 0.0 || !span.is_finite() {
        return (vec![lo], 1.0);
    }
    let raw = span / n.max(2) as f64;
    let p = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * p)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * p);
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    let ticks = (first..=last)
        .map(|k| {
            let v = k as f64 * step;
            // Snap round-off (0.30000000000000004 → 0.3; −0 → 0).
            if v.abs() < 1e-12 * step { 0.0 } else { v }
        })
        .collect();
    (ticks, step)
}

/// Log ticks inside [lo, hi]: (labelled, minor). Decades are labelled; when the range
/// spans at most three decades (and `n` ≥ 8) 2 and 5 are labelled too; minor ticks are
/// 1…9 × 10^k.
fn log_ticks(lo: f64, hi: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
    if lo.is_nan() || hi.is_nan() || lo <= 0.0 || hi <= lo {
        return (vec![], vec![]);
    }
    let k0 = lo.log10().floor() as i32;
    let k1 = hi.log10().ceil() as i32;
    let decades = (k1 - k0).max(1) as usize;
    let inside = |v: &f64| *v >= lo * (1.0 - 1e-9) && *v <= hi * (1.0 + 1e-9);
    let mut major = Vec::new();
    let mut minor = Vec::new();
    let every = decades.div_ceil(n.max(1));
    for k in k0..=k1 {
        let d = 10f64.powi(k);
        for m in 1..=9 {
            let v = m as f64 * d;
            if !inside(&v) {
                continue;
            }
            minor.push(v);
            let labelled = if m == 1 {
                ((k - k0) as usize).is_multiple_of(every.max(1))
            } else {
                (decades <= 2 || (decades <= 3 && n >= 8)) && (m == 2 || m == 5)
            };
            if labelled {
                major.push(v);
            }
        }
    }
    (major, minor)
}

/// Tick label for a linear axis with tick spacing `step`.
pub fn format_linear(v: f64, step: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs().max(step.abs());
    if !(1e-3..1e6).contains(&a) {
        return format_sci(v);
    }
    let decimals = (-(step.log10().floor())).max(0.0) as usize;
    format!("{v:.decimals$}")
}

/// Tick label for a log axis.
pub fn format_log(v: f64) -> String {
    if (1e-3..1e5).contains(&v) {
        let s = format!("{v:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        s.to_string()
    } else {
        format_sci(v)
    }
}

/// `1.5e-6` style, mantissa with at most 3 significant digits, no trailing zeros.
fn format_sci(v: f64) -> String {
    let s = format!("{v:.2e}");
    match s.split_once('e') {
        Some((m, e)) => {
            let m = if m.contains('.') {
                m.trim_end_matches('0').trim_end_matches('.')
            } else {
                m
            };
            format!("{m}e{e}")
        }
        None => s,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_are_round_and_inside() {
        let (t, step) = linear_ticks(-0.013, 0.047, 6);
        assert_eq!(step, 0.01);
        assert_eq!(t.first().copied(), Some(-0.01));
        assert_eq!(t.last().copied(), Some(0.04));
        assert!(t.contains(&0.0));
        assert_eq!(format_linear(0.03, step), "0.03");
        assert_eq!(format_linear(2.5, 0.5), "2.5");
        assert_eq!(format_linear(2.0, 0.5), "2.0");
        assert_eq!(format_linear(1.5e7, 5e6), "1.5e7");
    }

    #[test]
    fn log_ticks_label_decades() {
        let (major, minor) = log_ticks(3e-4, 2.0, 8);
        assert_eq!(major, vec![1e-3, 1e-2, 1e-1, 1.0]);
        assert!(minor.len() > major.len());
        let (major, _) = log_ticks(1.5, 40.0, 8);
        assert_eq!(major, vec![2.0, 5.0, 10.0, 20.0]);
        assert_eq!(format_log(1e-3), "0.001");
        assert_eq!(format_log(1e-7), "1e-7");
        assert_eq!(format_log(20.0), "20");
    }

    #[test]
    fn fitted_ranges() {
        let a = Axis::new("x (m)");
        let (lo, hi) = a.resolve(Some((0.0, 10.0)));
        assert!(lo < 0.0 && hi > 10.0);
        let z = Axis {
            include_zero: true,
            ..Axis::new("E (J)")
        };
        assert_eq!(z.resolve(Some((0.0, 10.0))).0, 0.0);
        let l = Axis {
            log: true,
            ..Axis::new("error (-)")
        };
        let (lo, hi) = l.resolve(Some((1e-6, 1e-2)));
        assert!(lo < 1e-6 && lo > 1e-7 && hi > 1e-2 && hi < 1e-1);
    }
}
