//! Cost of evaluating revolved surfaces: `Surface::eval` (point and first and second
//! derivatives) and `Surface::principal_curvatures` per segment kind (line, arc, Bezier), over a
//! fixed set of 1024 seeded (u, v) points. Criterion reports the time per batch of 1024 and the
//! throughput in evaluations per second.

use criterion::{BenchmarkId, Criterion, Throughput, black_box};
use geom_param::{
    ArcSegment, CubicBezier, DVec2, LineSegment, ProfileSegment, RevolvedSurface, Surface,
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

// What `criterion_group!` / `criterion_main!` expand to, written out so that no undocumented
// public function is generated (the workspace warns on missing docs).
fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench_eval(&mut c);
    bench_curvatures(&mut c);
    c.final_summary();
}
