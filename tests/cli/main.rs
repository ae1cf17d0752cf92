//! Tests of the hdot binary.
