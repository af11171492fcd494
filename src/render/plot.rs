//! Figure -> SVG text with plotters. Log axes are drawn as linear axes over log10 of the data with
//! `10⁻ᵏ` tick labels, so one code path serves every combination of scales. The plot area is
//! white with dark ink, so it reads the same on a light or a dark page and on paper.

use super::RenderError;
use super::memo::{self, Kept};
use super::renderer::{Context, Plots};
use crate::document::course::Documents;
use crate::model::figure::{Figure, Legend, Mark, Scale};
use crate::notation::Names;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

const SIZE: (u32, u32) = (720, 440);
const PALETTE: [RGBColor; 6] = [
    RGBColor(0, 90, 181),
    RGBColor(200, 70, 0),
    RGBColor(0, 130, 80),
    RGBColor(140, 60, 160),
    RGBColor(170, 130, 0),
    RGBColor(90, 90, 90),
];

fn xml_escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn to_axis(v: f64, s: Scale) -> f64 {
    match s {
        Scale::Linear => v,
        Scale::Log => v.log10(),
    }
}

/// Pads a range by 5 % on each side (a log range to whole decades), and widens an empty one.
fn padded(lo: f64, hi: f64, s: Scale) -> (f64, f64) {
    match s {
        Scale::Log => {
            let (a, b) = (lo.floor(), hi.ceil());
            if a == b { (a - 1.0, b + 1.0) } else { (a, b) }
        }
        Scale::Linear => {
            let w = if hi > lo { hi - lo } else { lo.abs().max(1.0) };
            (lo - 0.05 * w, hi + 0.05 * w)
        }
    }
}

fn tick(v: f64, s: Scale) -> String {
    match s {
        // A power of ten as a textbook prints it: 10⁻³, not 1e-3.
        Scale::Log if (v - v.round()).abs() < 1e-9 => {
            let superscript: String = (v.round() as i64)
                .to_string()
                .chars()
                .map(|c| match c {
                    '-' => '⁻',
                    d => SUPERSCRIPT_DIGITS[d.to_digit(10).unwrap_or(0) as usize],
                })
                .collect();
            format!("10{superscript}")
        }
        Scale::Log => String::new(),
        Scale::Linear => {
            let t = format!("{v:.3}");
            let t = t.trim_end_matches('0').trim_end_matches('.');
            // A minus sign, not a hyphen.
            if t == "-0" {
                "0".into()
            } else {
                t.replace('-', "−")
            }
        }
    }
}

const SUPERSCRIPT_DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];

/// Draws the figure; the result always starts with `<svg` and carries `<title>` and `<desc>`.
pub fn svg(fig: &Figure) -> Result<String, RenderError> {
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, SIZE).into_drawing_area();
        let failed = |e: &dyn std::fmt::Display| RenderError::Plot {
            slug: fig.slug.clone(),
            message: e.to_string(),
        };
        draw(fig, &root).map_err(|e| failed(&e))?;
        root.present().map_err(|e| failed(&e))?;
    }
    let head_end = out.find('>').ok_or_else(|| RenderError::Plot {
        slug: fig.slug.clone(),
        message: "no <svg> element".into(),
    })?;
    let meta = format!(
        "\n<title>{}</title>\n<desc>{}</desc>",
        xml_escape(&fig.title),
        xml_escape(&fig.desc.to_plain(Names::none()))
    );
    out.insert_str(head_end + 1, &meta);
    Ok(out)
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

/// A y-axis label of at most this many characters is set upright.
const UPRIGHT_LABEL: usize = 2;

fn draw(fig: &Figure, root: &Area<'_>) -> Result<(), Box<dyn std::error::Error>> {
    root.fill(&WHITE)?;
    let (xs, ys) = (fig.x_scale, fig.y_scale);
    let (xr, yr) = ranges(fig)?;
    let mut chart = ChartBuilder::on(root)
        .caption(&fig.title, ("sans-serif", 18).into_font().color(&BLACK))
        .margin(14)
        .x_label_area_size(if fig.equal_aspect { 0 } else { 40 })
        .y_label_area_size(if fig.equal_aspect { 0 } else { 64 })
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)?;
    if !fig.equal_aspect {
        axes(&mut chart, fig, root, xr, yr)?;
    }
    for s in &fig.series {
        series(&mut chart, s, xs, ys)?;
    }
    for (text, (x, y)) in &fig.labels {
        let at = (to_axis(*x, xs), to_axis(*y, ys));
        chart.draw_series(std::iter::once(Text::new(
            text.clone(),
            at,
            ("sans-serif", 14).into_font().color(&BLACK),
        )))?;
    }
    if fig.series.iter().any(|s| !s.name.is_empty()) {
        chart
            .configure_series_labels()
            .position(match fig.legend {
                Legend::UpperRight => SeriesLabelPosition::UpperRight,
                Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
                Legend::MiddleRight => SeriesLabelPosition::MiddleRight,
                Legend::LowerRight => SeriesLabelPosition::LowerRight,
                Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
            })
            .background_style(WHITE.mix(0.9))
            .border_style(RGBColor(160, 160, 160))
            .label_font(("sans-serif", 13).into_font().color(&BLACK))
            .draw()?;
    }
    Ok(())
}

/// The plot's ranges on its axes, padded; with equal aspect, the same units per pixel on both.
fn ranges(fig: &Figure) -> Result<Range2, Box<dyn std::error::Error>> {
    let ((x0, x1), (y0, y1)) = fig.bounds().ok_or("the figure has no finite points")?;
    let (xs, ys) = (fig.x_scale, fig.y_scale);
    let (mut xr, mut yr) = (
        padded(to_axis(x0, xs), to_axis(x1, xs), xs),
        padded(to_axis(y0, ys), to_axis(y1, ys), ys),
    );
    if fig.equal_aspect {
        // Same units per pixel on both axes: widen the narrower range about its centre.
        let plot = (SIZE.0 as f64 - 80.0, SIZE.1 as f64 - 80.0);
        let per_px = ((xr.1 - xr.0) / plot.0).max((yr.1 - yr.0) / plot.1);
        let grow = |(a, b): (f64, f64), px: f64| {
            let c = 0.5 * (a + b);
            (c - 0.5 * per_px * px, c + 0.5 * per_px * px)
        };
        xr = grow(xr, plot.0);
        yr = grow(yr, plot.1);
    }
    Ok((xr, yr))
}

/// The ranges of the two axes, in the axes' own units (log10 on a log axis).
type Range2 = ((f64, f64), (f64, f64));

/// The chart the series are drawn on.
type Chart<'a, 'b> = ChartContext<
    'a,
    SVGBackend<'b>,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

/// The grid, the ticks and the axes' labels; a short y label upright beside its axis.
fn axes(
    chart: &mut Chart<'_, '_>,
    fig: &Figure,
    root: &Area<'_>,
    xr: (f64, f64),
    yr: (f64, f64),
) -> Result<(), Box<dyn std::error::Error>> {
    let (xs, ys) = (fig.x_scale, fig.y_scale);
    let xf = |v: &f64| tick(*v, xs);
    let yf = |v: &f64| tick(*v, ys);
    let decades = |(a, b): (f64, f64)| ((b - a).round() as usize + 1).clamp(2, 12);
    // A label of a letter or two (ω) is set upright beside the axis below: turned on its
    // side it reads as another letter.
    let upright = fig.y_label.chars().count() <= UPRIGHT_LABEL;
    let mut mesh = chart.configure_mesh();
    if !upright {
        mesh.y_desc(fig.y_label.as_str());
    }
    mesh.x_desc(fig.x_label.as_str())
        .x_label_formatter(&xf)
        .y_label_formatter(&yf)
        .label_style(("sans-serif", 13).into_font().color(&BLACK))
        .axis_desc_style(("sans-serif", 14).into_font().color(&BLACK))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(210, 210, 210));
    if xs == Scale::Log {
        mesh.x_labels(decades(xr));
    }
    if ys == Scale::Log {
        mesh.y_labels(decades(yr));
    }
    mesh.draw()?;
    if upright {
        let (_, rows) = chart.plotting_area().get_pixel_range();
        root.draw(&Text::new(
            fig.y_label.clone(),
            (16, (rows.start + rows.end) / 2),
            ("sans-serif", 14)
                .into_font()
                .color(&BLACK)
                .pos(Pos::new(HPos::Left, VPos::Center)),
        ))?;
    }
    Ok(())
}

/// One series, in its colour and mark, with its legend entry where it is named.
fn series<'a>(
    chart: &mut Chart<'a, 'a>,
    s: &crate::model::figure::Series,
    xs: Scale,
    ys: Scale,
) -> Result<(), Box<dyn std::error::Error>> {
    let colour = PALETTE[s.colour % PALETTE.len()];
    let pts: Vec<(f64, f64)> = s
        .points
        .iter()
        .filter(|(x, y)| {
            x.is_finite()
                && y.is_finite()
                && (xs == Scale::Linear || *x > 0.0)
                && (ys == Scale::Linear || *y > 0.0)
        })
        .map(|(x, y)| (to_axis(*x, xs), to_axis(*y, ys)))
        .collect();
    let style = colour.stroke_width(2);
    let anno = match s.mark {
        Mark::Line => chart.draw_series(LineSeries::new(pts, style))?,
        Mark::Dashed => chart.draw_series(DashedLineSeries::new(pts, 6, 4, style))?,
        Mark::Points => chart.draw_series(
            pts.into_iter()
                .map(|p| Circle::new(p, 4, colour.filled()).into_dyn()),
        )?,
    };
    if !s.name.is_empty() {
        let mark = s.mark;
        anno.label(s.name.as_str())
            .legend(move |(x, y)| match mark {
                Mark::Points => Circle::new((x + 10, y), 4, colour.filled()).into_dyn(),
                _ => PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)).into_dyn(),
            });
    }
    Ok(())
}

/// Every plot of the documents as SVG, each drawn once (or taken from the memo), and the plots
/// drawn fresh, for the memo.
pub fn draw_all(docs: &Documents, cx: &Context) -> Result<(Plots, Vec<Kept>), RenderError> {
    let mut plots = Plots::new();
    let mut kept = Vec::new();
    for (i, file, fig) in &docs.figures {
        let name = file.replace('/', ".");
        let (drawn, k) = memo::recall_or(cx.memo, name, memo::key(&[&"plot", fig]), || {
            svg(fig).map_err(|e| e.in_scene(&docs.pages[*i].source))
        })?;
        kept.extend(k);
        if plots.insert(file.clone(), drawn).is_some() {
            return Err(RenderError::Collision { path: file.into() });
        }
    }
    Ok((plots, kept))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::figure::Series;

    fn fig() -> Figure {
        Figure {
            slug: "t".into(),
            title: "Error <and> law".into(),
            desc: String::from("Falls as 1/n².").into(),
            x_label: "points".into(),
            y_label: "relative error".into(),
            x_scale: Scale::Log,
            y_scale: Scale::Log,
            equal_aspect: false,
            series: vec![
                Series {
                    name: "measured".into(),
                    mark: Mark::Points,
                    colour: 0,
                    points: (1..6)
                        .map(|k| (10f64.powi(k), 10f64.powi(-2 * k)))
                        .collect(),
                },
                Series {
                    name: "law".into(),
                    mark: Mark::Dashed,
                    colour: 0,
                    points: vec![(10.0, 1e-2), (1e5, 1e-10)],
                },
            ],
            labels: vec![("n = 10".into(), (10.0, 1e-2))],
            legend: Legend::LowerLeft,
            accuracy: Vec::new(),
        }
    }

    #[test]
    fn svg_has_escaped_title_and_desc_and_is_deterministic() {
        let a = svg(&fig()).unwrap();
        assert!(a.starts_with("<svg"));
        assert!(a.contains("<title>Error &lt;and&gt; law</title>"));
        assert!(a.contains("<desc>Falls as 1/n².</desc>"));
        // Five markers plus the legend's one.
        assert_eq!(a.matches("<circle").count(), 6);
        // Log ticks are labelled by decade, as powers of ten; a minus is a minus sign.
        assert!(a.contains("10⁻⁴") && !a.contains("1e-4"), "{a}");
        assert_eq!(tick(-0.25, Scale::Linear), "−0.25");
        assert_eq!(tick(3.0, Scale::Log), "10³");
        assert!(a.contains("\nn = 10\n</text>"), "{a}");
        assert_eq!(a, svg(&fig()).unwrap());
    }

    #[test]
    fn a_figure_without_points_is_an_error() {
        let mut f = fig();
        f.series.clear();
        assert!(
            svg(&f)
                .unwrap_err()
                .to_string()
                .contains("no finite points")
        );
    }
}
