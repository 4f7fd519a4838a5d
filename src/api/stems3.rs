//! A 3D input in the answer of `POST /api/render` (docs/serve.md, "3D
//! view"): the page draws it in its own WebGL view (`page/view3d.js`), so
//! the answer carries no picture of it but its stems, as eight numbers a
//! stem, and the layout's volumes, each with its colour.

use serde::Serialize;

use super::shapes::{self, Geometry};
use crate::model::Solid;
use crate::pipeline::{Stems3, View};

/// The 3D part of a render answer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Stems3Json {
    /// Eight numbers a stem: from x, y, z, to x, y, z, width, decision
    /// (0 for an `.lsys`), three decimals; the compact body carries them as
    /// integers (compact.rs).
    pub stems: Vec<f64>,
    /// The last decision (the replay's end).
    pub decisions: u64,
    /// Whether widths are screen pixels (an `.lsys`'s `width`), else canvas
    /// units (a tree's `B`).
    pub width_in_pixels: bool,
    /// `#rrggbb`, or `null` for transparent.
    pub background: Option<String>,
    /// The camera a view starts from, `[az, el]` degrees: `--view`'s
    /// default, so the first picture is the one `stlc render` draws.
    pub view: [f64; 2],
    /// The layout's volumes in painting order (`[]` without a layout).
    pub volumes: Vec<VolumeJson>,
    /// The vertical axis a `Revolve` turns about: the first root's x and
    /// z (`null` without a root).
    pub axis: Option<[f64; 2]>,
}

/// A volume as the page draws it: its geometry, tagged by its STL name,
/// and its colour (`#rrggbb`; white carves).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct VolumeJson {
    #[serde(flatten)]
    solid: SolidJson,
    color: String,
}

#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "type")]
enum SolidJson {
    Box { corner: [f64; 3], size: [f64; 3] },
    Sphere { centre: [f64; 3], r: f64 },
    Ellipsoid { centre: [f64; 3], radii: [f64; 3] },
    Cylinder { base: [f64; 3], r: f64, h: f64 },
    Extrude { shape: Geometry, z1: f64, z2: f64 },
    Revolve { shape: Geometry },
}

fn solid(s: &Solid) -> SolidJson {
    match s {
        Solid::Box { corner, size } => SolidJson::Box {
            corner: *corner,
            size: *size,
        },
        Solid::Sphere { centre, r } => SolidJson::Sphere {
            centre: *centre,
            r: *r,
        },
        Solid::Ellipsoid { centre, radii } => SolidJson::Ellipsoid {
            centre: *centre,
            radii: *radii,
        },
        Solid::Cylinder { base, r, h } => SolidJson::Cylinder {
            base: *base,
            r: *r,
            h: *h,
        },
        Solid::Extrude { shape, z1, z2 } => SolidJson::Extrude {
            shape: shapes::geometry(shape),
            z1: *z1,
            z2: *z2,
        },
        Solid::Revolve { shape } => SolidJson::Revolve {
            shape: shapes::geometry(shape),
        },
    }
}

/// The answer's 3D part for `space`.
pub fn stems3_json(stems3: Stems3, round: fn(f64) -> f64) -> Stems3Json {
    let mut stems = stems3.stems;
    let mut decisions = 0;
    for (i, x) in stems.iter_mut().enumerate() {
        if i % 8 == 7 {
            decisions = decisions.max(*x as u64);
        } else {
            *x = round(*x);
        }
    }
    let volumes = stems3
        .volumes
        .iter()
        .map(|s| VolumeJson {
            solid: solid(&s.solid),
            color: s.color.to_string(),
        })
        .collect();
    Stems3Json {
        stems,
        decisions,
        width_in_pixels: stems3.width_in_pixels,
        background: stems3.background.map(|c| c.to_string()),
        view: [View::DEFAULT.az, View::DEFAULT.el],
        volumes,
        axis: stems3.axis,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn volumes_are_tagged_by_their_stl_names_with_their_colours() {
        let v = VolumeJson {
            solid: solid(&Solid::Revolve {
                shape: crate::model::Shape::Ellipse {
                    x: 1.0,
                    y: 2.0,
                    w: 3.0,
                    h: 4.0,
                },
            }),
            color: "#008000".into(),
        };
        assert_eq!(
            serde_json::to_string(&v).unwrap(),
            r##"{"type":"Revolve","shape":{"type":"Ellipse","x":1.0,"y":2.0,"w":3.0,"h":4.0},"color":"#008000"}"##
        );
        let b = solid(&Solid::Cylinder {
            base: [1.0, 2.0, 3.0],
            r: 4.0,
            h: 5.0,
        });
        assert_eq!(
            serde_json::to_string(&b).unwrap(),
            r#"{"type":"Cylinder","base":[1.0,2.0,3.0],"r":4.0,"h":5.0}"#
        );
    }
}
