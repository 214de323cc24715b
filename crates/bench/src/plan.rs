//! The cells a config measures: the matrix expanded in a fixed order (scene, technique,
//! photons, lights, resolution, lighting), then narrowed by `--filter` and `--shard i/n`.
//! Every cell has a stable index, so shards merge back into the same table.

use crate::config::{Config, QuickSpec};
use anyhow::Result;
use caustics::input_error;
use serde::{Deserialize, Serialize};

/// One measured point of the matrix. Keys are the axis labels used in tables and filters.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Cell {
    /// Position in the full (unfiltered, unsharded) matrix.
    pub index: usize,
    pub scene: String,
    /// Index into `Config::techniques`.
    pub technique: usize,
    pub technique_label: String,
    pub photons: u32,
    /// 0 = the scene's own lights.
    pub lights: u32,
    /// [0, 0] = the scene's camera.
    pub resolution: [u32; 2],
    pub lighting: String,
}

impl Cell {
    /// The label of this cell on `axis` (not `metric`).
    pub fn key(&self, axis: &str) -> String {
        match axis {
            "scene" => scene_label(&self.scene),
            "technique" => self.technique_label.clone(),
            "photons" => self.photons.to_string(),
            "lights" => lights_label(self.lights),
            "resolution" => resolution_label(self.resolution),
            "lighting" => self.lighting.clone(),
            _ => String::new(),
        }
    }

    /// `scene=… technique=… …`, for progress lines and errors.
    pub fn describe(&self) -> String {
        ["scene", "technique", "photons", "lights", "resolution", "lighting"]
            .iter()
            .map(|a| format!("{a}={}", self.key(a)))
            .collect::<Vec<_>>()
            .join(" ")
    }
}

pub fn scene_label(path: &str) -> String {
    std::path::Path::new(path).file_stem().and_then(|s| s.to_str()).unwrap_or(path).to_string()
}
pub fn lights_label(n: u32) -> String {
    if n == 0 {
        "scene".into()
    } else {
        n.to_string()
    }
}
pub fn resolution_label(r: [u32; 2]) -> String {
    if r == [0, 0] {
        "scene".into()
    } else {
        format!("{}x{}", r[0], r[1])
    }
}

/// Axis values after `--quick`: what the matrix expands over.
#[derive(Debug, Clone)]
pub struct Matrix {
    pub scenes: Vec<String>,
    pub photons: Vec<u32>,
    pub lights: Vec<u32>,
    pub resolution: Vec<[u32; 2]>,
    pub lighting: Vec<String>,
}

impl Matrix {
    pub fn new(c: &Config, quick: Option<&QuickSpec>) -> Matrix {
        let m = &c.matrix;
        let or = |v: &Vec<u32>| if v.is_empty() { vec![0] } else { v.clone() };
        let res = |v: &Vec<[u32; 2]>| if v.is_empty() { vec![[0, 0]] } else { v.clone() };
        Matrix {
            scenes: quick.and_then(|q| q.scenes.clone()).unwrap_or_else(|| m.scenes.clone()),
            photons: quick.map(|q| q.photons.clone()).unwrap_or_else(|| m.photons.clone()),
            lights: or(&m.lights),
            resolution: quick.map(|q| res(&q.resolution)).unwrap_or_else(|| res(&m.resolution)),
            lighting: m.lighting.clone(),
        }
    }

    /// The labels of `axis`, in matrix order.
    pub fn keys(&self, c: &Config, axis: &str) -> Vec<String> {
        match axis {
            "scene" => self.scenes.iter().map(|s| scene_label(s)).collect(),
            "technique" => c.techniques.iter().map(|t| t.label.clone()).collect(),
            "photons" => self.photons.iter().map(|p| p.to_string()).collect(),
            "lights" => self.lights.iter().map(|&l| lights_label(l)).collect(),
            "resolution" => self.resolution.iter().map(|&r| resolution_label(r)).collect(),
            "lighting" => self.lighting.clone(),
            "metric" => c.metrics.iter().map(|m| m.label.clone()).collect(),
            _ => vec![],
        }
    }

    /// Every cell, in index order: those whose technique can run at their photon count
    /// ([`Config::runs`]; the others are N/A in the table and have no index).
    pub fn cells(&self, c: &Config) -> Vec<Cell> {
        let mut out = vec![];
        for scene in &self.scenes {
            for (t, spec) in c.techniques.iter().enumerate() {
                for &photons in self.photons.iter().filter(|&&p| c.runs(t, p)) {
                    for &lights in &self.lights {
                        for &resolution in &self.resolution {
                            for lighting in &self.lighting {
                                out.push(Cell {
                                    index: out.len(),
                                    scene: scene.clone(),
                                    technique: t,
                                    technique_label: spec.label.clone(),
                                    photons,
                                    lights,
                                    resolution,
                                    lighting: lighting.clone(),
                                });
                            }
                        }
                    }
                }
            }
        }
        out
    }
}

/// `--filter axis=value[,axis=value...]`: a cell runs when it matches every term (several
/// terms on one axis: any of them).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Filter {
    pub terms: Vec<(String, String)>,
}

impl Filter {
    pub fn parse(arg: &str, c: &Config, m: &Matrix) -> Result<Filter> {
        let mut terms = vec![];
        for term in arg.split(',').map(str::trim).filter(|t| !t.is_empty()) {
            let Some((axis, value)) = term.split_once('=') else {
                return Err(input_error!("--filter: `{term}` is not axis=value (axes: scene, technique, photons, lights, resolution, lighting)").into());
            };
            let (axis, value) = (axis.trim(), value.trim());
            if axis == "metric" || !crate::config::AXES.contains(&axis) {
                return Err(input_error!(
                    "--filter: unknown axis `{axis}`; cells are chosen by scene, technique, photons, lights, resolution or lighting"
                )
                .into());
            }
            let keys = m.keys(c, axis);
            if !keys.iter().any(|k| k == value) {
                return Err(input_error!(
                    "--filter: `{axis}` has no value `{value}`; this config's values: {}",
                    keys.join(", ")
                )
                .into());
            }
            terms.push((axis.to_string(), value.to_string()));
        }
        Ok(Filter { terms })
    }

    pub fn matches(&self, cell: &Cell) -> bool {
        let mut axes: Vec<&str> = self.terms.iter().map(|(a, _)| a.as_str()).collect();
        axes.dedup();
        axes.iter().all(|a| self.terms.iter().filter(|(x, _)| x == a).any(|(_, v)| cell.key(a) == *v))
    }

    pub fn is_empty(&self) -> bool {
        self.terms.is_empty()
    }
}

/// `--shard i/n` (1-based): cells whose index ≡ i-1 (mod n), so shards of a sweep take turns
/// through the photon counts and finish at about the same time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    pub index: u32,
    pub count: u32,
}

impl Shard {
    pub fn parse(arg: &str) -> Result<Shard> {
        let bad = || input_error!("--shard: `{arg}` must be i/n with 1 <= i <= n, e.g. 2/4");
        let (i, n) = arg.split_once('/').ok_or_else(bad)?;
        let (i, n): (u32, u32) = (i.trim().parse().map_err(|_| bad())?, n.trim().parse().map_err(|_| bad())?);
        if n == 0 || i == 0 || i > n {
            return Err(bad().into());
        }
        Ok(Shard { index: i, count: n })
    }

    pub fn takes(&self, cell: &Cell) -> bool {
        cell.index % self.count as usize == (self.index - 1) as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_cells() {
        for n in 1..6u32 {
            let cells: Vec<Cell> = (0..17)
                .map(|i| Cell {
                    index: i,
                    scene: "s".into(),
                    technique: 0,
                    technique_label: "t".into(),
                    photons: 64,
                    lights: 0,
                    resolution: [0, 0],
                    lighting: "dynamic".into(),
                })
                .collect();
            let mut seen = vec![0; cells.len()];
            for i in 1..=n {
                let s = Shard::parse(&format!("{i}/{n}")).expect("valid shard");
                for c in cells.iter().filter(|c| s.takes(c)) {
                    seen[c.index] += 1;
                }
            }
            assert!(seen.iter().all(|&k| k == 1), "n={n}: {seen:?}");
        }
    }

    /// A config whose second technique (adaptive with a memory limit) alone runs at 16384².
    fn mixed() -> Config {
        let text = r#"
            [table]
            paper = "p"
            number = "1"
            caption = "c"
            [matrix]
            scenes = ["s.toml"]
            photons = [4096, 16384]
            [[technique]]
            label = "hier"
            technique = "hcm"
            [[technique]]
            label = "adaptive"
            technique = "adaptive"
            photon_memory_limit = 96
            [[metric]]
            label = "splatted"
            kind = "splats_drawn"
            [layout]
            rows = ["photons"]
            columns = ["technique"]
        "#;
        toml::from_str(text).expect("a config")
    }

    #[test]
    fn cells_a_technique_cannot_run_are_left_out() {
        let c = mixed();
        let cells = Matrix::new(&c, None).cells(&c);
        let got: Vec<(String, u32, usize)> =
            cells.iter().map(|x| (x.technique_label.clone(), x.photons, x.index)).collect();
        let want = [("hier".to_string(), 4096, 0), ("adaptive".into(), 4096, 1), ("adaptive".into(), 16384, 2)];
        assert_eq!(got, want);
        assert!(!c.runs(0, 16384) && c.runs(0, 4096) && c.runs(1, 16384));
    }

    #[test]
    fn a_quick_run_uses_its_scenes_and_sizes_and_a_full_run_the_matrix() {
        fn scenes(c: &Config, quick: bool) -> Vec<(String, u32)> {
            let m = Matrix::new(c, quick.then_some(&c.quick));
            m.cells(c).iter().map(|x| (x.scene.clone(), x.photons)).collect()
        }
        let mut c = mixed();
        c.matrix.scenes = vec!["a.toml".into(), "b.toml".into(), "c.toml".into()];
        c.quick.scenes = Some(vec!["c.toml".into(), "a.toml".into()]);
        // Two techniques run at the quick photon counts, on the quick scenes in their order.
        let want: Vec<(String, u32)> =
            ["c.toml", "a.toml"].iter().flat_map(|s| [64, 128, 64, 128].map(|p| (s.to_string(), p))).collect();
        assert_eq!(scenes(&c, true), want);
        assert_eq!(scenes(&c, false).len(), 3 * 3, "a full run: every scene, both photon counts for adaptive");
        c.quick.scenes = None;
        assert_eq!(scenes(&c, true).len(), 3 * 2 * 2, "no quick.scenes: every scene");
    }

    #[test]
    fn bad_shards_are_rejected() {
        for bad in ["0/2", "3/2", "1/0", "x/2", "1", "1/2/3", ""] {
            assert!(Shard::parse(bad).is_err(), "{bad} accepted");
        }
    }
}
