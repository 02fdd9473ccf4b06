//! Rapier simulations with exact contacts beside rapier's own mesh colliders: the "equivalent"
//! of a `contacts simulate` command that issue 17 allows (a cargo example, not a `contacts`
//! subcommand, so that rapier stays a dev-dependency of `contact-parry` alone).
//!
//! ```sh
//! cargo run --release -p contact-parry --example rapier_scenes -- --out DIR [--csv]
//!     [--hz F] [--iterations N] [--static-hz F] [--static-damping Z] [--damping-scale S]
//! ```
//!
//! Three scenes, each run with [`contact_parry::ExactDispatcher`] (exact shapes, and parry's
//! `Ball` / `Cuboid` turned into exact ones) and again with rapier's default narrow phase on
//! mesh colliders of the same objects (the welded closed mesh as a `TriMesh`, and its convex
//! hull where that is a fair stand-in), at the same time step and parameters:
//! - `pencil-bowl`: the pencil dropped across the fixed bowl comes to rest on the rim at two
//!   contacts;
//! - `vase-rolling`: the vase laid on its side on a fixed box, spun about its axis at 3 rad/s,
//!   rolls and rocks (damped) towards rest;
//! - `ball-bowl-crease`: a ball 12 mm across dropped into the bowl tilted by 10 degrees rolls
//!   into the concave crease between the flat bottom and the wall and settles there on two
//!   contacts (8 s simulated: see "Why rest takes damping, time and a short step" below).
//!
//! Rapier's parameters for a millimetre world, chosen deliberately and the same in every run:
//! `length_unit` 1000 (gravity 9810 mm/s²), time step 1/240 s (`--hz`), prediction distance 2 mm
//! (`normalized_prediction_distance` 0.002) with the pipeline's band reaching as far
//! (delta2 = 2 mm, margin 4 mm) so that every speculative contact rapier asks for is exact,
//! 8 solver iterations and contacts with fixed bodies at 960 Hz and damping ratio 1 (rapier's
//! defaults, 4 iterations at 60 Hz and ratio 10, rest about 0.06 mm deep whatever the
//! contacts: that is the soft contact's equilibrium, not detection), contact recycling off (it
//! reuses last step's points while a pair moves less than 50 mm at this scale), CCD off (the
//! exact dispatcher answers no shape casts), sleeping off for the moving body (its jitter is
//! measured). Damping: the vase 1/s linear and 3/s angular, the ball 2/s both.
//!
//! Per scene and run, measured the same way for every run: the penetration depth each step,
//! *exactly with the pipeline* at the run's poses (a penetration whose depth the pipeline cannot
//! certify is measured on the closed meshes and counted in `mesh_measured_steps`), the
//! solver's contact count (rapier's solver contacts of the pair), the exact minima within
//! 0.01 mm, whether and when the body comes to rest (speed below 1 mm/s and 0.02 rad/s until
//! the end, for at least 0.5 s), the jitter (rms linear speed over the last second), the
//! largest, last-second and final penetration, and for the exact run how the dispatcher
//! answered (full pipeline queries, warm coherent frames); and, after the first second, how
//! smoothly the body moves and how fast its motion dies out (`after_1_s`, see `smoothness`:
//! the decay rate of the speed's peaks beside the rate the body's damping alone gives, the
//! speed's step-to-step roughness, the step-to-step turn of the resultant contact normal, and
//! how often the solver contacts' features change). The JSON goes to
//! `DIR/rapier_scenes.json` (and stdout), one SVG per scene (`DIR/SCENE.svg`: penetration and
//! speed, on log scales, and solver contact count against time), and with `--csv` every step
//! of every run (`DIR/SCENE-RUN.csv`: velocities, kinetic energy and each solver contact's
//! features, distance, impulse and normal).
//!
//! # Why rest takes damping, time and a short step
//!
//! Exact contacts have no facets to lose energy on: a body rolling or rocking on them keeps
//! its energy up to the integrator, so a stated dissipation must stop it, the same in every
//! run: rapier's linear and angular damping of the moving body (rapier has no rolling
//! resistance), restitution 0 (rapier's default) and friction 0.5 (rapier's default). A
//! damped oscillation then decays at the amplitude rate (c_lin <K_lin> + c_ang <K_ang>) /
//! (2 <K>) (`damping_decay_rate_per_s`): 1.0/s for the ball (2/s both), 0.87/s for the vase.
//! Measured with the exact contacts at 60, 120 and 240 steps a second, the speed's peaks decay
//! at 0.32, 0.60, 0.74/s (vase) and 0.82, 0.91, 0.96/s (ball): linear in dt, extrapolating to
//! 0.88 and 1.00/s at dt = 0, the damping's own rates. The missing part, about ω0² dt / 4 for
//! an oscillation of angular frequency ω0 (vase rocking at 12 rad/s: 0.56/s at 1/60 s; ball
//! along the crease at 6.6 rad/s: 0.18/s), comes from rapier's step, not the contacts (they are
//! exact at every step, their normal turns by at most 0.005 rad a step and their features never
//! change after the first second). The likely mechanism: each contact is held at its
//! start-of-step point and normal for the whole step while the true contact rolls along the
//! body, so a body on a stable (concave-up) path ends each step slightly inside the surface,
//! and the position correction lifts it out without taking the matching kinetic energy.
//! Hence 240 steps a second (anti-damping 0.14/s for the vase), and 8 s for the ball, whose
//! rest threshold on spin (0.02 rad/s, 0.12 mm/s at its surface) its damping reaches after
//! about 6.5 s. The rest test itself is unchanged. `--damping-scale 0` runs the scenes
//! undamped: at 60 steps a second the exact ball's oscillation along the crease gains energy
//! (peak kinetic energy 2.5 times from the second to the eighth second), at 240 barely (1.1).

use contact_parry::{BeyondReach, DispatcherOptions, ExactDispatcher, ExactShape};
use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{MeshOptions, ObjectFile};
use parry3d_f64::math::{Pose, Vector};
use parry3d_f64::query::{DefaultQueryDispatcher, QueryDispatcher};
use parry3d_f64::shape::{SharedShape, TriMeshFlags};
use rapier3d_f64::prelude::{
    ColliderBuilder, ColliderHandle, NarrowPhase, PhysicsWorld, RigidBodyBuilder, RigidBodyHandle,
};
use serde_json::{Value, json};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

/// Default time step (s): 240 steps a second (`--hz`). Rapier's step holds each contact
/// still for the whole step and corrects the penetration it then finds by position, which
/// feeds a rocking or rolling oscillation of angular frequency ω0 with energy at an amplitude
/// rate of about ω0² dt / 4 (measured, see the module doc): 0.56/s for the vase's rocking at
/// 1/60 s, 0.14/s at 1/240 s.
const DEFAULT_HZ: f64 = 240.0;
/// Rest: linear speed below this (mm/s)...
const REST_SPEED: f64 = 1.0;
/// ... and angular speed below this (rad/s) ...
const REST_SPIN: f64 = 0.02;
/// ... for every step to the end, over at least this long (s).
const REST_HOLD: f64 = 0.5;
/// An exact minimum this close (mm) counts as a contact in `exact_contacts`.
const TOUCH: f64 = 0.01;
/// Smoothness and decay are measured after this (s): the drop and the first bounce are over.
const SETTLE: f64 = 1.0;

/// How the objects are given to rapier.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Variant {
    /// Exact shapes (and parry primitives) with the exact dispatcher.
    Exact,
    /// Rapier's default narrow phase, each exact object as its closed mesh (`TriMesh`).
    TriMesh,
    /// As `TriMesh`, but the moving object as the convex hull of its mesh.
    ConvexHull,
}

impl Variant {
    fn name(self) -> &'static str {
        match self {
            Self::Exact => "exact",
            Self::TriMesh => "trimesh",
            Self::ConvexHull => "convex_hull",
        }
    }
}

/// One body of a scene: an exact object, or a parry primitive (exact in every run).
#[derive(Clone)]
enum Body {
    Exact(ExactShape),
    Ball(f64),
    Cuboid(Vector),
}

struct Scene {
    name: &'static str,
    description: &'static str,
    fixed: Body,
    fixed_pose: Pose,
    moving: Body,
    moving_pose: Pose,
    angvel: Vector,
    linear_damping: f64,
    angular_damping: f64,
    seconds: f64,
    variants: &'static [Variant],
}

/// The collider of `body` for `variant` (`hull`: the moving body, as a convex hull there).
fn collider(body: &Body, variant: Variant, moving: bool) -> ColliderBuilder {
    match body {
        Body::Ball(r) => ColliderBuilder::ball(*r),
        Body::Cuboid(h) => ColliderBuilder::cuboid(h.x, h.y, h.z),
        Body::Exact(shape) => match variant {
            Variant::Exact => ColliderBuilder::new(SharedShape::new(shape.clone())),
            Variant::ConvexHull if moving => {
                ColliderBuilder::convex_hull(shape.closed_mesh().trimesh.vertices())
                    .expect("a closed mesh has a hull")
            }
            _ => {
                let mesh = &shape.closed_mesh().trimesh;
                ColliderBuilder::trimesh_with_flags(
                    mesh.vertices().to_vec(),
                    mesh.indices().to_vec(),
                    TriMeshFlags::ORIENTED | TriMeshFlags::FIX_INTERNAL_EDGES,
                )
                .expect("parry took this mesh once already")
            }
        },
    }
}

/// The exact shape of `body` for measuring (primitives built with `pipeline`).
fn exact_of(body: &Body, pipeline: &Arc<ContactPipeline>) -> ExactShape {
    match body {
        Body::Exact(s) => s.clone(),
        Body::Ball(r) => contact_parry::exact_ball(Arc::clone(pipeline), *r).expect("ball"),
        Body::Cuboid(h) => contact_parry::exact_cuboid(Arc::clone(pipeline), *h).expect("box"),
    }
}

/// Per-step record of one run.
#[derive(Default)]
struct Trace {
    time: Vec<f64>,
    penetration: Vec<f64>,
    solver_contacts: Vec<usize>,
    exact_contacts: Vec<usize>,
    speed: Vec<f64>,
    spin: Vec<f64>,
    mesh_measured: usize,
    quarantined: usize,
    z: Vec<f64>,
    /// Kinetic energy (rapier's mass unit × mm²/s²), and the part of it that is linear.
    kinetic: Vec<f64>,
    kinetic_linear: Vec<f64>,
    linvel: Vec<Vector>,
    angvel: Vec<Vector>,
    /// The moving body's pose.
    pose: Vec<Pose>,
    /// Direction of the resultant contact impulse on the moving body's pair (world frame, from
    /// the fixed body to the moving one), `None` when no impulse acts.
    contact_normal: Vec<Option<Vector>>,
    /// Whether the set of (subshape1, subshape2, fid1, fid2) of the pair's solver contacts
    /// differs from last step's (a mesh's triangle is its subshape).
    features_changed: Vec<bool>,
    /// Each solver contact of the pair: `subshape1:fid1 subshape2:fid2 dist impulse nx ny nz`
    /// (world normal, from the fixed body to the moving one), `;`-separated (for `--csv`).
    contacts_described: Vec<String>,
    /// Damping of the moving body (1/s): linear, angular.
    damping: (f64, f64),
    dt: f64,
    wall_seconds: f64,
    dispatcher: Option<contact_parry::DispatchCounts>,
}

/// Rapier's solver settings shared by every run.
#[derive(Clone, Copy, Debug)]
struct Solver {
    dt: f64,
    /// Factor on every moving body's damping (1: the scenes' own; 0: undamped, to watch the
    /// energy that contacts and integrator alone keep or feed).
    damping_scale: f64,
    iterations: usize,
    static_hz: f64,
    static_damping: f64,
}

fn run(scene: &Scene, variant: Variant, pipeline: &Arc<ContactPipeline>, solver: Solver) -> Trace {
    let mut world = PhysicsWorld::new();
    world.gravity = Vector::new(0.0, 0.0, -9810.0);
    let p = &mut world.integration_parameters;
    p.length_unit = 1000.0;
    p.dt = solver.dt;
    p.normalized_prediction_distance = 0.002;
    p.contact_recycling = false;
    p.num_solver_iterations = solver.iterations;
    // No CCD in any run: the exact dispatcher answers no shape casts.
    p.max_ccd_substeps = 0;
    p.static_contact_softness.natural_frequency = solver.static_hz;
    p.static_contact_softness.damping_ratio = solver.static_damping;
    let mut counters = None;
    if variant == Variant::Exact {
        // Strict: what the pipeline cannot answer exactly is `Unsupported` (counted).
        let dispatcher = ExactDispatcher::new(DispatcherOptions {
            beyond_reach: BeyondReach::Unsupported,
            ..DispatcherOptions::default()
        });
        counters = Some(dispatcher.counters());
        world.narrow_phase = NarrowPhase::with_query_dispatcher(dispatcher);
    }
    let fixed_body = world.insert_body(RigidBodyBuilder::fixed().pose(scene.fixed_pose));
    let fixed_collider: ColliderHandle = world.insert_collider(
        collider(&scene.fixed, variant, false).build(),
        Some(fixed_body),
    );
    let damping = (
        scene.linear_damping * solver.damping_scale,
        scene.angular_damping * solver.damping_scale,
    );
    let moving_body: RigidBodyHandle = world.insert_body(
        RigidBodyBuilder::dynamic()
            .pose(scene.moving_pose)
            .angvel(scene.angvel)
            .linear_damping(damping.0)
            .angular_damping(damping.1)
            .can_sleep(false),
    );
    let moving_collider = world.insert_collider(
        collider(&scene.moving, variant, true).build(),
        Some(moving_body),
    );
    let fixed_exact = exact_of(&scene.fixed, pipeline);
    let moving_exact = exact_of(&scene.moving, pipeline);
    let mut scratch = QueryScratch::default();
    let mut trace = Trace {
        damping,
        dt: solver.dt,
        ..Trace::default()
    };
    let mut last_features: Vec<(u32, u32, u32, u32)> = Vec::new();
    let steps = (scene.seconds / solver.dt).round() as usize;
    let mut wall = 0.0;
    for step in 1..=steps {
        let start = Instant::now();
        world.step();
        wall += start.elapsed().as_secs_f64();
        if !world.quarantine().is_empty() {
            trace.quarantined += 1;
        }
        let body = &world.bodies[moving_body];
        let pose = *body.position();
        trace.time.push(step as f64 * solver.dt);
        trace.z.push(pose.translation.z);
        trace.speed.push(body.linvel().length());
        trace.spin.push(body.angvel().length());
        trace.kinetic.push(body.kinetic_energy());
        trace
            .kinetic_linear
            .push(0.5 * body.mass() * body.linvel().length_squared());
        trace.linvel.push(body.linvel());
        trace.pose.push(pose);
        trace.angvel.push(body.angvel());
        let manifolds = world
            .narrow_phase
            .contact_pair(fixed_collider, moving_collider)
            .map_or(&[][..], |pair| pair.solver_manifolds());
        // Rapier orders the pair by collider handle: the normal goes from collider1 to 2.
        let sign = match world
            .narrow_phase
            .contact_pair(fixed_collider, moving_collider)
        {
            Some(pair) if pair.collider1 == moving_collider => -1.0,
            _ => 1.0,
        };
        trace
            .solver_contacts
            .push(manifolds.iter().map(|m| m.data.solver_contacts.len()).sum());
        let mut resultant = Vector::ZERO;
        let mut features = Vec::new();
        let mut described = Vec::new();
        for m in manifolds {
            let n = sign * m.data.normal;
            for c in &m.points {
                resultant += c.data.impulse * n;
                features.push((m.subshape1, m.subshape2, c.fid1.0, c.fid2.0));
                described.push(format!(
                    "{}:{} {}:{} {:.6} {:.6e} {:.6} {:.6} {:.6}",
                    m.subshape1,
                    c.fid1.0,
                    m.subshape2,
                    c.fid2.0,
                    c.dist,
                    c.data.impulse,
                    n.x,
                    n.y,
                    n.z
                ));
            }
        }
        features.sort_unstable();
        features.dedup();
        trace.features_changed.push(features != last_features);
        last_features = features;
        trace.contact_normal.push(resultant.try_normalize());
        trace.contacts_described.push(described.join(";"));
        let report = pipeline
            .query(
                fixed_exact.object(),
                &scene.fixed_pose,
                moving_exact.object(),
                &pose,
                &mut scratch,
            )
            .expect("rigid poses");
        trace.exact_contacts.push(
            report
                .contacts
                .iter()
                .filter(|c| c.distance <= TOUCH)
                .count(),
        );
        let certified = report
            .contacts
            .iter()
            .map(|c| c.distance)
            .fold(f64::INFINITY, f64::min);
        let depth = if report.state == PairState::Penetration && certified >= 0.0 {
            // No certified depth: measured on the closed meshes (within their chordal errors).
            trace.mesh_measured += 1;
            let pos12 = scene.fixed_pose.inverse() * pose;
            DefaultQueryDispatcher
                .contact(
                    &pos12,
                    &fixed_exact.closed_mesh().trimesh,
                    &moving_exact.closed_mesh().trimesh,
                    0.0,
                )
                .ok()
                .flatten()
                .map_or(0.0, |c| (-c.dist).max(0.0))
        } else {
            (-certified).max(0.0)
        };
        trace.penetration.push(depth);
    }
    trace.wall_seconds = wall;
    trace.dispatcher = counters.map(|c| c.snapshot());
    trace
}

/// The run's summary as JSON.
fn summary(trace: &Trace) -> Value {
    let n = trace.time.len();
    let last_second = ((1.0 / trace.dt).round() as usize).min(n);
    let tail = n - last_second;
    let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len().max(1) as f64).sqrt();
    // Rest: the first step from which speed and spin stay below the thresholds to the end.
    let mut rest_from = n;
    while rest_from > 0
        && trace.speed[rest_from - 1] < REST_SPEED
        && trace.spin[rest_from - 1] < REST_SPIN
    {
        rest_from -= 1;
    }
    let held = (n - rest_from) as f64 * trace.dt;
    let rest = (n > 0 && held >= REST_HOLD).then(|| trace.time[rest_from.min(n - 1)]);
    let max_pen = trace.penetration.iter().copied().fold(0.0, f64::max);
    let last_second_pen = trace.penetration[tail..]
        .iter()
        .copied()
        .fold(0.0, f64::max);
    let stats = |v: &[usize]| {
        json!({
            "min": v.iter().min().copied().unwrap_or(0),
            "max": v.iter().max().copied().unwrap_or(0),
            "final": v.last().copied().unwrap_or(0),
            "mean_last_second": v[tail..].iter().sum::<usize>() as f64 / last_second.max(1) as f64,
        })
    };
    json!({
        "rest_reached": rest.is_some(),
        "rest_time_s": rest,
        "max_penetration_mm": max_pen,
        "max_penetration_last_second_mm": last_second_pen,
        "final_penetration_mm": trace.penetration.last().copied().unwrap_or(0.0),
        "jitter_rms_speed_last_second_mm_per_s": rms(&trace.speed[tail..]),
        "jitter_rms_spin_last_second_rad_per_s": rms(&trace.spin[tail..]),
        "final_speed_mm_per_s": trace.speed.last().copied().unwrap_or(0.0),
        "solver_contacts": stats(&trace.solver_contacts),
        "exact_contacts_within_0_01_mm": stats(&trace.exact_contacts),
        "mesh_measured_steps": trace.mesh_measured,
        "quarantined_steps": trace.quarantined,
        "after_1_s": smoothness(trace),
        "steps": n,
        "wall_time_s": trace.wall_seconds,
        "dispatcher": trace.dispatcher.map(|c| json!({
            "full_queries": c.exact, "warm_frames": c.warm,
            "mesh_answers": c.mesh, "unsupported": c.unsupported,
        })),
    })
}

/// How smoothly the body moves and how its motion dies out, after [`SETTLE`]:
/// - `speed_decay_rate_per_s`: the least-squares slope of ln(speed) at the speed's local maxima
///   above 1e-3 mm/s (at least three; `null` otherwise): the amplitude decay of the rocking or
///   rolling oscillation;
/// - `damping_decay_rate_per_s`: the decay the body's damping alone gives that motion,
///   (c_lin <K_lin> + c_ang <K_ang>) / (2 <K>) with K the kinetic energy split into its linear
///   and angular parts, averaged over the same steps (damping takes c·2K of power from each
///   part, and the amplitude goes as the square root of the energy, 2 <K>); the difference
///   from the measured rate is what contacts and integrator add (positive: they feed energy);
/// - `speed_roughness_mm_per_s`: the rms of speed_k − (speed_(k−1) + speed_(k+1)) / 2, the part
///   of the speed that changes from step to step rather than smoothly (a smooth motion gives
///   O(acceleration' · dt²));
/// - `contact_normal_max_step_rad`, `contact_normal_rms_step_rad`: the angle between the
///   directions of the resultant contact impulse at consecutive steps (both non-zero);
/// - `contact_feature_changes`: steps at which the set of (subshape1, subshape2, fid1, fid2) of
///   the solver contacts differs from the last step's (contacts appearing, disappearing or
///   changing features or triangles).
fn smoothness(trace: &Trace) -> Value {
    let from = trace.time.partition_point(|&t| t <= SETTLE);
    let n = trace.time.len();
    let peaks: Vec<(f64, f64)> = (from.max(1)..n.saturating_sub(1))
        .filter(|&k| {
            let v = trace.speed[k];
            v > 1e-3 && v > trace.speed[k - 1] && v >= trace.speed[k + 1]
        })
        .map(|k| (trace.time[k], trace.speed[k].ln()))
        .collect();
    let decay = (peaks.len() >= 3).then(|| {
        let m = peaks.len() as f64;
        let (st, sy) = peaks
            .iter()
            .fold((0.0, 0.0), |(a, b), &(t, y)| (a + t, b + y));
        let (tm, ym) = (st / m, sy / m);
        let (num, den) = peaks.iter().fold((0.0, 0.0), |(a, b), &(t, y)| {
            (a + (t - tm) * (y - ym), b + (t - tm) * (t - tm))
        });
        -num / den
    });
    let kinetic: f64 = trace.kinetic[from..].iter().sum();
    let linear: f64 = trace.kinetic_linear[from..]
        .iter()
        .sum::<f64>()
        .min(kinetic);
    let (c_lin, c_ang) = trace.damping;
    let damping =
        (kinetic > 0.0).then(|| (c_lin * linear + c_ang * (kinetic - linear)) / (2.0 * kinetic));
    let rough: Vec<f64> = (from.max(1)..n.saturating_sub(1))
        .map(|k| trace.speed[k] - 0.5 * (trace.speed[k - 1] + trace.speed[k + 1]))
        .collect();
    let steps: Vec<f64> = (from.max(1)..n)
        .filter_map(|k| {
            let (a, b) = (trace.contact_normal[k - 1]?, trace.contact_normal[k]?);
            Some(a.angle_between(b))
        })
        .collect();
    let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len().max(1) as f64).sqrt();
    json!({
        "speed_decay_rate_per_s": decay,
        "damping_decay_rate_per_s": damping,
        "speed_roughness_mm_per_s": rms(&rough),
        "contact_normal_max_step_rad": steps.iter().copied().fold(0.0, f64::max),
        "contact_normal_rms_step_rad": rms(&steps),
        "contact_feature_changes": trace.features_changed[from..].iter().filter(|&&c| c).count(),
    })
}

/// One plotted quantity of a run.
type Series = Box<dyn Fn(&Trace) -> Vec<f64>>;

/// Hand-written SVG, one polyline per run against time: penetration depth (mm, log10 scale
/// from 1e-6 mm), linear speed (mm/s, log10 scale from 1e-6 mm/s, the rest threshold dashed)
/// and solver contact count (linear scale).
fn plot(scene: &Scene, runs: &[(Variant, Trace)]) -> String {
    let (w, h, pad) = (760.0, 230.0, 50.0);
    let colours = ["#1f77b4", "#d62728", "#2ca02c"];
    let t_max = scene.seconds;
    let floor: f64 = 1e-6;
    let panels: [(&str, bool, Series); 3] = [
        (
            "penetration depth (mm, exact, log scale)",
            true,
            Box::new(|t: &Trace| t.penetration.clone()),
        ),
        (
            "speed (mm/s, log scale; dashed: rest threshold)",
            true,
            Box::new(|t: &Trace| t.speed.clone()),
        ),
        (
            "solver contacts",
            false,
            Box::new(|t: &Trace| t.solver_contacts.iter().map(|&c| c as f64).collect()),
        ),
    ];
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{pad}\" y=\"20\" font-size=\"14\">{}: {}</text>\n",
        panels.len() as f64 * h + 40.0,
        scene.name,
        scene.description
    );
    for (k, (label, log, series)) in panels.iter().enumerate() {
        let top = 40.0 + k as f64 * h;
        let y_max = runs
            .iter()
            .flat_map(|(_, t)| series(t))
            .fold(0.0, f64::max)
            .max(if *log { 10.0 * floor } else { 1.0 });
        let (x0, x1, y0, y1) = (pad, w - 20.0, top + h - 40.0, top + 10.0);
        // Height of `v` above the axis, as a fraction of the panel.
        let scale = |v: f64| {
            if *log {
                (v.max(floor) / floor).log10() / (y_max / floor).log10()
            } else {
                v / y_max
            }
        };
        let range = if *log {
            format!("from {floor:e} to {y_max:.3e}")
        } else {
            format!("from 0 to {y_max}")
        };
        svg += &format!(
            "<line x1=\"{x0}\" y1=\"{y0}\" x2=\"{x1}\" y2=\"{y0}\" stroke=\"black\"/>\n<line x1=\"{x0}\" y1=\"{y0}\" x2=\"{x0}\" y2=\"{y1}\" stroke=\"black\"/>\n<text x=\"{x0}\" y=\"{}\">{label}, {range}</text>\n<text x=\"{}\" y=\"{}\">time (s), 0 to {t_max}</text>\n",
            y1 - 2.0,
            x1 - 120.0,
            y0 + 16.0
        );
        if k == 1 {
            let y = y0 - (y0 - y1) * scale(REST_SPEED);
            svg += &format!(
                "<line x1=\"{x0}\" y1=\"{y:.1}\" x2=\"{x1}\" y2=\"{y:.1}\" stroke=\"grey\" stroke-dasharray=\"4 4\"/>\n"
            );
        }
        for (i, (variant, trace)) in runs.iter().enumerate() {
            let points: Vec<String> = trace
                .time
                .iter()
                .zip(series(trace))
                .map(|(t, v)| {
                    format!(
                        "{:.1},{:.1}",
                        x0 + (x1 - x0) * t / t_max,
                        y0 - (y0 - y1) * scale(v)
                    )
                })
                .collect();
            let colour = colours[i % colours.len()];
            svg += &format!(
                "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"1\" points=\"{}\"/>\n<text x=\"{}\" y=\"{}\" fill=\"{colour}\">{}</text>\n",
                points.join(" "),
                x1 - 110.0,
                y1 + 14.0 * (i as f64 + 1.0),
                variant.name()
            );
        }
    }
    svg + "</svg>\n"
}

fn object(pipeline: &Arc<ContactPipeline>, fixtures: &Path, name: &str) -> ExactShape {
    let text = std::fs::read_to_string(fixtures.join(format!("objects/{name}.json")))
        .unwrap_or_else(|e| panic!("fixtures/objects/{name}.json: {e}"));
    let model = ObjectFile::from_json(&text)
        .expect("object file")
        .build(&MeshOptions {
            chordal_tolerance: pipeline.options().chordal_tolerance,
        })
        .expect("model");
    ExactShape::from_model(Arc::clone(pipeline), model).expect("closed mesh")
}

/// The lowest z (mm) of `shape`'s mesh posed by `pose`.
fn lowest(shape: &ExactShape, pose: &Pose) -> f64 {
    shape
        .closed_mesh()
        .trimesh
        .vertices()
        .iter()
        .map(|v| (*pose * *v).z)
        .fold(f64::INFINITY, f64::min)
}

fn scenes(pipeline: &Arc<ContactPipeline>, fixtures: &Path) -> Vec<Scene> {
    let bowl = object(pipeline, fixtures, "bowl");
    let pencil = object(pipeline, fixtures, "pencil");
    let vase = object(pipeline, fixtures, "vase");
    // The pencil across the bowl: its axis along x (local z -> world x), its centre of mass
    // (local z = 83.6) over the bowl's axis, yawed 20 degrees and pitched 2 degrees, 3 mm above
    // the rim's top (z = 42) at its lowest.
    let turn = glam::DQuat::from_rotation_z(20f64.to_radians())
        * glam::DQuat::from_rotation_y(88f64.to_radians());
    let centre = turn * Vector::new(0.0, 0.0, 83.6);
    let mut pencil_pose = Pose::from_parts(-centre, turn);
    pencil_pose.translation.z += 45.5 + 3.0;
    // The vase on its side (axis along y) 1 mm above the box's top (z = 0), spun about its axis.
    let lay = glam::DQuat::from_rotation_x(-std::f64::consts::FRAC_PI_2);
    let mut vase_pose = Pose::from_parts(Vector::ZERO, lay);
    vase_pose.translation.z = 1.0 - lowest(&vase, &vase_pose);
    // The bowl tilted 10 degrees about x; the ball of radius 6 mm dropped 4 mm above its bottom
    // near the middle.
    let tilt = Pose::from_parts(
        Vector::ZERO,
        glam::DQuat::from_rotation_x(10f64.to_radians()),
    );
    let ball_pose = Pose::translation(3.0, 2.0, 6.0 + 6.0 + 4.0);
    vec![
        Scene {
            name: "pencil-bowl",
            description: "pencil dropped across the bowl, rests on the rim at two contacts",
            fixed: Body::Exact(bowl.clone()),
            fixed_pose: Pose::IDENTITY,
            moving: Body::Exact(pencil),
            moving_pose: pencil_pose,
            angvel: Vector::ZERO,
            linear_damping: 0.0,
            angular_damping: 0.0,
            seconds: 3.0,
            variants: &[Variant::Exact, Variant::TriMesh, Variant::ConvexHull],
        },
        Scene {
            name: "vase-rolling",
            description: "vase on its side on a box, spun at 3 rad/s about its axis",
            fixed: Body::Cuboid(Vector::new(300.0, 300.0, 10.0)),
            fixed_pose: Pose::translation(0.0, 0.0, -10.0),
            moving: Body::Exact(vase),
            moving_pose: vase_pose,
            angvel: lay * Vector::new(0.0, 0.0, 3.0),
            linear_damping: 1.0,
            angular_damping: 3.0,
            seconds: 8.0,
            variants: &[Variant::Exact, Variant::TriMesh, Variant::ConvexHull],
        },
        Scene {
            name: "ball-bowl-crease",
            description: "ball 12 mm across in the bowl tilted 10 degrees, settles in the bottom crease",
            fixed: Body::Exact(bowl),
            fixed_pose: tilt,
            moving: Body::Ball(6.0),
            moving_pose: ball_pose,
            angvel: Vector::ZERO,
            linear_damping: 2.0,
            angular_damping: 2.0,
            seconds: 8.0,
            variants: &[Variant::Exact, Variant::TriMesh],
        },
    ]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let out = args
        .iter()
        .position(|a| a == "--out")
        .and_then(|i| args.get(i + 1))
        .map_or_else(|| PathBuf::from("target/rapier_scenes"), PathBuf::from);
    std::fs::create_dir_all(&out)?;
    let trace_csv = args.iter().any(|a| a == "--csv");
    let number = |flag: &str, default: f64| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(default)
    };
    let solver = Solver {
        dt: 1.0 / number("--hz", DEFAULT_HZ),
        damping_scale: number("--damping-scale", 1.0),
        iterations: number("--iterations", 8.0) as usize,
        static_hz: number("--static-hz", 960.0),
        static_damping: number("--static-damping", 1.0),
    };
    let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures");
    let pipeline = Arc::new(ContactPipeline::new(ContactOptions {
        margin: 4.0,
        delta1: -0.001,
        delta2: 2.0,
        chordal_tolerance: 0.05,
        ..ContactOptions::default()
    })?);
    let mut results = serde_json::Map::new();
    for scene in scenes(&pipeline, &fixtures) {
        let runs: Vec<(Variant, Trace)> = scene
            .variants
            .iter()
            .map(|&v| (v, run(&scene, v, &pipeline, solver)))
            .collect();
        let mut entry = serde_json::Map::new();
        entry.insert("description".into(), json!(scene.description));
        entry.insert("seconds".into(), json!(scene.seconds));
        for (variant, trace) in &runs {
            entry.insert(variant.name().into(), summary(trace));
            if trace_csv {
                let mut csv = String::from(
                    "t,z,speed,spin,penetration,solver_contacts,exact_contacts,kinetic,kinetic_linear,vx,vy,vz,wx,wy,wz,qx,qy,qz,qw,contacts\n",
                );
                for k in 0..trace.time.len() {
                    let (v, w, q) = (trace.linvel[k], trace.angvel[k], trace.pose[k].rotation);
                    csv += &format!(
                        "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},\"{}\"\n",
                        trace.time[k],
                        trace.z[k],
                        trace.speed[k],
                        trace.spin[k],
                        trace.penetration[k],
                        trace.solver_contacts[k],
                        trace.exact_contacts[k],
                        trace.kinetic[k],
                        trace.kinetic_linear[k],
                        v.x,
                        v.y,
                        v.z,
                        w.x,
                        w.y,
                        w.z,
                        q.x,
                        q.y,
                        q.z,
                        q.w,
                        trace.contacts_described[k]
                    );
                }
                std::fs::write(
                    out.join(format!("{}-{}.csv", scene.name, variant.name())),
                    csv,
                )?;
            }
        }
        std::fs::write(out.join(format!("{}.svg", scene.name)), plot(&scene, &runs))?;
        results.insert(scene.name.into(), Value::Object(entry));
    }
    let report = json!({
        "note": "generated by cargo run --release -p contact-parry --example rapier_scenes",
        "rapier": {
            "length_unit": 1000.0, "dt_s": solver.dt, "gravity_mm_per_s2": 9810.0,
            "prediction_distance_mm": 2.0, "solver_iterations": solver.iterations,
            "static_contact_natural_frequency_hz": solver.static_hz,
            "static_contact_damping_ratio": solver.static_damping, "contact_recycling": false,
            "moving_body_damping_scale": solver.damping_scale,
        },
        "pipeline": { "margin_mm": 4.0, "delta1_mm": -0.001, "delta2_mm": 2.0, "chordal_tolerance_mm": 0.05 },
        "rest": { "speed_mm_per_s": REST_SPEED, "spin_rad_per_s": REST_SPIN, "hold_s": REST_HOLD },
        "scenes": Value::Object(results),
    });
    let text = serde_json::to_string_pretty(&report)?;
    std::fs::write(out.join("rapier_scenes.json"), &text)?;
    println!("{text}");
    Ok(())
}
