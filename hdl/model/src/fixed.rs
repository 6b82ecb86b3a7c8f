//! filled by the number-format work
