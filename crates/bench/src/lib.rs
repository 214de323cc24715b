//! The benchmark harness: bench configs that regenerate the papers' tables (`config`,
//! `validate`), the cells they expand to (`plan`), running a cell (`measure`, `metrics`), and
//! the outputs (`results` JSON, `table` + `report` markdown/CSV/SVG, `index`), plus
//! `timings.json` of single renders (`record`).

pub mod config;
pub mod index;
pub mod measure;
pub mod meta;
pub mod metrics;
pub mod paper;
pub mod plan;
pub mod progress;
pub mod record;
pub mod report;
pub mod results;
pub mod run;
pub mod steal;
pub mod svg;
pub mod table;
mod validate;

pub use config::LoadedConfig;
pub use record::Timings;
pub use run::{merge, run, BenchOptions, Outcome};
