//! Tests of hdot-sim.
