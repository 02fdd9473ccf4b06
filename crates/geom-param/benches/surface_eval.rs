//! Cost of evaluating surfaces: `Surface::eval` (point and first and second derivatives) and
//! `Surface::principal_curvatures` of revolved surfaces per segment kind (line, arc, Bezier),
//! and `Surface::eval` of the general geometry (a bicubic rational NURBS patch, an analytic
//! torus, the NURBS torus of A8.1), over a fixed set of 1024 seeded (u, v) points mapped onto
//! each surface's domain. Criterion reports the time per batch of 1024 (divide by 1024 for ns
//! per eval) and the throughput in evaluations per second.

use criterion::{BenchmarkId, Criterion, Throughput, black_box};
use geom_param::{
    ArcSegment, CubicBezier, DVec2, DVec3, LineSegment, NurbsCurve, NurbsSurface, ParamRange,
    Placement, ProfileSegment, RevolvedSurface, Surface, TorusSurface,
};
use std::f64::consts::{PI, TAU};

/// Points per batch.
const POINTS: usize = 1024;

/// SplitMix64 (Steele, Lea, Flood 2014): a tiny, seedable, portable PRNG.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// Uniform in [0, 1) with 53 random bits.
    fn unit(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// The same 1024 (u, v) for every benchmark: u in [0, 2π), v in [0, 1).
fn params() -> Vec<(f64, f64)> {
    let mut rng = SplitMix64(0xBE4C_0001);
    (0..POINTS)
        .map(|_| (TAU * rng.unit(), rng.unit()))
        .collect()
}

/// One face per segment kind, all off the axis (so no pole or apex branch is taken).
fn surfaces() -> [(&'static str, RevolvedSurface); 3] {
    [
        (
            "line",
            RevolvedSurface {
                segment: ProfileSegment::Line(LineSegment {
                    from: DVec2::new(12.0, -4.0),
                    to: DVec2::new(7.0, 18.0),
                }),
            },
        ),
        (
            "arc",
            RevolvedSurface {
                segment: ProfileSegment::Arc(ArcSegment {
                    center: DVec2::new(20.0, 0.0),
                    radius: 5.0,
                    start_angle: -PI / 2.0 + 0.01,
                    sweep: TAU - 0.02,
                }),
            },
        ),
        (
            "bezier",
            RevolvedSurface {
                segment: ProfileSegment::Bezier(CubicBezier {
                    points: [
                        DVec2::new(35.0, 5.0),
                        DVec2::new(40.0, 20.0),
                        DVec2::new(45.0, 30.0),
                        DVec2::new(45.0, 40.0),
                    ],
                }),
            },
        ),
    ]
}

fn bench_eval(c: &mut Criterion) {
    let points = params();
    let mut group = c.benchmark_group("surface_eval");
    group.throughput(Throughput::Elements(POINTS as u64));
    for (kind, surface) in surfaces() {
        group.bench_with_input(BenchmarkId::new("eval", kind), &surface, |b, s| {
            b.iter(|| {
                for &(u, v) in &points {
                    black_box(s.eval(black_box(u), black_box(v)));
                }
            });
        });
    }
    group.finish();
}

fn bench_curvatures(c: &mut Criterion) {
    let points = params();
    let mut group = c.benchmark_group("principal_curvatures");
    group.throughput(Throughput::Elements(POINTS as u64));
    for (kind, surface) in surfaces() {
        // The closed-form override used by the library.
        group.bench_with_input(BenchmarkId::new("override", kind), &surface, |b, s| {
            b.iter(|| {
                for &(u, v) in &points {
                    black_box(s.principal_curvatures(black_box(u), black_box(v)));
                }
            });
        });
        // For comparison: the trait's default path (eval + fundamental forms) with the normal.
        group.bench_with_input(
            BenchmarkId::new("fundamental_forms", kind),
            &surface,
            |b, s| {
                b.iter(|| {
                    for &(u, v) in &points {
                        let (u, v) = (black_box(u), black_box(v));
                        let n = s.normal(u, v).unwrap_or_default();
                        black_box(s.eval(u, v).principal_curvatures_with(n));
                    }
                });
            },
        );
    }
    group.finish();
}

/// A bicubic rational patch: 8 × 8 control points on a wavy sheet, clamped uniform knots (5
/// spans each way), weights in [0.5, 2).
fn bicubic_patch() -> NurbsSurface {
    let mut rng = SplitMix64(0xBE4C_0002);
    let n = 8;
    let knots: Vec<f64> = (0..n + 4)
        .map(|i| (i.clamp(3, n) - 3) as f64 / (n - 3) as f64)
        .collect();
    let points = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| DVec3::new(10.0 * i as f64, 10.0 * j as f64, 5.0 * rng.unit()))
                .collect()
        })
        .collect();
    let weights = (0..n)
        .map(|_| (0..n).map(|_| 0.5 + 1.5 * rng.unit()).collect())
        .collect();
    NurbsSurface::new(
        [3, 3],
        [knots.clone(), knots],
        points,
        weights,
        [false, false],
    )
    .expect("valid patch")
}

/// The general surfaces, boxed so they share one loop.
fn general_surfaces() -> [(&'static str, Box<dyn Surface>); 3] {
    let turn = ParamRange {
        min: 0.0,
        max: TAU,
        periodic: true,
    };
    let torus = TorusSurface::new(Placement::IDENTITY, 20.0, 5.0, [turn, turn]).expect("torus");
    let tube_plane =
        Placement::new(DVec3::new(20.0, 0.0, 0.0), -DVec3::Y, DVec3::X).expect("meridian plane");
    let tube = NurbsCurve::circle_arc(&tube_plane, 5.0, 0.0, TAU).expect("tube");
    let nurbs_torus =
        NurbsSurface::revolution(&tube, DVec3::ZERO, DVec3::Z, TAU).expect("NURBS torus");
    [
        ("nurbs_bicubic_8x8", Box::new(bicubic_patch())),
        ("torus", Box::new(torus)),
        ("nurbs_torus", Box::new(nurbs_torus)),
    ]
}

fn bench_general_eval(c: &mut Criterion) {
    let unit: Vec<(f64, f64)> = params().into_iter().map(|(u, v)| (u / TAU, v)).collect();
    let mut group = c.benchmark_group("general_surface_eval");
    group.throughput(Throughput::Elements(POINTS as u64));
    for (kind, surface) in general_surfaces() {
        let [du, dv] = surface.domain();
        let points: Vec<(f64, f64)> = unit
            .iter()
            .map(|&(a, b)| (du.min + a * du.span(), dv.min + b * dv.span()))
            .collect();
        group.bench_with_input(BenchmarkId::new("eval", kind), &surface, |b, s| {
            b.iter(|| {
                for &(u, v) in &points {
                    black_box(s.eval(black_box(u), black_box(v)));
                }
            });
        });
    }
    group.finish();
}

// What `criterion_group!` / `criterion_main!` expand to, written out so that no undocumented
// public function is generated (the workspace warns on missing docs).
fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_eval(&mut c);
    bench_curvatures(&mut c);
    bench_general_eval(&mut c);
    c.final_summary();
}
