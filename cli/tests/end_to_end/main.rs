//! The `kepler` command end to end, as one test binary (one link instead of seven: the test
//! build of this crate was mostly linking). Each module is one concern; run one with
//! `cargo test -p kepler-hsr-cli --test end_to_end MODULE::`.

mod cli;
mod common;
mod diff;
mod goldens;
mod hostile;
mod import;
mod plot;
mod readme;
mod section;
mod views;
