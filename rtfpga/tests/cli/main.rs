//! The `rtfpga` binary run as a user runs it, as a list of contracts: one file per subcommand
//! or concern, one contract per test. Exit codes: 0 on success, 1 on an error the program
//! reports (`error: …` on stderr, naming the bad value and what was expected), 2 on a
//! command-line usage error. Every line a successful run prints that holds an `=` is a
//! `key=value` line (`common::check_lines`). Tests that need Verilator print `SKIPPED` without
//! it (`common::needs`).

mod common;

mod compare;
mod cosim;
mod dual;
mod hardware;
mod limits;
mod options;
mod outputs;
mod precision;
mod project;
mod render;
mod scenes;
mod traversal;
mod usage;
