//! The integration tests: what a user of the library can do through its public API alone,
//! one module per concern, linked as one binary. Tests that need the library's internals are
//! unit tests inside the crate (src/tests/).

mod fuzz;
mod progress;
