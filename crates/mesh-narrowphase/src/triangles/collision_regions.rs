//! Grouping colliding triangle pairs into connected regions, and the centre p_ci of the area
//! each region's intersection lines bound (paper section II, Stage 2).

use glam::DVec3;

/// One piece of intersection line: triangle `a_triangle` of A's mesh (or proxy) meets triangle
/// `b_triangle` of B's mesh (or proxy) along the segment `start`..`end` (A's frame).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntersectionSegment {
    /// Triangle index in A's component mesh.
    pub a_triangle: u32,
    /// Triangle index in B's component mesh.
    pub b_triangle: u32,
    /// Segment start (A's frame).
    pub start: DVec3,
    /// Segment end (A's frame).
    pub end: DVec3,
}

/// Reusable buffers for [`group_regions`], [`region_centres`] and [`region_extremes`].
#[derive(Clone, Debug, Default)]
pub struct RegionScratch {
    parent: Vec<u32>,
    ends: Vec<(DVec3, u32)>,
    compact: Vec<u32>,
    sums: Vec<(DVec3, f64, DVec3, u32)>,
    areas: Vec<DVec3>,
    moments: Vec<(DVec3, f64)>,
    farthest: Vec<f64>,
}

/// Groups `segments` into connected regions: two segments are connected when they share an end
/// point (within a rounding allowance of 1e-10 of the coordinates' magnitude), so a region is
/// one connected piece of intersection line, e.g. one closed loop around a contact. Mesh
/// adjacency is deliberately not used: one long triangle (a cylinder's side) can reach into
/// several contacts. Fills `region_of` (one region index per segment, regions numbered from 0 in
/// order of first appearance) and returns the number of regions. Runs in O(k log k) for k
/// segments (a sort of the end points along x and a sweep), independent of the mesh sizes.
pub fn group_regions(
    segments: &[IntersectionSegment],
    scratch: &mut RegionScratch,
    region_of: &mut Vec<u32>,
) -> u32 {
    let n = segments.len();
    scratch.parent.clear();
    scratch.parent.extend(0..n as u32);
    scratch.ends.clear();
    let mut magnitude = 0.0_f64;
    for (i, s) in segments.iter().enumerate() {
        for p in [s.start, s.end] {
            magnitude = magnitude.max(p.abs().max_element());
            scratch.ends.push((p, i as u32));
        }
    }
    let eps = 1e-10 * magnitude.max(1.0);
    scratch
        .ends
        .sort_unstable_by(|a, b| a.0.x.total_cmp(&b.0.x));
    for i in 0..scratch.ends.len() {
        let (p, si) = scratch.ends[i];
        for &(q, sj) in &scratch.ends[i + 1..] {
            if q.x - p.x > eps {
                break;
            }
            if si != sj && p.distance_squared(q) <= eps * eps {
                union(&mut scratch.parent, si, sj);
            }
        }
    }
    scratch.compact.clear();
    scratch.compact.resize(n, u32::MAX);
    region_of.clear();
    let mut count = 0;
    for i in 0..n as u32 {
        let root = find(&mut scratch.parent, i) as usize;
        if scratch.compact[root] == u32::MAX {
            scratch.compact[root] = count;
            count += 1;
        }
        region_of.push(scratch.compact[root]);
    }
    count
}

/// Appends to `centres` the centre p_ci of each of `regions` regions: the area-weighted centroid
/// of the surface the region's intersection loop bounds (fanned from the loop's length-weighted
/// centroid and measured along the loop's mean plane normal), or the length-weighted centroid of
/// its segments when the loop bounds no area (an open curve or a single touching point).
/// Segments must be oriented consistently along each loop, as the exact triangle test orients
/// them along n1 × n2. The centres are finite whenever the segments are.
pub fn region_centres(
    segments: &[IntersectionSegment],
    region_of: &[u32],
    regions: u32,
    scratch: &mut RegionScratch,
    centres: &mut Vec<DVec3>,
) {
    let r = regions as usize;
    scratch.sums.clear();
    scratch.sums.resize(r, (DVec3::ZERO, 0.0, DVec3::ZERO, 0));
    for (s, &k) in segments.iter().zip(region_of) {
        let mid = 0.5 * (s.start + s.end);
        let len = s.start.distance(s.end);
        let e = &mut scratch.sums[k as usize];
        e.0 += mid * len;
        e.1 += len;
        e.2 += mid;
        e.3 += 1;
    }
    // c0: length-weighted centroid of the loop (plain mean of midpoints if it has no length).
    let origin = |e: &(DVec3, f64, DVec3, u32)| {
        if e.1 > 0.0 {
            e.0 / e.1
        } else {
            e.2 / f64::from(e.3.max(1))
        }
    };
    scratch.areas.clear();
    scratch.areas.resize(r, DVec3::ZERO);
    for (s, &k) in segments.iter().zip(region_of) {
        let c0 = origin(&scratch.sums[k as usize]);
        scratch.areas[k as usize] += (s.start - c0).cross(s.end - c0);
    }
    scratch.moments.clear();
    scratch.moments.resize(r, (DVec3::ZERO, 0.0));
    for (s, &k) in segments.iter().zip(region_of) {
        let k = k as usize;
        let c0 = origin(&scratch.sums[k]);
        let normal = scratch.areas[k].normalize_or_zero();
        let w = (s.start - c0).cross(s.end - c0).dot(normal);
        scratch.moments[k].0 += (c0 + s.start + s.end) / 3.0 * w;
        scratch.moments[k].1 += w;
    }
    for k in 0..r {
        let c0 = origin(&scratch.sums[k]);
        let length = scratch.sums[k].1;
        let (moment, area) = scratch.moments[k];
        // A loop encloses area of order length²; below 1e-9 of that it is a curve, not a loop.
        let centre = if area > 1e-9 * length * length {
            moment / area
        } else {
            c0
        };
        centres.push(if centre.is_finite() { centre } else { c0 });
    }
}

/// The extent of each of `regions` regions about its centre (`centres[k]`, from
/// [`region_centres`]): appends to `extremes` the region's radius r_k (mm), the largest
/// distance from the centre to an end point of its segments, and two end points e1, e2 that
/// approximate the ends of the loop's diameter: e1 the end point farthest from the centre, e2
/// the one farthest from e1 (A's frame). A region of one isolated minimum of distance d* and
/// offset h is about the ellipse |x - p*|ᵀK|x - p*| <= 2 (h - d*) centred on the minimum p*;
/// where the loop encloses several minima, e1 and e2 lie in the outermost ones' lobes. O(k)
/// for k segments; a region of one point has r = 0 and e1 = e2 = that point.
pub fn region_extremes(
    segments: &[IntersectionSegment],
    region_of: &[u32],
    centres: &[DVec3],
    scratch: &mut RegionScratch,
    extremes: &mut Vec<(f64, [DVec3; 2])>,
) {
    let first = extremes.len();
    extremes.extend(centres.iter().map(|&c| (0.0, [c, c])));
    let regions = &mut extremes[first..];
    for (s, &k) in segments.iter().zip(region_of) {
        let Some(e) = regions.get_mut(k as usize) else {
            continue;
        };
        let c = centres[k as usize];
        for p in [s.start, s.end] {
            let r = p.distance(c);
            if r > e.0 {
                *e = (r, [p, p]);
            }
        }
    }
    let farthest = &mut scratch.farthest;
    farthest.clear();
    farthest.resize(regions.len(), 0.0);
    for (s, &k) in segments.iter().zip(region_of) {
        let Some(e) = regions.get_mut(k as usize) else {
            continue;
        };
        for p in [s.start, s.end] {
            let r = p.distance(e.1[0]);
            if r > farthest[k as usize] {
                farthest[k as usize] = r;
                e.1[1] = p;
            }
        }
    }
}

fn find(parent: &mut [u32], mut x: u32) -> u32 {
    while parent[x as usize] != x {
        let p = parent[parent[x as usize] as usize];
        parent[x as usize] = p;
        x = p;
    }
    x
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    if ra != rb {
        parent[ra.max(rb) as usize] = ra.min(rb);
    }
}
