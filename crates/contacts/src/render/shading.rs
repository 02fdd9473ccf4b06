//! Painting the objects: back faces culled, triangles sorted far to near (painter's algorithm),
//! each flat-shaded by Lambert's law plus ambient light.

use super::camera::Camera;
use super::world_mesh::WorldTriangle;
use tiny_skia::{FillRule, LineJoin, Paint, PathBuilder, Pixmap, Stroke, Transform};

/// Picture background (opaque RGB).
pub const BACKGROUND: [u8; 3] = [255, 255, 255];

/// Base colours (RGB) of the objects, in scene order, repeating: steel blue-grey, sand, sage,
/// mauve. None is close to the marker colours.
pub const OBJECT_COLOURS: [[u8; 3]; 4] = [
    [150, 165, 190],
    [222, 180, 120],
    [150, 190, 150],
    [195, 150, 180],
];

/// Share of the base colour lit by ambient light; the rest is Lambert's cos θ.
const AMBIENT: f64 = 0.38;

/// Width (pixels) of the outline drawn round each filled triangle in its own colour, so that
/// anti-aliased shared edges leave no background-coloured cracks.
const SEAM_WIDTH: f32 = 0.8;

/// Paints every triangle that faces the viewer, far to near.
///
/// Light comes from above, left and behind the viewer (a fixed direction in the camera's
/// frame), so each picture is lit the same way whatever the view.
pub(crate) fn paint_objects(pixmap: &mut Pixmap, camera: &Camera, triangles: &[WorldTriangle]) {
    let to_light = (-camera.forward + 0.8 * camera.up - 0.5 * camera.right).normalize();
    let mut visible: Vec<(f64, &WorldTriangle)> = triangles
        .iter()
        .filter(|t| t.normal.dot(camera.forward) < 0.0)
        .map(|t| (camera.depth(t.centroid()), t))
        .collect();
    visible.sort_by(|a, b| b.0.total_cmp(&a.0));
    let stroke = Stroke {
        width: SEAM_WIDTH,
        line_join: LineJoin::Bevel,
        ..Stroke::default()
    };
    let mut paint = Paint {
        anti_alias: true,
        ..Paint::default()
    };
    for (_, t) in visible {
        let [r, g, b] = shade(
            OBJECT_COLOURS[t.object % OBJECT_COLOURS.len()],
            t.normal.dot(to_light),
        );
        paint.set_color_rgba8(r, g, b, 255);
        let mut path = PathBuilder::new();
        for (k, corner) in t.corners.iter().enumerate() {
            let p = camera.project(*corner);
            let (x, y) = (p.x as f32, p.y as f32);
            if k == 0 {
                path.move_to(x, y);
            } else {
                path.line_to(x, y);
            }
        }
        path.close();
        // A triangle seen edge-on or smaller than a pixel may give no path; nothing to draw.
        if let Some(path) = path.finish() {
            pixmap.fill_path(
                &path,
                &paint,
                FillRule::Winding,
                Transform::identity(),
                None,
            );
            pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
        }
    }
}

/// `base` scaled by `AMBIENT + (1 − AMBIENT) max(0, cos θ)`, with cos θ between the surface
/// normal and the direction to the light.
fn shade(base: [u8; 3], cos_theta: f64) -> [u8; 3] {
    let intensity = AMBIENT + (1.0 - AMBIENT) * cos_theta.max(0.0);
    base.map(|c| (f64::from(c) * intensity).round().clamp(0.0, 255.0) as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lambert_shading_closed_form() {
        assert_eq!(shade([200, 100, 0], 1.0), [200, 100, 0]);
        assert_eq!(shade([200, 100, 0], -0.5), [76, 38, 0]);
        // 0.38 + 0.62 * 0.5 = 0.69
        assert_eq!(shade([200, 100, 0], 0.5), [138, 69, 0]);
    }
}
