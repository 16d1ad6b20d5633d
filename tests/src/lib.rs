//! footprint-tests: integration tests live in `tests/`.
