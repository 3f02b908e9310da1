//! tribosim: ball-on-disc tribocorrosion wear simulation after Dalmau et al., Wear 394-395
//! (2018) 166-175.
//!
//! The numerical core (`contact`, `hardness`, `corrosion`, `scene`) is plain synchronous Rust
//! in SI units; nothing here knows about HTTP or async runtimes.

pub mod bench;
pub mod contact;
pub mod corrosion;
pub mod hardness;
pub mod scene;
pub mod service;
pub mod simulation;
pub mod wear;
