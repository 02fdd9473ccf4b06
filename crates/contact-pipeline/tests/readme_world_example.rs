//! The README's "Many objects and frames" example, as a test: a row of four 10 mm balls
//! (one preparation shared by the four) 0.05 mm apart, spinning and gliding together over ten
//! frames; every frame has the three contacts at exactly the gap, and each keeps its id.

use contact_pipeline::{
    CoherenceOptions, ContactOptions, ContactPipeline, FrameKind, Groups, World,
};
use geom_param::{DPose3, DQuat, DVec3, ObjectDescription};
use std::sync::Arc;

#[test]
fn a_row_of_balls_over_frames() -> Result<(), Box<dyn std::error::Error>> {
    // --- README example starts here ---
    let pipeline = ContactPipeline::new(ContactOptions::default())?;
    let ball = ObjectDescription::from_json(
        r#"{"name": "ball", "profile": [{"arc": {"center": [0, 0], "from": [0, -10], "to": [0, 10], "ccw": true}}]}"#,
    )?;
    let ball = Arc::new(pipeline.prepare_description(&ball)?); // prepared once, placed 4 times
    let mut world = World::new(pipeline, Some(CoherenceOptions::default()));
    let gap = 0.05;
    let at = |i: usize, frame: f64| {
        let spin = DQuat::from_rotation_z(0.0005 * frame);
        DPose3::from_parts(
            DVec3::new(i as f64 * (20.0 + gap), 0.002 * frame, 0.0),
            spin,
        )
    };
    let balls = (0..4)
        .map(|i| world.insert(Arc::clone(&ball), at(i, 0.0), Groups::default()))
        .collect::<Result<Vec<_>, _>>()?;
    for frame in 0..10 {
        for (i, &key) in balls.iter().enumerate() {
            world.set_pose(key, at(i, f64::from(frame)))?;
        }
        let stats = world.step()?; // every pair in range, each with its coherence cache
        println!(
            "frame {frame}: {} pairs in range, {} warm",
            stats.pairs_queried, stats.warm
        );
        for pair in world.pairs() {
            for (contact, id) in pair.report.contacts.iter().zip(pair.ids) {
                println!(
                    "  {:?}-{:?} #{}: d = {:.9} mm",
                    pair.a.index, pair.b.index, id.0, contact.distance
                );
            }
        }
        // --- README example ends here ---
        let pairs: Vec<_> = world.pairs().collect();
        assert_eq!(pairs.len(), 3, "three neighbouring pairs touch");
        for (n, pair) in pairs.iter().enumerate() {
            assert_eq!((pair.a, pair.b), (balls[n], balls[n + 1]));
            assert_eq!(pair.report.contacts.len(), 1);
            assert!((pair.report.contacts[0].distance - gap).abs() < 1e-9);
            // Each pair's only contact keeps the first id its cache gave.
            assert_eq!(pair.ids.len(), 1);
            assert_eq!(pair.ids[0].0, 1);
            if frame > 0 {
                assert_eq!(pair.frame, FrameKind::Warm, "frame {frame}");
            }
        }
    }
    Ok(())
}
