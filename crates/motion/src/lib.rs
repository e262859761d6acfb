//! Ground motions for slipload: record readers, synthetic generators, scaling, spectra.
