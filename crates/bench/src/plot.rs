//! Draws a [`Figure`] with plotters, once as SVG and once as PNG (same layout): the title and the
//! device above panels stacked one per metric, each with its legend in a column on the right
//! sized to the longest label, so that no title or legend is clipped.

use crate::figure::{Figure, Panel, Series};
use crate::font::FAMILY;
use anyhow::{Context as _, Result};
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;

pub(crate) const WIDTH: u32 = 1100;
pub(crate) const PANEL_HEIGHT: u32 = 420;
pub(crate) const TITLE_HEIGHT: u32 = 64;
/// Matplotlib's "tab10": distinct, print-friendly.
pub(crate) const PALETTE: [RGBColor; 10] = [
    RGBColor(0x1f, 0x77, 0xb4),
    RGBColor(0xff, 0x7f, 0x0e),
    RGBColor(0x2c, 0xa0, 0x2c),
    RGBColor(0xd6, 0x27, 0x28),
    RGBColor(0x94, 0x67, 0xbd),
    RGBColor(0x8c, 0x56, 0x4b),
    RGBColor(0xe3, 0x77, 0xc2),
    RGBColor(0x7f, 0x7f, 0x7f),
    RGBColor(0xbc, 0xbd, 0x22),
    RGBColor(0x17, 0xbe, 0xcf),
];
pub(crate) const GREY: RGBColor = RGBColor(0x55, 0x55, 0x55);

/// The plot as SVG text and as PNG bytes.
pub struct Plot {
    pub svg: String,
    pub png: Vec<u8>,
}

pub fn render(fig: &Figure) -> Result<Plot> {
    crate::font::load()?;
    let height = TITLE_HEIGHT + fig.panels.iter().map(panel_height).sum::<u32>().max(PANEL_HEIGHT);
    encode(fig, height, "plot")
}

/// A picture drawn the same way on both backends (the SVG and the PNG of a plot).
pub(crate) trait Drawing {
    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult;
}

impl Drawing for Figure {
    fn draw_on<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult {
        draw_figure(root, self)
    }
}

/// `d` drawn `WIDTH` by `height` pixels as SVG and as PNG; `what` names it in errors.
pub(crate) fn encode(d: &impl Drawing, height: u32, what: &str) -> Result<Plot> {
    encode_sized(d, WIDTH, height, what)
}

/// `d` drawn `width` by `height` pixels as SVG and as PNG; `what` names it in errors.
pub(crate) fn encode_sized(d: &impl Drawing, width: u32, height: u32, what: &str) -> Result<Plot> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        d.draw_on(&root).map_err(anyhow::Error::msg).with_context(|| format!("drawing the SVG {what}"))?;
        root.present().map_err(|e| anyhow::anyhow!("writing the SVG {what}: {e}"))?;
    }
    let mut rgb = vec![0u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut rgb, (width, height)).into_drawing_area();
        d.draw_on(&root).map_err(anyhow::Error::msg).with_context(|| format!("drawing the PNG {what}"))?;
        root.present().map_err(|e| anyhow::anyhow!("drawing the PNG {what}: {e}"))?;
    }
    let mut png = vec![];
    {
        let mut enc = png::Encoder::new(&mut png, width, height);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_compression(png::Compression::Best);
        enc.set_adaptive_filter(png::AdaptiveFilterType::Adaptive);
        let mut w = enc.write_header().with_context(|| format!("encoding the PNG {what}"))?;
        w.write_image_data(&rgb).with_context(|| format!("encoding the PNG {what}"))?;
    }
    Ok(Plot { svg, png })
}

/// Fills `root` white and draws `title` and `subtitle` across its top; returns the area below.
pub(crate) fn draw_title<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    subtitle: &str,
) -> Result<DrawingArea<DB, Shift>, String> {
    root.fill(&WHITE).map_err(err)?;
    let (top, rest) = root.split_vertically(TITLE_HEIGHT);
    let room = WIDTH - 40;
    let size = fit_size(title, room, 22.0, 13.0);
    top.draw(&Text::new(ellipsize(title, room, size), (20, 12), (FAMILY, size).into_font())).map_err(err)?;
    let sub = ellipsize(subtitle, room, 14.0);
    top.draw(&Text::new(sub, (20, 20 + size as i32), (FAMILY, 14.0).into_font().color(&GREY))).map_err(err)?;
    Ok(rest)
}

/// Width in pixels of `text` at `size` in the plot font (0 if it cannot be measured).
pub(crate) fn text_width(text: &str, size: f64) -> u32 {
    (FAMILY, size).into_font().box_size(text).map(|(w, _)| w).unwrap_or(0)
}

/// The largest size from `max` down to `min` at which `text` fits in `width` pixels.
pub(crate) fn fit_size(text: &str, width: u32, max: f64, min: f64) -> f64 {
    let mut size = max;
    while size > min && text_width(text, size) > width {
        size -= 1.0;
    }
    size
}

/// `text`, cut with an ellipsis until it fits in `width` pixels at `size`.
pub(crate) fn ellipsize(text: &str, width: u32, size: f64) -> String {
    let mut s: Vec<char> = text.chars().collect();
    if text_width(text, size) <= width {
        return text.to_string();
    }
    while !s.is_empty() && text_width(&format!("{}…", s.iter().collect::<String>()), size) > width {
        s.pop();
    }
    format!("{}…", s.iter().collect::<String>())
}

pub(crate) type DrawResult = Result<(), String>;

pub(crate) fn err<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

fn draw_figure<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, fig: &Figure) -> DrawResult {
    let rest = draw_title(root, &fig.title, &fig.subtitle)?;
    if fig.panels.is_empty() {
        return rest.draw(&Text::new("no data", (20, 20), (FAMILY, 16.0).into_font())).map_err(err);
    }
    let mut rest = rest;
    for panel in &fig.panels {
        let (area, below) = rest.split_vertically(panel_height(panel));
        draw_panel(&area, panel)?;
        rest = below;
    }
    Ok(())
}

/// The most room under a panel for its category labels turned upright.
const MAX_LABEL_DROP: u32 = 360;

/// A panel's height: its chart, and the room its category labels take when turned upright.
/// Labels are measured in the plot's font: call after [`crate::font::load`] (as [`render`]
/// does), before which every label measures 0 and fits.
pub fn panel_height(p: &Panel) -> u32 {
    PANEL_HEIGHT + upright_labels(p).map_or(0, |(drop, _)| drop)
}

/// The legend's width: the longest series label at the legend's font, with its marker.
fn legend_width(p: &Panel) -> u32 {
    let (_, font) = legend_metrics(p.series.len());
    let widest = p.series.iter().map(|s| text_width(&s.label, font)).max().unwrap_or(0);
    (widest + 60).clamp(140, WIDTH * 42 / 100)
}

/// Each category's width in pixels along a panel's x axis.
fn category_slot(p: &Panel) -> u32 {
    (WIDTH - legend_width(p) - 110) / p.x_labels.len().max(1) as u32
}

/// Bar categories whose labels do not fit across their slots even at 9 px (Table Q4's 56 scene
/// and technique pairs were each cut to `…`) are written upright, reading down from the axis:
/// the room they take under the chart and their font size, or None where they fit across.
/// Call after [`crate::font::load`], as [`panel_height`].
pub fn upright_labels(p: &Panel) -> Option<(u32, f64)> {
    if !p.bars {
        return None;
    }
    let slot = category_slot(p);
    if p.x_labels.iter().all(|l| text_width(l, 9.0) <= slot.saturating_sub(6)) {
        return None;
    }
    let font = (slot as f64 - 3.0).clamp(8.0, 13.0);
    let longest = p.x_labels.iter().map(|l| text_width(l, font)).max().unwrap_or(0);
    Some(((longest + 14).min(MAX_LABEL_DROP), font))
}

/// Legend row height and font size for `n` entries in a panel.
fn legend_metrics(n: usize) -> (i32, f64) {
    let row = ((PANEL_HEIGHT as i32 - 40) / n.max(1) as i32).clamp(12, 22);
    (row, (row as f64 - 6.0).clamp(10.0, 14.0))
}

fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, p: &Panel) -> DrawResult {
    let (row, font) = legend_metrics(p.series.len());
    let legend_w = legend_width(p);
    let (chart_area, legend_area) = area.split_horizontally(WIDTH - legend_w);
    draw_legend(&legend_area, &p.series, legend_w - 56, row, font, p.bars)?;
    let values: Vec<f64> = p
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|&(_, v)| v))
        .chain(p.unit_line.then_some(1.0))
        .filter(|v| v.is_finite() && (!p.log_y || *v > 0.0))
        .collect();
    let (lo, hi) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    let n = p.x_labels.len().max(1);
    let caption_room = WIDTH - legend_w - 40;
    let caption_size = fit_size(&p.title, caption_room, 18.0, 12.0);
    let caption = ellipsize(&p.title, caption_room, caption_size);
    // Category labels shrink to fit their slot, or stand upright under it.
    let slot = category_slot(p);
    let upright = upright_labels(p);
    let widest_x = p.x_labels.iter().max_by_key(|l| text_width(l, 14.0)).cloned().unwrap_or_default();
    let x_font = fit_size(&widest_x, slot.saturating_sub(6), 14.0, 9.0);
    let x_labels: Vec<String> = match upright {
        Some(_) => vec![String::new(); n],
        None => p.x_labels.iter().map(|l| ellipsize(l, slot.saturating_sub(6), x_font)).collect(),
    };
    let mut builder = ChartBuilder::on(&chart_area);
    builder
        .caption(caption, (FAMILY, caption_size))
        .margin(12)
        .margin_right(24)
        .x_label_area_size(40 + upright.map_or(0, |(drop, _)| drop))
        .y_label_area_size(84);
    let x_range = -0.5..(n as f64 - 0.5);
    if values.is_empty() {
        let chart = builder.build_cartesian_2d(x_range, 0.0..1.0).map_err(err)?;
        return chart.plotting_area().draw(&Text::new("no data", (0.0, 0.5), (FAMILY, 16.0).into_font())).map_err(err);
    }
    if p.log_y {
        let (lo, hi) = (lo / 1.6, hi * 1.6);
        let y = (lo..hi).log_scale().with_key_points(log_ticks(lo, hi)).with_light_points(log_light_lines(lo, hi));
        let mut chart = builder.build_cartesian_2d(x_range, y).map_err(err)?;
        mesh(&mut chart, p, &x_labels, x_font)?;
        plot_series(&mut chart, p, lo)?;
        draw_upright_labels(&chart, area, p, upright)
    } else {
        let (lo, hi) = linear_range(lo, hi, p.bars);
        let mut chart = builder.build_cartesian_2d(x_range, lo..hi).map_err(err)?;
        mesh(&mut chart, p, &x_labels, x_font)?;
        // Bars stand on zero where the axis has it (a negative value hangs below it).
        plot_series(&mut chart, p, if lo < 0.0 && hi > 0.0 { 0.0 } else { lo })?;
        draw_upright_labels(&chart, area, p, upright)
    }
}

/// The labelled ticks of a log axis over `lo..=hi` (plotters labels powers of ten only, so a
/// ratio panel from 0.5 to 3 had a single tick, at 1): the powers of ten (every k-th of them
/// past ten powers); where fewer than four fall inside, 1, 2 and 5 times them; where even those
/// are fewer than four, every whole multiple; and where that still gives fewer than two (a range
/// inside one step, 1.01 to 1.99), evenly spaced round values.
pub fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) {
        return vec![];
    }
    let powers = log_multiples(lo, hi, &[1.0]);
    if powers.len() >= 4 {
        let k = powers.len().div_ceil(10);
        return powers.into_iter().step_by(k).collect();
    }
    let fives = log_multiples(lo, hi, &[1.0, 2.0, 5.0]);
    if fives.len() >= 4 {
        return fives;
    }
    let all = log_multiples(lo, hi, &ALL_MULTIPLES);
    if all.len() >= 2 {
        return all;
    }
    // Round steps of 1, 2 or 5 times a power of ten, at most ten of them across the range.
    let mut step = 10f64.powf((hi - lo).log10().floor() - 1.0);
    for m in [2.0, 2.5, 2.0, 2.0, 2.5, 2.0] {
        if (hi - lo) / step <= 10.0 {
            break;
        }
        step *= m;
    }
    let first = (lo / step).ceil() as i64;
    let last = (hi / step).floor() as i64;
    (first..=last).map(|i| i as f64 * step).collect()
}

/// The light grid lines of a log axis: every whole multiple of each power of ten inside it
/// (none when there would be more than a hundred).
pub fn log_light_lines(lo: f64, hi: f64) -> Vec<f64> {
    if !(lo > 0.0 && hi > lo && hi.is_finite()) || hi / lo > 1e11 {
        return vec![];
    }
    log_multiples(lo, hi, &ALL_MULTIPLES)
}

const ALL_MULTIPLES: [f64; 9] = [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0];

/// `multiples` of each power of ten, those inside `lo..=hi`, ascending.
fn log_multiples(lo: f64, hi: f64, multiples: &[f64]) -> Vec<f64> {
    let mut out = vec![];
    for e in lo.log10().floor() as i32..=hi.log10().ceil() as i32 {
        for m in multiples {
            // Divided for negative powers, so that 0.6 is the double nearest 0.6.
            let v = if e < 0 { m / 10f64.powi(-e) } else { m * 10f64.powi(e) };
            if v >= lo && v <= hi {
                out.push(v);
            }
        }
    }
    out
}

/// The y range of a linear panel whose values lie in `lo..=hi`: from zero for bars of values
/// not below zero (a bar's length is its value; bars stand on zero, see `draw_panel`) and when
/// zero is near (errors, counts); else around the data (flux ratios), padded.
pub fn linear_range(lo: f64, hi: f64, bars: bool) -> (f64, f64) {
    let pad = 0.08 * (hi - lo).max(hi.abs() * 0.01).max(1e-9);
    let lo = if lo >= 0.0 && (bars || lo < 0.5 * hi) { 0.0 } else { lo - pad };
    (lo, hi + pad)
}

/// A plot's subtitle: the device, its driver and the date of the run.
pub(crate) fn subtitle(m: &crate::results::Meta) -> String {
    format!("{} · {} {} · {}", m.device, m.driver_name, m.driver_info, m.date)
}

/// The grid, ticks and axis names of a log-log chart (the front's panels, progressive curves).
pub(crate) fn log_mesh<DB, X, Y>(
    chart: &mut ChartContext<DB, Cartesian2d<X, Y>>,
    x_desc: &str,
    y_desc: &str,
) -> DrawResult
where
    DB: DrawingBackend,
    X: Ranged<ValueType = f64> + ValueFormatter<f64>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    chart
        .configure_mesh()
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_label_style((FAMILY, 13.0))
        .y_label_style((FAMILY, 13.0))
        .axis_desc_style((FAMILY, 14.0))
        .light_line_style(RGBColor(0xf0, 0xf0, 0xf0))
        .bold_line_style(RGBColor(0xd8, 0xd8, 0xd8))
        .draw()
        .map_err(err)
}

fn mesh<DB, Y>(
    chart: &mut ChartContext<DB, Cartesian2d<RangedCoordf64, Y>>,
    p: &Panel,
    x: &[String],
    x_font: f64,
) -> DrawResult
where
    DB: DrawingBackend,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let label = |v: &f64| {
        let i = v.round();
        if (v - i).abs() < 1e-6 && i >= 0.0 {
            x.get(i as usize).cloned().unwrap_or_default()
        } else {
            String::new()
        }
    };
    chart
        .configure_mesh()
        .x_labels(x.len().max(1))
        .x_label_formatter(&label)
        .x_label_style((FAMILY, x_font))
        .y_label_style((FAMILY, 13.0))
        .y_label_formatter(&tick)
        .y_desc(p.y_label.as_str())
        .axis_desc_style((FAMILY, 14.0))
        .y_labels(8)
        .max_light_lines(2)
        .light_line_style(RGBColor(0xf0, 0xf0, 0xf0))
        .bold_line_style(RGBColor(0xd8, 0xd8, 0xd8))
        .draw()
        .map_err(err)
}

/// The category labels turned upright under the chart, reading down from the axis, each
/// centred on its category; cut with an ellipsis at the room the panel gave them.
fn draw_upright_labels<DB, Y>(
    chart: &ChartContext<DB, Cartesian2d<RangedCoordf64, Y>>,
    area: &DrawingArea<DB, Shift>,
    p: &Panel,
    upright: Option<(u32, f64)>,
) -> DrawResult
where
    DB: DrawingBackend,
    Y: Ranged<ValueType = f64>,
{
    let Some((drop, font)) = upright else { return Ok(()) };
    let (_, ys) = chart.plotting_area().get_pixel_range();
    let (base_x, base_y) = area.get_base_pixel();
    let style = TextStyle::from((FAMILY, font).into_font()).transform(FontTransform::Rotate90);
    let y_any = chart.y_range().start;
    for (i, label) in p.x_labels.iter().enumerate() {
        let (x, _) = chart.backend_coord(&(i as f64, y_any));
        let text = ellipsize(label, drop.saturating_sub(14), font);
        let at = (x - base_x + font as i32 / 2, ys.end - base_y + 8);
        area.draw(&Text::new(text, at, style.clone())).map_err(err)?;
    }
    Ok(())
}

/// A y tick as short as it reads: 1000, 2.5, 0.05, 1e-5.
pub(crate) fn tick(v: &f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if !(1e-3..1e6).contains(&a) {
        format!("{v:.0e}")
    } else {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    }
}

fn colour(s: &Series) -> RGBColor {
    PALETTE[s.colour % PALETTE.len()]
}

fn plot_series<DB, Y>(chart: &mut ChartContext<DB, Cartesian2d<RangedCoordf64, Y>>, p: &Panel, floor: f64) -> DrawResult
where
    DB: DrawingBackend,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let n = p.x_labels.len().max(1) as f64;
    if p.unit_line {
        let style = ShapeStyle::from(&BLACK.mix(0.6)).stroke_width(1);
        chart.draw_series(LineSeries::new([(-0.5, 1.0), (n - 0.5, 1.0)], style)).map_err(err)?;
    }
    let k = p.series.len().max(1) as f64;
    for (si, s) in p.series.iter().enumerate() {
        let c = colour(s);
        if p.bars {
            // Series side by side within each category, 80% of its slot.
            let w = 0.8 / k;
            let bar = |&(x, v): &(usize, f64)| {
                let x0 = x as f64 - 0.4 + si as f64 * w;
                let style = if s.paper { c.stroke_width(2) } else { c.filled() };
                Rectangle::new([(x0 + 0.1 * w, floor), (x0 + 0.9 * w, v)], style)
            };
            chart.draw_series(s.points.iter().map(bar)).map_err(err)?;
            continue;
        }
        let pts: Vec<(f64, f64)> = s.points.iter().map(|&(x, v)| (x as f64, v)).collect();
        let line = c.stroke_width(2);
        if s.paper {
            chart.draw_series(DashedLineSeries::new(pts.clone(), 8, 6, line)).map_err(err)?;
            chart.draw_series(pts.iter().map(|&q| Circle::new(q, 4, c.stroke_width(2)))).map_err(err)?;
        } else {
            chart.draw_series(LineSeries::new(pts.clone(), line)).map_err(err)?;
            chart.draw_series(pts.iter().map(|&q| Circle::new(q, 4, c.filled()))).map_err(err)?;
        }
    }
    Ok(())
}

fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    series: &[Series],
    text_room: u32,
    row: i32,
    font: f64,
    bars: bool,
) -> DrawResult {
    let top = 40;
    for (i, s) in series.iter().enumerate() {
        let y = top + i as i32 * row;
        let c = colour(s);
        if bars {
            let style = if s.paper { c.stroke_width(2) } else { c.filled() };
            area.draw(&Rectangle::new([(6, y - 6), (34, y + 6)], style)).map_err(err)?;
        } else if s.paper {
            area.draw(&PathElement::new(vec![(4, y), (13, y)], c.stroke_width(2))).map_err(err)?;
            area.draw(&PathElement::new(vec![(27, y), (36, y)], c.stroke_width(2))).map_err(err)?;
            area.draw(&Circle::new((20, y), 4, c.stroke_width(2))).map_err(err)?;
        } else {
            area.draw(&PathElement::new(vec![(4, y), (36, y)], c.stroke_width(2))).map_err(err)?;
            area.draw(&Circle::new((20, y), 4, c.filled())).map_err(err)?;
        }
        let label = ellipsize(&s.label, text_room, font);
        let style = TextStyle::from((FAMILY, font).into_font()).pos(plotters::style::text_anchor::Pos::new(
            plotters::style::text_anchor::HPos::Left,
            plotters::style::text_anchor::VPos::Center,
        ));
        area.draw(&Text::new(label, (44, y), style)).map_err(err)?;
    }
    Ok(())
}
