//! The `tribosim` command line.

fn main() {}
