//! The command line's own parts beside `main.rs`'s argument parsing: where results go
//! (`output`), `tribosim report` (`report`), `tribosim run` (`run`) and a fit's readable summary (`summary`).

pub mod error;
pub mod output;
pub mod report;
pub mod run;
pub mod summary;
