//! Dependency-free SVG line charts for benchmark tables, in the style of the papers' figures: time in
//! ms (or photon counts) against photon resolution, one coloured polyline with circle markers per
//! series, dashed lines for published values, a legend, "nice" 1-2-5 (or decade) y gridlines.
//!
//! [`render`] never panics: non-finite points (and non-positive ones on a log axis) are skipped, a
//! series left with nothing to draw is listed in the legend as "(no data)", and a chart with nothing
//! to draw at all is still a valid SVG that says "no data". All text is XML-escaped.

use std::fmt::Write as _;

/// One line of the chart.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Series {
    pub label: String,
    /// `(x, y)` in data units; drawn in ascending x order.
    pub points: Vec<(f64, f64)>,
    /// Dashed line and hollow markers (used for the papers' published values).
    pub dashed: bool,
    /// Palette index; `None` takes the series' position. A paper's series shares its
    /// measured twin's colour, and a technique keeps its colour across panels.
    pub colour: Option<usize>,
}

impl Series {
    fn colour(&self, position: usize) -> &'static str {
        PALETTE[self.colour.unwrap_or(position) % PALETTE.len()]
    }
}

/// A line chart: title, axes and series.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Chart {
    pub title: String,
    /// E.g. device and date, drawn smaller under the title.
    pub subtitle: String,
    pub x_label: String,
    pub y_label: String,
    /// Log2 x axis (photon counts 256²..4096²). Ticks sit at the data's x values unless
    /// `x_tick_labels` is given.
    pub x_log2: bool,
    /// Explicit x ticks `(value, label)`, e.g. `(65536.0, "256²")`; when non-empty they replace the
    /// automatic ones and the x range is widened to include them.
    pub x_tick_labels: Vec<(f64, String)>,
    /// Log10 y axis with decade gridlines (2 and 5 minor lines when the range spans few decades).
    /// A linear y axis always includes 0.
    pub y_log: bool,
    pub series: Vec<Series>,
}

const WIDTH: f64 = 800.0;
const HEIGHT: f64 = 440.0;
/// Plot area.
const LEFT: f64 = 80.0;
const RIGHT: f64 = 540.0;
const TOP: f64 = 58.0;
const BOTTOM: f64 = 384.0;
/// Legend column, right of the plot area.
const LEGEND_X: f64 = 556.0;
/// Legend labels longer than this many characters are cut with an ellipsis.
const LEGEND_MAX_CHARS: usize = 48;

/// Matplotlib's "tab10": distinct, print-friendly; series cycle through it.
const PALETTE: [&str; 10] =
    ["#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"];

/// Appends one formatted line; writing to a `String` cannot fail.
macro_rules! w {
    ($out:expr, $($arg:tt)*) => {{
        let _ = writeln!($out, $($arg)*);
    }};
}

/// Renders `chart` as a standalone 800×440 SVG document (ends with `</svg>\n`).
pub fn render(chart: &Chart) -> String {
    let mut out = String::with_capacity(4096);
    draw_chart(&mut out, chart, 0.0);
    out
}

/// Small multiples: `panels` stacked one above the other under a shared title and subtitle,
/// each an 800×440 chart with its own axes and legend (each panel's own title names it), so
/// a table of many techniques × metrics stays readable. One standalone SVG document.
pub fn render_panels(title: &str, subtitle: &str, panels: &[Chart]) -> String {
    const HEAD: f64 = 48.0;
    let height = HEAD + HEIGHT * panels.len() as f64;
    let mut out = String::with_capacity(4096 * panels.len().max(1));
    w!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{WIDTH}" height="{h}" viewBox="0 0 {WIDTH} {h}" font-family="Helvetica, Arial, sans-serif" font-size="11">"#,
        h = num(height)
    );
    w!(out, r##"<rect x="0" y="0" width="{WIDTH}" height="{}" fill="#ffffff"/>"##, num(height));
    draw_titles(&mut out, title, subtitle);
    for (i, panel) in panels.iter().enumerate() {
        draw_chart(&mut out, panel, HEAD + HEIGHT * i as f64);
    }
    out.push_str("</svg>\n");
    out
}

fn draw_titles(out: &mut String, title: &str, subtitle: &str) {
    if !title.is_empty() {
        w!(
            out,
            r#"<text x="{}" y="24" text-anchor="middle" font-size="16" font-weight="bold"{}>{}</text>"#,
            WIDTH / 2.0,
            fit(title, 9.0, WIDTH - 20.0),
            esc(title)
        );
    }
    if !subtitle.is_empty() {
        w!(
            out,
            r##"<text x="{}" y="42" text-anchor="middle" font-size="11" fill="#555555"{}>{}</text>"##,
            WIDTH / 2.0,
            fit(subtitle, 6.0, WIDTH - 20.0),
            esc(subtitle)
        );
    }
}

/// One chart as an `<svg>` element whose top edge is at `y` in its parent (a standalone
/// document when `y` is 0 and nothing encloses it).
fn draw_chart(out: &mut String, chart: &Chart, y: f64) {
    let sx = if chart.x_log2 { Scale::Log2 } else { Scale::Linear };
    let sy = if chart.y_log { Scale::Log10 } else { Scale::Linear };
    let drawable: Vec<Vec<(f64, f64)>> = chart
        .series
        .iter()
        .map(|s| {
            let mut pts: Vec<(f64, f64)> =
                s.points.iter().copied().filter(|&(x, y)| sx.valid(x) && sy.valid(y)).collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            pts
        })
        .collect();
    let xs: Vec<f64> = drawable.iter().flatten().map(|p| p.0).collect();
    let ys: Vec<f64> = drawable.iter().flatten().map(|p| p.1).collect();

    let at = if y == 0.0 { String::new() } else { format!(r#" x="0" y="{}""#, num(y)) };
    w!(
        out,
        r#"<svg xmlns="http://www.w3.org/2000/svg"{at} width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="Helvetica, Arial, sans-serif" font-size="11">"#,
        w = WIDTH,
        h = HEIGHT
    );
    w!(out, r##"<rect x="0" y="0" width="{WIDTH}" height="{HEIGHT}" fill="#ffffff"/>"##);
    draw_titles(out, &chart.title, &chart.subtitle);

    if xs.is_empty() {
        w!(
            out,
            r##"<rect x="{LEFT}" y="{TOP}" width="{}" height="{}" fill="none" stroke="#cccccc"/>"##,
            RIGHT - LEFT,
            BOTTOM - TOP
        );
        w!(
            out,
            r##"<text x="{}" y="{}" text-anchor="middle" font-size="14" fill="#888888">no data</text>"##,
            num((LEFT + RIGHT) / 2.0),
            num((TOP + BOTTOM) / 2.0)
        );
    } else {
        let (xa, xticks) = x_axis(&xs, sx, &chart.x_tick_labels);
        let (ya, yticks) = y_axis(&ys, sy);
        draw_grid_and_axes(out, &xa, &xticks, &ya, &yticks);
        draw_series(out, chart, &drawable, &xa, &ya);
    }
    draw_axis_labels(out, chart);
    draw_legend(out, chart, &drawable);
    out.push_str("</svg>\n");
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Scale {
    Linear,
    Log2,
    Log10,
}

impl Scale {
    fn valid(self, v: f64) -> bool {
        v.is_finite() && (self == Scale::Linear || v > 0.0)
    }

    fn fwd(self, v: f64) -> f64 {
        match self {
            Scale::Linear => v,
            Scale::Log2 => v.log2(),
            Scale::Log10 => v.log10(),
        }
    }
}

/// Maps transformed values in `[lo, hi]` onto pixels `[px0, px1]`.
#[derive(Debug)]
struct Axis {
    scale: Scale,
    lo: f64,
    hi: f64,
    px0: f64,
    px1: f64,
}

impl Axis {
    /// Pixel of a data value.
    fn map(&self, v: f64) -> f64 {
        self.map_t(self.scale.fwd(v))
    }

    /// Pixel of an already transformed value (clamped to the axis).
    fn map_t(&self, t: f64) -> f64 {
        let mut f = (t - self.lo) / (self.hi - self.lo);
        if !f.is_finite() {
            // Spans near f64::MAX overflow; halving keeps them finite.
            f = (t * 0.5 - self.lo * 0.5) / (self.hi * 0.5 - self.lo * 0.5);
        }
        if !f.is_finite() {
            f = 0.5;
        }
        self.px0 + f.clamp(0.0, 1.0) * (self.px1 - self.px0)
    }
}

/// A tick at transformed position `t`; `major` ticks get stronger gridlines.
#[derive(Debug, Clone)]
struct Tick {
    t: f64,
    label: String,
    major: bool,
}

/// Min and max of a non-empty slice of finite values.
fn min_max(v: &[f64]) -> (f64, f64) {
    v.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)))
}

/// Final axis range: `[lo, hi]` widened to every tick and made non-degenerate.
fn finish_axis(scale: Scale, lo: f64, hi: f64, ticks: &[Tick], px0: f64, px1: f64) -> Axis {
    let (mut lo, mut hi) = ticks.iter().fold((lo, hi), |(lo, hi), t| (lo.min(t.t), hi.max(t.t)));
    if hi <= lo || lo.is_nan() || hi.is_nan() {
        let pad = if lo == 0.0 || scale != Scale::Linear { 1.0 } else { lo.abs() * 0.1 };
        lo -= pad;
        hi += pad;
    }
    Axis { scale, lo, hi, px0, px1 }
}

/// Pads a transformed `[lo, hi]` by 5% of its span on each side (or by ±`pad0` if it is a point).
fn padded(lo: f64, hi: f64, pad0: f64) -> (f64, f64) {
    let pad = if hi > lo { (hi - lo) * 0.05 } else { pad0 };
    let (plo, phi) = (lo - pad, hi + pad);
    if plo.is_finite() && phi.is_finite() {
        (plo, phi)
    } else {
        (lo, hi)
    }
}

fn x_axis(xs: &[f64], scale: Scale, explicit: &[(f64, String)]) -> (Axis, Vec<Tick>) {
    let explicit: Vec<&(f64, String)> = explicit.iter().filter(|(v, _)| scale.valid(*v)).collect();
    let ts: Vec<f64> = xs.iter().chain(explicit.iter().map(|(v, _)| v)).map(|&v| scale.fwd(v)).collect();
    let (tmin, tmax) = min_max(&ts);
    let (lo, hi, ticks) = if !explicit.is_empty() {
        let ticks = explicit.iter().map(|(v, l)| Tick { t: scale.fwd(*v), label: l.clone(), major: true }).collect();
        let pad0 = if scale == Scale::Linear && tmin != 0.0 { tmin.abs() * 0.1 } else { 1.0 };
        let (lo, hi) = padded(tmin, tmax, pad0);
        (lo, hi, ticks)
    } else if scale == Scale::Linear {
        let ticks = nice_ticks(tmin, tmax, 6).into_iter().map(|v| Tick { t: v, label: fmt_num(v), major: true });
        (tmin, tmax, ticks.collect())
    } else {
        // Log2: ticks at the data's (distinct) x values, thinned to at most ~12.
        let mut distinct: Vec<f64> = xs.to_vec();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup_by(|a, b| (*a - *b).abs() <= 1e-9 * a.abs().max(b.abs()));
        let stride = distinct.len().div_ceil(12).max(1);
        let ticks = distinct
            .iter()
            .step_by(stride)
            .map(|&v| Tick { t: scale.fwd(v), label: fmt_num(v), major: true })
            .collect();
        let (lo, hi) = padded(tmin, tmax, 1.0);
        (lo, hi, ticks)
    };
    let ticks: Vec<Tick> = ticks_finite(ticks);
    (finish_axis(scale, lo, hi, &ticks, LEFT, RIGHT), ticks)
}

fn y_axis(ys: &[f64], scale: Scale) -> (Axis, Vec<Tick>) {
    if scale == Scale::Linear {
        let (dmin, dmax) = min_max(ys);
        let (lo, hi) = (dmin.min(0.0), dmax.max(0.0));
        let ticks = nice_ticks(lo, hi, 5).into_iter().map(|v| Tick { t: v, label: fmt_num(v), major: true });
        let ticks = ticks_finite(ticks.collect());
        return (finish_axis(scale, lo, hi, &ticks, BOTTOM, TOP), ticks);
    }
    let ts: Vec<f64> = ys.iter().map(|&v| scale.fwd(v)).collect();
    let (tmin, tmax) = min_max(&ts);
    // Decades; the log10 of any positive finite f64 lies within ±324, so the casts are exact.
    let (mut dlo, mut dhi) = (tmin.floor() as i32, tmax.ceil() as i32);
    if dhi <= dlo {
        dlo -= 1;
        dhi += 1;
    }
    let decades = dhi - dlo;
    let step = ((decades + 7) / 8).max(1);
    let mut ticks = Vec::new();
    let mut d = dlo;
    while d <= dhi {
        ticks.push(Tick { t: f64::from(d), label: pow10_label(1, d), major: true });
        if step == 1 && decades <= 3 && d < dhi {
            for m in [2, 5] {
                let label = if decades <= 2 { pow10_label(m, d) } else { String::new() };
                ticks.push(Tick { t: f64::from(d) + f64::from(m).log10(), label, major: false });
            }
        }
        d += step;
    }
    (finish_axis(scale, f64::from(dlo), f64::from(dhi), &ticks, BOTTOM, TOP), ticks)
}

fn ticks_finite(ticks: Vec<Tick>) -> Vec<Tick> {
    ticks.into_iter().filter(|t| t.t.is_finite()).collect()
}

/// Label of `m`·10^`d`.
fn pow10_label(m: i32, d: i32) -> String {
    if (-3..=14).contains(&d) {
        fmt_num(f64::from(m) * 10f64.powi(d))
    } else {
        format!("{m}e{d}")
    }
}

/// Ticks at multiples of a 1-2-5 step (1, 2, 5, 10, 20, ...) covering `[min, max]`, about `target`
/// intervals. Empty for non-finite input; a degenerate range is widened first.
fn nice_ticks(min: f64, max: f64, target: usize) -> Vec<f64> {
    if !min.is_finite() || !max.is_finite() {
        return Vec::new();
    }
    let (mut lo, mut hi) = if min <= max { (min, max) } else { (max, min) };
    if hi - lo <= f64::EPSILON * lo.abs().max(hi.abs()) {
        if lo == 0.0 && hi == 0.0 {
            hi = 1.0;
        } else {
            let pad = lo.abs().max(hi.abs()) * 0.1;
            lo -= pad;
            hi += pad;
        }
    }
    let fallback = || [lo, hi].into_iter().filter(|v| v.is_finite()).collect::<Vec<f64>>();
    let span = hi - lo;
    if !span.is_finite() || span <= 0.0 {
        return fallback();
    }
    let raw = span / target.max(1) as f64;
    let e = raw.log10().floor();
    let mag = 10f64.powf(e);
    if !(mag > 0.0 && mag.is_finite()) {
        return fallback();
    }
    let norm = raw / mag;
    let (m, e) = match norm {
        n if n <= 1.0 + 1e-9 => (1.0, e),
        n if n <= 2.0 + 1e-9 => (2.0, e),
        n if n <= 5.0 + 1e-9 => (5.0, e),
        _ => (1.0, e + 1.0),
    };
    let e = e as i32;
    let step = m * 10f64.powi(e);
    let (k0, k1) = ((lo / step + 1e-9).floor(), (hi / step - 1e-9).ceil());
    if !(k0.is_finite() && k1.is_finite() && k1 >= k0 && k1 - k0 <= 1000.0) {
        return fallback();
    }
    // k·m·10^e, dividing by an exact power of ten for negative e so that 3·0.1 comes out as 0.3.
    let value = |k: f64| if !(-300..0).contains(&e) { k * m * 10f64.powi(e) } else { k * m / 10f64.powi(-e) };
    let n = (k1 - k0) as usize;
    (0..=n).map(|i| value(k0 + i as f64)).filter(|v| v.is_finite()).collect()
}

fn draw_grid_and_axes(out: &mut String, xa: &Axis, xticks: &[Tick], ya: &Axis, yticks: &[Tick]) {
    w!(out, r##"<g class="grid" stroke-width="1" fill="none">"##);
    for t in yticks {
        let y = num(ya.map_t(t.t));
        let colour = if t.major { "#dddddd" } else { "#f0f0f0" };
        w!(out, r#"<line x1="{LEFT}" y1="{y}" x2="{RIGHT}" y2="{y}" stroke="{colour}"/>"#);
    }
    for t in xticks {
        let x = num(xa.map_t(t.t));
        w!(out, r##"<line x1="{x}" y1="{TOP}" x2="{x}" y2="{BOTTOM}" stroke="#f0f0f0"/>"##);
    }
    w!(out, "</g>");

    w!(out, r##"<g class="axes" stroke="#333333" stroke-width="1" fill="none">"##);
    w!(out, r#"<line x1="{LEFT}" y1="{BOTTOM}" x2="{RIGHT}" y2="{BOTTOM}"/>"#);
    w!(out, r#"<line x1="{LEFT}" y1="{TOP}" x2="{LEFT}" y2="{BOTTOM}"/>"#);
    for t in yticks.iter().filter(|t| t.major) {
        let y = num(ya.map_t(t.t));
        w!(out, r#"<line x1="{}" y1="{y}" x2="{LEFT}" y2="{y}"/>"#, LEFT - 5.0);
    }
    for t in xticks {
        let x = num(xa.map_t(t.t));
        w!(out, r#"<line x1="{x}" y1="{BOTTOM}" x2="{x}" y2="{}"/>"#, BOTTOM + 5.0);
    }
    w!(out, "</g>");

    w!(out, r##"<g class="tick-labels" fill="#333333">"##);
    // Greedy overlap avoidance: a label is dropped if it would touch the previous one drawn.
    let mut ylabels: Vec<(f64, &str)> =
        yticks.iter().filter(|t| !t.label.is_empty()).map(|t| (ya.map_t(t.t), t.label.as_str())).collect();
    ylabels.sort_by(|a, b| b.0.total_cmp(&a.0));
    let mut last = f64::INFINITY;
    for (y, label) in ylabels {
        if y <= last - 12.0 {
            w!(out, r#"<text x="{}" y="{}" text-anchor="end">{}</text>"#, LEFT - 8.0, num(y + 4.0), esc(label));
            last = y;
        }
    }
    let mut xlabels: Vec<(f64, &str)> =
        xticks.iter().filter(|t| !t.label.is_empty()).map(|t| (xa.map_t(t.t), t.label.as_str())).collect();
    xlabels.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut right = f64::NEG_INFINITY;
    for (x, label) in xlabels {
        let half = text_width(label, 6.2) / 2.0;
        if x - half >= right + 4.0 {
            w!(out, r#"<text x="{}" y="{}" text-anchor="middle">{}</text>"#, num(x), BOTTOM + 18.0, esc(label));
            right = x + half;
        }
    }
    w!(out, "</g>");
}

fn draw_series(out: &mut String, chart: &Chart, drawable: &[Vec<(f64, f64)>], xa: &Axis, ya: &Axis) {
    w!(out, r#"<g class="series">"#);
    for (i, (s, pts)) in chart.series.iter().zip(drawable).enumerate() {
        if pts.is_empty() {
            continue;
        }
        let colour = s.colour(i);
        let px: Vec<(String, String)> = pts.iter().map(|&(x, y)| (num(xa.map(x)), num(ya.map(y)))).collect();
        let coords: Vec<String> = px.iter().map(|(x, y)| format!("{x},{y}")).collect();
        w!(out, r#"<g stroke="{colour}">"#);
        w!(
            out,
            r#"<polyline points="{}" fill="none" stroke-width="2" stroke-linejoin="round"{}/>"#,
            coords.join(" "),
            dash(s.dashed)
        );
        let (fill, r) = marker(s.dashed, colour);
        for (x, y) in &px {
            w!(out, r#"<circle cx="{x}" cy="{y}" r="{r}" fill="{fill}" stroke-width="1.5"/>"#);
        }
        w!(out, "</g>");
    }
    w!(out, "</g>");
}

fn draw_axis_labels(out: &mut String, chart: &Chart) {
    if !chart.x_label.is_empty() {
        w!(
            out,
            r#"<text x="{}" y="{}" text-anchor="middle" font-size="12"{}>{}</text>"#,
            num((LEFT + RIGHT) / 2.0),
            BOTTOM + 40.0,
            fit(&chart.x_label, 6.8, RIGHT - LEFT),
            esc(&chart.x_label)
        );
    }
    if !chart.y_label.is_empty() {
        w!(
            out,
            r#"<text x="0" y="0" transform="translate(18,{}) rotate(-90)" text-anchor="middle" font-size="12"{}>{}</text>"#,
            num((TOP + BOTTOM) / 2.0),
            fit(&chart.y_label, 6.8, BOTTOM - TOP),
            esc(&chart.y_label)
        );
    }
}

fn draw_legend(out: &mut String, chart: &Chart, drawable: &[Vec<(f64, f64)>]) {
    if chart.series.is_empty() {
        return;
    }
    w!(out, r#"<g class="legend">"#);
    let y0 = TOP + 4.0;
    let spacing = ((HEIGHT - 8.0 - y0) / chart.series.len() as f64).min(18.0);
    let text_x = LEGEND_X + 30.0;
    for (i, s) in chart.series.iter().enumerate() {
        let colour = s.colour(i);
        let cy = y0 + spacing * (i as f64 + 0.5);
        let mut label: String = s.label.chars().take(LEGEND_MAX_CHARS).collect();
        if s.label.chars().nth(LEGEND_MAX_CHARS).is_some() {
            label.push('…');
        }
        let empty = drawable.get(i).map_or(0, Vec::len) == 0;
        if empty {
            label.push_str(" (no data)");
        }
        let (fill, r) = marker(s.dashed, colour);
        let (y, ty) = (num(cy), num(cy + 4.0));
        w!(out, r#"<g stroke="{colour}"{}>"#, if empty { r#" opacity="0.45""# } else { "" });
        w!(
            out,
            r#"<line x1="{LEGEND_X}" y1="{y}" x2="{}" y2="{y}" stroke-width="2"{}/>"#,
            LEGEND_X + 24.0,
            dash(s.dashed)
        );
        w!(out, r#"<circle cx="{}" cy="{y}" r="{r}" fill="{fill}" stroke-width="1.5"/>"#, LEGEND_X + 12.0);
        w!(
            out,
            r##"<text x="{text_x}" y="{ty}" stroke="none" fill="#222222"{}>{}</text>"##,
            fit(&label, 6.0, WIDTH - 4.0 - text_x),
            esc(&label)
        );
        w!(out, "</g>");
    }
    w!(out, "</g>");
}

fn dash(dashed: bool) -> &'static str {
    if dashed {
        r#" stroke-dasharray="6 4""#
    } else {
        ""
    }
}

/// Marker fill and radius: hollow for dashed (published) series.
fn marker(dashed: bool, colour: &str) -> (&str, &'static str) {
    if dashed {
        ("#ffffff", "3")
    } else {
        (colour, "3")
    }
}

/// Rough rendered width of `s` at `char_w` pixels a character.
fn text_width(s: &str, char_w: f64) -> f64 {
    s.chars().count() as f64 * char_w
}

/// `textLength` attributes squeezing `s` into `max` pixels when it would not fit.
fn fit(s: &str, char_w: f64, max: f64) -> String {
    if text_width(s, char_w) > max {
        format!(r#" textLength="{}" lengthAdjust="spacingAndGlyphs""#, num(max))
    } else {
        String::new()
    }
}

/// XML-escapes `s` for text and attribute values; drops characters XML 1.0 forbids and turns
/// tabs and line breaks into spaces.
fn esc(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            '\t' | '\n' | '\r' => out.push(' '),
            c if c.is_control() || c == '\u{FFFE}' || c == '\u{FFFF}' => {}
            c => out.push(c),
        }
    }
    out
}

/// SVG coordinate: at most two decimals, no trailing zeros; non-finite as 0.
fn num(v: f64) -> String {
    if !v.is_finite() {
        return "0".to_string();
    }
    let s = format!("{v:.2}");
    let s = if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.') } else { &s };
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

/// Compact label for a value: 4 significant digits, trailing zeros dropped; plain from 0.001 to
/// 9999, then k/M/G/T suffixes, scientific (`2.5e-7`) outside that. `0.1 + 0.2` gives `0.3`.
fn fmt_num(v: f64) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    if v == 0.0 {
        return "0".to_string();
    }
    let sign = if v < 0.0 { "-" } else { "" };
    // "d.ddde<exp>", correctly rounded to 4 significant digits.
    let sci = format!("{:.3e}", v.abs());
    let (mantissa, exp) = sci.split_once('e').unwrap_or((sci.as_str(), "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let digits: String = mantissa.chars().filter(char::is_ascii_digit).collect();
    let digits = digits.trim_end_matches('0');
    let digits = if digits.is_empty() { "0" } else { digits };
    match exp {
        -3..=3 => format!("{sign}{}", place_point(digits, exp)),
        4..=14 => {
            let group = exp / 3;
            let suffix = ["", "k", "M", "G", "T"].get(group as usize).copied().unwrap_or("");
            format!("{sign}{}{suffix}", place_point(digits, exp - 3 * group))
        }
        _ => format!("{sign}{}e{exp}", place_point(digits, 0)),
    }
}

/// `d1.d2d3…` × 10^`exp` written out in plain decimal.
fn place_point(digits: &str, exp: i32) -> String {
    let digits: Vec<char> = digits.chars().collect();
    if exp < 0 {
        let zeros = "0".repeat(exp.unsigned_abs() as usize - 1);
        return format!("0.{zeros}{}", digits.iter().collect::<String>());
    }
    let int_len = exp as usize + 1;
    let mut s: String = digits.iter().take(int_len).collect();
    if digits.len() < int_len {
        s.push_str(&"0".repeat(int_len - digits.len()));
    } else if digits.len() > int_len {
        s.push('.');
        s.extend(&digits[int_len..]);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn series(label: &str, points: &[(f64, f64)]) -> Series {
        Series { label: label.to_string(), points: points.to_vec(), dashed: false, colour: None }
    }

    fn chart(series: Vec<Series>) -> Chart {
        Chart {
            title: "Photon splatting".into(),
            subtitle: "test device, 2024-01-01".into(),
            x_label: "photons".into(),
            y_label: "time (ms)".into(),
            series,
            ..Chart::default()
        }
    }

    /// The `points` attribute of every polyline, parsed back into pixel pairs.
    fn polylines(svg: &str) -> Vec<Vec<(f64, f64)>> {
        svg.match_indices("<polyline")
            .map(|(i, _)| {
                let rest = &svg[i..];
                let start = rest.find("points=\"").expect("points attribute") + 8;
                let end = start + rest[start..].find('"').expect("closing quote");
                rest[start..end]
                    .split_whitespace()
                    .map(|p| {
                        let (x, y) = p.split_once(',').expect("x,y pair");
                        (x.parse().expect("x"), y.parse().expect("y"))
                    })
                    .collect()
            })
            .collect()
    }

    /// Checks that every tag is closed in order, and that no attribute or text holds `<` or a bare `&`.
    fn well_formed(svg: &str) -> Result<(), String> {
        let mut stack: Vec<&str> = Vec::new();
        let mut rest = svg;
        while let Some(open) = rest.find('<') {
            let text = &rest[..open];
            check_entities(text)?;
            let close = rest[open..].find('>').ok_or("unterminated tag")? + open;
            let tag = &rest[open + 1..close];
            if tag.contains('<') {
                return Err(format!("'<' inside tag {tag}"));
            }
            check_entities(tag)?;
            if let Some(name) = tag.strip_prefix('/') {
                if stack.pop() != Some(name) {
                    return Err(format!("unbalanced </{name}>"));
                }
            } else if !tag.ends_with('/') {
                stack.push(tag.split_whitespace().next().unwrap_or(""));
            }
            rest = &rest[close + 1..];
        }
        check_entities(rest)?;
        if stack.is_empty() {
            Ok(())
        } else {
            Err(format!("unclosed {stack:?}"))
        }
    }

    fn check_entities(s: &str) -> Result<(), String> {
        for (i, _) in s.match_indices('&') {
            let ok = ["&amp;", "&lt;", "&gt;", "&quot;", "&apos;"].iter().any(|e| s[i..].starts_with(e));
            if !ok {
                return Err(format!("bare & in {s}"));
            }
        }
        Ok(())
    }

    fn count(svg: &str, pat: &str) -> usize {
        svg.matches(pat).count()
    }

    #[test]
    fn document_shape() {
        let svg = render(&chart(vec![series("a", &[(1.0, 2.0), (2.0, 3.0)]), series("b", &[(1.0, 1.0)])]));
        assert!(svg.starts_with("<svg"), "{svg}");
        assert!(svg.ends_with("</svg>\n"));
        assert!(svg.contains(r#"xmlns="http://www.w3.org/2000/svg""#));
        assert!(svg.contains(r#"width="800""#) && svg.contains(r#"height="440""#));
        assert!(svg.contains(r##"fill="#ffffff""##));
        assert_eq!(count(&svg, "<g>") + count(&svg, "<g "), count(&svg, "</g>"));
        assert_eq!(count(&svg, "<svg"), 1);
        well_formed(&svg).unwrap();
    }

    #[test]
    fn escapes_text() {
        let mut c = chart(vec![series("a <&> \"b\" 'c'", &[(1.0, 2.0)])]);
        c.title = "t<&>".into();
        c.x_label = "x & y".into();
        c.x_tick_labels = vec![(1.0, "<1>".into())];
        let svg = render(&c);
        assert!(svg.contains("a &lt;&amp;&gt; &quot;b&quot; &apos;c&apos;"), "{svg}");
        assert!(svg.contains("t&lt;&amp;&gt;"));
        assert!(svg.contains("x &amp; y"));
        assert!(svg.contains("&lt;1&gt;"));
        assert!(!svg.contains("<&>") && !svg.contains("<1>"));
        well_formed(&svg).unwrap();
        assert_eq!(esc("\u{0}a\nb\u{1b}"), "a b");
    }

    #[test]
    fn one_polyline_per_series_with_all_points() {
        let c = chart(vec![
            series("a", &[(1.0, 2.0), (2.0, 3.0), (3.0, 5.0)]),
            series("b", &[(1.0, 1.0), (2.0, f64::NAN), (f64::INFINITY, 1.0), (4.0, 4.0)]),
            Series { label: "paper".into(), points: vec![(1.0, 1.5)], dashed: true, colour: None },
        ]);
        let svg = render(&c);
        let lines = polylines(&svg);
        assert_eq!(lines.iter().map(Vec::len).collect::<Vec<_>>(), [3, 2, 1]);
        assert_eq!(count(&svg, "stroke-dasharray"), 2, "dashed polyline and its legend line");
        // Markers: one per drawn point plus one per legend entry.
        assert_eq!(count(&svg, "<circle"), 6 + 3);
        for (i, colour) in PALETTE.iter().take(3).enumerate() {
            assert!(svg.contains(colour), "series {i} colour");
        }
        well_formed(&svg).unwrap();
    }

    #[test]
    fn larger_y_is_higher_up() {
        for y_log in [false, true] {
            let mut c = chart(vec![series("a", &[(3.0, 3.0), (1.0, 1.0), (2.0, 5.0)])]);
            c.y_log = y_log;
            let svg = render(&c);
            let line = &polylines(&svg)[0];
            // Sorted by x: y = 1, 5, 3.
            assert_eq!(line.len(), 3);
            assert!(line[0].0 < line[1].0 && line[1].0 < line[2].0, "{line:?}");
            assert!(line[1].1 < line[2].1 && line[2].1 < line[0].1, "y_log {y_log}: {line:?}");
            for &(x, y) in line {
                assert!((LEFT..=RIGHT).contains(&x) && (TOP..=BOTTOM).contains(&y), "{x},{y}");
            }
        }
    }

    #[test]
    fn log_axes_skip_non_positive() {
        let mut c = chart(vec![series("a", &[(1.0, 0.0), (2.0, -1.0), (4.0, 10.0), (8.0, 100.0)])]);
        c.y_log = true;
        assert_eq!(polylines(&render(&c))[0].len(), 2);

        let mut c = chart(vec![series("a", &[(0.0, 1.0), (-4.0, 2.0), (65536.0, 3.0), (262144.0, 4.0)])]);
        c.x_log2 = true;
        c.x_tick_labels = vec![(0.0, "zero".into()), (65536.0, "256²".into()), (262144.0, "512²".into())];
        let svg = render(&c);
        assert_eq!(polylines(&svg)[0].len(), 2);
        assert!(svg.contains("256²") && svg.contains("512²") && !svg.contains("zero"));

        // Only non-positive values on a log axis: nothing to draw.
        let mut c = chart(vec![series("a", &[(1.0, 0.0), (2.0, -3.0)])]);
        c.y_log = true;
        let svg = render(&c);
        assert!(svg.contains(">no data<") && svg.contains("a (no data)"));
        assert!(polylines(&svg).is_empty());
    }

    #[test]
    fn log2_x_ticks_at_data_values() {
        let xs = [65536.0, 262144.0, 1048576.0, 4194304.0, 16777216.0];
        let mut c = chart(vec![series("a", &xs.map(|x| (x, x / 1e5)))]);
        c.x_log2 = true;
        let svg = render(&c);
        for label in ["65.54k", "262.1k", "1.049M", "4.194M", "16.78M"] {
            assert!(svg.contains(&format!(">{label}<")), "{label}: {svg}");
        }
        // Equal spacing in log2.
        let line = &polylines(&svg)[0];
        let d0 = line[1].0 - line[0].0;
        for w in line.windows(2) {
            assert!((w[1].0 - w[0].0 - d0).abs() < 0.02, "{line:?}");
        }
    }

    #[test]
    fn empty_chart_says_no_data() {
        for c in [chart(vec![]), chart(vec![series("a", &[]), series("b", &[(f64::NAN, 1.0)])])] {
            let svg = render(&c);
            assert!(svg.contains(">no data<"), "{svg}");
            assert!(svg.starts_with("<svg") && svg.ends_with("</svg>\n"));
            assert!(polylines(&svg).is_empty());
            well_formed(&svg).unwrap();
        }
        let svg = render(&chart(vec![series("a", &[]), series("b", &[(1.0, 1.0)])]));
        assert!(svg.contains("a (no data)") && !svg.contains("b (no data)") && !svg.contains(">no data<"));
    }

    #[test]
    fn nice_ticks_are_1_2_5_and_cover() {
        let cases = [
            (0.0, 1.0),
            (0.0, 0.3),
            (0.1, 0.30000000000000004),
            (3.0, 97.0),
            (-12.5, 7.0),
            (0.0, 16777216.0),
            (1e-6, 3e-6),
            (42.0, 42.0),
            (0.0, 0.0),
            (5.0, -5.0),
            (1e300, 1.7e308),
        ];
        for (a, b) in cases {
            let t = nice_ticks(a, b, 5);
            assert!(t.len() >= 2 && t.len() <= 12, "{a}..{b}: {t:?}");
            let step = t[1] - t[0];
            // Covers the range (to within rounding; the axis range itself always covers the data).
            let slack = step * 1e-6;
            assert!(t[0] <= a.min(b) + slack, "{a}..{b}: {t:?}");
            assert!(t[t.len() - 1] >= a.max(b) - slack || b == 1.7e308, "{a}..{b}: {t:?}");
            let norm = step / 10f64.powf(step.log10().floor());
            assert!([1.0, 2.0, 5.0].iter().any(|m| (norm - m).abs() < 1e-6), "{a}..{b}: step {step}");
            for w in t.windows(2) {
                assert!(((w[1] - w[0]) - step).abs() <= step * 1e-6, "{a}..{b}: {t:?}");
            }
        }
        assert_eq!(nice_ticks(0.0, 1.0, 5), [0.0, 0.2, 0.4, 0.6, 0.8, 1.0]);
        assert_eq!(nice_ticks(0.0, 0.3, 3), [0.0, 0.1, 0.2, 0.3]);
        assert_eq!(nice_ticks(3.0, 97.0, 5), [0.0, 20.0, 40.0, 60.0, 80.0, 100.0]);
        assert!(nice_ticks(f64::NAN, 1.0, 5).is_empty());
        // Tick labels come out clean.
        let labels: Vec<String> = nice_ticks(0.0, 0.7, 7).into_iter().map(fmt_num).collect();
        assert_eq!(labels, ["0", "0.1", "0.2", "0.3", "0.4", "0.5", "0.6", "0.7"]);
    }

    #[test]
    fn log_y_decades() {
        let mut c = chart(vec![series("a", &[(1.0, 0.5), (2.0, 30.0)])]);
        c.y_log = true;
        let svg = render(&c);
        for label in [">0.1<", ">1<", ">10<", ">100<"] {
            assert!(svg.contains(label), "{label}: {svg}");
        }
        assert!(!svg.contains(">1000<"));
    }

    #[test]
    fn compact_numbers() {
        assert_eq!(fmt_num(0.1 + 0.2), "0.3");
        assert_eq!(fmt_num(0.0), "0");
        assert_eq!(fmt_num(-0.0), "0");
        assert_eq!(fmt_num(1234.0), "1234");
        assert_eq!(fmt_num(12.345678), "12.35");
        assert_eq!(fmt_num(-0.0015), "-0.0015");
        assert_eq!(fmt_num(65536.0), "65.54k");
        assert_eq!(fmt_num(1e6), "1M");
        assert_eq!(fmt_num(16777216.0), "16.78M");
        assert_eq!(fmt_num(999_960.0), "1M");
        assert_eq!(fmt_num(2.5e-7), "2.5e-7");
        assert_eq!(fmt_num(1e20), "1e20");
        assert_eq!(fmt_num(0.001), "0.001");
        assert_eq!(num(1.0 / 3.0), "0.33");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(f64::NAN), "0");
    }

    #[test]
    fn extreme_inputs_stay_valid() {
        let nasty = [
            (f64::MAX, f64::MAX),
            (-f64::MAX, -f64::MAX),
            (f64::MIN_POSITIVE, 5e-324),
            (1e-300, 1e300),
            (0.0, 0.0),
            (f64::NAN, f64::NEG_INFINITY),
        ];
        for x_log2 in [false, true] {
            for y_log in [false, true] {
                for pts in [&nasty[..], &nasty[2..3], &nasty[4..5], &[(1.0, 1.0), (1.0, 1.0)][..]] {
                    let mut c = chart(vec![series("\u{0}&\u{FFFF}", pts)]);
                    c.x_log2 = x_log2;
                    c.y_log = y_log;
                    c.x_tick_labels = vec![(f64::NAN, "n".into()), (1.0, "one".into())];
                    let svg = render(&c);
                    well_formed(&svg).unwrap_or_else(|e| panic!("{e}: {svg}"));
                    assert!(!svg.contains("NaN") && !svg.contains("inf"), "{svg}");
                    for line in polylines(&svg) {
                        for (x, y) in line {
                            assert!((LEFT..=RIGHT).contains(&x) && (TOP..=BOTTOM).contains(&y), "{x},{y}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn many_series_cycle_palette_and_long_labels_fit() {
        let many: Vec<Series> = (0..12).map(|i| series(&format!("s{i} {}", "x".repeat(60)), &[(1.0, 1.0)])).collect();
        let svg = render(&chart(many));
        assert_eq!(polylines(&svg).len(), 12);
        assert!(svg.contains("lengthAdjust") && svg.contains('…'));
        // Series 10 reuses the first colour.
        assert_eq!(count(&svg, &format!(r#"<g stroke="{}">"#, PALETTE[0])), 4);
        well_formed(&svg).unwrap();
    }

    #[test]
    fn panels_stack_charts_and_twins_share_a_colour() {
        let mut paper = series("a (paper)", &[(1.0, 1.5), (2.0, 2.5)]);
        paper.dashed = true;
        paper.colour = Some(3);
        let mut ours = series("a", &[(1.0, 1.0), (2.0, 2.0)]);
        ours.colour = Some(3);
        let mut first = chart(vec![ours, paper]);
        first.title = "Gather".into();
        let mut second = chart(vec![series("b", &[(1.0, 4.0)])]);
        second.title = "Final Render".into();
        let svg = render_panels("Table 3", "device", &[first, second]);
        well_formed(&svg).unwrap();
        // One document holding a chart per panel, each below the shared title.
        assert_eq!(count(&svg, "<svg"), 3);
        assert!(svg.contains(r#"height="928""#), "48 + 2 × 440");
        assert!(svg.contains(r#" y="48" "#) && svg.contains(r#" y="488" "#));
        for t in ["Table 3", "Gather", "Final Render"] {
            assert!(svg.contains(&format!(">{t}</text>")), "no title {t}");
        }
        // Both lines of `a` and their legend entries in palette colour 3; `b` takes its position.
        assert_eq!(count(&svg, &format!(r#"<g stroke="{}">"#, PALETTE[3])), 4);
        assert_eq!(count(&svg, &format!(r#"<g stroke="{}">"#, PALETTE[0])), 2);
        assert_eq!(polylines(&svg).len(), 3);
    }
}
