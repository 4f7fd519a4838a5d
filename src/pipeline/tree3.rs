//! A 3D tree in the pipeline (docs/3d.md): a BED whose roots have three
//! coordinates (read, or grown from a 3D OD) is drawn by
//! [`crate::interpret::bed3`] with the 3D turtle; its pictures are views
//! (`--view AZ,EL`), its mesh has its stems in space, its `stats` a 3D box
//! and end. The 3D `.lsys` has the same in `lsys3.rs`; this file only adds
//! trees, so the two read side by side.

use std::fmt::Write as _;
use std::io::Write;

use super::stats3::{box_text, list, num};
use super::{Rendered, Scene, style};
use crate::bed::Bed;
use crate::diag::{Diagnostic, Diagnostics, RenderError};
use crate::interpret::bed3::{bounds3, draw3};
use crate::interpret::dress::{Dress, gather};
use crate::interpret::lsys::param::Mark;
use crate::interpret::stats::STATS_TRAVERSAL_SYMBOLS;
use crate::limits::Limits;
use crate::progress::{NoProgress, Phase, Progress};
use crate::render::view::{Gathered, MAX_VIEW_SEGMENTS, View, view_too_large};
use crate::render::{Frame, RenderOptions, render_framed};
use crate::turtle::Turtle;
use crate::turtle::turtle3::Segment3;

/// The 3D tree of a scene, if it is one.
pub(crate) fn bed3(scene: &Scene) -> Option<&Bed> {
    scene.bed().filter(|b| b.description().is_3d())
}

/// Draws a 3D tree, `bed`, the scene's, seen from `view`.
pub(crate) fn render_view(
    scene: &Scene,
    bed: &Bed,
    view: View,
    look: &super::Look,
    opts: &RenderOptions,
    out: &mut dyn Write,
    progress: &mut dyn Progress,
) -> Result<Rendered, Diagnostics> {
    let stems = bed.size().stems;
    if stems > MAX_VIEW_SEGMENTS {
        return Err(view_too_large(stems.to_string()));
    }
    let style = style(scene, look);
    let (sorted, stems) = if crate::interpret::dress::dresses(bed.description()) {
        // Colours by order and leaves (section 13), each kept through the sort.
        let segs = gather(
            bed,
            scene.derivation,
            &scene.limits,
            &mut Phase::new(progress, "drawing"),
        )?;
        let dress = Dress::new(bed.description(), &segs, style.stroke);
        let mut gathered = Gathered::with_organs(view, dress.palette().to_vec());
        dress.emit(&mut |m| match m {
            Mark::Step(s, _) => gathered.push(s),
            Mark::Paint(i) => gathered.paint(i),
            Mark::Polygon(points) => gathered.push_polygon(points),
        })?;
        if gathered.over {
            return Err(view_too_large(format!("more than {MAX_VIEW_SEGMENTS}")));
        }
        (Some(gathered.sorted_organs()), Vec::new())
    } else {
        let mut gathered = Gathered::new(view);
        draw3(
            bed,
            scene.derivation,
            &scene.limits,
            &mut |s| gathered.push(s),
            &mut Phase::new(progress, "drawing"),
        )?;
        (None, gathered.sorted())
    };
    let n = sorted.as_ref().map_or(stems.len() as u64, |s| s.stems());
    let mut drawing = |t: &mut dyn Turtle, _: &mut dyn Progress| {
        match &sorted {
            Some(s) => s.draw(t),
            None => {
                for s in &stems {
                    t.segment(*s);
                }
            }
        }
        Ok(())
    };
    // Framed by its volumes' outlines, as a 2D picture by its layout.
    let desc = bed.description();
    let outlines = match &desc.layout {
        Some(layout) => {
            let axis = [desc.root.0, desc.root_z.unwrap_or(0.0)];
            crate::render::volumes::outlines(layout, axis, &view.projection())
        }
        None => Vec::new(),
    };
    let frame = match crate::render::fills_bbox(&outlines) {
        Some(b) => Frame::View {
            view: crate::render::layout_frame(b, desc.params.width.base),
            segments: Some(n),
        },
        None => Frame::Fit,
    };
    let underlay: Vec<_> = if look.show_layout != super::ShowLayout::No {
        outlines.into_iter().map(faint).collect()
    } else {
        Vec::new()
    };
    render_framed(&mut drawing, frame, &underlay, &style, opts, out, progress)?;
    let mut warnings = Vec::new();
    if n == 0 {
        warnings.push(
            Diagnostic::warning(RenderError::NothingDrawn)
                .with_help("check the seed: only `F` draws (and in an .od, a rule that grows)"),
        );
    }
    Ok(Rendered {
        segments: n,
        count: Some(n.to_string()),
        warnings,
    })
}

/// A volume's outline painted faintly: its colour a third of the way from
/// white (white, which carves, stays white), so the tree stands out over
/// volumes that overlap on the screen.
fn faint(mut fill: crate::turtle::Fill) -> crate::turtle::Fill {
    let [r, g, b] =
        [fill.color.r, fill.color.g, fill.color.b].map(|c| (255 - (255 - u16::from(c)) / 3) as u8);
    fill.color = crate::color::Rgb::new(r, g, b);
    fill
}

/// Hands a 3D tree's stems to `sink` (for a mesh); `false` if the scene
/// is no 3D tree.
pub(crate) fn draw_tree3(
    scene: &Scene,
    sink: &mut dyn FnMut(Segment3),
    progress: &mut dyn Progress,
) -> Result<bool, Diagnostics> {
    let Some(bed) = bed3(scene) else {
        return Ok(false);
    };
    draw3(bed, scene.derivation, &scene.limits, sink, progress)?;
    Ok(true)
}

/// `stats` of a 3D BED: its symbols (turtle operations, one `Enter` and
/// one `Leave` per rule application included, as the BED's measure counts
/// them) and stems, and the box `[minx, miny, minz, maxx, maxy, maxz]` of
/// its stems and the turtle's `end` `[x, y, z]` in canvas units (the
/// BED's own lengths, from its roots), by drawing it when it has at most
/// `min(--max-symbols, STATS_TRAVERSAL_SYMBOLS)` symbols. Past that `bbox`
/// and `end` are `null` and `bound` is a box every point lies in: its
/// roots' box grown by the longest stem (`L`'s base) times the symbols.
pub(crate) fn stats_bed3(bed: &Bed, json: bool, limits: &Limits) -> Result<String, Diagnostics> {
    let size = bed.size();
    let budget = limits.max_symbols.min(STATS_TRAVERSAL_SYMBOLS);
    let geo = if size.symbols <= budget {
        let (bbox, end, _) = bounds3(bed, limits, &mut NoProgress)?;
        Ok((bbox, end.to_array()))
    } else {
        let d = bed.description();
        let reach = d.params.length.base * size.symbols as f64;
        let mut b = [
            f64::INFINITY,
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ];
        let roots =
            std::iter::once((d.root, d.root_z)).chain(d.forest.iter().map(|t| (t.root, t.root_z)));
        for ((x, y), z) in roots {
            for (i, v) in [x, y, z.unwrap_or(0.0)].into_iter().enumerate() {
                b[i] = b[i].min(v - reach);
                b[i + 3] = b[i + 3].max(v + reach);
            }
        }
        Err(b)
    };
    let mut out = String::new();
    if json {
        let _ = write!(
            out,
            "{{\"dimensions\": 3, \"symbols\": \"{}\", \"stems\": \"{}\", ",
            size.symbols, size.stems
        );
        let _ = match &geo {
            Ok((bbox, end)) => write!(
                out,
                "\"bbox\": {}, \"end\": {}}}",
                bbox.map_or("null".to_string(), |b| list(&b)),
                list(end)
            ),
            Err(bound) => write!(
                out,
                "\"bbox\": null, \"end\": null, \"bound\": {}}}",
                list(bound)
            ),
        };
        return Ok(out);
    }
    let _ = writeln!(out, "tree      {} (3D BED)", bed.description().name);
    let _ = writeln!(out, "symbols   {}", size.symbols);
    let _ = writeln!(out, "stems     {}", size.stems);
    match &geo {
        Ok((bbox, end)) => {
            match bbox {
                Some(b) => {
                    let _ = writeln!(
                        out,
                        "bbox      {} (canvas units, y down, z away)",
                        box_text(b)
                    );
                }
                None => {
                    let _ = writeln!(out, "bbox      (nothing drawn)");
                }
            }
            let _ = writeln!(
                out,
                "end       ({}, {}, {})",
                num(end[0]),
                num(end[1]),
                num(end[2])
            );
        }
        Err(b) => {
            let _ = writeln!(
                out,
                "bbox      (not traversed: too many symbols) within {}",
                box_text(b)
            );
            let _ = writeln!(out, "end       (not traversed)");
        }
    }
    Ok(out)
}
