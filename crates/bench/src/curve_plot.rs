//! Draws progressive accumulation's curves (`crate::progressive`): one log-log panel per scene
//! (and photon count), the receiver map's relative RMSE against the accumulated time, a line per
//! technique through every frame's point, its first frame marked. A table whose cells have
//! curves gets this plot instead of the bars of its metrics, which read the same curves at a
//! few frames and times.

use crate::font::FAMILY;
use crate::plot::{
    draw_title, encode, err, log_light_lines, log_mesh, log_ticks, DrawResult, Drawing, Plot, PALETTE, PANEL_HEIGHT,
    TITLE_HEIGHT,
};
use crate::progressive::Point;
use crate::results::Results;
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

/// One panel: its title and, per technique (in the config's order), its curve.
struct Panel {
    title: String,
    curves: Vec<(String, Vec<Point>)>,
}

struct Curves {
    title: String,
    subtitle: String,
    techniques: Vec<String>,
    panels: Vec<Panel>,
}

/// Whether any cell of `results` has a curve.
pub fn has_curves(results: &Results) -> bool {
    results.cells.iter().any(|c| !c.progressive.is_empty())
}

/// The curves as SVG and PNG.
pub fn render(config: &crate::config::Config, results: &Results) -> Result<Plot> {
    crate::font::load()?;
    let mut panels: Vec<Panel> = vec![];
    for c in results.cells.iter().filter(|c| !c.progressive.is_empty()) {
        let title = format!("{}, {}² photons a frame", crate::plan::scene_label(&c.cell.scene), c.cell.photons);
        let curve = (c.cell.technique_label.clone(), c.progressive.clone());
        match panels.iter_mut().find(|p| p.title == title) {
            Some(p) => p.curves.push(curve),
            None => panels.push(Panel { title, curves: vec![curve] }),
        }
    }
    let curves = Curves {
        title: config.table.title(),
        subtitle: crate::plot::subtitle(&results.meta),
        techniques: config.techniques.iter().map(|t| t.label.clone()).collect(),
        panels,
    };
    encode(&curves, TITLE_HEIGHT + PANEL_HEIGHT * curves.panels.len().max(1) as u32, "curves")
}

impl Drawing for Curves {
    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        let rest = draw_title(root, &self.title, &self.subtitle)?;
        for (area, p) in rest.split_evenly((self.panels.len().max(1), 1)).iter().zip(&self.panels) {
            panel(area, self, p)?;
        }
        Ok(())
    }
}

fn panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, f: &Curves, p: &Panel) -> DrawResult {
    let points = p.curves.iter().flat_map(|(_, c)| c).filter(|q| q.ms > 0.0 && q.rel_rmse > 0.0);
    let (mut x0, mut x1, mut y0, mut y1) = (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64);
    for q in points {
        (x0, x1, y0, y1) = (x0.min(q.ms), x1.max(q.ms), y0.min(q.rel_rmse), y1.max(q.rel_rmse));
    }
    if !(x1 > 0.0 && y1 > 0.0) {
        return area
            .draw(&Text::new(format!("{}: no curve", p.title), (20, 20), (FAMILY, 16.0).into_font()))
            .map_err(err);
    }
    let (x0, x1, y0, y1) = (x0 / 1.3, x1 * 1.3, y0 / 1.3, y1 * 1.3);
    let mut chart = ChartBuilder::on(area)
        .caption(&p.title, (FAMILY, 18.0))
        .margin(12)
        .margin_right(24)
        .x_label_area_size(44)
        .y_label_area_size(84)
        .build_cartesian_2d(
            (x0..x1).log_scale().with_key_points(log_ticks(x0, x1)).with_light_points(log_light_lines(x0, x1)),
            (y0..y1).log_scale().with_key_points(log_ticks(y0, y1)).with_light_points(log_light_lines(y0, y1)),
        )
        .map_err(err)?;
    log_mesh(&mut chart, "accumulated ms", "rel. RMSE of the receiver map")?;
    for (label, curve) in &p.curves {
        let colour = PALETTE[f.techniques.iter().position(|t| t == label).unwrap_or(0) % PALETTE.len()];
        let line: Vec<(f64, f64)> = curve.iter().map(|q| (q.ms, q.rel_rmse)).collect();
        chart
            .draw_series(LineSeries::new(line.clone(), colour.stroke_width(2)))
            .map_err(err)?
            .label(label.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)));
        chart.draw_series(line.first().map(|&at| Circle::new(at, 4, colour.filled()))).map_err(err)?;
    }
    chart
        .configure_series_labels()
        .label_font((FAMILY, 13.0))
        .background_style(WHITE.mix(0.8))
        .border_style(RGBColor(0xd8, 0xd8, 0xd8))
        .position(SeriesLabelPosition::UpperRight)
        .draw()
        .map_err(err)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_with_curves_draws_a_panel_per_scene() {
        // The committed T4 table (lavapipe) and the config it embeds.
        let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../results");
        let path = root
            .join("llvmpipe-llvmpipe-llvm-15-0-6-256-bits-mesa-22-3-6-llvm-15-0-6/photon_trace_progressive.json.gz");
        let mut results = crate::results::read(&path, "T4").expect("the T4 table");
        let config: crate::config::Config = toml::from_str(&results.config.toml).expect("its config");
        assert!(has_curves(&results));
        let plot = render(&config, &results).expect("a plot");
        for scene in ["sphere_on_plane", "ring_cardioid", "bunny_in_room"] {
            assert!(plot.svg.contains(&format!("{scene}, 256² photons a frame")), "{scene}'s panel");
        }
        // plotters writes each text on a line of its own.
        assert!(plot.svg.contains("\naccumulated ms\n") && plot.svg.contains("\nalpha 1\n"), "axes and legend");
        results.cells.iter_mut().for_each(|c| c.progressive.clear());
        assert!(!has_curves(&results));
    }
}
