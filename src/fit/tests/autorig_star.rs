//! `sweepffd::fit::autorig` on a procedural star (a ball with five tubes of known axes, built
//! in code as one closed mesh): exactly the five tubes are found, each part holds its tube's
//! tip, and each part's fitted key centers and first-guess skeleton lie within 2% of the tube's
//! radius of the tube's axis (the skeleton's level-set centroids before their centering on
//! plane sections do not).

use crate::common::{autorig_report, star};

use glam::DVec3;
use sweepffd::fit::autorig::{AutorigOptions, autorig};
use sweepffd::fit::axis::Polyline;
use sweepffd::fit::largest_connected;
use sweepffd::fit::part::Part;
use sweepffd::fit::skeleton::skeleton;

use autorig_report::print_parts;
use star::{TUBE_RADIUS, Tube, off_axis, star_mesh, tubes};

/// The tube whose axis the direction of `p` from the center is nearest.
fn nearest_tube(p: DVec3) -> usize {
    let direction = p.normalize();
    (0..5).max_by(|&a, &b| tubes()[a].axis.dot(direction).total_cmp(&tubes()[b].axis.dot(direction))).unwrap()
}

/// The largest distance from `tube`'s axis of `points`: over all of them, and over those on
/// its cylinder (from the end of the blend, 1.2 from the center, to the center of its round
/// end, where level sets of the edge-path distance from an oblique rim are no longer
/// circles about the axis).
fn worst_off_axis(tube: &Tube, points: impl Iterator<Item = DVec3>) -> (f64, f64) {
    let mut worst = (0.0, 0.0);
    for p in points {
        let off = off_axis(tube, p);
        worst.0 = f64::max(worst.0, off);
        let along = p.dot(tube.axis);
        if (BLEND_END..=tube.reach).contains(&along) {
            worst.1 = f64::max(worst.1, off);
        }
    }
    worst
}

/// Where the blend ends along each tube: √(a² + r²) − 1 = [`star::BLEND`] at a = 1.174.
const BLEND_END: f64 = 1.2;

#[test]
fn the_star_mesh_is_closed_and_connected() {
    let mesh = star_mesh(0.06);
    eprintln!("star: {} vertices, {} triangles", mesh.positions.len(), mesh.faces.len());
    assert!(mesh.is_closed(), "every edge lies on two faces");
    assert_eq!(largest_connected(&mesh, |_| true).len(), mesh.positions.len());
    let volume = mesh.enclosed_volume(&mesh.positions);
    // The ball's 4.19 and five tubes of about 0.2 each beyond it.
    assert!(volume > 4.5 && volume < 6.0, "volume {volume}");
}

#[test]
fn the_star_gets_exactly_its_five_tubes_each_on_its_axis() {
    let mesh = star_mesh(0.06);
    let rigged = autorig(&mesh, &AutorigOptions::default()).unwrap();
    print_parts("star", &mesh, &rigged);
    assert_eq!(rigged.parts.len(), 5, "one part per tube");
    let mut found = [false; 5];
    let mut worst_level_off: f64 = 0.0;
    for part in &rigged.parts {
        let t = nearest_tube(mesh.positions[part.tip as usize]);
        assert!(!std::mem::replace(&mut found[t], true), "two parts on tube {t}");
        let tube = &tubes()[t];
        // The tube's tip: its vertex farthest along its axis.
        let tip = (0..mesh.positions.len() as u32)
            .max_by(|&a, &b| {
                mesh.positions[a as usize].dot(tube.axis).total_cmp(&mesh.positions[b as usize].dot(tube.axis))
            })
            .unwrap();
        assert!(part.vertices.binary_search(&tip).is_ok(), "{} holds tube {t}'s tip", part.name);
        // Every vertex of the part lies on the tube (within 1.5 radii of its axis).
        let stray = part.vertices.iter().filter(|&&v| off_axis(tube, mesh.positions[v as usize]) > 1.5 * TUBE_RADIUS);
        assert_eq!(stray.count(), 0, "{}: vertices off tube {t}", part.name);
        let part_skeleton = skeleton(&Part::new(&mesh, &part.vertices)).unwrap();
        let samples = |polyline: &Polyline| {
            (0..=100).map(|i| polyline.point(polyline.length() * i as f64 / 100.0)).collect::<Vec<_>>()
        };
        let skeleton_off = worst_off_axis(tube, samples(&part_skeleton.axis).into_iter());
        let level_off = worst_off_axis(tube, samples(&part_skeleton.level_axis).into_iter());
        worst_level_off = worst_level_off.max(level_off.1);
        let keys_off = worst_off_axis(tube, part.fit.keys.iter().map(|k| k.center));
        eprintln!(
            "star {} on tube {t}: skeleton within {:.2}% of the tube's radius of its axis on the cylinder \
             ({:.2}% with the blend and the round end; {:.2}% before centering), key centers within \
             {:.2}% ({:.2}%)",
            part.name,
            100.0 * skeleton_off.1 / TUBE_RADIUS,
            100.0 * skeleton_off.0 / TUBE_RADIUS,
            100.0 * level_off.1 / TUBE_RADIUS,
            100.0 * keys_off.1 / TUBE_RADIUS,
            100.0 * keys_off.0 / TUBE_RADIUS
        );
        // The fitted sweep's centers and the first guess within 2% of a radius.
        assert!(skeleton_off.1 <= 0.02 * TUBE_RADIUS, "{}: skeleton {skeleton_off:?}", part.name);
        assert!(keys_off.1 <= 0.02 * TUBE_RADIUS, "{}: key centers {keys_off:?}", part.name);
        assert!(part.fit.quality.rms_d <= 0.10, "{}: {:?}", part.name, part.fit.quality);
    }
    // The level-set centroids alone, whose isolines lean from the oblique rims and around the
    // round ends on this grid-made mesh, miss the same check on some tube.
    assert!(worst_level_off > 0.02 * TUBE_RADIUS, "before centering: {worst_level_off}");
}
