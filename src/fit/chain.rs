//! A limb as a chain of sweeps (§5's hierarchy, branch children on their parents): where one
//! tube's keys describe a limb poorly, it is cut into links, each a child of the link it hangs
//! from, so that turning the limb carries its end.
//!
//! Cuts are found from the geodesic distance s from the limb's rim (where it is attached to
//! the body), measured once over the whole limb. A stretch of the limb between two cuts is
//! cut again where its one sweep fits more loosely than the target, at most [`DEPTH`] deep:
//!
//! - **Widening** ([`Profile::widening`]): a hand past its wrist, a foot past its ankle, a
//!   hoof, a knee's bulge. The stretch's level sets, [`LEVELS`] of them, have perimeters P(s)
//!   that give a radius r(s) = P(s)/2π (`super::limb::perimeters`); the wrist is the level of
//!   least radius between [`FIRST`] and [`LAST`] of the stretch beyond which the radius grows
//!   to at least [`WIDENING`] times it.
//! - **Bend** ([`Profile::bend`]): an elbow, a knee, an ankle. The level sets' centroids
//!   make a skeleton; the bend is the level between [`FIRST`] and [`LAST`] of the stretch
//!   where it turns most, at least [`BEND_DEGREES`] over [`BEND_SPAN`] levels either side.
//!
//! A level set leans across a bend (its edge paths are shorter on the inside), so a cut is
//! made near its level by the plane through the level set's centroid normal to the skeleton
//! there (`Cut`). Each link's sweep is fitted to its vertices and [`OVERLAP`] of its
//! radius beyond each of its cuts, so that the links overlap and a child's first key lies on
//! a cross-section of its parent (§5's branch link binds it there); on a coarse limb (fewer
//! than [`COARSE`] vertices), whose rings may lie a whole forearm apart, a link is also
//! fitted to the ring of vertices just past its far cut.
//!
//! - **Forks** (`Profile::branches`): toes past a foot, fingers past a hand. The levels, at
//!   least [`FIRST`] of the limb's length from the rim, where the vertices farther than them fall
//!   apart into pieces that each reach at least [`BRANCH`] of the limb's length beyond
//!   (`super::limb::fork_levels`: the saddles of the merge tree of s's superlevel sets). From
//!   the highest down, each piece past a fork that holds no branch yet is a branch (a hand's two
//!   fingers that part last, then the third where it parts from them), one that holds one
//!   branch is that branch grown (a finger below a fork at its claw): one sweep, a child of the
//!   stem's link it meets most, fitted with a ring of that link's vertices around its base. A
//!   shorter piece (a dewclaw) and the palm between two forks ride in the stem, which is cut as
//!   a limb is. The branches are first squared off (`Profile::squared_off`: what lies before
//!   a splayed toe's crotch stays in the stem); where that chain's loosest link misses the
//!   target, each branch whose link alone fits closer than that loosest link when whole from
//!   its fork is taken whole, and the chain so forked, its stem one sweep, is kept where its
//!   links fit closer, loosest first (`fits_closer`: where both chains' loosest link is one
//!   finger, their stems decide). Squared off, the toes' or fingers' bases left the dino's
//!   stems at 13.9% and 18.3%; with both toes whole, and two of three fingers, at 9.0% and
//!   6.6%. The cartoon man's arm stems went from 18.3% and 19.1% to 13.4% and 15.3% by their
//!   sections (10.75% and 13.7% to 6.95% and 8.2% fitted) with one finger whole each, while
//!   each chain's loosest link stayed one finger, at 23.6% and 23.9%. The chain is given up as
//!   soon as its links fit no closer than the squared chain's.
//!
//! A limb that forks is kept forked where every branch fits and binds (unforked, its last link
//! would hold its toes); otherwise its best chain unforked, the one whose loosest link fits
//! best. A chain whose child's first key does not bind to its parent is none. A limb with no
//! rim (a whole component) has no profile and stays one sweep.
//!
//! - **Trimmed** ([`Profile::trimmed`]): a coarse limb that is no tube only at its attached end
//!   (a leg cut above its crotch, holding the pelvis's slab) is the stretch past the first of
//!   its first [`TRIMMED`] levels from which it fits.
//! - **End branched** ([`Profile::with_end_branched`]): a coarse limb that is rigged none of
//!   these ways may be its stem chained without its end past a widening, and the end (a hand
//!   with its thumb apart, raised to the face) a branch, fitted as a finger is.
//!
//! A seam's copy of a vertex (on none of the welded part's triangles) takes its twin's s.

use std::f64::consts::TAU;

use glam::DVec3;

use super::Fit;
use super::disjoint_sets::DisjointSets;
use super::geodesic::EdgeGraph;
use super::limb::{COARSE, fork_levels, level_segment, perimeters};
use super::part::Part;
use super::protrusions::flood;
use crate::mesh::Mesh;
use crate::rig::KeyBinding;
use crate::sweep::Sweep;

/// Levels of a stretch's profile.
pub const LEVELS: usize = 32;
/// A cut lies at least this fraction of its stretch's length from the stretch's start…
pub const FIRST: f64 = 0.3;
/// …and at most this fraction.
pub const LAST: f64 = 0.85;
/// Past the wrist the radius grows to at least this many times the wrist's.
pub const WIDENING: f64 = 1.3;
/// A bend turns the skeleton by at least this many degrees…
pub const BEND_DEGREES: f64 = 30.0;
/// …between the directions this many levels before and after it.
pub const BEND_SPAN: usize = 3;
/// A branch past a fork reaches at least this fraction of the limb's length beyond it.
pub const BRANCH: f64 = 0.05;
/// A vertex on none of a limb's triangles within this fraction of its length of one that is on
/// one is a seam's copy of it (`copies_take_distances`).
pub const COPY: f64 = 1e-6;
/// A limb is trimmed ([`Profile::trimmed`]) by at most this many [`LEVELS`] of its length.
pub const TRIMMED: usize = LEVELS / 4;
/// A bend and a widening nearer each other than this fraction of their stretch are one cut.
pub const SAME_CUT: f64 = 0.1;
/// A link has at least this many vertices, as a limb has.
pub const MIN_LINK: usize = super::autorig::MIN_VERTICES;
/// Stretches are cut at most this many times deep (a limb of at most 2^DEPTH links before its
/// branches)…
pub const DEPTH: usize = 2;
/// …and not at all in a limb of more vertices than this, whose links each take long to fit: a
/// dense scan's limb is only forked (a hand from its fingers).
pub const DENSE: usize = 2000;
/// A link's sweep is fitted to the vertices within this many radii of the cut beyond each of
/// its cuts too.
pub const OVERLAP: f64 = 0.5;
/// A limb's end is branched ([`Profile::with_end_branched`]) past at most this many widenings,
/// each of the stretch past the one before (each at least [`FIRST`] of the way along it).
pub const ENDS: usize = 8;
/// Near its level, within this many radii, a cut is a plane.
pub const PLANE_REACH: f64 = 2.0;

/// One link of a chain, fitted.
#[derive(Clone, Debug)]
pub struct FittedLink {
    /// The link's vertices (the mesh's, increasing).
    pub vertices: Vec<u32>,
    /// The vertices its sweep was fitted to and measured on (the mesh's, increasing): its own
    /// and those of its neighbours within the overlap.
    pub fitted: Vec<u32>,
    /// Its sweep, key 0 where it is attached.
    pub fit: Fit,
    /// Seconds its fit took.
    pub seconds: f64,
    /// The link it hangs from (an index into the chain), `None` for the link on the body.
    pub parent: Option<usize>,
}

/// A chain and its loosest link's RMS |d|.
#[derive(Clone, Debug)]
pub struct Chain {
    /// The links, each after its parent.
    pub links: Vec<FittedLink>,
    /// The largest of the links' `loose`.
    pub worst: f64,
}

impl Chain {
    /// Its links' [`LinkFitter::loose`], loosest first.
    fn loosest_first(&self, fitter: &impl LinkFitter) -> Vec<f64> {
        let mut loose: Vec<f64> = self.links.iter().map(|link| fitter.loose(&link.fit)).collect();
        loose.sort_by(|a, b| b.total_cmp(a));
        loose
    }
}

/// Whether links as loose as `loose` (loosest first, [`Chain::loosest_first`]) fit closer
/// than `than`: the loosest that differ decide, so two chains that share their loosest link (a
/// finger) are told apart by the next (their stems). Where one's are the other's and more, the
/// one with fewer fits closer: a link added to a chain never makes it fit closer.
fn fits_closer(loose: &[f64], than: &[f64]) -> bool {
    // Slices compare lexicographically, a prefix before what extends it.
    loose < than
}

/// How to fit a link: its fitted vertices (the mesh's, increasing) → its fit and seconds.
pub trait LinkFitter: Sync {
    /// Fits the sweep of `vertices`; `None` where the fit refuses them.
    fn fit(&self, vertices: &[u32]) -> Option<(Fit, f64)>;
    /// How loosely `fit` follows its part (RMS |d| over the mean radius; infinite for a sweep
    /// that is no link).
    fn loose(&self, fit: &Fit) -> f64;
}

/// Where a limb is cut at a level of s: within [`PLANE_REACH`] radii of the level by the
/// plane through its level set's centroid normal to the limb there, farther off by the level.
#[derive(Clone, Copy, Debug)]
struct Cut {
    level: f64,
    center: DVec3,
    normal: DVec3,
    radius: f64,
}

impl Cut {
    /// The same cut moved by `by` along the limb.
    fn moved(&self, by: f64) -> Cut {
        Cut { level: self.level + by, center: self.center + self.normal * by, ..*self }
    }
}

/// A limb's distance from its rim, for cutting it into links.
pub struct Profile {
    part: Part,
    graph: EdgeGraph,
    /// Per local vertex, s: its geodesic distance from the rim.
    s: Vec<f64>,
    /// The largest finite s.
    length: f64,
    /// The centroid of the rim's vertices.
    rim_center: DVec3,
}

impl Profile {
    /// The profile of the limb of `mesh` made of `vertices`; `None` where it has no rim or too
    /// few triangles to cut.
    pub fn new(mesh: &Mesh, vertices: &[u32]) -> Option<Profile> {
        let part = Part::new(mesh, vertices);
        if part.rim.is_empty() || part.triangles.len() < 8 {
            return None;
        }
        let graph = EdgeGraph::new(&part.positions, &part.triangles);
        let mut sources: Vec<u32> = part.rim.iter().flatten().copied().collect();
        sources.sort_unstable();
        sources.dedup();
        let mut s = graph.distances(&sources);
        let length = s.iter().copied().filter(|d| d.is_finite()).fold(0.0, f64::max);
        copies_take_distances(&part, &mut s, COPY * length);
        let rim_center = sources.iter().map(|&v| part.positions[v as usize]).sum::<DVec3>() / sources.len() as f64;
        (length > 0.0).then_some(Profile { part, graph, s, length, rim_center })
    }

    /// The level of the widening between levels `from` and `to` (see the module docs).
    pub fn widening(&self, from: f64, to: f64) -> Option<f64> {
        let h = (to - from) / LEVELS as f64;
        if h.is_nan() || h <= 0.0 {
            return None;
        }
        let shifted: Vec<f64> = self.s.iter().map(|&s| s - from).collect();
        let perimeter = perimeters(&self.part.positions, &self.part.triangles, &shifted, h, LEVELS, to - from);
        let radius: Vec<f64> = perimeter.iter().map(|p| p / TAU).collect();
        let (first, last) = ((FIRST * LEVELS as f64).ceil() as usize, (LAST * LEVELS as f64).floor() as usize);
        let wrist = (first..=last)
            .filter(|&k| radius[k] > 0.0)
            .filter(|&k| radius[k + 1..].iter().copied().fold(0.0, f64::max) >= WIDENING * radius[k])
            .min_by(|&a, &b| radius[a].total_cmp(&radius[b]).then(a.cmp(&b)))?;
        Some(from + wrist as f64 * h)
    }

    /// The level of the bend between levels `from` and `to` (see the module docs).
    pub fn bend(&self, from: f64, to: f64) -> Option<f64> {
        let h = (to - from) / LEVELS as f64;
        if h.is_nan() || h <= 0.0 {
            return None;
        }
        let centers: Vec<Option<DVec3>> =
            (0..=LEVELS).map(|k| self.level_set(from + k as f64 * h).map(|(center, _)| center)).collect();
        let (first, last) = ((FIRST * LEVELS as f64).ceil() as usize, (LAST * LEVELS as f64).floor() as usize);
        let turn = |k: usize| -> Option<f64> {
            let (before, here, after) = (centers[k - BEND_SPAN]?, centers[k]?, centers[k + BEND_SPAN]?);
            let (a, b) = ((here - before).try_normalize()?, (after - here).try_normalize()?);
            Some(a.dot(b).clamp(-1.0, 1.0).acos().to_degrees())
        };
        let (k, degrees) = (first.max(BEND_SPAN)..=last.min(LEVELS - BEND_SPAN))
            .filter_map(|k| Some((k, turn(k)?)))
            .max_by(|a, b| a.1.total_cmp(&b.1).then(b.0.cmp(&a.0)))?;
        (degrees >= BEND_DEGREES).then_some(from + k as f64 * h)
    }

    /// The level set s = `level`: the centroid of its segments (their midpoints weighted by
    /// their lengths) and its radius P/2π; `None` where it is empty.
    fn level_set(&self, level: f64) -> Option<(DVec3, f64)> {
        let (mut sum, mut perimeter) = (DVec3::ZERO, 0.0);
        for t in &self.part.triangles {
            let g = t.map(|v| self.s[v as usize]);
            if g.iter().all(|d| d.is_finite())
                && let Some([a, b]) = level_segment(&self.part.positions, *t, g, level)
            {
                let l = a.distance(b);
                sum += (a + b) * 0.5 * l;
                perimeter += l;
            }
        }
        (perimeter > 0.0).then(|| (sum / perimeter, perimeter / TAU))
    }

    /// The cut at `level` (see [`Cut`]); `None` where its level set is empty.
    fn cut(&self, level: f64) -> Option<Cut> {
        let (center, radius) = self.level_set(level)?;
        let step = radius.max(self.length / LEVELS as f64);
        let before = self.level_set(level - step).map_or(center, |l| l.0);
        let after = self.level_set(level + step).map_or(center, |l| l.0);
        let normal = (after - before).try_normalize().unwrap_or(DVec3::ZERO);
        Some(Cut { level, center, normal, radius })
    }

    /// Whether local vertex `v` lies past `cut`.
    fn beyond(&self, cut: &Cut, v: u32) -> bool {
        let s = self.s[v as usize];
        if (s - cut.level).abs() <= PLANE_REACH * cut.radius && cut.normal != DVec3::ZERO {
            (self.part.positions[v as usize] - cut.center).dot(cut.normal) >= 0.0
        } else {
            s >= cut.level
        }
    }

    /// The limb's local vertices past `from` (all where `None`) and not past `to` (none where
    /// `None`) that are in none of `excluded`.
    fn stretch(&self, from: Option<&Cut>, to: Option<&Cut>, excluded: &[bool]) -> Vec<u32> {
        (0..self.s.len() as u32)
            .filter(|&v| !excluded[v as usize])
            .filter(|&v| from.is_none_or(|cut| self.beyond(cut, v)) && to.is_none_or(|cut| !self.beyond(cut, v)))
            .collect()
    }

    /// The levels where the limb forks (see the module docs), lowest first.
    fn forks(&self) -> Vec<f64> {
        let mut levels = fork_levels(&self.graph, &self.s, f64::INFINITY, BRANCH * self.length);
        levels.retain(|&level| level >= FIRST * self.length);
        levels.sort_by(f64::total_cmp);
        levels.dedup();
        levels
    }

    /// The limb's branches (see the module docs), whole (each from its fork): from the highest
    /// fork down, each piece past it that holds no branch yet is a branch, and one that holds
    /// one branch is that branch, grown (a finger below a fork at its claw); one that holds more
    /// (the palm under two fingers) stays in the stem. `None` where there are fewer than two.
    fn branches(&self) -> Option<Vec<Vec<u32>>> {
        let significant = BRANCH * self.length;
        let mut owner = vec![usize::MAX; self.s.len()];
        let mut branches: Vec<Vec<u32>> = Vec::new();
        for level in self.forks().into_iter().rev() {
            for piece in self.pieces_past(level, significant) {
                let mut holds: Vec<usize> = piece.iter().map(|&v| owner[v as usize]).filter(|&b| b != usize::MAX).collect();
                holds.sort_unstable();
                holds.dedup();
                let branch = match holds[..] {
                    [] => {
                        branches.push(Vec::new());
                        branches.len() - 1
                    }
                    [one] => one,
                    _ => continue,
                };
                for &v in &piece {
                    owner[v as usize] = branch;
                }
                branches[branch] = piece;
            }
        }
        (branches.len() >= 2).then_some(branches)
    }

    /// The pieces of the limb past `level` (s > level, finite: a stray piece the distance does
    /// not reach is none) that reach at least `significant` beyond it and have at least
    /// [`MIN_LINK`] vertices, each as local vertices, increasing.
    fn pieces_past(&self, level: f64, significant: f64) -> Vec<Vec<u32>> {
        let count = self.s.len();
        let mut sets = DisjointSets::new(count);
        let beyond = |v: u32| self.s[v as usize] > level && self.s[v as usize].is_finite();
        for v in (0..count as u32).filter(|&v| beyond(v)) {
            for &(n, _) in self.graph.neighbours(v) {
                if beyond(n) {
                    let (a, b) = (sets.root(v), sets.root(n));
                    if a != b {
                        sets.attach(b, a);
                    }
                }
            }
        }
        let mut pieces: std::collections::BTreeMap<u32, (Vec<u32>, f64)> = Default::default();
        for v in (0..count as u32).filter(|&v| beyond(v)) {
            let piece = pieces.entry(sets.root(v)).or_default();
            piece.0.push(v);
            piece.1 = piece.1.max(self.s[v as usize]);
        }
        pieces
            .into_values()
            .filter(|(vertices, reach)| reach - level >= significant && vertices.len() >= MIN_LINK)
            .map(|(vertices, _)| vertices)
            .collect()
    }

    /// The branch `vertices` (local) without what lies before its rim's deepest point along it
    /// (from the rim's centroid to its farthest vertex): a fork's level set cuts a splayed toe
    /// obliquely, from the crotch between it and the next out to the side of the foot, and no
    /// section normal to the toe holds what lies before the crotch. That stays in the stem.
    /// What is kept is the piece that holds the farthest vertex; the branch stays whole where
    /// that would keep fewer than half its vertices.
    fn squared_off(&self, vertices: Vec<u32>) -> Vec<u32> {
        let inside = self.marked(std::slice::from_ref(&vertices));
        let rim: Vec<u32> = vertices
            .iter()
            .copied()
            .filter(|&v| self.graph.neighbours(v).iter().any(|&(n, _)| !inside[n as usize]))
            .collect();
        let position = |v: u32| self.part.positions[v as usize];
        let Some(&tip) = vertices.iter().max_by(|&&a, &&b| self.s[a as usize].total_cmp(&self.s[b as usize])) else {
            return vertices;
        };
        let centroid = rim.iter().map(|&v| position(v)).sum::<DVec3>() / rim.len().max(1) as f64;
        let Some(direction) = (position(tip) - centroid).try_normalize() else { return vertices };
        let along = |v: u32| (position(v) - centroid).dot(direction);
        let deepest = rim.iter().map(|&v| along(v)).fold(f64::NEG_INFINITY, f64::max);
        let mut kept = vec![false; self.s.len()];
        for &v in &vertices {
            kept[v as usize] = along(v) >= deepest;
        }
        // The piece that holds the tip.
        let piece = flood(&self.graph, tip, |v| kept[v as usize]);
        if 2 * piece.len() < vertices.len() {
            return vertices;
        }
        piece
    }

    /// The mesh's vertices of the local `vertices`, increasing.
    fn mesh_vertices(&self, vertices: impl Iterator<Item = u32>) -> Vec<u32> {
        let mut out: Vec<u32> = vertices.map(|v| self.part.vertices[v as usize]).collect();
        out.sort_unstable();
        out
    }

    /// The centroid of local `vertices`.
    fn centroid(&self, vertices: &[u32]) -> DVec3 {
        vertices.iter().map(|&v| self.part.positions[v as usize]).sum::<DVec3>() / vertices.len().max(1) as f64
    }

    /// The best chain of the limb (see the module docs), `None` where it has none whose links
    /// all fit.
    pub fn chain(&self, fitter: &impl LinkFitter, target: f64) -> Option<Chain> {
        let depth = if self.s.len() > DENSE { 0 } else { DEPTH };
        // Squared off first; whole only where that misses the target (see the module docs).
        let forked = self.branches().and_then(|whole| {
            let squared_off: Vec<Vec<u32>> = whole.iter().map(|branch| self.squared_off(branch.clone())).collect();
            let squared = self.forked_with_links(squared_off.clone(), target, depth, fitter);
            if squared_off == whole || squared.as_ref().is_some_and(|chain| chain.worst <= target) {
                return squared;
            }
            // Each branch whole where its link alone fits closer than the squared chain's
            // loosest (see the module docs).
            let bound = squared.as_ref().map(|chain| chain.loosest_first(fitter));
            let loosest = bound.as_ref().map(|bound| bound[0]);
            let mixed: Vec<Vec<u32>> = whole
                .into_iter()
                .zip(&squared_off)
                .map(|(whole, squared)| {
                    let closer = whole != *squared
                        && loosest.is_none_or(|loosest| self.branch_link(&whole, None, fitter).is_some_and(|link| fitter.loose(&link.fit) < loosest));
                    if closer { whole } else { squared.clone() }
                })
                .collect();
            if mixed == squared_off {
                return squared;
            }
            // Where the squared chain failed, a whole branch that fits no link leaves no chain
            // here either: the limb is then cut unforked, as before.
            self.forked_within(&mixed, target, 0, bound.as_deref(), fitter)
                .filter(|chain| chain.worst.is_finite())
                .or(squared)
        });
        // A limb that forks is kept forked where its branches fit and bind: unforked, its last
        // link would hold its toes or fingers.
        if forked.is_some() {
            return forked;
        }
        let none = vec![false; self.s.len()];
        self.stretch_chain(None, None, &none, target, depth, fitter).filter(|chain| chain.links.len() > 1)
    }

    /// The limb's chain forked at `branches` ([`Profile::forked`]), where a branch that fits no
    /// link (a stubby finger whose fit folds or zigzags) rides in the stem, where at least two
    /// others are links.
    fn forked_with_links(
        &self,
        branches: Vec<Vec<u32>>,
        target: f64,
        depth: usize,
        fitter: &impl LinkFitter,
    ) -> Option<Chain> {
        let chain = self.forked(&branches, target, depth, fitter)?;
        let first_branch = chain.links.len() - branches.len();
        let links: Vec<bool> =
            chain.links[first_branch..].iter().map(|link| fitter.loose(&link.fit).is_finite()).collect();
        if links.iter().all(|&link| link) {
            return Some(chain);
        }
        let kept: Vec<Vec<u32>> =
            branches.into_iter().zip(links).filter_map(|(branch, link)| link.then_some(branch)).collect();
        if kept.len() < 2 {
            return None;
        }
        self.forked(&kept, target, depth, fitter)
    }

    /// The limb's chain forked at `branches`: its stem without them, cut as a stretch is, and
    /// each branch a child of the stem's link it meets most; `None` where the stem has no
    /// chain or a branch's fit is refused or does not bind.
    fn forked(&self, branches: &[Vec<u32>], target: f64, depth: usize, fitter: &impl LinkFitter) -> Option<Chain> {
        self.forked_within(branches, target, depth, None, fitter)
    }

    /// [`Profile::forked`], `None` as soon as its links fit no closer ([`fits_closer`]) than
    /// links as loose as `bound` (loosest first) where there is one: adding links to a chain
    /// never makes it fit closer, so it is given up at the first that leaves it no closer.
    fn forked_within(
        &self,
        branches: &[Vec<u32>],
        target: f64,
        depth: usize,
        bound: Option<&[f64]>,
        fitter: &impl LinkFitter,
    ) -> Option<Chain> {
        let within = |chain: &Chain| bound.is_none_or(|bound| fits_closer(&chain.loosest_first(fitter), bound));
        let excluded: Vec<bool> = self.marked(branches);
        let mut chain = self.stretch_chain(None, None, &excluded, target, depth, fitter)?;
        for branch in branches {
            if !within(&chain) {
                return None;
            }
            self.add_branch(&mut chain, branch, fitter)?;
        }
        within(&chain).then_some(chain)
    }

    /// The limb without its attached end, where that end is the body's and not a tube's (a
    /// coarse leg cut above its crotch, its rim on the pelvis's top and holding the slab
    /// between the legs' tops): the stretch past the cut at level k/[`LEVELS`] of its length,
    /// for k = 1, 2, … [`TRIMMED`], as one link fitted to its own vertices (not past its cut,
    /// where the body is), key 0 at the cut; the first within `target` both as a link
    /// ([`LinkFitter::loose`]) and by its sections' radii (a flat ribbon whose fitted radii
    /// follow it is no limb). `None` where none is.
    pub fn trimmed(&self, fitter: &impl LinkFitter, target: f64) -> Option<Chain> {
        (1..=TRIMMED).find_map(|k| {
            let cut = self.cut(k as f64 * self.length / LEVELS as f64)?;
            // By the level alone: near the rim the level set holds the body's piece, and the
            // plane through its centroid may pass below a neighbouring limb's top.
            let vertices: Vec<u32> = (0..self.s.len() as u32).filter(|&v| self.s[v as usize] >= cut.level).collect();
            if vertices.len() < MIN_LINK {
                return None;
            }
            let link = self.fitted_link(&vertices, &vertices, self.attached_at(Some(&cut)), None, fitter)?;
            let worst = fitter.loose(&link.fit);
            (worst <= target && link.fit.sections_quality().rms_d <= target)
                .then(|| Chain { links: vec![link], worst })
        })
    }

    /// The limb with its end past a widening as a branch (a child fitted with a ring of the
    /// link it hangs from, as a finger is: [`Profile::add_branch`]) and the stem before it
    /// chained as a limb is ([`Profile::stretch_chain`]), where the stem's links fit within
    /// `most` and the end's fit is not refused (it neither folds nor zigzags), however loosely
    /// it fits. The widenings are the limb's, the one of the stretch past it, and so on towards
    /// the tip (at most [`ENDS`]), the last tried first; an end of fewer than [`MIN_LINK`]
    /// vertices is none. For a coarse limb that no chain of cuts rigs, whose hand would
    /// otherwise take its arm out of the rig: Sydney's arm raised to her face (a public game
    /// mesh, 38 vertices; 65% as one sweep), its hand cut at its wrist fitting at 57.8%, as a
    /// branch at 41.7% and at 2.8% with its radii smoothed, its stem at 25.4%. `None` where no
    /// widening leaves such a chain.
    pub fn with_end_branched(&self, fitter: &impl LinkFitter, target: f64, most: f64) -> Option<Chain> {
        let mut widenings: Vec<f64> = Vec::new();
        while widenings.len() < ENDS {
            let from = widenings.last().copied().unwrap_or(0.0);
            let Some(level) = self.widening(from, self.length).filter(|&level| level > from) else { break };
            widenings.push(level);
        }
        widenings.into_iter().rev().find_map(|level| {
            let cut = self.cut(level)?;
            let end: Vec<u32> = (0..self.s.len() as u32).filter(|&v| self.beyond(&cut, v)).collect();
            if end.len() < MIN_LINK {
                return None;
            }
            let mut chain = self.stretch_chain(None, None, &self.marked(std::slice::from_ref(&end)), target, DEPTH, fitter)?;
            if chain.worst > most {
                return None;
            }
            self.add_branch(&mut chain, &end, fitter)?;
            chain.worst.is_finite().then_some(chain)
        })
    }

    /// Per local vertex, whether it is in one of `sets`.
    fn marked(&self, sets: &[Vec<u32>]) -> Vec<bool> {
        let mut marked = vec![false; self.s.len()];
        for &v in sets.iter().flatten() {
            marked[v as usize] = true;
        }
        marked
    }

    /// The best chain of the stretch between `from` and `to` without `excluded`: its one sweep
    /// where that fits within `target` or `depth` is 0, else the best of it and its cuts at
    /// its widening and at its bend, each side cut again.
    fn stretch_chain(
        &self,
        from: Option<&Cut>,
        to: Option<&Cut>,
        excluded: &[bool],
        target: f64,
        depth: usize,
        fitter: &impl LinkFitter,
    ) -> Option<Chain> {
        let single = self.fitted_stretch(from, to, excluded, fitter);
        if depth == 0 || single.as_ref().is_some_and(|chain| chain.worst <= target) {
            return single;
        }
        let (lo, hi) = (from.map_or(0.0, |cut| cut.level), to.map_or(self.length, |cut| cut.level));
        let mut levels: Vec<f64> = [self.bend(lo, hi), self.widening(lo, hi)].into_iter().flatten().collect();
        levels.dedup_by(|a, b| (*a - *b).abs() < SAME_CUT * (hi - lo));
        let mut best = single;
        for level in levels {
            let Some(cut) = self.cut(level) else { continue };
            let (near, far) = crate::parallel::join(
                || self.stretch_chain(from, Some(&cut), excluded, target, depth - 1, fitter),
                || self.stretch_chain(Some(&cut), to, excluded, target, depth - 1, fitter),
            );
            let Some(joined) = near.zip(far).and_then(|(near, far)| joined(near, far)) else { continue };
            if best.as_ref().is_none_or(|best| joined.worst < best.worst) {
                best = Some(joined);
            }
            // A cut whose links all fit within the target is kept without trying the next.
            if best.as_ref().is_some_and(|best| best.worst <= target) {
                break;
            }
        }
        best
    }

    /// The stretch between `from` and `to` without `excluded` as one link, fitted with
    /// [`OVERLAP`] of its neighbours; `None` where it has fewer than [`MIN_LINK`] vertices or
    /// its fit is refused.
    fn fitted_stretch(
        &self,
        from: Option<&Cut>,
        to: Option<&Cut>,
        excluded: &[bool],
        fitter: &impl LinkFitter,
    ) -> Option<Chain> {
        let vertices = self.stretch(from, to, excluded);
        if vertices.len() < MIN_LINK {
            return None;
        }
        let (wider_from, wider_to) =
            (from.map(|cut| cut.moved(-OVERLAP * cut.radius)), to.map(|cut| cut.moved(OVERLAP * cut.radius)));
        let mut fitted = self.stretch(wider_from.as_ref(), wider_to.as_ref(), excluded);
        if let Some(to) = to.filter(|_| self.s.len() < COARSE) {
            fitted = self.with_ring_past(&vertices, fitted, to, excluded);
        }
        let link = self.fitted_link(&vertices, &fitted, self.attached_at(from), None, fitter)?;
        let worst = fitter.loose(&link.fit);
        Some(Chain { links: vec![link], worst })
    }

    /// The point a link past `from` (the rim where `None`) is attached at, for turning its key 0
    /// there: a coarse link may reach a whole span past its far cut, so it is seen from a point
    /// the limb's length back along its near cut's normal, from which key 0 is still the end on
    /// the parent's side.
    fn attached_at(&self, from: Option<&Cut>) -> DVec3 {
        let back = if self.s.len() < COARSE { self.length } else { 0.0 };
        from.map_or(self.rim_center, |cut| cut.center - cut.normal * back)
    }

    /// `fitted` (increasing) and the neighbours of local `vertices` past `cut` in none of
    /// `excluded`: on a coarse limb, whose rings lie farther apart than [`OVERLAP`] of its
    /// radius, the ring past a link's far cut, so that the link reaches its child's first key
    /// (the faerie's forearm is one span of long triangles from its elbow's ring to its
    /// wrist's: the upper arm's link ended at the elbow, and the hand's first key, at the
    /// wrist, lay on no cross-section of it). The child is not grown back: it would take the
    /// whole span and fit it as loosely as one sweep.
    fn with_ring_past(&self, vertices: &[u32], fitted: Vec<u32>, cut: &Cut, excluded: &[bool]) -> Vec<u32> {
        let mut grown = self.neighbours_where(vertices, |n| !excluded[n as usize] && self.beyond(cut, n));
        grown.extend(fitted);
        grown.sort_unstable();
        grown.dedup();
        grown
    }

    /// The neighbours of local `vertices` that `keep` accepts, increasing, each once.
    fn neighbours_where(&self, vertices: &[u32], keep: impl Fn(u32) -> bool) -> Vec<u32> {
        let mut found: Vec<u32> = vertices
            .iter()
            .flat_map(|&v| self.graph.neighbours(v).iter().map(|&(n, _)| n))
            .filter(|&n| keep(n))
            .collect();
        found.sort_unstable();
        found.dedup();
        found
    }

    /// The link of local `vertices` fitted to local `fitted`, turned so that key 0 is the end
    /// nearer `attached_at`.
    fn fitted_link(
        &self,
        vertices: &[u32],
        fitted: &[u32],
        attached_at: DVec3,
        parent: Option<usize>,
        fitter: &impl LinkFitter,
    ) -> Option<FittedLink> {
        let fitted = self.mesh_vertices(fitted.iter().copied());
        let (fit, seconds) = fitter.fit(&fitted)?;
        let (first, last) = (fit.keys[0].center, fit.keys[fit.keys.len() - 1].center);
        let fit = if last.distance(attached_at) < first.distance(attached_at) { fit.reversed() } else { fit };
        Some(FittedLink {
            vertices: self.mesh_vertices(vertices.iter().copied()),
            fitted,
            fit,
            seconds,
            parent,
        })
    }

    /// The link of branch `vertices` (local), a child of link `parent`: fitted with the ring of
    /// its neighbours around its base (its collar), key 0 at that ring.
    fn branch_link(&self, vertices: &[u32], parent: Option<usize>, fitter: &impl LinkFitter) -> Option<FittedLink> {
        let inside = self.marked(&[vertices.to_vec()]);
        let collar = self.neighbours_where(vertices, |n| !inside[n as usize]);
        let mut fitted = vertices.to_vec();
        fitted.extend(&collar);
        self.fitted_link(vertices, &fitted, self.centroid(&collar), parent, fitter)
    }

    /// Adds the branch of local `vertices` to `chain` as a child of the link whose vertices it
    /// meets most, fitted with a ring of that link's vertices around its base (its collar);
    /// `None` where its fit is refused or its first key does not bind to that link.
    fn add_branch(&self, chain: &mut Chain, vertices: &[u32], fitter: &impl LinkFitter) -> Option<()> {
        let inside = self.marked(&[vertices.to_vec()]);
        let collar = self.neighbours_where(vertices, |n| !inside[n as usize]);
        let owner = |v: u32| {
            let v = self.part.vertices[v as usize];
            chain.links.iter().position(|link| link.vertices.binary_search(&v).is_ok())
        };
        let mut votes = vec![0usize; chain.links.len()];
        for link in collar.iter().filter_map(|&v| owner(v)) {
            votes[link] += 1;
        }
        let parent = (0..votes.len()).max_by_key(|&i| (votes[i], i))?;
        let link = self.branch_link(vertices, Some(parent), fitter)?;
        binds(&chain.links[parent].fit, &link.fit)?;
        chain.worst = chain.worst.max(fitter.loose(&link.fit));
        chain.links.push(link);
        Some(())
    }
}

/// Gives each vertex of `part` on none of its triangles and within `reach` of one that is (a
/// seam's copy, whose welded twin the triangles use) the distance `s` of the nearest such, so
/// that it goes with its twin to the same side of every cut (with an infinite s it lay past
/// them all, and the last link took every copy in the limb).
fn copies_take_distances(part: &Part, s: &mut [f64], reach: f64) {
    let mut on_triangle = vec![false; part.positions.len()];
    for &v in part.triangles.iter().flatten() {
        on_triangle[v as usize] = true;
    }
    let reached: Vec<usize> = (0..s.len()).filter(|&v| on_triangle[v] && s[v].is_finite()).collect();
    for v in (0..s.len()).filter(|&v| !on_triangle[v]) {
        let p = part.positions[v];
        let twin = reached.iter().copied().min_by(|&a, &b| {
            part.positions[a].distance_squared(p).total_cmp(&part.positions[b].distance_squared(p)).then(a.cmp(&b))
        });
        if let Some(twin) = twin.filter(|&twin| part.positions[twin].distance(p) <= reach) {
            s[v] = s[twin];
        }
    }
}

/// `Some` where the first key of `child` lies on a cross-section of `parent`.
pub fn binds(parent: &Fit, child: &Fit) -> Option<()> {
    let parent = Sweep::try_new(&parent.keys, None).ok()?;
    KeyBinding::new(&parent, &child.keys[0]).map(|_| ())
}

/// The chain `near` followed by `far`, whose first link becomes a child of `near`'s last;
/// `None` where its first key does not bind to it.
fn joined(mut near: Chain, far: Chain) -> Option<Chain> {
    let offset = near.links.len();
    let last = offset - 1;
    binds(&near.links[last].fit, &far.links[0].fit)?;
    near.worst = near.worst.max(far.worst);
    near.links.extend(far.links.into_iter().map(|link| {
        let parent = Some(link.parent.map_or(last, |p| p + offset));
        FittedLink { parent, ..link }
    }));
    Some(near)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fit::tests::bent_tube::{elbow_centers, tube_along};
    use crate::mesh::Faces;
    use glam::DVec3;

    /// A surface of revolution about z: rings of `around` vertices at the heights and radii of
    /// `profile`, the first ring the rim of a flat flange (the body) of radius 4 at its height,
    /// the last closed by a cap. Returns the mesh and the limb's vertices (every ring's and the
    /// cap's, not the flange's).
    fn limb_on_a_flange(profile: &[(f64, f64)], around: u32) -> (Mesh, Vec<u32>) {
        let mut positions = Vec::new();
        let ring = |positions: &mut Vec<DVec3>, z: f64, r: f64| {
            let first = positions.len() as u32;
            for a in 0..around {
                let angle = std::f64::consts::TAU * a as f64 / around as f64;
                positions.push(DVec3::new(r * angle.cos(), r * angle.sin(), z));
            }
            first
        };
        let mut faces = Faces::new();
        let flange = ring(&mut positions, profile[0].0, 4.0);
        let rings: Vec<u32> = profile.iter().map(|&(z, r)| ring(&mut positions, z, r)).collect();
        let cap = positions.len() as u32;
        positions.push(DVec3::new(0.0, 0.0, profile.last().unwrap().0 + 0.2));
        let band = |faces: &mut Faces, lo: u32, hi: u32| {
            for a in 0..around {
                let b = (a + 1) % around;
                faces.push(&[lo + a, lo + b, hi + b, hi + a]);
            }
        };
        band(&mut faces, flange, rings[0]);
        for pair in rings.windows(2) {
            band(&mut faces, pair[0], pair[1]);
        }
        let last = *rings.last().unwrap();
        for a in 0..around {
            faces.push(&[last + a, last + (a + 1) % around, cap]);
        }
        let mesh = Mesh::from_parts(positions, faces, Vec::new()).unwrap();
        (mesh, (around..=cap).collect())
    }

    /// A seam's copy of a vertex (at its position, on no triangle: its welded twin the
    /// triangles use) goes with its twin to the near side of a cut past them; with an infinite
    /// distance from the rim, as before copies took their twins' distances, it lay past every
    /// cut.
    #[test]
    fn a_seam_copy_goes_with_its_twin() {
        let profile: Vec<(f64, f64)> = (0..12).map(|i| (i as f64 * 0.5, 0.5)).collect();
        let (mesh, mut limb) = limb_on_a_flange(&profile, 12);
        // A copy of a vertex of the third ring (the rings start after the flange's 12).
        let twin = 12 + 2 * 12 + 5;
        let mut positions = mesh.positions.clone();
        positions.push(positions[twin as usize]);
        let copy = positions.len() as u32 - 1;
        let mesh = Mesh::from_parts(positions, mesh.faces.clone(), Vec::new()).unwrap();
        limb.push(copy);
        let profile = Profile::new(&mesh, &limb).expect("a rim");
        let local = |v: u32| profile.part.vertices.binary_search(&v).unwrap();
        assert_eq!(profile.s[local(copy)], profile.s[local(twin)]);
        let (near, far) = cut_at(&profile, 0.5 * profile.length);
        assert!(near.binary_search(&twin).is_ok() && near.binary_search(&copy).is_ok(), "near the rim with its twin");
        assert!(far.binary_search(&copy).is_err());
    }

    /// Fits links with the default options and measures them by their sections' radii.
    struct Plain<'a>(&'a Mesh);
    impl LinkFitter for Plain<'_> {
        fn fit(&self, vertices: &[u32]) -> Option<(Fit, f64)> {
            crate::fit::fit(self.0, vertices, &crate::fit::FitOptions::default()).ok().map(|fitted| (fitted, 0.0))
        }
        fn loose(&self, fitted: &Fit) -> f64 {
            fitted.sections_quality().rms_d
        }
    }

    /// The vertices of the limb of `rigged` one of whose parts holds `tip`: every link of its
    /// chain (the parts named like it), increasing.
    fn limb_holding(rigged: &crate::fit::autorig::Autorig, tip: u32) -> Vec<u32> {
        let part = rigged.parts.iter().find(|p| p.vertices.binary_search(&tip).is_ok()).expect("a part holds the tip");
        let limb_name = part.name.split('.').next().unwrap();
        let mut limb: Vec<u32> = rigged
            .parts
            .iter()
            .filter(|p| p.name.split('.').next() == Some(limb_name))
            .flat_map(|p| p.vertices.clone())
            .collect();
        limb.sort_unstable();
        limb.dedup();
        limb
    }

    /// How many of `chain`'s links are branches of `whole` (local vertices) taken whole.
    fn kept_whole(profile: &Profile, chain: &Chain, whole: &[Vec<u32>]) -> usize {
        chain.links.iter().filter(|l| whole.iter().any(|w| profile.mesh_vertices(w.iter().copied()) == l.vertices)).count()
    }

    #[test]
    fn chains_are_compared_loosest_link_first_then_the_next() {
        // The loosest that differ decide: a shared loosest link (one finger) leaves it to the
        // stems.
        assert!(fits_closer(&[0.24, 0.13, 0.05], &[0.24, 0.18, 0.05]));
        assert!(!fits_closer(&[0.24, 0.18, 0.05], &[0.24, 0.13, 0.05]));
        assert!(fits_closer(&[0.2, 0.19, 0.18], &[0.24, 0.01]));
        // Equal chains are not closer; with one's links the other's and more, the fewer are.
        assert!(!fits_closer(&[0.24, 0.13], &[0.24, 0.13]));
        assert!(fits_closer(&[0.24, 0.13], &[0.24, 0.13, 0.01]));
        // A link added never makes a chain closer, so a chain no closer than a bound stays so
        // as links are added (what lets a chain be given up at its first such link).
        let chain: [f64; 3] = [0.3, 0.2, 0.1];
        for added in [0.5, 0.3, 0.25, 0.2, 0.15, 0.1, 0.05] {
            let mut more = chain.to_vec();
            more.push(added);
            more.sort_by(|a, b| b.total_cmp(a));
            assert!(!fits_closer(&more, &chain), "{added}");
        }
    }

    /// The armadillo's +x hand: squared off, its loosest link is a finger and its stem misses
    /// the target. Whole from their fork, two fingers leave that finger the chain's loosest
    /// link, so the two chains' loosest links tie, and the stems decide: the whole fingers' stem
    /// fits closer, and the limb is forked so. By its loosest link alone (the rule before), the
    /// chain fit no closer and the squared one was kept.
    #[test]
    fn chains_whose_loosest_links_tie_are_told_apart_by_their_stems() {
        use crate::fit::autorig::{AutorigOptions, TARGET, autorig};

        let Some(path) = crate::common::shared_mesh("armadillo_50k.obj") else { return };
        let mesh = Mesh::load(&path).unwrap();
        let rigged = autorig(&mesh, &AutorigOptions::default()).unwrap();
        let hand = crate::common::extreme_vertex(&mesh, |p| p.y > 40.0, |p| p.x);
        let profile = Profile::new(&mesh, &limb_holding(&rigged, hand)).expect("a rim");
        let depth = if profile.s.len() > DENSE { 0 } else { DEPTH };
        let fitter = Plain(&mesh);
        let whole = profile.branches().expect("the fingers");
        let squared: Vec<Vec<u32>> = whole.iter().map(|branch| profile.squared_off(branch.clone())).collect();
        let old = profile.forked_with_links(squared, TARGET, depth, &fitter).expect("forked at squared branches");
        let chain = profile.chain(&fitter, TARGET).expect("a chain");
        let stem = |chain: &Chain| fitter.loose(&chain.links.iter().find(|l| l.parent.is_none()).unwrap().fit);
        let kept_whole = kept_whole(&profile, &chain, &whole);
        eprintln!(
            "armadillo hand: squared off, loosest link {:.1}%, stem {:.1}%; kept: {kept_whole} of {} fingers whole, \
             loosest {:.1}%, stem {:.1}%",
            100.0 * old.worst,
            100.0 * stem(&old),
            whole.len(),
            100.0 * chain.worst,
            100.0 * stem(&chain)
        );
        assert!(stem(&old) > TARGET, "squared off, the stem misses the target");
        assert!(kept_whole >= 1, "a finger whole");
        assert_eq!(chain.worst, old.worst, "the loosest links tie");
        assert!(stem(&chain) < stem(&old), "the stems decide");
        assert!(fits_closer(&chain.loosest_first(&fitter), &old.loosest_first(&fitter)));
        assert!(chain.worst >= old.worst, "by the loosest link alone, the chain was refused");
    }

    /// A ball with an arm along +x ending in a round hand and three fingers spread 0.4 apart
    /// (the figure of the autorig hand test, one arm, its fingers farther apart): the mesh and
    /// the arm's vertices beyond x = 1.6.
    fn hand_on_a_ball() -> (Mesh, Vec<u32>) {
        use crate::common::star::{implicit_mesh, smooth_min};
        let capsule = |p: DVec3, a: DVec3, b: DVec3, radius: f64| {
            let t = ((p - a).dot(b - a) / (b - a).length_squared()).clamp(0.0, 1.0);
            p.distance(a + (b - a) * t) - radius
        };
        let figure = |p: DVec3| {
            let mut d = p.length() - 1.4;
            d = smooth_min(d, capsule(p, DVec3::ZERO, DVec3::new(2.6, 0.0, 0.0), 0.25));
            d = smooth_min(d, capsule(p, DVec3::new(2.9, 0.0, 0.0), DVec3::new(3.4, 0.0, 0.0), 0.55));
            for (y, reach) in [(-0.4, 4.3), (0.0, 4.5), (0.4, 4.3)] {
                d = smooth_min(d, capsule(p, DVec3::new(3.6, y, 0.0), DVec3::new(reach, y, 0.0), 0.14));
            }
            d
        };
        let mesh = implicit_mesh(&figure, 4.8, 0.06);
        let arm = (0..mesh.positions.len() as u32).filter(|&v| mesh.positions[v as usize].x > 1.6).collect();
        (mesh, arm)
    }

    /// A finger that fits no link (here: a fitter that takes the middle finger's fits for
    /// folded) rides in the stem, and the hand keeps the other two as children: with every
    /// branch a child, as before, the chain's loosest link is infinite and the limb is no chain.
    #[test]
    fn a_branch_that_fits_no_link_rides_in_the_stem() {
        use crate::fit::autorig::TARGET;

        struct MiddleFolds<'a>(Plain<'a>);
        impl LinkFitter for MiddleFolds<'_> {
            fn fit(&self, vertices: &[u32]) -> Option<(Fit, f64)> {
                self.0.fit(vertices)
            }
            // A finger's link (a finger and its collar: under 600 vertices, the stem over 8,000)
            // reaching past the other fingers' tips, x = 4.44.
            fn loose(&self, fitted: &Fit) -> f64 {
                let middle = fitted.quality.vertices < 2000 && fitted.keys.iter().any(|k| k.center.x > 4.5);
                if middle { f64::INFINITY } else { self.0.loose(fitted) }
            }
        }
        let (mesh, arm) = hand_on_a_ball();
        let fitter = MiddleFolds(Plain(&mesh));
        let profile = Profile::new(&mesh, &arm).unwrap();
        let branches = profile.branches().expect("the hand's fingers");
        assert_eq!(branches.len(), 3);
        let middle_tip = *arm.iter().max_by(|&&a, &&b| mesh.positions[a as usize].x.total_cmp(&mesh.positions[b as usize].x)).unwrap();
        let every = profile.forked(&branches, TARGET, DEPTH, &fitter).expect("forked at every finger");
        assert!(every.worst.is_infinite(), "the middle finger's link is no link: {}", every.worst);
        let chain = profile.chain(&fitter, TARGET).expect("a chain");
        let children: Vec<&FittedLink> = chain.links.iter().filter(|l| l.parent.is_some()).collect();
        let stem: Vec<u32> = chain.links.iter().filter(|l| l.parent.is_none()).flat_map(|l| l.vertices.clone()).collect();
        eprintln!(
            "hand: {} links, the stem {} vertices, children {:?}, loosest {:.3}",
            chain.links.len(),
            stem.len(),
            children.iter().map(|l| l.vertices.len()).collect::<Vec<_>>(),
            chain.worst
        );
        assert!(chain.worst.is_finite());
        assert_eq!(children.len(), 2, "the other two fingers are children");
        assert!(stem.contains(&middle_tip), "the middle finger rides in the stem");
        assert!(children.iter().all(|l| !l.vertices.contains(&middle_tip)));
    }

    /// The dino's legs fork at two toes, its arms at three fingers. Squared off, each branch
    /// leaves the part of it before its crotch in the stem: the stem then ends in the bases of
    /// the toes or fingers, no tube's, and misses the target. Kept whole from their fork, the
    /// toes leave the leg's stem a tube down to the foot; but one of the fingers, whole, is no
    /// tube (its sections miss by over half its radius), so the arm keeps that finger squared
    /// off and the other two whole. Either way the stem is within the target and the chain's
    /// loosest link fits closer: the limb is forked so.
    #[test]
    fn branches_are_kept_whole_where_their_links_then_fit_closer() {
        use crate::fit::autorig::{AutorigOptions, TARGET, autorig};

        let Some(path) = crate::common::shared_mesh("dino.off") else { return };
        let mesh = Mesh::load(&path).unwrap();
        let rigged = autorig(&mesh, &AutorigOptions::default()).unwrap();
        // A toe's tip: the lowest vertex at x < −0.2 (the legs reach down to z ≈ −2); a
        // fingertip: the arms reach towards −y, their hands at x ≈ −0.9, z ≈ −0.5.
        let toe = crate::common::extreme_vertex(&mesh, |p| p.x < -0.2, |p| -p.z);
        let fingertip = crate::common::extreme_vertex(&mesh, |p| p.x < -0.6 && p.z > -0.8, |p| -p.y);
        let stem = |chain: &Chain| chain.links.iter().find(|l| l.parent.is_none()).unwrap().fit.quality.rms_d;
        for (name, tip, branches) in [("leg", toe, 2), ("arm", fingertip, 3)] {
            let profile = Profile::new(&mesh, &limb_holding(&rigged, tip)).expect("a rim");
            let fitter = Plain(&mesh);
            let whole = profile.branches().expect("the toes or fingers");
            assert_eq!(whole.len(), branches, "dino {name}");
            let squared: Vec<Vec<u32>> = whole.iter().map(|branch| profile.squared_off(branch.clone())).collect();
            let old = profile.forked_with_links(squared.clone(), TARGET, DEPTH, &fitter).expect("forked at squared branches");
            let all_whole = profile.forked_with_links(whole.clone(), TARGET, DEPTH, &fitter);
            let chain = profile.chain(&fitter, TARGET).expect("a chain");
            let kept_whole = kept_whole(&profile, &chain, &whole);
            eprintln!(
                "dino {name}: squared off, loosest link {:.1}%, stem {:.1}%; every branch whole, loosest {:.1}%; \
                 kept: {kept_whole} of {branches} branches whole, loosest {:.1}%, stem {:.1}%",
                100.0 * old.worst,
                100.0 * stem(&old),
                100.0 * all_whole.as_ref().map_or(f64::NAN, |c| c.worst),
                100.0 * chain.worst,
                100.0 * stem(&chain)
            );
            assert!(stem(&old) > TARGET, "dino {name}: with its branches squared off the stem misses the target");
            assert!(stem(&chain) <= TARGET, "dino {name}: the stem is within it");
            assert!(chain.worst < old.worst, "dino {name}");
            if name == "leg" {
                assert_eq!(kept_whole, branches, "the toes whole");
            } else {
                assert_eq!(kept_whole, branches - 1, "two fingers whole, one squared off");
                assert!(all_whole.is_some_and(|c| c.worst > 0.5), "every finger whole: one is no tube");
            }
        }
    }

    /// A part that is no tube at its attached end: the faerie's hair, found from its tip, whose
    /// part holds a piece of the back of her head where it starts. As one sweep it misses its
    /// sections by over [`MAX_RMS`](crate::fit::autorig::MAX_RMS); trimmed of its first levels it
    /// fits within the target by its sections' radii and keeps at least half its vertices (12
    /// of 19).
    #[test]
    fn a_part_that_is_no_tube_at_its_attached_end_is_trimmed() {
        use crate::fit::autorig::{MAX_RMS, TARGET};
        use crate::fit::body::Body;
        use crate::fit::protrusions::protrusions;
        use crate::fit::{FitOptions, fit};

        let Some(path) = crate::common::shared_mesh("characters/faerie.obj") else { return };
        let mesh = Mesh::load(&path).unwrap();
        let body = Body::new(&mesh);
        let welded = body.welded_mesh(&mesh);
        let on = welded.as_ref().unwrap_or(&mesh);
        let ys = || mesh.positions.iter().map(|p| p.y);
        let height = ys().fold(f64::NEG_INFINITY, f64::max) - ys().fold(f64::INFINITY, f64::min);
        // Her hair hangs behind her (she faces +x), over a quarter of her height.
        let hair = protrusions(&mesh, &body, 0.04 * body.diagonal, 32)
            .0
            .into_iter()
            .find(|p| {
                let at = |v: &u32| mesh.positions[*v as usize];
                let (lo, hi) = p.vertices.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                    (lo.min(at(v).y), hi.max(at(v).y))
                });
                p.vertices.iter().all(|v| at(v).x < -2.0) && hi - lo >= 0.25 * height
            })
            .expect("her hair is found");
        let whole = fit(on, &hair.vertices, &FitOptions::default()).unwrap().sections_quality().rms_d;
        let trimmed = Profile::new(on, &hair.vertices).unwrap().trimmed(&Plain(on), TARGET).expect("trimmed");
        let kept = &trimmed.links[0];
        eprintln!(
            "faerie's hair: {} vertices at {:.0}% as one sweep; trimmed, {} at {:.1}%",
            hair.vertices.len(),
            100.0 * whole,
            kept.vertices.len(),
            100.0 * kept.fit.sections_quality().rms_d
        );
        assert!(whole > MAX_RMS, "as one sweep its sections are no tube's");
        assert!(kept.fit.sections_quality().rms_d <= TARGET);
        assert!(2 * kept.vertices.len() >= hair.vertices.len(), "most of it kept");
    }

    /// The limb's vertices before and past the cut at `level`.
    fn cut_at(profile: &Profile, level: f64) -> (Vec<u32>, Vec<u32>) {
        let cut = profile.cut(level).expect("a level set");
        let none = vec![false; profile.s.len()];
        let near = profile.stretch(None, Some(&cut), &none);
        let far = profile.stretch(Some(&cut), None, &none);
        (profile.mesh_vertices(near.into_iter()), profile.mesh_vertices(far.into_iter()))
    }

    #[test]
    fn a_limb_ending_in_a_widening_is_cut_at_its_wrist() {
        // Radius 1 up to z = 6, a wrist of 0.8 at z = 6.5, a hand of radius 2 from z = 7.5 to 9.
        let mut profile: Vec<(f64, f64)> = (0..=12).map(|k| (0.5 * k as f64, 1.0)).collect();
        profile.extend([(6.5, 0.8), (7.0, 1.4), (7.5, 2.0), (8.0, 2.0), (8.5, 2.0), (9.0, 1.6)]);
        let (mesh, limb) = limb_on_a_flange(&profile, 16);
        let limb_profile = Profile::new(&mesh, &limb).expect("a rim");
        let wrist = limb_profile.widening(0.0, limb_profile.length).expect("a wrist");
        let (near, far) = cut_at(&limb_profile, wrist);
        let top = |vertices: &[u32]| vertices.iter().map(|&v| mesh.positions[v as usize].z).fold(f64::MIN, f64::max);
        let bottom = |vertices: &[u32]| vertices.iter().map(|&v| mesh.positions[v as usize].z).fold(f64::MAX, f64::min);
        eprintln!("near up to z = {}, far from z = {}", top(&near), bottom(&far));
        assert!(top(&near) < 6.6 && top(&near) >= 6.0, "the limb ends at its wrist: {}", top(&near));
        assert!(bottom(&far) > 6.0 && bottom(&far) <= 7.0, "the hand starts past it: {}", bottom(&far));
        assert_eq!(near.len() + far.len(), limb.len());
    }

    #[test]
    fn a_tube_without_a_widening_stays_one_limb() {
        // A tube tapering from radius 1 to 0.6: no level grows again, nor does it bend.
        let profile: Vec<(f64, f64)> = (0..=18).map(|k| (0.5 * k as f64, 1.0 - 0.4 * k as f64 / 18.0)).collect();
        let (mesh, limb) = limb_on_a_flange(&profile, 16);
        let limb_profile = Profile::new(&mesh, &limb).expect("a rim");
        assert_eq!(limb_profile.widening(0.0, limb_profile.length), None);
        assert_eq!(limb_profile.bend(0.0, limb_profile.length), None);
        assert!(limb_profile.forks().is_empty());
        // Nor does a part with no rim (the whole mesh, attached nowhere) have a profile.
        let all: Vec<u32> = (0..mesh.positions.len() as u32).collect();
        assert!(Profile::new(&mesh, &all).is_none());
    }

    /// A tube of radius 1 bent by a right angle ([`elbow_centers`]) on a flange of radius 4.
    fn elbow() -> (Mesh, Vec<u32>) {
        tube_along(&elbow_centers(), 1.0, 16, 4.0, None)
    }

    #[test]
    fn a_bent_limb_is_cut_at_its_elbow_by_a_plane_across_it() {
        let (mesh, limb) = elbow();
        let profile = Profile::new(&mesh, &limb).expect("a rim");
        let level = profile.bend(0.0, profile.length).expect("a bend");
        let cut = profile.cut(level).unwrap();
        // The elbow's middle: the center (2 − √2, 0, 6 + √2), the limb's direction (1, 0, 1)/√2.
        let middle = DVec3::new(2.0 - 2f64.sqrt(), 0.0, 6.0 + 2f64.sqrt());
        let direction = DVec3::new(1.0, 0.0, 1.0).normalize();
        eprintln!("bend at s = {level:.3}: center {:.3}, normal {:.3}", cut.center, cut.normal);
        assert!(cut.center.distance(middle) < 1.0, "cut at {} for the elbow at {middle}", cut.center);
        assert!(cut.normal.dot(direction) > 0.95, "cut normal {} across the limb {direction}", cut.normal);
        // The plane keeps the two sides apart: no vertex before it on the arm along x, none past
        // it on the upright, and every vertex on the side of the plane it is assigned to.
        let (near, far) = cut_at(&profile, level);
        let p = |v: u32| mesh.positions[v as usize];
        assert!(near.iter().all(|&v| p(v).x < 2.0), "a vertex of the arm before the elbow");
        assert!(far.iter().all(|&v| p(v).z > 6.0), "a vertex of the upright past the elbow");
        let side = |v: u32| (p(v) - cut.center).dot(cut.normal);
        assert!(near.iter().all(|&v| side(v) < 0.0) && far.iter().all(|&v| side(v) >= 0.0));
        // A straight stretch has no bend.
        let upright = profile.cut(0.4 * profile.length).unwrap().level;
        assert_eq!(profile.bend(0.0, upright), None);
    }
}
