//! The README's example for general solids, as a test: a rounded box and a tube built in a few
//! lines of Rust, each resting on the paper's bowl's inner bottom (z = 6 mm), give one exact
//! contact each at the gap they were placed at.

use contact_pipeline::{ContactOptions, ContactPipeline, PairState, QueryScratch};
use geom_param::{DPose3, DQuat, DVec3, MeshOptions, ObjectDescription, ObjectModel};
use geom_param::{rounded_box, tube};

#[test]
fn a_rounded_box_and_a_tube_in_the_bowl() -> Result<(), Box<dyn std::error::Error>> {
    // --- README example starts here ---
    let pipeline = ContactPipeline::new(ContactOptions::default())?;
    let mesh = MeshOptions {
        chordal_tolerance: pipeline.options().chordal_tolerance,
    };
    let bowl_file = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../fixtures/objects/bowl.json"
    ))?;
    let bowl = pipeline.prepare_description(&ObjectDescription::from_json(&bowl_file)?)?;

    // A 20 x 12 x 8 mm box with 1.5 mm rounded edges, and a tube 10 mm across with a 6 mm bore.
    let boxed = pipeline.prepare(ObjectModel::from_solid(
        "box",
        rounded_box(DVec3::new(10.0, 6.0, 4.0), 1.5)?,
        &mesh,
    )?);
    let tube = pipeline.prepare(ObjectModel::from_solid(
        "tube",
        tube(5.0, 3.0, 30.0)?,
        &mesh,
    )?);

    // The box turned onto a corner, the tube leaning on its bottom rim, each 0.02 mm above the
    // bowl's inner bottom (z = 6): the lowest corner sphere (radius 1.5) of the box, the rim
    // point at depth 5 sin(0.5) of the tube.
    let gap = 0.02;
    let turn = DQuat::from_rotation_x(0.3) * DQuat::from_rotation_y(0.4);
    let lowest_corner = (0..8)
        .map(|k| {
            let sign = |bit: i32| if k & bit == 0 { 1.0 } else { -1.0 };
            turn * DVec3::new(sign(1) * 8.5, sign(2) * 4.5, sign(4) * 2.5)
        })
        .map(|c| c.z)
        .fold(f64::INFINITY, f64::min);
    let box_pose = DPose3::from_parts(DVec3::new(0.0, 0.0, 6.0 + gap + 1.5 - lowest_corner), turn);
    let tube_pose = DPose3::from_parts(
        DVec3::new(0.0, 0.0, 6.0 + gap + 5.0 * 0.5f64.sin()),
        DQuat::from_rotation_x(0.5),
    );

    let mut scratch = QueryScratch::default();
    for (object, pose) in [(&boxed, box_pose), (&tube, tube_pose)] {
        let report = pipeline.query(&bowl, &DPose3::IDENTITY, object, &pose, &mut scratch)?;
        println!(
            "{}: {:?}, {} contact(s)",
            object.model.name,
            report.state,
            report.contacts.len()
        );
        for c in &report.contacts {
            println!(
                "  d = {:.9} mm at {:.4} on {:?}",
                c.distance, c.point_a, c.location_b
            );
        }
        // --- README example ends here ---
        assert_eq!(report.state, PairState::Contact);
        assert_eq!(report.contacts.len(), 1);
        assert!(
            (report.contacts[0].distance - gap).abs() < 1e-9,
            "{:?}",
            report.contacts[0]
        );
        assert!((report.contacts[0].point_a.z - 6.0).abs() < 1e-9);
    }
    Ok(())
}
