//! slipload-opt.
