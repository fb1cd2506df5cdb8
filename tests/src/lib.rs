//! gc2d-rs regression scenes (reference §10.3, items 13 and 19): a poured polydisperse sandpile and a Janssen silo,
//! each in a CI-sized and a thesis-sized version. The scenes are in `tests/scenes/`, the tests with their acceptance
//! numbers in `tests/tests/`, and the measured values in `docs/validation.md` ("Regression scenes (§10.3)").
