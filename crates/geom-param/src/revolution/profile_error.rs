//! Why a profile is not a valid solid of revolution.

/// A profile that does not describe a closed solid of revolution. Every variant names the
/// offending segment(s) by their index in the profile (0-based).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ProfileError {
    /// The profile has no segments.
    #[error("the profile has no segments")]
    Empty,
    /// A coordinate is NaN or infinite.
    #[error("segment {segment} ({kind}): a coordinate is not a finite number")]
    NotFinite {
        /// Offending segment.
        segment: usize,
        /// Its kind: line, arc or bezier.
        kind: &'static str,
    },
    /// A segment does not start where the previous one ends.
    #[error(
        "segment {segment} starts at {start:?} but segment {previous} ends at {end:?} (gap of {gap:e} mm)"
    )]
    Gap {
        /// Segment whose start is off.
        segment: usize,
        /// The segment before it.
        previous: usize,
        /// Where `segment` starts, [r, z].
        start: [f64; 2],
        /// Where `previous` ends, [r, z].
        end: [f64; 2],
        /// Distance between the two (mm).
        gap: f64,
    },
    /// A segment (or the arc's span) reaches r < 0.
    #[error(
        "segment {segment} ({kind}) reaches r = {r} < 0: profiles live in the half-plane r >= 0"
    )]
    NegativeRadius {
        /// Offending segment.
        segment: usize,
        /// Its kind.
        kind: &'static str,
        /// The smallest r reached (mm).
        r: f64,
    },
    /// A segment touches the axis somewhere other than the two ends of an axis-to-axis profile.
    #[error("segment {segment} ({kind}) touches the axis (r = 0) away from the profile's ends")]
    TouchesAxis {
        /// Offending segment.
        segment: usize,
        /// Its kind.
        kind: &'static str,
    },
    /// An arc's `from` and `to` are at different distances from its `center`.
    #[error(
        "segment {segment} (arc): `from` is {from_radius} mm from the centre but `to` is {to_radius} mm"
    )]
    ArcRadiusMismatch {
        /// Offending segment.
        segment: usize,
        /// |from - center| (mm).
        from_radius: f64,
        /// |to - center| (mm).
        to_radius: f64,
    },
    /// A segment has zero length, or a Bezier has a point where its tangent vanishes.
    #[error("segment {segment} ({kind}) has zero length or a vanishing tangent")]
    ZeroLength {
        /// Offending segment.
        segment: usize,
        /// Its kind.
        kind: &'static str,
    },
    /// Two segments cross or touch away from their shared end.
    #[error("segments {first} and {second} intersect near [r, z] = {at:?}")]
    SelfIntersection {
        /// The earlier segment.
        first: usize,
        /// The later segment.
        second: usize,
        /// Approximate intersection point [r, z].
        at: [f64; 2],
    },
    /// Two consecutive segments fold back on each other (the tangent reverses at the joint).
    #[error("segments {first} and {second} fold back on each other at their joint (a cusp)")]
    Cusp {
        /// The earlier segment.
        first: usize,
        /// The later segment.
        second: usize,
    },
    /// The profile neither runs from the axis to the axis nor closes on itself.
    #[error(
        "the profile is not closed: it starts at {start:?} and ends at {end:?}; it must start and end on the axis (r = 0) or end where it starts"
    )]
    NotClosed {
        /// First point [r, z].
        start: [f64; 2],
        /// Last point [r, z].
        end: [f64; 2],
    },
    /// The profile goes clockwise around the material (the material must be on the left).
    #[error(
        "the profile runs clockwise around the material (signed area {area:e} mm²); list the segments counter-clockwise, material on the left"
    )]
    WrongOrientation {
        /// Signed area enclosed in the (r, z) plane (negative here).
        area: f64,
    },
}
