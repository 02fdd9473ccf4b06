//! A validated profile: the closed (r, z) outline that is revolved into a solid.

use crate::revolution::profile_error::ProfileError;
use crate::revolution::profile_segment::{ArcSegment, CubicBezier, LineSegment, ProfileSegment};
use glam::DVec2;

/// One segment as written in an object file: endpoints explicit, arcs by centre and endpoints.
/// Points are [r, z] in millimetres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SegmentSpec {
    /// Straight segment.
    Line {
        /// Start [r, z].
        from: [f64; 2],
        /// End [r, z].
        to: [f64; 2],
    },
    /// Circular arc about `center`, counter-clockwise when `ccw`.
    Arc {
        /// Centre [r, z].
        center: [f64; 2],
        /// Start [r, z].
        from: [f64; 2],
        /// End [r, z], at the same distance from `center` as `from`.
        to: [f64; 2],
        /// Direction of travel.
        ccw: bool,
    },
    /// Cubic Bezier through control points P0..P3.
    Bezier {
        /// Control points [r, z].
        points: [[f64; 2]; 4],
    },
}

impl SegmentSpec {
    fn kind(&self) -> &'static str {
        match self {
            Self::Line { .. } => "line",
            Self::Arc { .. } => "arc",
            Self::Bezier { .. } => "bezier",
        }
    }

    fn start(&self) -> [f64; 2] {
        match *self {
            Self::Line { from, .. } | Self::Arc { from, .. } => from,
            Self::Bezier { points } => points[0],
        }
    }

    fn end(&self) -> [f64; 2] {
        match *self {
            Self::Line { to, .. } | Self::Arc { to, .. } => to,
            Self::Bezier { points } => points[3],
        }
    }

    fn coordinates(&self) -> Vec<f64> {
        match *self {
            Self::Line { from, to } => vec![from[0], from[1], to[0], to[1]],
            Self::Arc {
                center, from, to, ..
            } => {
                vec![center[0], center[1], from[0], from[1], to[0], to[1]]
            }
            Self::Bezier { points } => points.iter().flatten().copied().collect(),
        }
    }
}

/// How the profile closes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Closure {
    /// Starts and ends on the axis: revolves into a solid with a vertex (pole or apex) at each
    /// end.
    Axis,
    /// A closed loop with r > 0 everywhere: revolves into a ring (a solid torus-like shape).
    Ring,
}

/// A profile checked to bound a solid of revolution: closed, counter-clockwise around the
/// material, without gaps, self-intersections or points with r < 0.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    segments: Vec<ProfileSegment>,
    closure: Closure,
    scale: f64,
}

impl Profile {
    /// Validates `specs` and builds the profile. Segment ends that agree to within 1e-9 of the
    /// profile's size are joined exactly, and ends within that distance of the axis are put on it.
    ///
    /// # Errors
    /// A [`ProfileError`] naming the first offending segment.
    pub fn new(specs: &[SegmentSpec]) -> Result<Self, ProfileError> {
        if specs.is_empty() {
            return Err(ProfileError::Empty);
        }
        for (i, spec) in specs.iter().enumerate() {
            if spec.coordinates().iter().any(|c| !c.is_finite()) {
                return Err(ProfileError::NotFinite {
                    segment: i,
                    kind: spec.kind(),
                });
            }
        }
        let scale = specs
            .iter()
            .flat_map(SegmentSpec::coordinates)
            .fold(0.0_f64, |m, c| m.max(c.abs()))
            .max(f64::MIN_POSITIVE);
        let eps = 1e-9 * scale;
        let dist = |a: [f64; 2], b: [f64; 2]| DVec2::from(a).distance(DVec2::from(b));

        for i in 1..specs.len() {
            let (end, start) = (specs[i - 1].end(), specs[i].start());
            let gap = dist(end, start);
            if gap > eps {
                return Err(ProfileError::Gap {
                    segment: i,
                    previous: i - 1,
                    start,
                    end,
                    gap,
                });
            }
        }
        let (first, last) = (specs[0].start(), specs[specs.len() - 1].end());
        let closure = if first[0].abs() <= eps && last[0].abs() <= eps {
            Closure::Axis
        } else if dist(first, last) <= eps {
            Closure::Ring
        } else {
            return Err(ProfileError::NotClosed {
                start: first,
                end: last,
            });
        };

        let mut segments = Vec::with_capacity(specs.len());
        for (i, spec) in specs.iter().enumerate() {
            segments.push(build_segment(i, spec, eps)?);
        }
        snap_joints(&mut segments, closure, eps);

        let profile = Self {
            segments,
            closure,
            scale,
        };
        profile.check_radius_and_axis(eps)?;
        profile.check_joints()?;
        profile.check_self_intersection(eps)?;
        let area = profile.signed_area();
        if area <= 0.0 {
            return Err(ProfileError::WrongOrientation { area });
        }
        Ok(profile)
    }

    /// The segments, in order, counter-clockwise around the material.
    #[must_use]
    pub fn segments(&self) -> &[ProfileSegment] {
        &self.segments
    }

    /// How the profile closes.
    #[must_use]
    pub fn closure(&self) -> Closure {
        self.closure
    }

    /// Largest absolute coordinate (mm): the length scale for relative tolerances.
    #[must_use]
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// Index pairs (i, j) of consecutive segments that meet at an edge circle (r > 0): every
    /// joint of an axis profile, plus the closing joint of a ring.
    #[must_use]
    pub fn joints(&self) -> Vec<(usize, usize)> {
        let n = self.segments.len();
        let mut out: Vec<(usize, usize)> = (1..n).map(|j| (j - 1, j)).collect();
        if self.closure == Closure::Ring {
            out.push((n - 1, 0));
        }
        out
    }

    /// A dense polyline of segment `i` (s from 0 to 1), fine enough for intersection and area
    /// checks: 1 piece for a line, about 2° per piece on an arc, 64 pieces on a Bezier.
    fn polyline(&self, i: usize) -> Vec<DVec2> {
        let segment = &self.segments[i];
        let pieces = match segment {
            ProfileSegment::Line(_) => 1,
            ProfileSegment::Arc(a) => (a.sweep.abs() / 2f64.to_radians()).ceil().max(2.0) as usize,
            ProfileSegment::Bezier(_) => 64,
        };
        (0..=pieces)
            .map(|k| segment.eval(k as f64 / pieces as f64).point)
            .collect()
    }

    fn signed_area(&self) -> f64 {
        // Green's theorem, ½ ∮ (r dz - z dr); the closing run along the axis adds nothing.
        let mut area = 0.0;
        for i in 0..self.segments.len() {
            let line = self.polyline(i);
            for w in line.windows(2) {
                area += 0.5 * w[0].perp_dot(w[1]);
            }
        }
        area
    }

    fn check_radius_and_axis(&self, eps: f64) -> Result<(), ProfileError> {
        let n = self.segments.len();
        for (i, segment) in self.segments.iter().enumerate() {
            let kind = segment.kind_name();
            let mut samples = segment.sign_breakpoints();
            samples.extend((1..32).map(|k| f64::from(k) / 32.0));
            // The samples include every extremum of r (sign_breakpoints), so this is the minimum.
            let min_r = samples
                .iter()
                .map(|&s| segment.eval(s).point.x)
                .fold(f64::INFINITY, f64::min);
            if min_r < -eps {
                return Err(ProfileError::NegativeRadius {
                    segment: i,
                    kind,
                    r: min_r,
                });
            }
            for &s in &samples {
                let r = segment.eval(s).point.x;
                let is_profile_end = self.closure == Closure::Axis
                    && ((i == 0 && s == 0.0) || (i == n - 1 && s == 1.0));
                if r <= eps && !is_profile_end {
                    return Err(ProfileError::TouchesAxis { segment: i, kind });
                }
            }
            // Zero speed anywhere (a Bezier with a collapsed control leg) leaves no tangent.
            let length_scale = match segment {
                ProfileSegment::Line(l) => l.from.distance(l.to),
                ProfileSegment::Arc(a) => a.radius * a.sweep.abs(),
                // The control polygon's length: a closed Bezier has a zero chord but not length.
                ProfileSegment::Bezier(b) => b.points.windows(2).map(|w| w[0].distance(w[1])).sum(),
            };
            if length_scale <= eps {
                return Err(ProfileError::ZeroLength { segment: i, kind });
            }
            if (0..=16)
                .any(|k| segment.eval(f64::from(k) / 16.0).d1.length() <= 1e-6 * length_scale)
            {
                return Err(ProfileError::ZeroLength { segment: i, kind });
            }
        }
        Ok(())
    }

    fn check_joints(&self) -> Result<(), ProfileError> {
        for (i, j) in self.joints() {
            let a = self.segments[i].eval(1.0).d1.normalize();
            let b = self.segments[j].eval(0.0).d1.normalize();
            if a.dot(b) < -1.0 + 1e-9 {
                return Err(ProfileError::Cusp {
                    first: i,
                    second: j,
                });
            }
        }
        Ok(())
    }

    fn check_self_intersection(&self, eps: f64) -> Result<(), ProfileError> {
        let n = self.segments.len();
        let lines: Vec<Vec<DVec2>> = (0..n).map(|i| self.polyline(i)).collect();
        let adjacent = |i: usize, j: usize| {
            j == i + 1 || (self.closure == Closure::Ring && i == 0 && j == n - 1 && n > 1)
        };
        for i in 0..n {
            for j in i..n {
                let (a, b) = (&lines[i], &lines[j]);
                for (ka, wa) in a.windows(2).enumerate() {
                    for (kb, wb) in b.windows(2).enumerate() {
                        if i == j && kb <= ka + 1 {
                            continue; // same or neighbouring pieces of one segment
                        }
                        // Pieces that share the joint between adjacent segments.
                        if adjacent(i, j) {
                            let last_a = a.len() - 2;
                            let last_b = b.len() - 2;
                            if (j == i + 1 && ka == last_a && kb == 0)
                                || (i == 0 && j == n - 1 && ka == 0 && kb == last_b)
                            {
                                continue;
                            }
                        }
                        if i == j && n == 1 && ka == 0 && kb == a.len() - 2 {
                            continue; // a single closed segment's own ends
                        }
                        if let Some(at) = pieces_meet(wa[0], wa[1], wb[0], wb[1], eps) {
                            return Err(ProfileError::SelfIntersection {
                                first: i,
                                second: j,
                                at: [at.x, at.y],
                            });
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

fn build_segment(i: usize, spec: &SegmentSpec, eps: f64) -> Result<ProfileSegment, ProfileError> {
    let kind = spec.kind();
    Ok(match *spec {
        SegmentSpec::Line { from, to } => {
            if DVec2::from(from).distance(DVec2::from(to)) <= eps {
                return Err(ProfileError::ZeroLength { segment: i, kind });
            }
            ProfileSegment::Line(LineSegment {
                from: from.into(),
                to: to.into(),
            })
        }
        SegmentSpec::Arc {
            center,
            from,
            to,
            ccw,
        } => {
            let (c, f, t) = (DVec2::from(center), DVec2::from(from), DVec2::from(to));
            let (from_radius, to_radius) = (f.distance(c), t.distance(c));
            if (from_radius - to_radius).abs() > eps {
                return Err(ProfileError::ArcRadiusMismatch {
                    segment: i,
                    from_radius,
                    to_radius,
                });
            }
            if from_radius <= eps || f.distance(t) <= eps {
                // A collapsed arc, or a full circle (which would close on itself).
                return Err(ProfileError::ZeroLength { segment: i, kind });
            }
            ProfileSegment::Arc(ArcSegment::from_endpoints(c, f, t, ccw))
        }
        SegmentSpec::Bezier { points } => ProfileSegment::Bezier(CubicBezier {
            points: points.map(DVec2::from),
        }),
    })
}

/// Makes joints exact: each line or Bezier start is set to the previous end, and profile ends
/// within `eps` of the axis are put on it.
fn snap_joints(segments: &mut [ProfileSegment], closure: Closure, eps: f64) {
    let n = segments.len();
    for i in 0..n {
        let previous_end = if i > 0 {
            Some(segments[i - 1].end())
        } else if closure == Closure::Ring {
            Some(segments[n - 1].end())
        } else {
            None
        };
        match &mut segments[i] {
            ProfileSegment::Line(l) => {
                if let Some(p) = previous_end {
                    l.from = p;
                }
            }
            ProfileSegment::Bezier(b) => {
                if let Some(p) = previous_end {
                    b.points[0] = p;
                }
            }
            ProfileSegment::Arc(_) => {}
        }
    }
    if closure == Closure::Axis {
        let snap = |p: &mut DVec2| {
            if p.x.abs() <= eps {
                p.x = 0.0;
            }
        };
        match &mut segments[0] {
            ProfileSegment::Line(l) => snap(&mut l.from),
            ProfileSegment::Bezier(b) => snap(&mut b.points[0]),
            ProfileSegment::Arc(_) => {}
        }
        match &mut segments[n - 1] {
            ProfileSegment::Line(l) => snap(&mut l.to),
            ProfileSegment::Bezier(b) => snap(&mut b.points[3]),
            ProfileSegment::Arc(_) => {}
        }
    }
}

/// Whether closed segments [a0, a1] and [b0, b1] come within `eps` of each other; returns a
/// point where they do.
fn pieces_meet(a0: DVec2, a1: DVec2, b0: DVec2, b1: DVec2, eps: f64) -> Option<DVec2> {
    let da = a1 - a0;
    let db = b1 - b0;
    let denom = da.perp_dot(db);
    if denom.abs() > f64::EPSILON * da.length() * db.length() {
        let s = (b0 - a0).perp_dot(db) / denom;
        let t = (b0 - a0).perp_dot(da) / denom;
        if (0.0..=1.0).contains(&s) && (0.0..=1.0).contains(&t) {
            return Some(a0 + da * s);
        }
    }
    // Near misses and parallel overlaps: endpoint-to-segment distances.
    let near = |p: DVec2, q0: DVec2, q1: DVec2| {
        let d = q1 - q0;
        let t = ((p - q0).dot(d) / d.length_squared()).clamp(0.0, 1.0);
        (q0 + d * t).distance(p) <= eps
    };
    [(a0, b0, b1), (a1, b0, b1), (b0, a0, a1), (b1, a0, a1)]
        .into_iter()
        .find(|&(p, q0, q1)| near(p, q0, q1))
        .map(|(p, _, _)| p)
}
