//! Synthetic results for the table and plausibility tests: cells with given samples, run
//! through the same code that renders a real run.
#![allow(dead_code)]

use bench::config::Config;
use bench::plan::Cell;
use bench::results::{CellResult, ConfigInfo, Meta, Results, RunInfo, Value, SCHEMA};
use std::collections::BTreeMap;

pub fn value(samples: &[f64]) -> Value {
    let (q1, m, q3) = bench::stats::quartiles(samples).expect("samples");
    Value {
        kind: "pass_ms".into(),
        value: Some(m),
        min: samples.iter().copied().reduce(f64::min),
        max: samples.iter().copied().reduce(f64::max),
        q1: Some(q1),
        q3: Some(q3),
        samples: samples.to_vec(),
    }
}

/// A metric's value without samples: `v` exactly (an error, a FLIP, a time given as is).
pub fn exact(kind: &str, v: f64) -> Value {
    Value { kind: kind.into(), value: Some(v), min: Some(v), max: Some(v), q1: None, q3: None, samples: vec![] }
}

pub fn cell(index: usize, technique: usize, label: &str, photons: u32, samples: &[f64]) -> CellResult {
    CellResult {
        cell: Cell {
            index,
            scene: "../scenes/sphere_on_plane.toml".into(),
            technique,
            technique_label: label.into(),
            photons,
            lights: 0,
            resolution: [0, 0],
            lighting: "dynamic".into(),
        },
        caustics: serde_json::Value::Null,
        photon_copy: "none".into(),
        triangles: 0,
        models: vec![],
        metrics: BTreeMap::from([("Gather".to_string(), value(samples))]),
        wall_ms: samples.to_vec(),
        pose_ms: vec![],
        passes: vec![],
        cpu_steal: None,
        other_cores: None,
        host_probe_ms: None,
        busy: false,
        list_sizes: None,
        frame_counters: BTreeMap::new(),
        block_ms: vec![],
        temporal_changes: vec![],
        progressive: vec![],
        spread_attempts: vec![],
        final_flip: None,
    }
}

pub fn results(config: &Config, toml: &str, cells: Vec<CellResult>) -> Results {
    Results {
        schema: SCHEMA,
        config: ConfigInfo {
            file: "synthetic.toml".into(),
            name: "synthetic".into(),
            hash: "0".into(),
            paper: config.table.paper.clone(),
            table: config.table.number.clone(),
            caption: config.table.caption.clone(),
            toml: toml.into(),
        },
        run: RunInfo {
            quick: false,
            warmup_frames: 1,
            measured_frames: 5,
            time_budget_s: Some(1.0),
            max_frames: Some(1000),
            light_path: "static".into(),
            camera_path: "static".into(),
            object_path: "static".into(),
            period_frames: 60,
            validation: false,
            filter: Default::default(),
            shard: None,
            not_run: vec![],
            explained: None,
            copy_bandwidth_gbs: None,
            total_cells: cells.len(),
        },
        meta: Meta {
            device: "synthetic device".into(),
            device_type: "other".into(),
            device_slug: "synthetic".into(),
            driver_name: "none".into(),
            driver_info: "none".into(),
            vulkan_version: "1.3".into(),
            timestamp_period_ns: 1.0,
            cpu: "none".into(),
            commit: "0000000".into(),
            date: "2026-01-01T00:00:00Z".into(),
            causticlab_version: "0".into(),
            quirks: vec![],
        },
        cells,
        plausibility: vec![],
        front_curves: None,
    }
}

/// `text` as if loaded from `<dir>/synthetic.toml`.
pub fn loaded_config(dir: &std::path::Path, text: &str) -> bench::LoadedConfig {
    bench::LoadedConfig {
        path: dir.join("synthetic.toml"),
        name: "synthetic".into(),
        hash: bench::config::fnv1a(text.as_bytes()),
        text: text.into(),
        config: toml::from_str(text).expect("parses"),
    }
}

/// Writes `text` to `path` and loads it as the bench does (validation included): the error it
/// gives, with its causes. Panics where it loads.
pub fn load_error(path: &std::path::Path, text: &str) -> String {
    std::fs::write(path, text).expect("a config");
    match bench::LoadedConfig::load(path) {
        Ok(_) => panic!("{} loaded", path.display()),
        Err(e) => format!("{e:#}"),
    }
}
