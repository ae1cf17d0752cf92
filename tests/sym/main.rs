//! Tests of hdot-sym.
