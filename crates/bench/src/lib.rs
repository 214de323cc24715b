//! Per-pass timing statistics.
