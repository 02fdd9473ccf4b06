//! Runs the coherence bench's trajectory of one fixture scene (B rolls back and forth about the
//! first contact, amplitude 2e-3 rad, 2.5e-5 rad per frame, lifted 2 µm) with warm frames only
//! (the chain never broken by the frame count) and prints what the warm frames did: Newton
//! steps per refinement and contacts per frame. Made for instruction counts, which are stable on
//! a busy machine where wall-clock is not:
//!
//! ```text
//! cargo build --release -p contact-pipeline --example warm_frames
//! valgrind --tool=callgrind --toggle-collect='*query_coherent*' \
//!     target/release/examples/warm_frames pencil-bowl-two-contacts 320
//! ```
//!
//! The first frame is a full query; the rest are warm as long as the certificate holds. Divide
//! the collected instructions by the frame count (the full frame is printed apart so that it
//! can be subtracted).

use contact_pipeline::{CoherenceOptions, FrameKind, PairCache, PairReport, QueryScratch};
use geom_param::{DPose3, DQuat};

#[path = "../tests/support/fixture_scene.rs"]
mod fixture_scene;

/// Frames of one back-and-forth roll (the bench's).
const FRAMES: usize = 320;

fn main() {
    let mut args = std::env::args().skip(1);
    let name = args
        .next()
        .unwrap_or_else(|| "pencil-bowl-two-contacts".to_owned());
    let frames: usize = args
        .next()
        .map_or(FRAMES, |n| n.parse().expect("frame count"));
    let scene = fixture_scene::load_scene(&name);
    let start = scene
        .pipeline
        .query(
            &scene.a,
            &scene.pose_a,
            &scene.b,
            &scene.pose_b,
            &mut QueryScratch::default(),
        )
        .expect("query");
    let (c, n) = (start.contacts[0].point_a, start.contacts[0].normal);
    let axis = n.cross(n.any_orthonormal_vector()).normalize();
    let options = CoherenceOptions {
        max_warm_frames: u32::MAX,
        ..CoherenceOptions::default()
    };
    let (mut cache, mut scratch, mut report) = (
        PairCache::new(),
        QueryScratch::default(),
        PairReport::default(),
    );
    let (mut warm, mut full, mut refined, mut contacts) = (0_u32, 0_u32, 0, 0);
    let (mut iterations, mut warm_contacts) = (0_u32, 0_u32);
    for k in 0..frames {
        let angle = 2e-3 * (std::f64::consts::TAU * (k % FRAMES) as f64 / FRAMES as f64).sin();
        let r = DQuat::from_axis_angle(axis, angle);
        let pose_b = DPose3::from_parts(c - r * c + n * 0.002, r) * scene.pose_b;
        let kind = scene
            .pipeline
            .query_coherent(
                &scene.a,
                &scene.pose_a,
                &scene.b,
                &pose_b,
                &options,
                &mut cache,
                &mut scratch,
                &mut report,
            )
            .expect("query");
        contacts += report.contacts.len();
        match kind {
            FrameKind::Warm => {
                warm += 1;
                refined += report.stats.refined;
                warm_contacts += u32::try_from(report.contacts.len()).unwrap_or(u32::MAX);
                iterations += report
                    .contacts
                    .iter()
                    .map(|c| c.diagnostics.iterations)
                    .sum::<u32>();
            }
            FrameKind::Full => full += 1,
        }
    }
    println!(
        "{name}: {frames} frames, {warm} warm, {full} full; {:.2} contacts per frame, {:.2} \
         refinements per warm frame, {:.2} Newton steps per reported warm contact",
        contacts as f64 / frames as f64,
        refined as f64 / f64::from(warm.max(1)),
        f64::from(iterations) / f64::from(warm_contacts.max(1)),
    );
}
