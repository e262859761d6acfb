//! The figures a study command draws at its end, behind one trait: the figure crate
//! implements [`FigureWriter`] (the fronts pass it in), so that opt draws nothing itself
//! and every front writes the same figures through the same call.

use crate::base::error::OptError;
use crate::phases::figures::FigureData;
use crate::phases::pareto::ParetoReport;
use crate::plan::PlanFigureData;
use std::path::Path;

/// Draws a study's figures into its folder. Each method returns the names written (the
/// stems: `convergence` stands for `convergence.{svg,png,csv}`); an error of the writer's
/// own is returned as [`OptError::Figure`].
pub trait FigureWriter: Sync {
    /// Checks, before any work, that the figures can be drawn (the font of the PNG text
    /// is there), so that a long run does not fail at its end.
    fn check(&self) -> Result<(), OptError>;
    /// The study figures of a sweep or of `optimize` (objective map, convergence, drift
    /// profiles, per-record scatter: those `data` holds).
    fn study(&self, data: &FigureData, dir: &Path) -> Result<Vec<String>, OptError>;
    /// The front of a study with `objectives`.
    fn front(&self, report: &ParetoReport, dir: &Path) -> Result<Vec<String>, OptError>;
    /// The figures of a study in plan: the plan view and the drift profiles by line.
    fn plan(&self, data: &PlanFigureData, dir: &Path) -> Result<Vec<String>, OptError>;
}

/// Draws nothing (a run whose caller wants no figures, such as a test of the files).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoFigures;

impl FigureWriter for NoFigures {
    fn check(&self) -> Result<(), OptError> {
        Ok(())
    }
    fn study(&self, _data: &FigureData, _dir: &Path) -> Result<Vec<String>, OptError> {
        Ok(Vec::new())
    }
    fn front(&self, _report: &ParetoReport, _dir: &Path) -> Result<Vec<String>, OptError> {
        Ok(Vec::new())
    }
    fn plan(&self, _data: &PlanFigureData, _dir: &Path) -> Result<Vec<String>, OptError> {
        Ok(Vec::new())
    }
}
