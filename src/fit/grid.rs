//! Points bucketed in a uniform grid, for nearest-point searches within a fixed reach (a
//! vertex's mirror image, `super::mirror`; the surface a small piece sits on,
//! `super::hanging`).

use std::collections::HashMap;
use std::hash::BuildHasherDefault;

use glam::{DVec3, IVec3};

use crate::mesh::weld::PositionHasher;

/// Points bucketed in cubes twice as wide as the reach of a search, so that a search looks in
/// at most two cubes along each axis.
pub struct Grid {
    reach: f64,
    cells: HashMap<IVec3, Vec<usize>, BuildHasherDefault<PositionHasher>>,
}

impl Grid {
    /// Buckets `points` for searches within `reach` of a point.
    pub fn new(points: &[DVec3], reach: f64) -> Grid {
        let mut cells: HashMap<IVec3, Vec<usize>, BuildHasherDefault<PositionHasher>> = HashMap::default();
        for (i, &p) in points.iter().enumerate() {
            cells.entry(Grid::cell(p, reach)).or_default().push(i);
        }
        Grid { reach, cells }
    }

    fn cell(p: DVec3, reach: f64) -> IVec3 {
        (p / (2.0 * reach)).floor().as_ivec3()
    }

    /// The index of the point of `points` nearest `q` within the reach (the lower index of
    /// two as near); `None` where none is.
    pub fn nearest(&self, points: &[DVec3], q: DVec3) -> Option<usize> {
        self.nearest_where(points, q, |_| true)
    }

    /// [`Grid::nearest`] among the points whose index `keep` accepts.
    pub fn nearest_where(&self, points: &[DVec3], q: DVec3, keep: impl Fn(usize) -> bool) -> Option<usize> {
        let (lo, hi) = (Grid::cell(q - DVec3::splat(self.reach), self.reach), Grid::cell(q + DVec3::splat(self.reach), self.reach));
        let mut best: Option<(f64, usize)> = None;
        for x in lo.x..=hi.x {
            for y in lo.y..=hi.y {
                for z in lo.z..=hi.z {
                    let Some(bucket) = self.cells.get(&IVec3::new(x, y, z)) else { continue };
                    for &i in bucket.iter().filter(|&&i| keep(i)) {
                        let d = points[i].distance(q);
                        if d <= self.reach && best.is_none_or(|(bd, bi)| d < bd || (d == bd && i < bi)) {
                            best = Some((d, i));
                        }
                    }
                }
            }
        }
        best.map(|(_, i)| i)
    }
}
