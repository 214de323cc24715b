//! The benchmark harness: bench configs that regenerate the papers' tables (`config`,
//! `validate`), the cells they expand to (`plan`), running a cell (`measure`, `metrics`), and
//! the outputs (`results` JSON; `table` + `sections` + `report`: Markdown, terminal summary and
//! CSV; `figure` + `plot`: SVG and PNG; `index`), plus
//! `timings.json` of single renders (`record`).

#![forbid(unsafe_code)]

pub mod claims;
pub mod config;
pub mod curve_plot;
pub mod drift;
pub mod explain;
pub mod figure;
pub mod final_flip;
pub mod font;
pub mod format;
pub mod front;
pub mod front_curves;
pub mod front_plot;
pub mod host_speed;
pub mod index;
pub mod measure;
pub mod meta;
pub mod metrics;
pub mod one_cpu;
pub mod paper;
pub mod plan;
pub mod plausibility;
pub mod plot;
pub mod progress;
pub mod progressive;
pub mod record;
pub mod report;
pub mod results;
pub mod run;
pub mod same;
pub mod sections;
pub mod stats;
pub mod steal;
pub mod table;
pub mod text_table;
mod validate;
mod validate_layout;

pub use config::LoadedConfig;
pub use record::Timings;
pub use run::{merge, run, BenchOptions, Outcome};
