//! Cross-sections of a part (§3, Fig. 3b): the part cut by a key's plane, as contours in the
//! plane, and the center of the section the key describes.

use std::collections::HashMap;
use std::hash::BuildHasherDefault;

use glam::{DVec2, DVec3};

use super::part::Part;
use crate::mesh::weld::PositionHasher;

/// A key's plane with its in-plane axes: `x` is θ = 0, `y` is θ = π/2, `normal` = x × y.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Plane {
    /// A point of the plane, the origin of in-plane coordinates.
    pub origin: DVec3,
    /// In-plane x axis (unit).
    pub x: DVec3,
    /// In-plane y axis (unit).
    pub y: DVec3,
    /// Unit normal.
    pub normal: DVec3,
}

impl Plane {
    /// The in-plane coordinates of `p` (which should lie in the plane).
    pub fn coordinates_of(&self, p: DVec3) -> DVec2 {
        let d = p - self.origin;
        DVec2::new(d.dot(self.x), d.dot(self.y))
    }

    /// The point with in-plane coordinates `q`.
    pub fn point_at(&self, q: DVec2) -> DVec3 {
        self.origin + self.x * q.x + self.y * q.y
    }
}

/// A connected piece of a section's boundary, in in-plane coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct Contour {
    /// The points in order along the boundary.
    pub points: Vec<DVec2>,
    /// Whether the last point joins the first (false where the cut leaves the part through an
    /// open boundary, such as the rim where the part meets the rest of the mesh).
    pub closed: bool,
}

impl Contour {
    /// The contour's segments, the closing one included for a closed contour.
    pub fn segments(&self) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
        let n = self.points.len();
        let count = if self.closed { n } else { n.saturating_sub(1) };
        (0..count).map(move |i| (self.points[i], self.points[(i + 1) % n]))
    }

    /// The signed area (counter-clockwise positive) of a closed contour; 0 for an open one.
    pub fn signed_area(&self) -> f64 {
        if !self.closed {
            return 0.0;
        }
        0.5 * self.segments().map(|(a, b)| a.perp_dot(b)).sum::<f64>()
    }

    /// The distance from `q` to the contour.
    pub fn distance_to(&self, q: DVec2) -> f64 {
        let point_distance = self.points.iter().map(|p| p.distance(q));
        self.segments().map(|(a, b)| segment_distance(q, a, b)).chain(point_distance).fold(f64::INFINITY, f64::min)
    }

    /// The least distance between a point of this contour and a point of `other` (their
    /// vertices, which lie a triangle's size apart along each).
    pub fn gap_to(&self, other: &Contour) -> f64 {
        self.points
            .iter()
            .flat_map(|p| other.points.iter().map(move |o| p.distance_squared(*o)))
            .fold(f64::INFINITY, f64::min)
            .sqrt()
    }

    /// Whether a closed contour winds around `q` (even-odd rule).
    pub fn encloses(&self, q: DVec2) -> bool {
        self.closed
            && self.segments().fold(false, |inside, (a, b)| {
                let crosses = (a.y > q.y) != (b.y > q.y) && q.x < a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x);
                inside != crosses
            })
    }
}

/// The distance from `q` to the segment `a`–`b`.
fn segment_distance(q: DVec2, a: DVec2, b: DVec2) -> f64 {
    let ab = b - a;
    let u = if ab.length_squared() > 0.0 { ((q - a).dot(ab) / ab.length_squared()).clamp(0.0, 1.0) } else { 0.0 };
    q.distance(a + ab * u)
}

/// Cuts the part's triangles with `plane` and joins the pieces into contours. A vertex exactly
/// on the plane counts as above it, so every crossing is through the inside of an edge, and
/// each crossing point is computed from its edge's endpoints in a fixed order: neighbouring
/// triangles agree on it bit for bit.
pub fn cut(part: &Part, plane: &Plane) -> Vec<Contour> {
    SCRATCH.with_borrow_mut(|scratch| scratch.cut(part, plane))
}

thread_local! {
    /// A thread's working lists for [`cut`]: a fit cuts its part thousands of times.
    static SCRATCH: std::cell::RefCell<CutScratch> = std::cell::RefCell::new(CutScratch::default());
}

/// The working lists of one cut, kept from cut to cut (cleared, not freed).
#[derive(Default)]
struct CutScratch {
    heights: Vec<f64>,
    /// Each crossed edge's node. Edge keys are no adversary's: the multiply-rotate hash, not
    /// the default SipHash.
    nodes: HashMap<(u32, u32), usize, BuildHasherDefault<PositionHasher>>,
    points: Vec<DVec2>,
    segments: Vec<[usize; 2]>,
    /// [`CutScratch::chain`]'s lists.
    offsets: Vec<usize>,
    filled: Vec<usize>,
    incident: Vec<usize>,
    used: Vec<bool>,
    starts: Vec<usize>,
    path: Vec<usize>,
}

impl CutScratch {
    fn cut(&mut self, part: &Part, plane: &Plane) -> Vec<Contour> {
        let CutScratch { heights, nodes, points, segments, .. } = self;
        heights.clear();
        heights.extend(part.positions.iter().map(|p| (*p - plane.origin).dot(plane.normal)));
        nodes.clear();
        points.clear();
        segments.clear();
        let mut node = |a: u32, b: u32| -> usize {
            let key = (a.min(b), a.max(b));
            *nodes.entry(key).or_insert_with(|| {
                let (ha, hb) = (heights[key.0 as usize], heights[key.1 as usize]);
                let (pa, pb) = (part.positions[key.0 as usize], part.positions[key.1 as usize]);
                points.push(plane.coordinates_of(pa + (pb - pa) * (ha / (ha - hb))));
                points.len() - 1
            })
        };
        for triangle in &part.triangles {
            let above = triangle.map(|v| heights[v as usize] >= 0.0);
            if above[0] == above[1] && above[1] == above[2] {
                continue;
            }
            let mut ends = [0usize; 2];
            let mut found = 0;
            for k in 0..3 {
                let (a, b) = (triangle[k], triangle[(k + 1) % 3]);
                if above[k] != above[(k + 1) % 3] {
                    ends[found] = node(a, b);
                    found += 1;
                }
            }
            segments.push(ends);
        }
        self.chain()
    }

    /// Joins the segments sharing end nodes into contours: open chains first (from nodes used
    /// once), then closed loops.
    fn chain(&mut self) -> Vec<Contour> {
        let CutScratch { points, segments, offsets, filled, incident, used, starts, path, .. } = self;
        // Each node's segments, in increasing order: `incident[offsets[n]..offsets[n + 1]]`.
        offsets.clear();
        offsets.resize(points.len() + 1, 0);
        for ends in segments.iter() {
            offsets[ends[0] + 1] += 1;
            offsets[ends[1] + 1] += 1;
        }
        for n in 0..points.len() {
            offsets[n + 1] += offsets[n];
        }
        filled.clear();
        filled.extend_from_slice(offsets);
        incident.clear();
        incident.resize(offsets[points.len()], 0);
        for (s, ends) in segments.iter().enumerate() {
            for &n in ends {
                incident[filled[n]] = s;
                filled[n] += 1;
            }
        }
        let incident_to = |n: usize| &incident[offsets[n]..offsets[n + 1]];
        used.clear();
        used.resize(segments.len(), false);
        let mut contours = Vec::new();
        starts.clear();
        starts.extend((0..points.len()).filter(|&n| incident_to(n).len() == 1).chain(0..points.len()));
        for &start in starts.iter() {
            while let Some(&first) = incident_to(start).iter().find(|&&s| !used[s]) {
                path.clear();
                path.push(start);
                let (mut at, mut segment) = (start, first);
                loop {
                    used[segment] = true;
                    let [a, b] = segments[segment];
                    at = if a == at { b } else { a };
                    if at == start {
                        break;
                    }
                    path.push(at);
                    match incident_to(at).iter().find(|&&s| !used[s]) {
                        Some(&next) => segment = next,
                        None => break,
                    }
                }
                let closed = at == start;
                contours.push(Contour { points: path.iter().map(|&n| points[n]).collect(), closed });
            }
        }
        contours
    }
}

/// The contours that make up the section around `q` (in-plane coordinates of the key's current
/// center): the smallest closed contour around `q`, or failing that the contour nearest to
/// `q`, together with every other contour that comes as near to `q` as that contour's
/// farthest point, and then every closed contour separated from those chosen by a gap of at
/// most [`GAP`] times that reach, again and again (the toes of a foot, the fingers of a hand:
/// one section whose radii span them all). `None` when there are no contours.
pub fn around(contours: &[Contour], q: DVec2) -> Option<Vec<&Contour>> {
    let enclosing = contours
        .iter()
        .filter(|c| c.encloses(q))
        .min_by(|a, b| a.signed_area().abs().total_cmp(&b.signed_area().abs()));
    let primary = enclosing.or_else(|| contours.iter().min_by(|a, b| a.distance_to(q).total_cmp(&b.distance_to(q))))?;
    let reach = primary.points.iter().map(|p| p.distance(q)).fold(0.0, f64::max);
    let mut chosen: Vec<bool> =
        contours.iter().map(|c| std::ptr::eq(c, primary) || c.distance_to(q) <= reach).collect();
    let gap = GAP * reach;
    // Bounding boxes first: two contours whose boxes lie farther apart than the gap are.
    let boxes: Vec<(DVec2, DVec2)> = contours
        .iter()
        .map(|c| c.points.iter().fold((DVec2::INFINITY, DVec2::NEG_INFINITY), |(lo, hi), &p| (lo.min(p), hi.max(p))))
        .collect();
    let near = |i: usize, j: usize| {
        let ((lo_i, hi_i), (lo_j, hi_j)) = (boxes[i], boxes[j]);
        (lo_i - hi_j).max(lo_j - hi_i).max(DVec2::ZERO).length() <= gap && contours[i].gap_to(&contours[j]) <= gap
    };
    loop {
        let joined: Vec<usize> = (0..contours.len())
            .filter(|&i| !chosen[i] && contours[i].closed)
            .filter(|&i| (0..contours.len()).any(|j| chosen[j] && near(i, j)))
            .collect();
        if joined.is_empty() {
            break;
        }
        for i in joined {
            chosen[i] = true;
        }
    }
    Some(contours.iter().zip(chosen).filter(|(_, c)| *c).map(|(c, _)| c).collect())
}

/// Closed contours separated from a section's chosen contours by at most this multiple of the
/// section's reach (see [`around`]) belong to the same section.
pub const GAP: f64 = 1.0;

/// The center of a section: the area centroid of its closed contours, or the length-weighted
/// centroid of its segments when none encloses any area.
pub fn center(contours: &[&Contour]) -> DVec2 {
    let (mut area, mut moment) = (0.0, DVec2::ZERO);
    for contour in contours {
        let (mut a, mut m) = (0.0, DVec2::ZERO);
        for (p, q) in contour.segments().filter(|_| contour.closed) {
            let cross = p.perp_dot(q);
            a += cross;
            m += (p + q) * cross;
        }
        // Orientation of each contour does not matter: weigh it by its unsigned area.
        if a != 0.0 {
            area += a.abs();
            moment += m * a.signum();
        }
    }
    if area > 0.0 {
        return moment / (3.0 * area);
    }
    let (mut length, mut sum) = (0.0, DVec2::ZERO);
    for (p, q) in contours.iter().flat_map(|c| c.segments()) {
        let l = p.distance(q);
        length += l;
        sum += (p + q) * 0.5 * l;
    }
    if length > 0.0 {
        sum / length
    } else {
        contours.iter().flat_map(|c| c.points.first()).copied().next().unwrap_or_default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Faces, Mesh};

    /// An open prism of `n`-gons of radius 1 around the z axis from z = 0 to z = 1, offset by
    /// `shift` in x.
    fn prism(n: usize, shift: f64) -> Part {
        let mut positions = Vec::new();
        for z in [0.0, 1.0] {
            for i in 0..n {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                positions.push(DVec3::new(shift + a.cos(), a.sin(), z));
            }
        }
        let mut faces = Faces::new();
        for i in 0..n as u32 {
            let j = (i + 1) % n as u32;
            faces.push(&[i, j, j + n as u32, i + n as u32]);
        }
        let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
        Part::new(&mesh, &(0..2 * n as u32).collect::<Vec<_>>())
    }

    fn z_plane(z: f64) -> Plane {
        Plane { origin: DVec3::new(0.0, 0.0, z), x: DVec3::X, y: DVec3::Y, normal: DVec3::Z }
    }

    #[test]
    fn a_prism_cuts_into_one_closed_polygon_centered_on_its_axis() {
        let contours = cut(&prism(8, 0.5), &z_plane(0.3));
        assert_eq!(contours.len(), 1);
        assert!(contours[0].closed);
        // Each side quad is two triangles, so its diagonal crosses the plane too.
        assert_eq!(contours[0].points.len(), 16);
        let area = contours[0].signed_area().abs();
        assert!((area - 2.0 * 2f64.sqrt()).abs() < 1e-12, "{area}");
        let c = center(&[&contours[0]]);
        assert!((c - DVec2::new(0.5, 0.0)).length() < 1e-12, "{c}");
        assert!(contours[0].encloses(DVec2::new(0.5, 0.0)));
        assert!(!contours[0].encloses(DVec2::new(2.0, 0.0)));
    }

    #[test]
    fn a_plane_missing_the_part_cuts_nothing() {
        assert!(cut(&prism(8, 0.0), &z_plane(2.0)).is_empty());
        assert!(around(&[], DVec2::ZERO).is_none());
    }

    #[test]
    fn a_plane_along_the_side_gives_open_chains() {
        let part = prism(8, 0.0);
        let plane = Plane { origin: DVec3::new(0.1, 0.0, 0.5), x: DVec3::Y, y: DVec3::Z, normal: DVec3::X };
        let contours = cut(&part, &plane);
        assert_eq!(contours.len(), 2);
        // Each crossing quad gives two triangles, three crossing edges, one open chain.
        assert!(contours.iter().all(|c| !c.closed && c.points.len() == 3));
        let chosen = around(&contours, DVec2::new(0.9, 0.0)).unwrap();
        assert_eq!(chosen.len(), 1, "the far side lies beyond the near side's reach");
        assert!(chosen[0].points.iter().all(|p| p.x > 0.0));
    }

    #[test]
    fn far_contours_are_left_out() {
        let square = |x0: f64| Contour {
            points: vec![
                DVec2::new(x0, 0.0),
                DVec2::new(x0 + 1.0, 0.0),
                DVec2::new(x0 + 1.0, 1.0),
                DVec2::new(x0, 1.0),
            ],
            closed: true,
        };
        let contours = [square(0.0), square(5.0)];
        let chosen = around(&contours, DVec2::new(0.5, 0.5)).unwrap();
        assert_eq!(chosen.len(), 1);
        assert_eq!(chosen[0].points[0], DVec2::ZERO);
    }
}
