//! Tests of hdot-num.
