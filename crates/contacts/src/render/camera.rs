//! The orthographic camera: world (mm) to picture (pixel) coordinates.

use glam::{DVec2, DVec3};

/// The scenes' up direction: objects are solids of revolution about their local z axis and
/// the fixtures stand them on the world xy plane, so "elevated" means "from higher z".
pub const WORLD_UP: DVec3 = DVec3::Z;

/// An orthographic view of the world frame.
///
/// A world point p (mm) lands at picture pixel coordinates
/// `x = width/2 + scale (p·right − centre.x)`, `y = height/2 − scale (p·up − centre.y)`
/// (x to the right, y down, origin at the top-left corner of the picture, pixel (i, j)
/// covering [i, i+1) × [j, j+1)). `forward`, `right`, `up` form a right-handed orthonormal
/// basis with `forward × up = right`; depth grows along `forward`, away from the viewer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    /// Unit viewing direction (world frame), from the viewer into the scene.
    pub forward: DVec3,
    /// Unit world direction drawn to the right.
    pub right: DVec3,
    /// Unit world direction drawn upwards.
    pub up: DVec3,
    /// (right, up) coordinates (mm) of the world points drawn at the picture's centre.
    pub centre: DVec2,
    /// Pixels per millimetre.
    pub scale: f64,
    /// Picture width (pixels).
    pub width: u32,
    /// Picture height (pixels).
    pub height: u32,
}

impl Camera {
    /// A camera looking along `forward` (need not be unit, must not be zero) whose picture of
    /// `width` × `height` pixels shows the (right, up) rectangle `[lo, hi] = frame(basis)` (mm)
    /// as large as fits inside a border of `margin` pixels, centred. `frame` is called once
    /// with a camera whose basis is final (centre and scale not yet set), so it can measure
    /// what to show with [`Camera::screen_mm`].
    ///
    /// The screen's up is [`WORLD_UP`] made perpendicular to `forward` (world x when looking
    /// straight up or down).
    #[must_use]
    pub fn fitting(
        forward: DVec3,
        frame: impl Fn(&Self) -> (DVec2, DVec2),
        width: u32,
        height: u32,
        margin: f64,
    ) -> Self {
        let forward = forward.normalize();
        let right = forward
            .cross(WORLD_UP)
            .try_normalize()
            .unwrap_or_else(|| forward.cross(DVec3::X).normalize());
        let up = right.cross(forward);
        let mut camera = Self {
            forward,
            right,
            up,
            centre: DVec2::ZERO,
            scale: 1.0,
            width,
            height,
        };
        let (lo, hi) = frame(&camera);
        let size = (hi - lo).max(DVec2::splat(1e-9));
        let room = DVec2::new(f64::from(width), f64::from(height)) - 2.0 * margin;
        camera.scale = (room / size).min_element().max(1e-9);
        camera.centre = 0.5 * (lo + hi);
        camera
    }

    /// (right, up) coordinates (mm) of a world point.
    #[must_use]
    pub fn screen_mm(&self, p: DVec3) -> DVec2 {
        DVec2::new(p.dot(self.right), p.dot(self.up))
    }

    /// Picture coordinates (pixels, y down) of a world point (mm).
    #[must_use]
    pub fn project(&self, p: DVec3) -> DVec2 {
        let s = self.screen_mm(p) - self.centre;
        DVec2::new(
            0.5 * f64::from(self.width) + self.scale * s.x,
            0.5 * f64::from(self.height) - self.scale * s.y,
        )
    }

    /// Picture displacement (pixels, y down) of a world displacement `v` (mm).
    #[must_use]
    pub fn project_direction(&self, v: DVec3) -> DVec2 {
        self.scale * DVec2::new(v.dot(self.right), -v.dot(self.up))
    }

    /// Depth (mm) of a world point along `forward`: larger is farther from the viewer.
    #[must_use]
    pub fn depth(&self, p: DVec3) -> f64 {
        p.dot(self.forward)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Looking along +y from above the xy plane fitting the square x, z in [−10, 10]
    /// (in (right, up) = (x, z)) into 200 × 100 pixels with a 10 pixel margin.
    fn front_camera() -> Camera {
        let frame = |_: &Camera| (DVec2::splat(-10.0), DVec2::splat(10.0));
        Camera::fitting(DVec3::new(0.0, 2.0, 0.0), frame, 200, 100, 10.0)
    }

    #[test]
    fn basis_is_right_handed_and_orthonormal() {
        let c = front_camera();
        assert_eq!((c.forward, c.right, c.up), (DVec3::Y, DVec3::X, DVec3::Z));
        let top = Camera::fitting(DVec3::NEG_Z, |_| (DVec2::ZERO, DVec2::ONE), 10, 10, 0.0);
        assert!(top.right.dot(top.up).abs() < 1e-15);
        assert!((top.forward.cross(top.up) - top.right).length() < 1e-15);
    }

    #[test]
    fn fit_and_projection_closed_form() {
        let c = front_camera();
        // Height limits: (100 − 2·10) px / 20 mm = 4 px/mm.
        assert_eq!(c.scale, 4.0);
        assert_eq!(
            c.project(DVec3::new(0.0, 7.0, 0.0)),
            DVec2::new(100.0, 50.0)
        );
        assert_eq!(
            c.project(DVec3::new(-10.0, 0.0, 10.0)),
            DVec2::new(60.0, 10.0)
        );
        assert_eq!(c.project_direction(DVec3::Z), DVec2::new(0.0, -4.0));
        assert_eq!(c.depth(DVec3::new(1.0, 3.0, 2.0)), 3.0);
    }
}
