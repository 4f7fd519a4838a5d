//! The grower: an Outline Description into a Branch-Expansion Description
//! under space occupancy, breadth-first or depth-first.
//!
//! `docs/growth.md` states the semantics this module implements; in short:
//!
//! - **Growth points** are the rule references of the seed: bare ones (`R1`,
//!   no count) and `[I n R1]` (n levels), at the top level of the seed or in
//!   a slot of a term written out in the seed (`R1{R1,}`). Everything else in
//!   the seed (drawing components, fixed figures, written terms) is drawn as
//!   given and occupies space without being tested.
//! - **Applying** rule `X` at a growth point of order `c` draws all of `X`
//!   (trunk, fixed figures, every branch) from the turtle state there, at
//!   order `c+1`. It succeeds only if that order has a positive length and
//!   width, the order does not exceed `--max-depth`, every segment lies in
//!   the open interior of the layout region ([`region::Region`]) and keeps the
//!   clearance from every segment already placed and from the application's
//!   own earlier segments ([`occupancy::conflicts`], with its joint
//!   exception). On success its segments are placed and the tip of each
//!   branch becomes a growth point for the rule named at the branch's end, or
//!   `X` again, with one level fewer if counted. On failure the slot stays
//!   empty (a failed growth point of the seed is left out of the BED).
//! - **Order of decisions.** `bfs`: a FIFO queue, so every growth point of a
//!   level is decided before the next level, in the order the points were
//!   made (branches in written order); the seed's points are level 1. `dfs`:
//!   a stack, so a branch's whole subtree is decided before its next
//!   sibling. Neither recurses.
//! - **The seed** is walked once in written order. Its drawing is laid down
//!   before its growth points are decided whenever the positions of that
//!   drawing cannot depend on a decision: a growth point is deferred unless
//!   its rule moves or turns the turtle outside its branches *and* more seed
//!   follows it before the enclosing `]`; such a point (and every deferred
//!   one before it) is decided when the walk reaches it, because the drawing
//!   after it starts where its trunk ends.
//! - **Stops.** Counts, decrements, the region and clearance end growth
//!   naturally. `--max-stems` (stems = drawn segments, the seed's included)
//!   stops all growth with a warning when the next application would pass
//!   it; growth applications are limited to the same number (rules that
//!   draw nothing). Growth with no LAYOUT, where a growth point can branch
//!   forever with neither count nor decrement, is refused unless
//!   `--max-stems` was given explicitly ([`GrowOptions::max_stems_explicit`]).
//!
//! The steps, one file each: `seed.rs` flattens the seed into drawing
//! operations and growth points, and writes the grown seed back;
//! `bounded.rs` refuses growth that nothing bounds; `grower.rs` draws the
//! seeds (one per root of a forest) and decides the growth points, choosing
//! among a rule's alternatives by [`crate::choice`], once for the plane and
//! for space: `plane.rs` says what it draws with (the `Space` trait, and
//! the 2D turtle and region), [`grow3`] the 3D turtle with `D=` and the
//! volumes (`stl-language.md` section 11); `rules.rs` works out what growth
//! needs of each rule; `tree.rs` holds what it
//! records (the grown tree, the budget spent against the limits); [`region`] and [`occupancy`] answer
//! where a segment may go (they alone know the spatial index).

mod bounded;
pub mod colonize;
pub mod explain;
pub mod grow3;
mod grower;
pub mod occupancy;
mod options;
mod plane;
pub mod region;
mod rules;
mod seed;
mod tree;

use crate::bed::Bed;
use crate::diag::{Diagnostic, Diagnostics, GrowError};
use crate::limits::Bound;
use crate::model::{Description, Format, Loc, Seed};
use crate::progress::Progress;
use crate::turtle::Point;
use crate::turtle::turtle3::Point3;

use explain::RuleTally;
use grow3::Volume;
use grow3::region::Region3;
use grower::Grower;
use plane::{Plane, Space};

use occupancy::Backend;
use region::Region;

pub use crate::model::GrowthOrder;
pub use options::{DEFAULT_CLEARANCE_FRACTION, GrowOptions, default_clearance};
use options::{SEED_STEMS, span_of};

/// The result of growth: the BED and any warnings (a limit that stopped growth).
#[derive(Debug, Clone, PartialEq)]
pub struct Grown {
    /// The Branch-Expansion Description, validated and measured.
    pub bed: Bed,
    /// Warnings, e.g. `--max-stems` reached.
    pub warnings: Vec<Diagnostic>,
    /// Number of stems (segments) in the grown tree.
    pub stems: u64,
    /// What became of each rule's tries, by [`crate::model::RuleId`]
    /// (each alternative on its own): tries, fits, misses by reason, the
    /// first miss ([`explain`]).
    pub tallies: Vec<RuleTally>,
}

/// Grows `od` into a BED, with the R-tree occupancy index.
pub fn grow(
    od: &Description,
    opts: &GrowOptions,
    progress: &mut dyn Progress,
) -> Result<Grown, Diagnostics> {
    grow_with(od, opts, Backend::Rstar, progress)
}

/// One stem as growth placed it: what a replay of growth shows, in order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlacedStem {
    /// Where the turtle was.
    pub from: Point,
    /// Where it went.
    pub to: Point,
    /// The third coordinates of `from` and `to` (0 in a 2D tree).
    pub z: [f64; 2],
    /// The stroke width, canvas units.
    pub width: f64,
    /// Which decision placed it: 0 for the seed's own drawing, `k` for the
    /// `k`-th successful rule application (in `bfs` level by level, in
    /// `dfs` a branch's subtree before its sibling).
    pub decision: u64,
}

/// Grows `od` like [`grow`] and also returns every stem in the order growth
/// placed it (the seed's drawing first, then each successful application's
/// stems in drawing order). The BED is the same as [`grow`]'s; the list
/// costs memory in proportion to the stems, so only front ends that replay
/// growth ask for it.
pub fn grow_traced(
    od: &Description,
    opts: &GrowOptions,
    progress: &mut dyn Progress,
) -> Result<(Grown, Vec<PlacedStem>), Diagnostics> {
    if od.is_3d() {
        let (grown, trace) = grow_3d(od, opts, true, progress)?;
        return Ok((grown, placed(trace, |s| [s.a[2], s.b[2]])));
    }
    let (grown, trace) = grow_inner(od, opts, Backend::Rstar, true, progress)?;
    Ok((grown, placed(trace, |_| [0.0; 2])))
}

/// The stems of a trace, each with the z of its ends (`z`).
fn placed<const N: usize>(
    trace: Trace<N>,
    z: impl Fn(&occupancy::Cap<N>) -> [f64; 2],
) -> Vec<PlacedStem> {
    trace
        .unwrap_or_default()
        .into_iter()
        .map(|(s, decision)| PlacedStem {
            from: Point::new(s.a[0], s.a[1]),
            to: Point::new(s.b[0], s.b[1]),
            z: z(&s),
            width: 2.0 * s.r,
            decision,
        })
        .collect()
}

/// Grows `od` into a BED with a chosen occupancy index: [`Backend`] has
/// one, the R*-tree, since the Delaunay experiment was measured and
/// removed (`docs/dependencies.md`); the parameter names what a benchmark
/// measures.
pub fn grow_with(
    od: &Description,
    opts: &GrowOptions,
    backend: Backend,
    progress: &mut dyn Progress,
) -> Result<Grown, Diagnostics> {
    if od.is_3d() {
        return grow_3d(od, opts, false, progress).map(|(g, _)| g);
    }
    grow_inner(od, opts, backend, false, progress).map(|(g, _)| g)
}

/// The trace of placed stems, with their decisions, when asked for.
type Trace<const N: usize> = Option<Vec<(occupancy::Cap<N>, u64)>>;

/// The roots of `od`, in root order, with their places in the text.
type Roots<'a> = Vec<((f64, f64), &'a Loc)>;

/// Grows a 2D description.
fn grow_inner(
    od: &Description,
    opts: &GrowOptions,
    backend: Backend,
    trace: bool,
    progress: &mut dyn Progress,
) -> Result<(Grown, Trace<2>), Diagnostics> {
    grow_in(od, opts, backend, trace, progress, |roots: &Roots<'_>| {
        let region = match &od.layout {
            Some(l) => Some(Region::from_layout(l, opts.limits.max_layout_vertices)?),
            None => None,
        };
        let points = roots.iter().map(|&((x, y), _)| Point::new(x, y)).collect();
        Ok(Plane::new(od, region, points))
    })
}

/// Grows a 3D description (`stl-language.md` section 11).
fn grow_3d(
    od: &Description,
    opts: &GrowOptions,
    trace: bool,
    progress: &mut dyn Progress,
) -> Result<(Grown, Trace<3>), Diagnostics> {
    grow_in(
        od,
        opts,
        Backend::Rstar,
        trace,
        progress,
        |roots: &Roots<'_>| {
            let z = |t: usize| match t {
                0 => od.root_z,
                t => od.forest[t - 1].root_z,
            };
            let points: Vec<Point3> = (0..roots.len())
                .map(|t| Point3::new(roots[t].0.0, roots[t].0.1, z(t).unwrap_or(0.0)))
                .collect();
            let region = match &od.layout {
                Some(l) => Some(Region3::from_layout(
                    l,
                    [points[0].x, points[0].z],
                    opts.limits.max_layout_vertices,
                )?),
                None => None,
            };
            Ok(Volume::new(od, region, points))
        },
    )
}

/// Grows `od` in the space `make` builds for its roots.
fn grow_in<'a, const N: usize, S: Space<N>>(
    od: &'a Description,
    opts: &GrowOptions,
    backend: Backend,
    trace: bool,
    progress: &mut dyn Progress,
    make: impl FnOnce(&Roots<'a>) -> Result<S, Diagnostics>,
) -> Result<(Grown, Trace<N>), Diagnostics>
where
    occupancy::Cap<N>: occupancy::Dim,
{
    let seed = od.effective_seed().ok_or_else(|| {
        Diagnostic::error(GrowError::NothingToGrow)
            .with_help("declare a rule after RULE, or write a SEED")
    })?;
    let clearance = opts
        .clearance
        .or(od.params.clearance)
        .unwrap_or_else(|| default_clearance(&od.params));
    if !clearance.is_finite() || clearance < 0.0 {
        return Err(
            Diagnostic::error(GrowError::BadClearance { value: clearance })
                .with_help("give C= (or --clearance) a value such as 1")
                .into(),
        );
    }
    // A seed that alone passes the stem limit is refused before any work
    // (a generated seed of millions of stems would otherwise be flattened
    // and drawn into the occupancy index first).
    let trees = 1 + od.forest.len() as u64;
    let seed_stems = seed::drawn_stems(od, &seed).saturating_mul(trees);
    if seed_stems > opts.limits.max_stems {
        return Err(Bound::Stems
            .exceeded_by(SEED_STEMS, seed_stems, opts.limits.max_stems)
            .with_help(Bound::Stems.raise() + ", or draw a smaller seed")
            .into());
    }
    let flat = seed::flatten(od, &seed)?;
    bounded::check_bounded(od, &flat.gps, opts)?;

    // The roots, in root order (one for a tree, several for a forest).
    let roots: Roots<'_> = std::iter::once((od.root, &od.root_loc))
        .chain(od.forest.iter().map(|t| (t.root, &t.root_loc)))
        .collect();
    let space = make(&roots)?;
    let zs: Vec<Option<f64>> = std::iter::once(od.root_z)
        .chain(od.forest.iter().map(|t| t.root_z))
        .collect();
    for (t, &((x, y), loc)) in roots.iter().enumerate() {
        if !space.covers_root(t) {
            let (z, what) = match zs[t] {
                Some(z) => (Some(z), "volume"),
                None => (None, "layout shape"),
            };
            let mut d = Diagnostic::error(GrowError::RootOutside { x, y, z }).with_help(format!(
                "move the root into a coloured (non-white) {what}, or change the LAYOUT"
            ));
            if let Some(s) = span_of(loc) {
                d = d.with_span(s).with_label("the root");
            }
            return Err(d.into());
        }
    }

    let zs: Vec<f64> = zs.iter().map(|z| z.unwrap_or(0.0)).collect();
    let shared = shared_roots(&roots, &zs);

    let mut g = Grower::new(
        od,
        opts,
        backend,
        clearance,
        space,
        flat.gps.len(),
        roots.len(),
    );
    if trace {
        g.trace = Some(Vec::new());
    }
    progress.start("stems", opts.limits.max_stems);
    let walked = g.grow_trees(&flat, roots.len(), progress);
    progress.finish();
    walked?;

    let placed = g.trace.take();
    let (tree, budget, tallies) = g.finish();
    let owner = seed::owners(&tree);
    let mut grown_seeds = (0..roots.len()).map(|t| {
        let (items, terms) = seed::grown_seed(od, &tree, &seed, t, &owner);
        Seed {
            items,
            terms,
            loc: seed.loc.clone(),
        }
    });
    let first = grown_seeds.next();
    let forest = od
        .forest
        .iter()
        .zip(grown_seeds)
        .map(|(t, s)| crate::model::Tree {
            root: t.root,
            root_z: t.root_z,
            root_loc: t.root_loc.clone(),
            seed: Some(s),
        })
        .collect();
    let mut params = od.params.clone();
    params.clearance = Some(clearance);
    let desc = Description {
        format: Format::Bed,
        name: od.name.clone(),
        name_loc: od.name_loc.clone(),
        root: od.root,
        root_z: od.root_z,
        root_loc: od.root_loc.clone(),
        params,
        rules: od.rules.clone(),
        seed: first,
        layout: od.layout.clone(),
        forest,
        surfaces: od.surfaces.clone(),
    };
    let grown = Grown {
        bed: Bed::new(desc, &opts.limits)?,
        warnings: shared
            .into_iter()
            .chain(budget.warnings)
            .chain(explain::never_fitted(od, &tallies))
            .chain(explain::ran_out(od, &tallies, budget.stems))
            .collect(),
        stems: budget.stems,
        tallies,
    };
    Ok((grown, placed))
}

/// A warning for the first root on the very point of an earlier one (two
/// clicks of the Root tool in one place, a point typed twice), if any: its
/// tree starts on top of the earlier tree and finds its room taken. `zs`
/// are the roots' third coordinates (0 in 2D): 3D roots over one another
/// at different depths are different points.
fn shared_roots(roots: &[((f64, f64), &Loc)], zs: &[f64]) -> Option<Diagnostic> {
    // `+ 0.0` makes -0 and 0 one point.
    let key = |(x, y): (f64, f64), z: f64| [x, y, z].map(|c| (c + 0.0).to_bits());
    let mut seen = std::collections::BTreeMap::new();
    for (i, (&(point, loc), &z)) in roots.iter().zip(zs).enumerate() {
        let Some(&first) = seen.get(&key(point, z)) else {
            seen.insert(key(point, z), i);
            continue;
        };
        let mut d = Diagnostic::warning(GrowError::SharedRoot {
            root: i + 1,
            first: first + 1,
        })
        .with_help("give each tree its own point on the root line, or delete the repeated root");
        if let Some(s) = span_of(loc) {
            d = d.with_span(s).with_label("this root");
        }
        if let Some(s) = span_of(roots[first].1) {
            d = d.with_note_at(s, "the earlier root");
        }
        return Some(d);
    }
    None
}
