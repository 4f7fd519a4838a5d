//! The volumes of a 3D layout (`../shared/stl-language.md` section 11):
//! `Box`, `Sphere`, `Ellipsoid`, `Cylinder`, and `Extrude` or `Revolve` of
//! a 2D shape; and the check that a layout line has its description's
//! dimensions (a volume needs a 3D root; a 2D shape in a 3D layout must be
//! extruded or revolved). The 2D shapes and the line itself are `layout`'s.

use pest::iterators::Pair;

use super::super::Rule;
use super::builder::{Builder, not_in_grammar, span_of};
use super::names::{Arg, ShapeName, SolidName};
use crate::diag::{LayoutError, Span};
use crate::model::Solid;
use crate::num::{Trim, fixed};

impl Builder<'_> {
    /// Whether the shape `p` (`stl_shape`) has the description's
    /// dimensions: reports a volume in a 2D description (a 3D root is
    /// needed) and a 2D shape in a 3D one (extrude or revolve it).
    pub(super) fn dimensions_fit(&mut self, p: &Pair<'_, Rule>) -> bool {
        let name = p.clone().into_inner().next();
        let name = name.expect("grammar: stl_shape starts with a name");
        let (text, nspan) = (name.as_str(), span_of(&name));
        if let (false, Some(v)) = (self.three_d, SolidName::from_name(text)) {
            let help = self.flat_root.as_ref().map_or_else(
                || "give the root a third coordinate".to_string(),
                |(_, fixed)| {
                    format!(
                        "give the root a third coordinate to make the description 3D: `{fixed}`"
                    )
                },
            );
            self.report(
                LayoutError::SolidIn2d { shape: v.name() },
                nspan,
                "a volume",
                &format!(
                    "{help}; or draw a 2D shape here ({})",
                    ShapeName::Ellipse.usage()
                ),
            );
            return false;
        }
        if let (true, Some(s)) = (self.three_d, ShapeName::from_name(text)) {
            let written = p.as_str().trim();
            self.report(
                LayoutError::FlatShapeIn3d { shape: s.name() },
                span_of(p),
                "a 2D shape",
                &format!(
                    "make it a volume: `Extrude {written}, z1, z2` (the shape between two \
                     depths) or `Revolve {written}` (turned about the first root's vertical line)"
                ),
            );
            return false;
        }
        true
    }

    /// A volume (`stl_shape` in a 3D layout): its name and arguments
    /// checked against its spelling, sizes positive, `z1 < z2`.
    pub(super) fn solid(&mut self, p: Pair<'_, Rule>) -> Option<Solid> {
        let span = span_of(&p);
        let mut it = p.into_inner();
        let name_pair = it.next().expect("grammar: stl_shape starts with a name");
        let Some(kind) = SolidName::from_name(name_pair.as_str()) else {
            self.unknown_shape(name_pair.as_str(), span_of(&name_pair));
            return None;
        };
        // The 2D shape of `Extrude` and `Revolve`, and whether it was in
        // angle brackets (then the arguments after it are the volume's).
        let mut inner = None;
        let mut args = Vec::new();
        for c in it {
            match c.as_rule() {
                Rule::stl_inner_angled => {
                    let i = c.into_inner().next();
                    inner = Some((i.expect("grammar: stl_inner_angled holds stl_inner"), true));
                }
                Rule::stl_inner => inner = Some((c, false)),
                Rule::stl_shape_arg => args.push(self.arg(c)),
                other => not_in_grammar("stl_shape", other),
            }
        }
        let wrong = |b: &mut Self| {
            b.report(
                LayoutError::ShapeArguments { shape: kind.name() },
                span.clone(),
                "these arguments",
                &format!("write {}", kind.usage()),
            );
            None
        };
        let positive =
            |b: &mut Self, v: f64, s: &Span, what| b.positive_size(kind.name(), v, s, what);
        match kind {
            SolidName::Extrude | SolidName::Revolve => {
                let Some((inner, angled)) = inner else {
                    return wrong(self);
                };
                let ispan = span_of(&inner);
                let mut iit = inner.into_inner();
                let iname = iit.next().expect("grammar: stl_inner starts with a name");
                let mut iargs: Vec<Arg> = iit.map(|a| self.arg(a)).collect();
                // Plain, the volume's own numbers are the inner shape's last.
                if !angled {
                    let own = if kind == SolidName::Extrude { 2 } else { 0 };
                    if iargs.len() < own {
                        return wrong(self);
                    }
                    args = iargs.split_off(iargs.len() - own);
                }
                let Some(sname) = ShapeName::from_name(iname.as_str()) else {
                    if SolidName::from_name(iname.as_str()).is_some() {
                        self.report(
                            LayoutError::ShapeArguments { shape: kind.name() },
                            span_of(&iname),
                            &format!("a volume: `{}` takes a 2D shape", kind.name()),
                            &format!("write {}", kind.usage()),
                        );
                        return None;
                    }
                    self.unknown_shape(iname.as_str(), span_of(&iname));
                    return None;
                };
                let shape = self.shape_of(sname, &iargs, ispan);
                if kind == SolidName::Revolve {
                    if !args.is_empty() {
                        return wrong(self);
                    }
                    return Some(Solid::Revolve { shape: shape?.0 });
                }
                let [Arg::Num(z1, s1), Arg::Num(z2, s2)] = args.as_slice() else {
                    return wrong(self);
                };
                if z1 >= z2 {
                    self.report(
                        LayoutError::ExtrudeRange,
                        s1.start..s2.end,
                        "z1 is not below z2",
                        &format!(
                            "write the smaller depth first: `{}, {}`",
                            fixed(z1.min(*z2), 3, Trim::Zeros),
                            fixed(z1.max(*z2), 3, Trim::Zeros)
                        ),
                    );
                    return None;
                }
                Some(Solid::Extrude {
                    shape: shape?.0,
                    z1: *z1,
                    z2: *z2,
                })
            }
            _ => {
                if inner.is_some() {
                    return wrong(self);
                }
                let (point, sizes) = match args.as_slice() {
                    [Arg::Group(g), rest @ ..]
                        if g.len() == 3 && rest.iter().all(|a| matches!(a, Arg::Num(..))) =>
                    {
                        let sizes: Vec<(f64, Span)> = rest
                            .iter()
                            .filter_map(|a| match a {
                                Arg::Num(v, s) => Some((*v, s.clone())),
                                Arg::Group(..) => None,
                            })
                            .collect();
                        ([g[0].0, g[1].0, g[2].0], sizes)
                    }
                    _ => return wrong(self),
                };
                let (names, wanted): (&[&'static str], usize) = match kind {
                    SolidName::Box => (&["width", "height", "depth"], 3),
                    SolidName::Sphere => (&["radius"], 1),
                    SolidName::Ellipsoid => (&["x radius", "y radius", "z radius"], 3),
                    _ => (&["radius", "height"], 2),
                };
                if sizes.len() != wanted {
                    return wrong(self);
                }
                let mut ok = true;
                for ((v, s), what) in sizes.iter().zip(names) {
                    ok &= positive(self, *v, s, what);
                }
                let v: Vec<f64> = sizes.iter().map(|(v, _)| *v).collect();
                ok.then(|| match kind {
                    SolidName::Box => Solid::Box {
                        corner: point,
                        size: [v[0], v[1], v[2]],
                    },
                    SolidName::Sphere => Solid::Sphere {
                        centre: point,
                        r: v[0],
                    },
                    SolidName::Ellipsoid => Solid::Ellipsoid {
                        centre: point,
                        radii: [v[0], v[1], v[2]],
                    },
                    _ => Solid::Cylinder {
                        base: point,
                        r: v[0],
                        h: v[1],
                    },
                })
            }
        }
    }
}
