//! tribosim: ball-on-disc tribocorrosion wear simulation after Dalmau et al., Wear 394-395
//! (2018) 166-175.
//!
//! The numerical core (`simulation` over `scene`, `wear`, `contact`, `hardness` and
//! `corrosion`) is plain synchronous Rust in SI units; nothing in it knows about HTTP or
//! async runtimes. The service and the command line use the core through `simulation`;
//! `docs/architecture.md` gives the layers, a paragraph per module and where each of the
//! paper's equations lives.

pub mod bench;
pub mod calibration;
pub mod contact;
pub mod corrosion;
pub mod csv;
pub mod hardness;
pub mod json;
pub mod report;
pub mod scene;
pub mod service;
pub mod simulation;
pub mod study;
pub mod surface;
pub mod text;
pub mod wear;
