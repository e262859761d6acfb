//! Box-constrained convex QP (stub, to be replaced).

/// Stub.
pub struct BoxQp;
/// Stub.
#[derive(Debug, Clone, Copy, Default)]
pub struct BoxQpStats;
/// Stub.
#[derive(Debug, thiserror::Error)]
#[error("stub")]
pub struct BoxQpError;
