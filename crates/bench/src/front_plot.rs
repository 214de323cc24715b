//! Draws the error-against-time front (`crate::front`): one row per time metric and scene, in it
//! one log-log panel per error metric side by side (the receiver map's relative RMSE beside the
//! final image's FLIP), every cell a marker (its colour the technique, its shape the technique's
//! paper), the Pareto front a grey line through its points, and a legend of the techniques'
//! colours and the papers' shapes. Progressive accumulation's curves (`crate::front_curves`), on
//! the panels of their x and y, are lines of their own colours (not the techniques'), an open
//! square at 1, 4, 16, 64, ... frames.

use crate::config::{Config, FrontSpec};
use crate::font::FAMILY;
use crate::front::{fronts, SceneFront};
use crate::front_curves::{Curve, CurvesSpec};
use crate::plot::{
    draw_title, ellipsize, encode_sized, err, log_light_lines, log_mesh, log_ticks, text_width, DrawResult, Drawing,
    Plot, GREY, PALETTE, PANEL_HEIGHT, TITLE_HEIGHT, WIDTH,
};
use crate::progressive::Point;

use crate::results::Results;
use anyhow::Result;
use plotters::coord::Shift;
use plotters::prelude::*;

/// The width a panel of each error metric past the first adds.
const PANEL_WIDTH: u32 = 700;

/// What the panels share: the title, the techniques' colours and the papers' shapes.
struct Frame {
    title: String,
    subtitle: String,
    techniques: Vec<String>,
    papers: Vec<String>,
    /// Per row (x metric and scene), a front per y metric.
    rows: Vec<Vec<SceneFront>>,
    width: u32,
    /// Progressive accumulation's curves, the `[front.curves]` that says on which panels they
    /// are drawn, and their techniques' labels in order (their colours).
    curves: Vec<Curve>,
    curves_spec: Option<CurvesSpec>,
    curve_labels: Vec<String>,
    /// The table the curves come from (the legend names it).
    curve_table: String,
}

/// The curves' colours: dark, and none of the techniques' palette, so that a line is not read
/// as a technique's markers.
const CURVE_COLOURS: [RGBColor; 4] =
    [RGBColor(0, 0, 0), RGBColor(0x8c, 0x2d, 0x04), RGBColor(0x54, 0x27, 0x8f), RGBColor(0x00, 0x5a, 0x32)];

impl Frame {
    /// The curves of one panel, each with its colour.
    fn curves_of(&self, f: &SceneFront) -> Vec<(&Curve, RGBColor)> {
        if !self.curves_spec.as_ref().is_some_and(|s| s.drawn_on(&f.x, &f.y)) {
            return vec![];
        }
        self.curves
            .iter()
            .filter(|c| c.scene == f.scene)
            .map(|c| {
                let k = self.curve_labels.iter().position(|l| *l == c.technique).unwrap_or(0);
                (c, CURVE_COLOURS[k % CURVE_COLOURS.len()])
            })
            .collect()
    }
}

/// The rows of the plot: per x metric and scene (the x metrics' rows one after the other), the
/// scene's front of each y metric.
fn rows(config: &Config, results: &Results, spec: &FrontSpec) -> Vec<Vec<SceneFront>> {
    let mut rows: Vec<Vec<SceneFront>> = vec![];
    for x in &spec.x {
        let per_y: Vec<Vec<SceneFront>> = spec.y.iter().map(|y| fronts(config, results, x, y)).collect();
        let scenes = crate::format::first_seen(per_y.iter().flatten().map(|f| f.scene.clone()));
        for scene in scenes {
            // A y metric no cell of the scene has keeps its panel, empty.
            let row = per_y
                .iter()
                .zip(&spec.y)
                .map(|(fs, y)| {
                    fs.iter().find(|f| f.scene == scene).cloned().unwrap_or_else(|| SceneFront {
                        scene: scene.clone(),
                        x: x.clone(),
                        y: y.clone(),
                        points: vec![],
                        front: vec![],
                    })
                })
                .collect();
            rows.push(row);
        }
    }
    rows
}

/// The front as SVG and PNG.
pub fn render(config: &Config, results: &Results, spec: &FrontSpec) -> Result<Plot> {
    crate::font::load()?;
    let rows = rows(config, results, spec);
    let papers = crate::format::first_seen(rows.iter().flatten().flat_map(|f| &f.points).map(|p| p.paper.clone()));
    let drawn = results.front_curves.as_ref().filter(|c| c.missing.is_none());
    let curves = drawn.map_or_else(Vec::new, |c| c.curves.clone());
    let frame = Frame {
        curves_spec: spec.curves.clone(),
        curve_labels: crate::format::first_seen(curves.iter().map(|c| c.technique.clone())),
        curve_table: drawn.map_or_else(String::new, |c| c.table.clone()),
        curves,
        title: config.table.title(),
        subtitle: crate::plot::subtitle(&results.meta),
        techniques: config.techniques.iter().map(|t| t.label.clone()).collect(),
        papers,
        width: WIDTH + PANEL_WIDTH * (spec.y.len().max(1) as u32 - 1),
        rows,
    };
    let height = TITLE_HEIGHT + PANEL_HEIGHT * frame.rows.len().max(1) as u32;
    encode_sized(&frame, frame.width, height, "front")
}

impl Drawing for Frame {
    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        let rest = draw_title(root, &self.title, &self.subtitle)?;
        if self.rows.is_empty() {
            return rest.draw(&Text::new("no data", (20, 20), (FAMILY, 16.0).into_font())).map_err(err);
        }
        for (area, row) in rest.split_evenly((self.rows.len(), 1)).iter().zip(&self.rows) {
            let legend_w = legend(area, self)?;
            let (charts, _) = area.split_horizontally(self.width - legend_w);
            for (a, f) in charts.split_evenly((1, row.len().max(1))).iter().zip(row) {
                panel(a, self, f)?;
            }
        }
        Ok(())
    }
}

/// The points of curve `c` a log-log panel can place (time and error above 0).
fn plotted(c: &Curve) -> impl Iterator<Item = &Point> {
    c.points.iter().filter(|p| p.ms > 0.0 && p.rel_rmse > 0.0)
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

/// The legend at the right of a row: the techniques' colours in their papers' shapes, then the
/// papers' shapes; returns its width.
fn legend<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, f: &Frame) -> Result<u32, String> {
    let curve_rows = if f.curve_labels.is_empty() { 0 } else { f.curve_labels.len() + 2 };
    let rows = f.techniques.len() + f.papers.len() + 1 + curve_rows;
    let row = ((PANEL_HEIGHT as i32 - 40) / rows.max(1) as i32).clamp(12, 22);
    let font = (row as f64 - 6.0).clamp(10.0, 14.0);
    let widest = f.techniques.iter().chain(&f.papers).map(|s| text_width(s, font)).max().unwrap_or(0);
    let legend_w = (widest + 60).clamp(140, WIDTH * 42 / 100);
    let (_, legend) = area.split_horizontally(f.width - legend_w);
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
        let paper = f.rows.iter().flatten().flat_map(|sc| &sc.points).find(|p| p.technique == *t).map(|p| &p.paper);
        let shape = paper.and_then(|p| f.papers.iter().position(|q| q == p)).unwrap_or(0);
        marker(&legend, shape, (20, y), PALETTE[i % PALETTE.len()])?;
        legend.draw(&(EmptyElement::at((44, y)) + text(t))).map_err(err)?;
    }
    for (k, p) in f.papers.iter().enumerate() {
        let y = 40 + (f.techniques.len() + 1 + k) as i32 * row;
        marker(&legend, k, (20, y), GREY)?;
        legend.draw(&(EmptyElement::at((44, y)) + text(p))).map_err(err)?;
    }
    if !f.curve_labels.is_empty() {
        let first = f.techniques.len() + f.papers.len() + 2;
        let y = 40 + first as i32 * row;
        legend.draw(&(EmptyElement::at((8, y)) + text(&format!("curves of {}", f.curve_table)))).map_err(err)?;
        for (k, label) in f.curve_labels.iter().enumerate() {
            let y = 40 + (first + 1 + k) as i32 * row;
            let colour = CURVE_COLOURS[k % CURVE_COLOURS.len()];
            legend.draw(&PathElement::new(vec![(8, y), (32, y)], colour.stroke_width(2))).map_err(err)?;
            legend.draw(&Rectangle::new([(17, y - 3), (23, y + 3)], colour.stroke_width(1))).map_err(err)?;
            legend.draw(&(EmptyElement::at((44, y)) + text(label))).map_err(err)?;
        }
    }
    Ok(legend_w)
}

/// One scene's front of one error metric against one time metric.
fn panel<DB: DrawingBackend>(chart_area: &DrawingArea<DB, Shift>, f: &Frame, scene: &SceneFront) -> DrawResult {
    if scene.points.is_empty() {
        let caption = format!("{}: {} against {}: no cell has both", scene.scene, scene.y, scene.x);
        return chart_area.draw(&Text::new(caption, (20, 20), (FAMILY, 16.0).into_font())).map_err(err);
    }
    let curves = f.curves_of(scene);
    // The axes hold the cells and the curves (whose points are all finite and positive: a
    // time and an error of a frame that ran).
    let curve_points = curves.iter().flat_map(|(c, _)| plotted(c));
    let (xs, ys): (Vec<f64>, Vec<f64>) =
        scene.points.iter().map(|p| (p.x, p.y)).chain(curve_points.map(|p| (p.ms, p.rel_rmse))).unzip();
    let span = |v: &[f64]| v.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    let ((x0, x1), (y0, y1)) = (span(&xs), span(&ys));
    let caption = format!("{}: {} against {}", scene.scene, scene.y, scene.x);
    let mut chart = ChartBuilder::on(chart_area)
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
    log_mesh(&mut chart, &scene.x, &scene.y)?;
    let front: Vec<(f64, f64)> = scene.front.iter().map(|&i| (scene.points[i].x, scene.points[i].y)).collect();
    chart.draw_series(LineSeries::new(front, GREY.stroke_width(2))).map_err(err)?;
    for (c, colour) in &curves {
        let line = plotted(c).map(|p| (p.ms, p.rel_rmse));
        chart.draw_series(LineSeries::new(line, colour.stroke_width(2))).map_err(err)?;
        // An open square at 1, 4, 16, 64, ... frames: the frames can be read off the line.
        let marks = plotted(c).filter(|p| p.frames.is_power_of_two() && p.frames.trailing_zeros() % 2 == 0);
        let squares = marks
            .map(|p| EmptyElement::at((p.ms, p.rel_rmse)) + Rectangle::new([(-3, -3), (3, 3)], colour.stroke_width(1)));
        chart.draw_series(squares).map_err(err)?;
    }
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
