//! A box with every edge filleted: 6 planes, 12 quarter cylinders and 8 sphere octants, all
//! tangent-continuous, sewn along their sides.

use crate::builders::build_error::BuildError;
use crate::builders::sew::sew_rectangles;
use crate::curves::curve::ParamRange;
use crate::surfaces::cylinder_surface::CylinderSurface;
use crate::surfaces::placement::Placement;
use crate::surfaces::plane::Plane;
use crate::surfaces::sphere_surface::SphereSurface;
use crate::surfaces::surface::Surface;
use crate::topology::solid::Solid;
use glam::DVec3;
use std::f64::consts::FRAC_PI_2;
use std::sync::Arc;

fn range(min: f64, max: f64) -> ParamRange {
    ParamRange {
        min,
        max,
        periodic: false,
    }
}

/// The quarter of longitude (about z, from +x) between the outward directions sx·x and sy·y.
fn quadrant(sx: f64, sy: f64) -> ParamRange {
    let start = match (sx > 0.0, sy > 0.0) {
        (true, true) => 0.0,
        (false, true) => FRAC_PI_2,
        (false, false) => 2.0 * FRAC_PI_2,
        (true, false) => 3.0 * FRAC_PI_2,
    };
    range(start, start + FRAC_PI_2)
}

/// The box [−h.x, h.x] × [−h.y, h.y] × [−h.z, h.z] (mm, centred at the origin of its frame) with
/// every edge rounded at `radius`: a convex solid with 26 faces, every edge smooth. The model
/// tolerance is 1e-9 of the box's size.
///
/// # Errors
/// [`BuildError::BadDimension`] unless every half extent is finite and 0 < `radius` < the
/// smallest half extent.
pub fn rounded_box(half_extents: DVec3, radius: f64) -> Result<Solid, BuildError> {
    if !(half_extents.is_finite() && half_extents.min_element() > 0.0) {
        return Err(BuildError::BadDimension {
            what: "half extent",
            value: half_extents.min_element(),
            requirement: "finite and > 0",
        });
    }
    if !(radius > 0.0 && radius < half_extents.min_element()) {
        return Err(BuildError::BadDimension {
            what: "fillet radius",
            value: radius,
            requirement: "> 0 and below the smallest half extent",
        });
    }
    let inner = half_extents - DVec3::splat(radius);
    let axes = [DVec3::X, DVec3::Y, DVec3::Z];
    let mut surfaces: Vec<Arc<dyn Surface>> = Vec::new();

    // Planes: in-plane axes (x_p, y_p) with x_p × y_p the outward normal.
    for k in 0..3 {
        let (i, j) = ((k + 1) % 3, (k + 2) % 3);
        for s in [1.0, -1.0] {
            let (x, y) = if s > 0.0 { (i, j) } else { (j, i) };
            let normal = s * axes[k];
            let placement = Placement::new(half_extents[k] * normal, normal, axes[x])?;
            let domain = [range(-inner[x], inner[x]), range(-inner[y], inner[y])];
            surfaces.push(Arc::new(Plane::new(placement, domain)?));
        }
    }
    let signs = [1.0, -1.0];
    // Vertical quarter cylinders (axis z): longitude as the spheres'.
    for sx in signs {
        for sy in signs {
            let placement = Placement::new(
                DVec3::new(sx * inner.x, sy * inner.y, 0.0),
                DVec3::Z,
                DVec3::X,
            )?;
            let domain = [quadrant(sx, sy), range(-inner.z, inner.z)];
            surfaces.push(Arc::new(CylinderSurface::new(placement, radius, domain)?));
        }
    }
    // Horizontal quarter cylinders: angle from the horizontal outward direction d towards
    // sz·z... measured as the spheres' latitude (frame x = d, y = z, axis d × z).
    for (d_axis, along) in [(0usize, 1usize), (1, 0)] {
        for sd in signs {
            for sz in signs {
                let d = sd * axes[d_axis];
                let mut origin = DVec3::ZERO;
                origin[d_axis] = sd * inner[d_axis];
                origin.z = sz * inner.z;
                let placement = Placement::new(origin, d.cross(DVec3::Z), d)?;
                let latitude = if sz > 0.0 {
                    range(0.0, FRAC_PI_2)
                } else {
                    range(-FRAC_PI_2, 0.0)
                };
                let domain = [latitude, range(-inner[along], inner[along])];
                surfaces.push(Arc::new(CylinderSurface::new(placement, radius, domain)?));
            }
        }
    }
    // Sphere octants at the inner box's corners.
    for sx in signs {
        for sy in signs {
            for sz in signs {
                let corner = DVec3::new(sx * inner.x, sy * inner.y, sz * inner.z);
                let placement = Placement::new(corner, DVec3::Z, DVec3::X)?;
                let latitude = if sz > 0.0 {
                    range(0.0, FRAC_PI_2)
                } else {
                    range(-FRAC_PI_2, 0.0)
                };
                let domain = [quadrant(sx, sy), latitude];
                surfaces.push(Arc::new(SphereSurface::new(placement, radius, domain)?));
            }
        }
    }
    sew_rectangles(surfaces, 1e-9 * half_extents.max_element())
}
