//! Tests of hdot-sim. One module per source module, plus the stability
//! studies of issue 5.

// Shared named proptest strategies.
mod strategies;

// The Whipple bicycle's linearized equations against the published benchmark.
mod bicycle;

// The hand-written right-hand sides against the derived equations.
mod derived;
// systems/derived.rs: equations of motion from derivation files, integrated.
mod derived_model;
// scene/derived.rs and models/derived.rs: scenes of kind "derived".
mod derived_scene;
// systems/derived/first_order.rs: first-order scenes in (q, u), the gyrostat with its attitude.
mod derived_first_order;
// systems/derived/holonomic.rs: configuration constraints solved at the start and kept by projection.
mod holonomic;
// systems/derived/unit_norm.rs: Euler parameters normalized after each step, against 3-1-3 angles.
mod quaternion;
// systems/derived/multiplier.rs: the multiplier form M u' - f = A_c^T lambda, A_c u' + b = 0.
mod multiplier;
// scene/derived.rs: a derived scene's `[[body]]` tables bind the derivation's symbols.
mod derived_bodies;
// systems/derived/positions.rs: where each declared body is, and gravity in N.
mod positions;
// stability/: eigenvalue sweeps of linearised equations (hdot stability).
mod eigen_sweep;
// elliptic.rs: identities, special values, series of K.
mod elliptic;
// exact.rs: closed forms against the ODE and against each other.
mod exact;
// exact.rs near the separatrix against the double-double Taylor reference.
mod exact_separatrix;
// Charts of where methods fail near the separatrix.
mod charts;
// scene.rs: the bodies of every scene (the shared `[[body]]` schema).
mod bodies;
// estimate.rs and run.rs: error estimates of closed forms, --check, non-finite refusal.
mod honest;
// models/rigid_body.rs: the pilot-based method choice for a heavy top.
mod pilot;
// Test support: a 32-digit Taylor integrator of the torque-free body.
mod reference;
// integrate.rs: orders, invariants, step control.
mod integrate;
// models/mod.rs: the registry's docs table and help list every model.
mod registry;
// Issue 21's reproducers: crashes, wrong closed forms, misplaced blame.
mod reliability;
// Issue 24's trial findings: drifts of quantities that start at zero, the
// default error met, tilted gravity.
mod trial;
// Stability where methods fail (issue 5, item 4).
mod stability;
// scene.rs and run.rs: bad input, model choice (snapshots).
mod scene;
