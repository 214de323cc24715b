//! Draws the error-against-time front (`crate::front`): one log-log panel per scene, every cell
//! a marker (its colour the technique, its shape the technique's paper), the Pareto front a grey
//! line through its points, and a legend of the techniques' colours and the papers' shapes.

use crate::config::{Config, FrontSpec};
use crate::font::FAMILY;
use crate::front::{fronts, SceneFront};
use crate::plot::{
    draw_title, ellipsize, encode, err, log_light_lines, log_ticks, text_width, tick, DrawResult, Drawing, Plot, GREY,
    PALETTE, PANEL_HEIGHT, TITLE_HEIGHT, WIDTH,
};
use crate::results::Results;
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

/// What the panels share: the title, the techniques' colours and the papers' shapes.
struct Frame<'a> {
    title: String,
    subtitle: String,
    spec: &'a FrontSpec,
    techniques: Vec<String>,
    papers: Vec<String>,
    scenes: Vec<SceneFront>,
}

/// The front as SVG and PNG.
pub fn render(config: &Config, results: &Results, spec: &FrontSpec) -> Result<Plot> {
    crate::font::load()?;
    // One panel per x metric and scene, the x metrics' panels one after the other.
    let scenes: Vec<SceneFront> = spec.x.iter().flat_map(|x| fronts(config, results, spec, x)).collect();
    let mut papers: Vec<String> = vec![];
    for p in scenes.iter().flat_map(|f| &f.points) {
        if !papers.contains(&p.paper) {
            papers.push(p.paper.clone());
        }
    }
    let m = &results.meta;
    let frame = Frame {
        title: config.table.title(),
        subtitle: format!("{} · {} {} · {}", m.device, m.driver_name, m.driver_info, m.date),
        spec,
        techniques: config.techniques.iter().map(|t| t.label.clone()).collect(),
        papers,
        scenes,
    };
    let height = TITLE_HEIGHT + PANEL_HEIGHT * frame.scenes.len().max(1) as u32;
    encode(&frame, height, "front")
}

impl Drawing for Frame<'_> {
    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        let rest = draw_title(root, &self.title, &self.subtitle)?;
        if self.scenes.is_empty() {
            return rest.draw(&Text::new("no data", (20, 20), (FAMILY, 16.0).into_font())).map_err(err);
        }
        for (area, scene) in rest.split_evenly((self.scenes.len(), 1)).iter().zip(&self.scenes) {
            panel(area, self, scene)?;
        }
        Ok(())
    }
}

/// Draws marker `shape` (a paper's) at `at` in `colour`.
fn marker<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    shape: usize,
    at: (i32, i32),
    colour: RGBColor,
) -> DrawResult {
    let (x, y) = at;
    let fill = colour.filled();
    match shape % 5 {
        0 => area.draw(&Circle::new(at, 5, fill)),
        1 => area.draw(&TriangleMarker::new(at, 7, fill)),
        2 => area.draw(&Rectangle::new([(x - 4, y - 4), (x + 4, y + 4)], fill)),
        3 => area.draw(&Cross::new(at, 5, colour.stroke_width(2))),
        _ => area.draw(&Circle::new(at, 5, colour.stroke_width(2))),
    }
    .map_err(err)
}

fn panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, f: &Frame, scene: &SceneFront) -> DrawResult {
    let rows = f.techniques.len() + f.papers.len() + 1;
    let row = ((PANEL_HEIGHT as i32 - 40) / rows.max(1) as i32).clamp(12, 22);
    let font = (row as f64 - 6.0).clamp(10.0, 14.0);
    let widest = f.techniques.iter().chain(&f.papers).map(|s| text_width(s, font)).max().unwrap_or(0);
    let legend_w = (widest + 60).clamp(140, WIDTH * 42 / 100);
    let (chart_area, legend) = area.split_horizontally(WIDTH - legend_w);
    let text = |label: &str| {
        Text::new(
            ellipsize(label, legend_w - 56, font),
            (0, 0),
            TextStyle::from((FAMILY, font).into_font()).pos(plotters::style::text_anchor::Pos::new(
                plotters::style::text_anchor::HPos::Left,
                plotters::style::text_anchor::VPos::Center,
            )),
        )
    };
    for (i, t) in f.techniques.iter().enumerate() {
        let y = 40 + i as i32 * row;
        // The technique's colour in its paper's shape, as on the chart: colours repeat past
        // the palette's ten, the pair does not.
        let paper = f.scenes.iter().flat_map(|sc| &sc.points).find(|p| p.technique == *t).map(|p| &p.paper);
        let shape = paper.and_then(|p| f.papers.iter().position(|q| q == p)).unwrap_or(0);
        marker(&legend, shape, (20, y), PALETTE[i % PALETTE.len()])?;
        legend.draw(&(EmptyElement::at((44, y)) + text(t))).map_err(err)?;
    }
    for (k, p) in f.papers.iter().enumerate() {
        let y = 40 + (f.techniques.len() + 1 + k) as i32 * row;
        marker(&legend, k, (20, y), GREY)?;
        legend.draw(&(EmptyElement::at((44, y)) + text(p))).map_err(err)?;
    }
    let (xs, ys): (Vec<f64>, Vec<f64>) = scene.points.iter().map(|p| (p.x, p.y)).unzip();
    let span = |v: &[f64]| v.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    let ((x0, x1), (y0, y1)) = (span(&xs), span(&ys));
    let caption = format!("{}: {} against {}", scene.scene, f.spec.y, scene.x);
    let mut chart = ChartBuilder::on(&chart_area)
        .caption(caption, (FAMILY, 18.0))
        .margin(12)
        .margin_right(24)
        .x_label_area_size(44)
        .y_label_area_size(84)
        .build_cartesian_2d(
            (x0 / 1.4..x1 * 1.4)
                .log_scale()
                .with_key_points(log_ticks(x0 / 1.4, x1 * 1.4))
                .with_light_points(log_light_lines(x0 / 1.4, x1 * 1.4)),
            (y0 / 1.4..y1 * 1.4)
                .log_scale()
                .with_key_points(log_ticks(y0 / 1.4, y1 * 1.4))
                .with_light_points(log_light_lines(y0 / 1.4, y1 * 1.4)),
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .x_desc(scene.x.as_str())
        .y_desc(f.spec.y.as_str())
        .x_label_style((FAMILY, 13.0))
        .y_label_style((FAMILY, 13.0))
        .axis_desc_style((FAMILY, 14.0))
        .light_line_style(RGBColor(0xf0, 0xf0, 0xf0))
        .bold_line_style(RGBColor(0xd8, 0xd8, 0xd8))
        .draw()
        .map_err(err)?;
    let front: Vec<(f64, f64)> = scene.front.iter().map(|&i| (scene.points[i].x, scene.points[i].y)).collect();
    chart.draw_series(LineSeries::new(front, GREY.stroke_width(2))).map_err(err)?;
    let plot = chart.plotting_area();
    for p in &scene.points {
        let colour = PALETTE[f.techniques.iter().position(|t| *t == p.technique).unwrap_or(0) % PALETTE.len()];
        let shape = f.papers.iter().position(|q| *q == p.paper).unwrap_or(0);
        let at = plot.map_coordinate(&(p.x, p.y));
        let (dx, dy) = plot.get_base_pixel();
        marker(&plot.strip_coord_spec(), shape, (at.0 - dx, at.1 - dy), colour)?;
    }
    Ok(())
}
