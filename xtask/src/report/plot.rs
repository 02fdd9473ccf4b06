//! Log-log scatter figures written as SVG with plotters.

use plotters::prelude::*;

/// One named set of (x, y) points.
pub struct Series {
    /// Legend text.
    pub name: String,
    /// The points; non-positive values are drawn at the axis floor ([`FLOOR`]).
    pub points: Vec<(f64, f64)>,
}

/// One panel of a figure: a y quantity against the shared x quantity.
pub struct Panel {
    /// Panel title.
    pub title: String,
    /// x axis label.
    pub x_label: String,
    /// y axis label.
    pub y_label: String,
    /// Series, drawn in order with the palette's colours and markers.
    pub series: Vec<Series>,
}

/// Values at or below this are drawn on the floor of a log axis (an error of exactly 0).
pub const FLOOR: f64 = 1e-16;

const PANEL_SIZE: (u32, u32) = (560, 420);

/// Series colours, in order: distinct in print and for the common colour-vision deficiencies
/// (Okabe-Ito: vermillion, bluish green, orange, blue, reddish purple, sky blue).
const PALETTE: [RGBColor; 6] = [
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(230, 159, 0),
    RGBColor(0, 114, 178),
    RGBColor(204, 121, 167),
    RGBColor(86, 180, 233),
];

/// Renders `panels` side by side, log-log, as an SVG document.
///
/// # Errors
/// A message if plotters fails to draw.
pub fn log_log_svg(panels: &[Panel]) -> Result<String, String> {
    let mut svg = String::new();
    {
        let width = PANEL_SIZE.0 * u32::try_from(panels.len().max(1)).unwrap_or(1);
        let root = SVGBackend::with_string(&mut svg, (width, PANEL_SIZE.1)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let areas = root.split_evenly((1, panels.len().max(1)));
        for (panel, area) in panels.iter().zip(&areas) {
            draw_panel(panel, area).map_err(|e| e.to_string())?;
        }
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}

fn bounds(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .map(|v| v.max(FLOOR))
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    if lo > hi {
        return (FLOOR, 1.0);
    }
    // Whole decades around the data.
    (
        10f64.powf(lo.log10().floor()),
        10f64.powf(hi.log10().ceil().max(lo.log10().floor() + 1.0)),
    )
}

type Area<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

fn draw_panel(panel: &Panel, area: &Area<'_>) -> Result<(), DrawingAreaErrorKind<std::io::Error>> {
    let all = || panel.series.iter().flat_map(|s| s.points.iter().copied());
    let (x0, x1) = bounds(all().map(|p| p.0));
    let (y0, y1) = bounds(all().map(|p| p.1));
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 16))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(64)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc(panel.x_label.as_str())
        .y_desc(panel.y_label.as_str())
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .x_label_formatter(&|v| format!("{v}"))
        .draw()?;
    for (i, series) in panel.series.iter().enumerate() {
        let colour = PALETTE[i % PALETTE.len()].to_rgba();
        let points: Vec<(f64, f64)> = series
            .points
            .iter()
            .map(|&(x, y)| (x.max(FLOOR), y.max(FLOOR)))
            .collect();
        let marker = move |(x, y): (f64, f64)| -> DynElement<'static, SVGBackend<'_>, (f64, f64)> {
            match i % 3 {
                0 => Circle::new((x, y), 5, colour.filled()).into_dyn(),
                1 => TriangleMarker::new((x, y), 6, colour.filled()).into_dyn(),
                _ => Cross::new((x, y), 5, colour.stroke_width(2)).into_dyn(),
            }
        };
        chart
            .draw_series(points.iter().map(|&p| marker(p)))?
            .label(series.name.as_str())
            .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour.filled()));
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::MiddleLeft)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()?;
    Ok(())
}
