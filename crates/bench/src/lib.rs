//! Turns GPU timings into records and tables: what ran (device, driver, code path, config) and
//! how long each pass took (median/min/max with every raw sample).

pub mod record;

pub use record::Timings;
