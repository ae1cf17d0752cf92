//! A course's derivations under test: nothing here but the tests in
//! `tests/` (see docs/user-crate.md in the hdot repository).
