//! Views of a 3D drawing (`--view AZ,EL`): orthographic projection to 2D
//! segments, drawn far to near, handed to the 2D renderers.
//!
//! The camera (`../shared/stl-language.md` section 11): from the front
//! view (`0,0`: looking along +z, x right and y down as on the canvas), it
//! turns AZ degrees about the vertical axis, positive moving it toward +x,
//! then EL degrees upward (positive: looking from above). With
//! `f = (-sin AZ cos EL, sin EL, cos AZ cos EL)` the direction it looks,
//! `r = (cos AZ, 0, sin AZ)` its right and `u = r x f` its up, a point p
//! is drawn at `(p . r, -(p . u))` and lies at depth `p . f`. Stems are
//! drawn far to near by the depth of their midpoints, ties in drawing
//! order (a stable sort), so `--view 0,0` of a planar drawing is the 2D
//! picture: its depths are all 0 and its projected points are its x and y
//! exactly (cos and sin of multiples of 90 degrees are exact).

use crate::color::Rgb;
use crate::diag::{Diagnostic, Diagnostics, RenderError};
use crate::turtle::turtle3::{Point3, Segment3, cos_sin};
use crate::turtle::{Footprint, Point, Segment, StandIn, Turtle};

/// A view direction, degrees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    /// Azimuth: the camera turned about the vertical axis, toward +x.
    pub az: f64,
    /// Elevation: the camera raised (looking from above).
    pub el: f64,
}

impl View {
    /// The view of 3D inputs when none is asked for: `30,20`.
    pub const DEFAULT: View = View { az: 30.0, el: 20.0 };

    /// The front view, `0,0`.
    pub const FRONT: View = View { az: 0.0, el: 0.0 };

    /// Reads `AZ,EL` (two finite numbers of degrees).
    pub fn parse(text: &str) -> Option<View> {
        let (a, e) = text.split_once(',')?;
        let az: f64 = a.trim().parse().ok()?;
        let el: f64 = e.trim().parse().ok()?;
        (az.is_finite() && el.is_finite()).then_some(View { az, el })
    }

    /// The projection of this view.
    pub fn projection(&self) -> Projection {
        let (ca, sa) = cos_sin(self.az);
        let (ce, se) = cos_sin(self.el);
        Projection {
            right: [ca, 0.0, sa],
            // -(up): up = (-sa se, -ce, ca se), the screen's y grows down.
            down: [sa * se, ce, -(ca * se)],
            forward: [-(sa * ce), se, ca * ce],
        }
    }
}

/// An orthographic projection: screen x, screen y (down) and depth (away
/// from the camera) of a 3D point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    right: [f64; 3],
    down: [f64; 3],
    forward: [f64; 3],
}

impl Projection {
    /// The direction away from the camera.
    pub fn forward(&self) -> [f64; 3] {
        self.forward
    }

    /// The point on the screen, and its depth.
    #[inline]
    pub fn project(&self, p: Point3) -> (Point, f64) {
        let d = |v: [f64; 3]| p.x * v[0] + p.y * v[1] + p.z * v[2];
        (Point::new(d(self.right), d(self.down)), d(self.forward))
    }
}

/// Most stems a 3D view holds: drawing far to near sorts them all, 48
/// bytes each (about 480 MB at this many).
pub const MAX_VIEW_SEGMENTS: u64 = 10_000_000;

/// The refusal of a view with more than [`MAX_VIEW_SEGMENTS`] stems.
pub fn view_too_large(segments: String) -> Diagnostics {
    Diagnostic::error(RenderError::ViewTooLarge {
        segments,
        limit: MAX_VIEW_SEGMENTS,
    })
    .with_help("a 3D view sorts every stem far to near and so holds them all: use a smaller depth")
    .into()
}

/// 3D stems gathered for a view: projected as they come, sorted far to
/// near by [`Gathered::sorted`].
pub struct Gathered {
    projection: Projection,
    /// Depth, projected stem, and its look's index in `looks` (`NO_LOOK`
    /// for a plain stem).
    items: Vec<(f64, Segment, u32)>,
    /// Colours and polygons (a `.lsys` with organs): each tagged item's.
    looks: Option<Looks>,
    /// The stand-ins' bushes, indexed from their stems' orders.
    bushes: Vec<Bush>,
    /// More stems came than [`MAX_VIEW_SEGMENTS`] (the rest were dropped).
    pub over: bool,
}

impl Gathered {
    /// Nothing gathered yet, for `view`.
    pub fn new(view: View) -> Self {
        Gathered {
            projection: view.projection(),
            items: Vec::new(),
            bushes: Vec::new(),
            over: false,
            looks: None,
        }
    }

    /// Nothing gathered yet, for `view`, of a drawing with colours from
    /// `palette` (empty: none) and polygons: each stem and polygon keeps
    /// its colour index through the sort.
    pub fn with_organs(view: View, palette: Vec<Rgb>) -> Self {
        let mut g = Gathered::new(view);
        g.looks = Some(Looks {
            palette,
            paint: 0,
            each: Vec::new(),
        });
        g
    }

    /// Later stems and polygons have colour index `i`.
    pub fn paint(&mut self, i: usize) {
        if let Some(l) = &mut self.looks {
            l.paint = i;
        }
    }

    /// Projects and keeps one polygon, at the mean depth of its vertices.
    pub fn push_polygon(&mut self, points: &[Point3]) {
        if self.items.len() as u64 >= MAX_VIEW_SEGMENTS {
            self.over = true;
            return;
        }
        let Some(l) = &mut self.looks else { return };
        let mut depth = 0.0;
        let flat: Vec<Point> = points
            .iter()
            .map(|&p| {
                let (q, d) = self.projection.project(p);
                depth += d;
                q
            })
            .collect();
        let tag = l.each.len() as u32;
        l.each.push((l.paint, Some(flat)));
        let at = Point::new(0.0, 0.0);
        let seg = Segment {
            from: at,
            to: at,
            order: 0,
        };
        self.items
            .push((depth / points.len().max(1) as f64, seg, tag));
    }

    /// Projects and keeps one stem.
    pub fn push(&mut self, s: Segment3) {
        if self.items.len() as u64 >= MAX_VIEW_SEGMENTS {
            self.over = true;
            return;
        }
        let (from, a) = self.projection.project(s.from);
        let (to, b) = self.projection.project(s.to);
        let tag = match &mut self.looks {
            Some(l) => {
                l.each.push((l.paint, None));
                (l.each.len() - 1) as u32
            }
            None => NO_LOOK,
        };
        self.items.push((
            (a + b) / 2.0,
            Segment {
                from,
                to,
                order: s.order,
            },
            tag,
        ));
    }

    /// Projects and keeps one stand-in of the level of detail: a capsule
    /// about `s` reaching `spread` canvas units to either side, standing
    /// for `length` of strokes in `runs` runs, drawn with
    /// [`Turtle::stand_in`] by [`draw_sorted`] (or [`Sorted::draw`]) in
    /// `color` (`None`: the colour in force) with strokes of stem order
    /// `order`. (Its stem's order, under `BLOT_MARK`, indexes the bush.)
    pub fn push_stand_in(&mut self, s: Segment3, bush: Bush) {
        let before = self.items.len();
        self.push(s);
        if let Some(item) = self.items.get_mut(before) {
            item.1.order = BLOT_MARK | self.bushes.len() as u32;
            self.bushes.push(bush);
        }
    }

    /// The projected stems, far to near, ties in the order they came.
    pub fn sorted(self) -> Vec<Segment> {
        self.sorted_with_bushes().0
    }

    /// [`Gathered::sorted`], with the stand-ins' bushes for [`draw_sorted`].
    pub fn sorted_with_bushes(mut self) -> (Vec<Segment>, Vec<Bush>) {
        self.items.sort_by(|a, b| b.0.total_cmp(&a.0));
        let stems = self.items.into_iter().map(|(_, s, _)| s).collect();
        (stems, self.bushes)
    }

    /// The stems and polygons of [`Gathered::with_organs`], far to near,
    /// ties in the order they came, each with its look.
    pub fn sorted_organs(mut self) -> Sorted {
        self.items.sort_by(|a, b| b.0.total_cmp(&a.0));
        let looks = self.looks.unwrap_or_default();
        Sorted {
            items: self.items.into_iter().map(|(_, s, t)| (s, t)).collect(),
            looks,
            bushes: self.bushes,
        }
    }
}

/// A look's index of an item that has none.
const NO_LOOK: u32 = u32::MAX;

/// The colours and polygons of gathered items.
#[derive(Debug, Clone, Default)]
struct Looks {
    palette: Vec<Rgb>,
    /// The colour index in force.
    paint: usize,
    /// Each tagged item's colour index, and its vertices if a polygon.
    each: Vec<(usize, Option<Vec<Point>>)>,
}

/// Gathered stems and polygons, sorted far to near
/// ([`Gathered::sorted_organs`]).
pub struct Sorted {
    items: Vec<(Segment, u32)>,
    looks: Looks,
    bushes: Vec<Bush>,
}

impl Sorted {
    /// How many stems and stand-ins (polygons not counted).
    pub fn stems(&self) -> u64 {
        self.items
            .iter()
            .filter(|(_, t)| {
                self.looks
                    .each
                    .get(*t as usize)
                    .is_none_or(|l| l.1.is_none())
            })
            .count() as u64
    }

    /// Draws every stem and polygon into `t`, far to near, each in its
    /// colour ([`Turtle::paint`], [`Turtle::polygon`]), a stand-in in its
    /// own where it has one.
    pub fn draw(&self, t: &mut dyn Turtle) {
        let mut current = None;
        for (s, tag) in &self.items {
            if s.order & BLOT_MARK != 0
                && let Some(b) = self.bushes.get((s.order & !BLOT_MARK) as usize)
                && let Some(c) = b.color
            {
                t.paint(c);
                current = None;
                draw_bush(s, b, t);
                continue;
            }
            let Some((i, poly)) = self.looks.each.get(*tag as usize) else {
                t.segment(*s);
                continue;
            };
            if current != Some(*i)
                && let Some(&c) = self.looks.palette.get(*i)
            {
                t.paint(c);
                current = Some(*i);
            }
            match poly {
                Some(points) => t.polygon(points),
                None if s.order & BLOT_MARK != 0 => {
                    if let Some(b) = self.bushes.get((s.order & !BLOT_MARK) as usize) {
                        draw_bush(s, b, t);
                    }
                }
                None => t.segment(*s),
            }
        }
    }
}

/// What a stand-in of a 3D view stands for.
#[derive(Debug, Clone, Copy)]
pub struct Bush {
    /// How far it reaches to either side of its segment, canvas units.
    pub spread: f64,
    /// The length of its strokes in space, canvas units.
    pub length: f64,
    /// The runs they come in (one, and one more for each `]` and `f`).
    pub runs: f64,
    /// The colour its ink mixes to (`None`: the colour in force).
    pub color: Option<Rgb>,
    /// The stem order of its strokes (their width; 0: the picture's).
    pub order: u32,
}

/// The mean length on the screen of a unit stroke turned every way
/// alike (the mean of `sin` over the sphere): a bush's strokes turn every
/// way, so it inks this share of their length.
pub const SEEN_SHARE: f64 = std::f64::consts::FRAC_PI_4;

/// The bit of a gathered stem's order that marks a stand-in.
const BLOT_MARK: u32 = 1 << 31;

/// Draws [`Gathered::sorted_with_bushes`] stems into `t`: a stand-in as
/// the bush of its strokes' ink ([`Turtle::stand_in`]; the strokes'
/// length seen on the screen over the projected segment's is its density).
pub fn draw_sorted(stems: &[Segment], bushes: &[Bush], t: &mut dyn Turtle) {
    for s in stems {
        if s.order & BLOT_MARK != 0 {
            if let Some(b) = bushes.get((s.order & !BLOT_MARK) as usize) {
                draw_bush(s, b, t);
            }
        } else {
            t.segment(*s);
        }
    }
}

/// Draws the bush `b` of the stand-in stem `s` ([`Turtle::stand_in`]).
fn draw_bush(s: &Segment, b: &Bush, t: &mut dyn Turtle) {
    let mut seg = Segment {
        order: b.order,
        ..*s
    };
    let chord = libm::hypot(seg.to.x - seg.from.x, seg.to.y - seg.from.y);
    // Seen end-on, the segment is a point: a short one across the
    // screen carries the ink.
    let chord = if chord > 1e-9 * (1.0 + b.spread) {
        chord
    } else {
        let e = 1e-6 * (1.0 + b.spread);
        seg.to = crate::turtle::Point::new(seg.from.x + e, seg.from.y);
        e
    };
    let density = b.length * SEEN_SHARE / chord;
    if density.is_finite() {
        t.stand_in(&StandIn {
            seg,
            density,
            footprint: Some(Footprint {
                spread: b.spread,
                runs: b.runs,
            }),
            sample: None,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64, z: f64) -> Point3 {
        Point3::new(x, y, z)
    }

    #[test]
    fn the_front_view_is_the_canvas() {
        let pr = View::FRONT.projection();
        assert_eq!(
            pr.project(p(3.5, -2.25, 7.0)),
            (Point::new(3.5, -2.25), 7.0)
        );
    }

    #[test]
    fn turning_toward_plus_x_shows_z_to_the_right() {
        // From +x (az 90) the camera looks along -x: +z is to its right,
        // and +x is nearest (depth -1).
        let pr = View { az: 90.0, el: 0.0 }.projection();
        assert_eq!(pr.project(p(0.0, 0.0, 1.0)).0, Point::new(1.0, 0.0));
        assert_eq!(pr.project(p(1.0, 0.0, 0.0)).1, -1.0);
        // From above (el 90) the camera looks down (+y): the far side
        // (+z) is up the screen, and a point below (+y) is far.
        let pr = View { az: 0.0, el: 90.0 }.projection();
        assert_eq!(pr.project(p(0.0, 0.0, 1.0)).0, Point::new(0.0, -1.0));
        assert_eq!(pr.project(p(0.0, 1.0, 0.0)).1, 1.0);
    }

    #[test]
    fn far_stems_come_first_and_ties_keep_their_order() {
        let mut g = Gathered::new(View::FRONT);
        let s = |z: f64, x: f64| Segment3 {
            from: p(x, 0.0, z),
            to: p(x, 1.0, z),
            order: 0,
        };
        for (z, x) in [(0.0, 1.0), (5.0, 2.0), (0.0, 3.0), (-1.0, 4.0)] {
            g.push(s(z, x));
        }
        let xs: Vec<f64> = g.sorted().iter().map(|s| s.from.x).collect();
        assert_eq!(xs, [2.0, 1.0, 3.0, 4.0]);
    }

    #[test]
    fn views_are_read_as_two_numbers() {
        assert_eq!(View::parse("30,20"), Some(View::DEFAULT));
        assert_eq!(
            View::parse(" -45 , 10.5"),
            Some(View {
                az: -45.0,
                el: 10.5
            })
        );
        assert_eq!(View::parse("30"), None);
        assert_eq!(View::parse("a,b"), None);
        assert_eq!(View::parse("inf,0"), None);
    }
}
