//! Which contours make up a key's section ([`sweepffd::fit::section::around`]): the toes of a
//! foot or the fingers of a hand, cut by one plane, are one section; a contour far from them is
//! not.

use glam::DVec2;
use sweepffd::fit::section::{Contour, GAP, around};

/// A closed square contour of half-size `half` around `center`.
fn square(center: DVec2, half: f64) -> Contour {
    let corners = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
    Contour { points: corners.iter().map(|&(x, y)| center + DVec2::new(x, y) * half).collect(), closed: true }
}

#[test]
fn toes_side_by_side_are_one_section_and_a_far_contour_is_not() {
    // The middle toe around the key's center (its reach √2), a toe beside it (a gap of 0.7,
    // its nearest point 1.7 from the center, beyond the reach), a third beside that one (a gap
    // of 0.9 from the second, 3.4 from the first) and a contour 10 away.
    let contours = [
        square(DVec2::ZERO, 1.0),
        square(DVec2::new(2.5, 0.0), 0.8),
        square(DVec2::new(4.9, 0.0), 0.7),
        square(DVec2::new(0.0, 10.0), 1.0),
    ];
    let chosen = around(&contours, DVec2::ZERO).unwrap();
    let picked: Vec<usize> = contours
        .iter()
        .enumerate()
        .filter(|(_, c)| chosen.iter().any(|d| std::ptr::eq(*d, *c)))
        .map(|(i, _)| i)
        .collect();
    assert_eq!(picked, [0, 1, 2], "the three toes and not the far contour");
    // A toe whose gap is wider than GAP times the reach stays out.
    let apart = [square(DVec2::ZERO, 1.0), square(DVec2::new(2.0 + GAP * 2f64.sqrt() + 0.8 + 0.1, 0.0), 0.8)];
    assert_eq!(around(&apart, DVec2::ZERO).unwrap().len(), 1);
}
