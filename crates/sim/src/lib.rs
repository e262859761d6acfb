//! slipload-sim: N-storey frames with one friction dissipator per floor under earthquake
//! records — building model, scenes, plans, integrators, responses and energies.

pub mod friction;
