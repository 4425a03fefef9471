//! Points bucketed in a uniform grid, for nearest-point searches within a fixed reach (a
//! vertex's mirror image, `super::mirror`; the surface a small piece sits on,
//! `super::hanging`).

use std::collections::HashMap;
use std::hash::BuildHasherDefault;

use glam::{DVec3, IVec3};

use crate::mesh::weld::PositionHasher;

/// Points bucketed in cubes as wide as the reach of a search, so that a search looks in at
/// most three cubes along each axis, the one holding the query first and then only those
/// nearer than the nearest point found so far.
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
        (p / reach).floor().as_ivec3()
    }

    /// The index of the point of `points` nearest `q` within the reach (the lower index of
    /// two as near); `None` where none is.
    pub fn nearest(&self, points: &[DVec3], q: DVec3) -> Option<usize> {
        self.nearest_where(points, q, |_| true)
    }

    /// [`Grid::nearest`] among the points whose index `keep` accepts.
    pub fn nearest_where(&self, points: &[DVec3], q: DVec3, keep: impl Fn(usize) -> bool) -> Option<usize> {
        let reach = self.reach;
        let own = Grid::cell(q, reach);
        let (lo, hi) = (Grid::cell(q - DVec3::splat(reach), reach), Grid::cell(q + DVec3::splat(reach), reach));
        // A cell is passed over only where it lies farther than the nearest point so far by more
        // than rounding in its bounds and in the points' cells can make up.
        let slack = 1e-9 * (q.abs().max_element() + reach);
        let mut best: Option<(f64, usize)> = None;
        let search = |cell: IVec3, best: &mut Option<(f64, usize)>| {
            let Some(bucket) = self.cells.get(&cell) else { return };
            for &i in bucket.iter().filter(|&&i| keep(i)) {
                let d = points[i].distance(q);
                if d <= reach && best.is_none_or(|(bd, bi)| d < bd || (d == bd && i < bi)) {
                    *best = Some((d, i));
                }
            }
        };
        search(own, &mut best);
        for x in lo.x..=hi.x {
            for y in lo.y..=hi.y {
                for z in lo.z..=hi.z {
                    let cell = IVec3::new(x, y, z);
                    if cell == own {
                        continue;
                    }
                    let corner = cell.as_dvec3() * reach;
                    let gap = (corner - q).max(q - (corner + reach)).max(DVec3::ZERO).length();
                    if best.is_some_and(|(bd, _)| gap > bd + slack) {
                        continue;
                    }
                    search(cell, &mut best);
                }
            }
        }
        best.map(|(_, i)| i)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The nearest point within `reach` by looking at every point, the lower index of two as near.
    fn nearest_of_all(points: &[DVec3], q: DVec3, reach: f64, keep: impl Fn(usize) -> bool) -> Option<usize> {
        let mut best: Option<(f64, usize)> = None;
        for (i, p) in points.iter().enumerate().filter(|&(i, _)| keep(i)) {
            let d = p.distance(q);
            if d <= reach && best.is_none_or(|(bd, _)| d < bd) {
                best = Some((d, i));
            }
        }
        best.map(|(_, i)| i)
    }

    #[test]
    fn the_nearest_point_is_the_one_found_by_looking_at_every_point() {
        // A scatter on a lattice of a third of the reach (points on cell bounds, ties at equal
        // distances, duplicates) and off it, queried on and between the points.
        let reach = 0.3;
        let mut points: Vec<DVec3> = Vec::new();
        let mut state = 12345u64;
        let mut random = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for _ in 0..400 {
            let snapped = |v: f64| (v * 9.0).round() / 9.0 * reach * 3.0;
            let p = DVec3::new(random(), random(), random()) * 2.0 - 1.0;
            points.push(if points.len().is_multiple_of(2) { p.map(snapped) } else { p });
        }
        points.push(points[10]);
        let grid = Grid::new(&points, reach);
        let mut found = 0;
        for k in 0..2000 {
            let q = if k % 3 == 0 { points[k % points.len()] } else { DVec3::new(random(), random(), random()) * 2.4 - 1.2 };
            let odd = |i: usize| i % 2 == 1;
            assert_eq!(grid.nearest(&points, q), nearest_of_all(&points, q, reach, |_| true), "query {q}");
            assert_eq!(grid.nearest_where(&points, q, odd), nearest_of_all(&points, q, reach, odd), "query {q}");
            found += usize::from(grid.nearest(&points, q).is_some());
        }
        assert!(found > 1000 && found < 2000, "{found} of 2000 queries found a point");
    }
}
