//! Contact markers drawn over the objects: both closest points as dots, A's normal as an
//! arrow of fixed length on screen, penetration witnesses as crosses.

use super::camera::Camera;
use contact_pipeline::{PairReport, PairState};
use glam::{DVec2, DVec3};
use tiny_skia::{FillRule, LineCap, Paint, Path, PathBuilder, Pixmap, Stroke, Transform};

/// Dot on object A's closest point of a contact (opaque RGB, green).
pub const POINT_A_COLOUR: [u8; 3] = [0, 170, 60];
/// Dot on object B's closest point of a contact (opaque RGB, blue).
pub const POINT_B_COLOUR: [u8; 3] = [20, 80, 235];
/// Dots of a penetrating pair's contacts and penetration witness crosses (opaque RGB, red).
pub const PENETRATION_COLOUR: [u8; 3] = [225, 20, 20];
/// Contact normal arrows (opaque RGB, near black).
pub const NORMAL_COLOUR: [u8; 3] = [25, 25, 25];
/// Outline behind every marker so it stands out on any object colour (opaque RGB, white).
const HALO_COLOUR: [u8; 3] = [255, 255, 255];

/// Marker sizes (pixels) for a picture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarkerStyle {
    /// Radius of the dot on object A's point (drawn first).
    pub dot_a_radius: f32,
    /// Radius of the dot on object B's point (drawn over A's; the points are usually within a
    /// fraction of a pixel of each other).
    pub dot_b_radius: f32,
    /// Length of a normal arrow, arrowhead included.
    pub arrow_length: f32,
    /// Width of arrow shafts and crosses.
    pub line_width: f32,
    /// Width of the white halo round each marker, beyond its own extent.
    pub halo: f32,
}

impl MarkerStyle {
    /// Sizes for a `width` × `height` picture: proportional to its smaller side, with floors
    /// that keep markers legible on small pictures.
    #[must_use]
    pub fn for_picture(width: u32, height: u32) -> Self {
        let side = width.min(height) as f32;
        let dot_a_radius = (0.009 * side).max(5.0);
        Self {
            dot_a_radius,
            dot_b_radius: 0.5 * dot_a_radius,
            arrow_length: (0.09 * side).max(24.0),
            line_width: (0.0035 * side).max(2.0),
            halo: (0.002 * side).max(1.5),
        }
    }
}

/// Draws every pair's markers in layers, so that no marker's halo hides another's ink and no
/// arrow hides a dot: all white halos, then arrows and crosses, then the dots.
pub(crate) fn draw_markers<'a>(
    pixmap: &mut Pixmap,
    camera: &Camera,
    style: &MarkerStyle,
    reports: impl Iterator<Item = &'a PairReport>,
) {
    // Stroked lines (arrow shafts, crosses) with their colour; filled arrowheads; dots as
    // (centre, radius, colour, haloed).
    let mut lines: Vec<(Path, [u8; 3])> = Vec::new();
    let mut heads: Vec<Path> = Vec::new();
    let mut dots: Vec<(DVec2, f32, [u8; 3], bool)> = Vec::new();
    for report in reports {
        let (colour_a, colour_b) = match report.state {
            PairState::Penetration => (PENETRATION_COLOUR, PENETRATION_COLOUR),
            PairState::Contact | PairState::Separated => (POINT_A_COLOUR, POINT_B_COLOUR),
        };
        for c in &report.contacts {
            if let Some((shaft, head)) = arrow(camera, style, c.point_a, c.normal) {
                lines.push((shaft, NORMAL_COLOUR));
                heads.push(head);
            }
            dots.push((
                camera.project(c.point_a),
                style.dot_a_radius,
                colour_a,
                true,
            ));
            dots.push((
                camera.project(c.point_b),
                style.dot_b_radius,
                colour_b,
                false,
            ));
        }
        for &w in &report.penetration_witnesses {
            if let Some(cross) = cross(camera.project(w), 1.2 * style.dot_a_radius) {
                lines.push((cross, PENETRATION_COLOUR));
            }
        }
    }
    let line = |width: f32| Stroke {
        width,
        line_cap: LineCap::Round,
        ..Stroke::default()
    };
    let id = Transform::identity();
    let halo = paint(HALO_COLOUR);
    let (ink_width, halo_width) = (style.line_width, style.line_width + 2.0 * style.halo);
    for (path, _) in &lines {
        pixmap.stroke_path(path, &halo, &line(halo_width), id, None);
    }
    for head in &heads {
        pixmap.stroke_path(head, &halo, &line(2.0 * style.halo), id, None);
    }
    for &(centre, radius, _, haloed) in &dots {
        if haloed {
            dot(pixmap, centre, radius + style.halo, HALO_COLOUR);
        }
    }
    for (path, colour) in &lines {
        pixmap.stroke_path(path, &paint(*colour), &line(ink_width), id, None);
    }
    let ink = paint(NORMAL_COLOUR);
    for head in &heads {
        pixmap.fill_path(head, &ink, FillRule::Winding, id, None);
    }
    for &(centre, radius, colour, _) in &dots {
        dot(pixmap, centre, radius, colour);
    }
}

fn paint(rgb: [u8; 3]) -> Paint<'static> {
    let mut paint = Paint {
        anti_alias: true,
        ..Paint::default()
    };
    paint.set_color_rgba8(rgb[0], rgb[1], rgb[2], 255);
    paint
}

fn point(p: DVec2) -> (f32, f32) {
    (p.x as f32, p.y as f32)
}

fn dot(pixmap: &mut Pixmap, centre: DVec2, radius: f32, rgb: [u8; 3]) {
    let (x, y) = point(centre);
    if let Some(circle) = PathBuilder::from_circle(x, y, radius) {
        pixmap.fill_path(
            &circle,
            &paint(rgb),
            FillRule::Winding,
            Transform::identity(),
            None,
        );
    }
}

/// The shaft and the arrowhead of a normal arrow from `from`, or `None` when the normal points
/// (nearly) along the line of sight and has no screen direction.
fn arrow(camera: &Camera, style: &MarkerStyle, from: DVec3, normal: DVec3) -> Option<(Path, Path)> {
    let direction = camera.project_direction(normal);
    if direction.length() < 0.05 * camera.scale {
        return None;
    }
    let direction = direction.normalize();
    let start = camera.project(from);
    let length = f64::from(style.arrow_length);
    let head = (3.5 * f64::from(style.line_width)).max(0.3 * length);
    let tip = start + length * direction;
    let base = tip - head * direction;
    let side = 0.45 * head * direction.perp();
    let mut shaft = PathBuilder::new();
    let (x0, y0) = point(start);
    let (x1, y1) = point(base);
    shaft.move_to(x0, y0);
    shaft.line_to(x1, y1);
    let mut arrowhead = PathBuilder::new();
    for (k, p) in [tip, base + side, base - side].into_iter().enumerate() {
        let (x, y) = point(p);
        if k == 0 {
            arrowhead.move_to(x, y);
        } else {
            arrowhead.line_to(x, y);
        }
    }
    arrowhead.close();
    Some((shaft.finish()?, arrowhead.finish()?))
}

/// An × of half-diagonal `arm` pixels centred on `centre` (`None` if not finite).
fn cross(centre: DVec2, arm: f32) -> Option<Path> {
    let (x, y) = point(centre);
    let mut path = PathBuilder::new();
    path.move_to(x - arm, y - arm);
    path.line_to(x + arm, y + arm);
    path.move_to(x - arm, y + arm);
    path.line_to(x + arm, y - arm);
    path.finish()
}
