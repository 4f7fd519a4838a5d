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
    items: Vec<(f64, Segment)>,
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
        }
    }

    /// Projects and keeps one stem.
    pub fn push(&mut self, s: Segment3) {
        if self.items.len() as u64 >= MAX_VIEW_SEGMENTS {
            self.over = true;
            return;
        }
        let (from, a) = self.projection.project(s.from);
        let (to, b) = self.projection.project(s.to);
        self.items.push((
            (a + b) / 2.0,
            Segment {
                from,
                to,
                order: s.order,
            },
        ));
    }

    /// Projects and keeps one stand-in of the level of detail: a capsule
    /// about `s` reaching `spread` canvas units to either side, standing
    /// for `length` of strokes in `runs` runs, drawn with
    /// [`Turtle::stand_in`] by [`draw_sorted`]. (Its stem's order, under
    /// `BLOT_MARK`, indexes the bush: an `.lsys`'s stems are all of
    /// order 0.)
    pub fn push_stand_in(&mut self, s: Segment3, spread: f64, length: f64, runs: f64) {
        let before = self.items.len();
        self.push(s);
        if let Some(item) = self.items.get_mut(before) {
            item.1.order = BLOT_MARK | self.bushes.len() as u32;
            self.bushes.push(Bush {
                spread,
                length,
                runs,
            });
        }
    }

    /// The projected stems, far to near, ties in the order they came.
    pub fn sorted(self) -> Vec<Segment> {
        self.sorted_with_bushes().0
    }

    /// [`Gathered::sorted`], with the stand-ins' bushes for [`draw_sorted`].
    pub fn sorted_with_bushes(mut self) -> (Vec<Segment>, Vec<Bush>) {
        self.items.sort_by(|a, b| b.0.total_cmp(&a.0));
        let stems = self.items.into_iter().map(|(_, s)| s).collect();
        (stems, self.bushes)
    }
}

/// What a stand-in of a 3D view stands for.
#[derive(Debug, Clone, Copy)]
pub struct Bush {
    /// How far it reaches to either side of its segment, canvas units.
    spread: f64,
    /// The length of its strokes in space, canvas units.
    length: f64,
    /// The runs they come in (one, and one more for each `]` and `f`).
    runs: f64,
}

/// The mean length on the screen of a unit stroke turned every way
/// alike (the mean of `sin` over the sphere): a bush's strokes turn every
/// way, so it inks this share of their length.
const SEEN_SHARE: f64 = std::f64::consts::FRAC_PI_4;

/// The bit of a gathered stem's order that marks a stand-in.
const BLOT_MARK: u32 = 1 << 31;

/// Draws [`Gathered::sorted_with_bushes`] stems into `t`: a stand-in as
/// the bush of its strokes' ink ([`Turtle::stand_in`]; the strokes'
/// length seen on the screen over the projected segment's is its density).
pub fn draw_sorted(stems: &[Segment], bushes: &[Bush], t: &mut dyn Turtle) {
    for s in stems {
        if s.order & BLOT_MARK != 0 {
            let Some(b) = bushes.get((s.order & !BLOT_MARK) as usize) else {
                continue;
            };
            let mut seg = Segment { order: 0, ..*s };
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
        } else {
            t.segment(*s);
        }
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
