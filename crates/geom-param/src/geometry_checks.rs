//! Input checks shared by the constructors of surfaces, curves and B-splines.

use crate::curves::curve::ParamRange;
use crate::geometry_error::GeometryError;
use glam::DVec3;

/// Relative slack with which a range counts as exactly one period (a few ulps of 2π, so that
/// `[a, a + TAU]` passes for any representable `a` of moderate size).
const PERIOD_RELATIVE_SLACK: f64 = 1e-12;

/// `x` if finite.
pub(crate) fn finite(what: &'static str, x: f64) -> Result<f64, GeometryError> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(GeometryError::NonFinite { what })
    }
}

/// `v` if every coordinate is finite.
pub(crate) fn finite_vector(what: &'static str, v: DVec3) -> Result<DVec3, GeometryError> {
    if v.is_finite() {
        Ok(v)
    } else {
        Err(GeometryError::NonFinite { what })
    }
}

/// `x` if finite and > 0.
pub(crate) fn positive(what: &'static str, x: f64) -> Result<f64, GeometryError> {
    if finite(what, x)? > 0.0 {
        Ok(x)
    } else {
        Err(GeometryError::NonPositiveRadius { what, value: x })
    }
}

/// The unit vector along `v`, if `v` is finite and non-zero.
pub(crate) fn unit_direction(what: &'static str, v: DVec3) -> Result<DVec3, GeometryError> {
    finite_vector(what, v)?
        .try_normalize()
        .ok_or(GeometryError::ZeroDirection { what })
}

/// `range` if its ends are finite, `min < max`, and its periodic flag fits `period`: a
/// parameter without a period (`None`) may not be flagged periodic; an angle (`Some(2π)`) may
/// span at most one period and may be flagged periodic only when it spans exactly one.
pub(crate) fn checked_range(
    range: ParamRange,
    period: Option<f64>,
) -> Result<ParamRange, GeometryError> {
    finite("parameter range bound", range.min)?;
    finite("parameter range bound", range.max)?;
    if range.min >= range.max {
        return Err(GeometryError::EmptyRange {
            min: range.min,
            max: range.max,
        });
    }
    let fits = match period {
        None => !range.periodic,
        Some(p) => {
            let slack = PERIOD_RELATIVE_SLACK * p.max(range.min.abs()).max(range.max.abs());
            let span = range.span();
            span <= p + slack && (!range.periodic || span >= p - slack)
        }
    };
    if fits {
        Ok(range)
    } else {
        Err(GeometryError::BadPeriod {
            min: range.min,
            max: range.max,
            periodic: range.periodic,
            period,
        })
    }
}

/// `range` if it lies inside `[lower, upper]` (after [`checked_range`]).
pub(crate) fn range_within(
    range: ParamRange,
    lower: f64,
    upper: f64,
) -> Result<ParamRange, GeometryError> {
    if range.min >= lower && range.max <= upper {
        Ok(range)
    } else {
        Err(GeometryError::RangeOutsideSurface {
            min: range.min,
            max: range.max,
            lower,
            upper,
        })
    }
}
