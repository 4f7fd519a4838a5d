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
    /// The colours of an input that paints (a palette `.lsys`, an `S=`
    /// ramp, leaves), `#rrggbb`; absent when every stem is in the stroke
    /// colour (the answer is then as before colours).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub colors: Vec<String>,
    /// Each stem's index into `colors` (absent with them).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub stem_colors: Vec<u32>,
    /// The leaves, absent without any.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub leaves: Vec<LeafJson>,
}

/// A leaf (a polygon) as the page draws it: its index into `colors` and
/// its vertices, three numbers each (three decimals).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LeafJson {
    /// Its index into `colors`.
    pub color: u32,
    /// Its vertices: x, y, z each.
    pub points: Vec<f64>,
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
        colors: stems3.colors.iter().map(|c| c.to_string()).collect(),
        stem_colors: stems3.stem_colors,
        leaves: stems3
            .leaves
            .into_iter()
            .map(|(color, points)| LeafJson {
                color,
                points: points
                    .iter()
                    .flat_map(|p| [p.x, p.y, p.z])
                    .map(round)
                    .collect(),
            })
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::api::calls::render;
    use crate::api::{Settings, body::parse};
    use crate::pipeline::ImageFormat;
    use crate::progress::NoProgress;

    /// The 3D part of the served page's answer for `source` of `kind`.
    fn space(kind: &str, source: &str) -> Stems3Json {
        let text = format!(r#"{{"source": {source:?}, "kind": {kind:?}}}"#);
        let body = parse(text.as_bytes()).unwrap();
        let s = Settings::defaults(crate::api::Page::Served);
        let up_to = Some(crate::api::BIG_TREE_STEMS);
        let (answer, _) = render(&body, &s, ImageFormat::Svg, up_to, &mut NoProgress).unwrap();
        answer.stems3.unwrap()
    }

    /// Palette steps and a polygon, worked by hand: `'` steps to the next
    /// colour and stops at the last (section 13); the polygon is filled
    /// with the colour in force, its first vertex where the last stem ends.
    #[test]
    fn a_palette_lsys_s_stems_and_leaf_carry_their_colours() {
        let a = space(
            "lsys",
            "dimensions 3\ngenerations 0\nangle 90\npalette #ff0000 #00ff00\naxiom F'F'F'F{.f.+f.+f.}\n",
        );
        assert_eq!(a.colors, ["#ff0000", "#00ff00", "#000000"]);
        assert_eq!(a.stem_colors, [0, 1, 1, 1]);
        assert_eq!(a.stems.len(), 4 * 8);
        assert_eq!(a.leaves.len(), 1);
        let leaf = &a.leaves[0];
        assert_eq!(leaf.color, 1);
        assert_eq!(leaf.points.len(), 4 * 3, "four vertices");
        assert_eq!(&leaf.points[..3], &a.stems[3 * 8 + 3..3 * 8 + 6]);
        // Without a palette or organs the answer is as before: no colours.
        let plain = space("lsys", "dimensions 3\ngenerations 0\nangle 90\naxiom F+F\n");
        assert!(plain.colors.is_empty() && plain.stem_colors.is_empty() && plain.leaves.is_empty());
        let json = serde_json::to_string(&plain).unwrap();
        assert!(
            !json.contains("colors") && !json.contains("leaves"),
            "{json}"
        );
    }

    /// A dressed tree (an `S=` ramp from black to red over orders 0 to 1,
    /// `P=` leaves): the trunk black, the two branches red, a leaf at each
    /// of the two tips in the ramp's end colour.
    #[test]
    fn a_dressed_tree_s_stems_take_the_ramp_by_order_and_its_tips_leaves() {
        let bed = "T\n(0, 0, 0)\nL=10(0) B=1(0) A=90 S=#000000..#ff0000 P=L\nRULE\nR1: [+F][-F]\n\
                   SEED\nF R1{,}\nENDSEED\nSURFACES\nsurface L { {.f.+f.+f.} }\nENDSURFACES\n";
        let a = space("bed", bed);
        assert_eq!(a.stems.len(), 3 * 8);
        assert_eq!(a.colors, ["#000000", "#ff0000", "#ff0000"]);
        assert_eq!(a.stem_colors, [0, 1, 1]);
        assert_eq!(a.leaves.len(), 2);
        for (leaf, tip) in a.leaves.iter().zip([1, 2]) {
            assert_eq!(leaf.color, 2, "the leaves' colour is the palette's last");
            assert_eq!(leaf.points.len(), 12);
            assert_eq!(&leaf.points[..3], &a.stems[tip * 8 + 3..tip * 8 + 6]);
        }
        // Its OD, grown on the page: the stems as growth placed them (with
        // their decisions), each in the colour of the drawn stem there.
        let od = space("od", &bed.replace("R1{,}", "[I 1 R1]"));
        assert_eq!(od.stems.len(), 3 * 8);
        assert_eq!(od.decisions, 1);
        assert_eq!((od.colors, od.stem_colors), (a.colors, a.stem_colors));
        assert_eq!(od.leaves, a.leaves);
    }

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
