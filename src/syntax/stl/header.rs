//! The header's stem parameters: `L=10(0) B=1(0) A=30 C=1`.
//!
//! The grammar reads any `key=number(decrement)`; which keys exist, which
//! take a decrement and which values are allowed is checked here, against
//! the one table of parameters, [`Param`].

use pest::iterators::Pair;

use super::super::Rule;
use super::builder::{Builder, span_of};
use crate::diag::{Diagnostic, Span, StlError};
use crate::model::{Loc, MAX_ATTRACTION_POINTS, StemParams};
use crate::num::Linear;

/// A stem parameter of the header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Param {
    /// `L=base(decrement)`: segment length at order 0 and its decrement
    /// per order.
    Length,
    /// `B=base(decrement)`: stroke width at order 0 and its decrement.
    Broadness,
    /// `A=degrees`: the turning angle.
    Angle,
    /// `C=distance`: the clearance between stems.
    Clearance,
    /// `D=degrees`: the divergence of a 3D description (section 11).
    Divergence,
    /// `S=colour`: the stroke colour.
    Stroke,
    /// `G=colour` or `G=none`: the background (ground) colour.
    Ground,
    /// `O=bfs` or `O=dfs`: the growth order of an OD.
    Order,
    /// `V=n`: the seed of an OD's choices.
    Seed,
    /// `M=n`: the stems an OD's growth stops after.
    MaxStems,
    /// `N=n`: the attraction points of space-first growth.
    Points,
    /// `Q=d`: the radius of influence of space-first growth.
    Reach,
    /// `P=X`: the surface drawn at every tip that grew no further
    /// (section 13).
    Leaf,
}

impl Param {
    /// Every parameter, in the order the docs list them.
    pub const ALL: [Param; 13] = [
        Param::Length,
        Param::Broadness,
        Param::Angle,
        Param::Clearance,
        Param::Divergence,
        Param::Stroke,
        Param::Ground,
        Param::Order,
        Param::Seed,
        Param::MaxStems,
        Param::Points,
        Param::Reach,
        Param::Leaf,
    ];

    /// The key as written: `L`, `B`, `A` or `C`.
    pub fn key(self) -> &'static str {
        match self {
            Param::Length => "L",
            Param::Broadness => "B",
            Param::Angle => "A",
            Param::Clearance => "C",
            Param::Divergence => "D",
            Param::Stroke => "S",
            Param::Ground => "G",
            Param::Order => "O",
            Param::Seed => "V",
            Param::MaxStems => "M",
            Param::Points => "N",
            Param::Reach => "Q",
            Param::Leaf => "P",
        }
    }

    /// What the parameter is, in words.
    pub fn what(self) -> &'static str {
        match self {
            Param::Length => "length",
            Param::Broadness => "broadness",
            Param::Angle => "angle",
            Param::Clearance => "clearance",
            Param::Divergence => "divergence",
            Param::Stroke => "stroke colour",
            Param::Ground => "background colour",
            Param::Order => "growth order",
            Param::Seed => "seed",
            Param::MaxStems => "max stems",
            Param::Points => "attraction points",
            Param::Reach => "reach",
            Param::Leaf => "leaf surface",
        }
    }

    /// Whether the parameter's value is a colour rather than a number.
    pub fn is_colour(self) -> bool {
        matches!(self, Param::Stroke | Param::Ground)
    }

    /// Whether the parameter's value is a word (a colour, `bfs`/`dfs`).
    fn is_word(self) -> bool {
        self.is_colour() || self == Param::Order || self == Param::Leaf
    }

    /// Whether the parameter is part of an OD's design (`O`, `V`, `M`,
    /// `N`, `Q`), which a BED, whose decisions are written out, does not
    /// have.
    fn is_design(self) -> bool {
        matches!(
            self,
            Param::Order | Param::Seed | Param::MaxStems | Param::Points | Param::Reach
        )
    }

    /// The parameter whose key is `key`, exactly as written.
    pub fn from_key(key: &str) -> Option<Param> {
        Param::ALL.into_iter().find(|p| p.key() == key)
    }
}

/// `L (length), B (broadness), A (angle) and C (clearance)`.
fn param_list() -> String {
    let items: Vec<String> = Param::ALL
        .iter()
        .map(|p| format!("{} ({})", p.key(), p.what()))
        .collect();
    let (last, rest) = items.split_last().expect("Param::ALL is not empty");
    format!("{} and {last}", rest.join(", "))
}

impl Builder<'_> {
    /// The stem parameters; without `L` or `B` a stem is 10 long and 1 wide
    /// at every order.
    pub(super) fn params(&mut self, pairs: Vec<Pair<'_, Rule>>, root_loc: &Loc) -> StemParams {
        let mut out = StemParams {
            length: Linear::constant(10.0),
            width: Linear::constant(1.0),
            angle: None,
            clearance: None,
            divergence: None,
            stroke: None,
            stroke_end: None,
            leaf: None,
            background: None,
            design: Default::default(),
            loc: Loc(root_loc.0.end..root_loc.0.end),
        };
        let mut seen: Vec<(String, Span)> = Vec::new();
        let mut whole: Option<Span> = None;
        for p in pairs {
            let span = span_of(&p);
            whole = Some(whole.map_or(span.clone(), |w| w.start..span.end));
            let mut it = p.into_inner();
            let key = it.next().expect("grammar: stl_param starts with a key");
            let val = it
                .next()
                .expect("grammar: stl_param has a number or a colour");
            // `(d)` and the number inside it.
            let dec = it.next().map(|d| {
                let n = d.clone().into_inner().next();
                (
                    span_of(&d),
                    n.expect("grammar: stl_param_dec holds a number"),
                )
            });
            let k = key.as_str().to_string();
            let kspan = span_of(&key);
            if let Some((_, first)) = seen.iter().find(|(s, _)| *s == k) {
                let first = first.clone();
                self.err(
                    Diagnostic::error(StlError::DuplicateParam { key: k })
                        .with_span(kspan)
                        .with_label("given again here")
                        .with_note_at(first, "first given here")
                        .with_help("keep one of them"),
                );
                continue;
            }
            seen.push((k.clone(), kspan.clone()));
            let vspan = span_of(&val);
            let param = Param::from_key(&k);
            let colour_given = val.as_rule() == Rule::stl_param_colour;
            if let Some(p) = param
                && p.is_design()
                && self.format == crate::model::Format::Bed
            {
                self.report(
                    StlError::ParamValue {
                        key: p.key(),
                        expected: "nothing in a BED: its decisions are written out",
                    },
                    kspan.start..vspan.end,
                    "a BED grows nothing",
                    &format!(
                        "remove `{}=`: it belongs in the OD the BED was compiled from",
                        p.key()
                    ),
                );
                continue;
            }
            if let Some(p) = param
                && p.is_word() != colour_given
            {
                let expected = if p == Param::Order {
                    "`bfs`, `dfs` or `space`"
                } else if p == Param::Leaf {
                    "a surface's one-character name, defined in SURFACES"
                } else if p.is_colour() {
                    "a colour (a Delphi name such as `clMaroon`, `#rrggbb`, or `none` for G)"
                } else {
                    "a number"
                };
                self.report(
                    StlError::ParamValue {
                        key: p.key(),
                        expected,
                    },
                    vspan,
                    "not this kind of value",
                    &format!("write `{}=` followed by {expected}", p.key()),
                );
                continue;
            }
            if param == Some(Param::Leaf) {
                self.no_decrement(Param::Leaf, dec.as_ref().map(|(s, _)| s.clone()));
                let text = val.as_str();
                let mut chars = text.chars();
                match (chars.next(), chars.next()) {
                    (Some(c), None) => out.leaf = Some((c, Loc(vspan))),
                    _ => self.report(
                        StlError::ParamValue {
                            key: "P",
                            expected: "a surface's one-character name, defined in SURFACES",
                        },
                        vspan,
                        "not one character",
                        "a surface is named with one character, as in `.lsys`: `P=L`",
                    ),
                }
                continue;
            }
            if let Some(p) = param.filter(|p| p.is_colour())
                && let Some((a, b)) = val.as_str().split_once("..")
            {
                // A ramp by order (section 13): only `S=` takes one.
                if p != Param::Stroke {
                    self.report(
                        StlError::ParamValue {
                            key: p.key(),
                            expected: "one colour (only `S=` takes a ramp)",
                        },
                        vspan,
                        "a ramp",
                        &format!("write `{}=` followed by one colour", p.key()),
                    );
                    continue;
                }
                let start = span_of(&val).start;
                let first = self.colour(a, start..start + a.len());
                let bstart = start + a.len() + 2;
                let last = self.colour(b, bstart..bstart + b.len());
                if let (Some(first), Some(last)) = (first, last) {
                    out.stroke = Some(crate::model::Colour {
                        rgb: Some(first),
                        text: val.as_str().to_string(),
                    });
                    out.stroke_end = Some(last);
                }
                continue;
            }
            if let Some(p) = param.filter(|p| p.is_colour()) {
                let text = val.as_str().to_string();
                let rgb = if p == Param::Ground && text.eq_ignore_ascii_case("none") {
                    Some(None)
                } else {
                    self.colour(&text, vspan).map(Some)
                };
                if let Some(rgb) = rgb {
                    let c = Some(crate::model::Colour { rgb, text });
                    if p == Param::Stroke {
                        out.stroke = c;
                    } else {
                        out.background = c;
                    }
                }
                continue;
            }
            if let Some(p @ (Param::Order | Param::Seed | Param::MaxStems | Param::Points)) = param
            {
                self.no_decrement(p, dec.as_ref().map(|(s, _)| s.clone()));
                let text = val.as_str();
                match p {
                    Param::Order => match text {
                        "bfs" => out.design.order = Some(crate::model::GrowthOrder::Bfs),
                        "dfs" => out.design.order = Some(crate::model::GrowthOrder::Dfs),
                        "space" => out.design.order = Some(crate::model::GrowthOrder::Space),
                        _ => self.report(
                            StlError::ParamValue {
                                key: p.key(),
                                expected: "`bfs`, `dfs` or `space`",
                            },
                            vspan,
                            "not a growth order",
                            "write `O=bfs` (level by level), `O=dfs` (a branch's subtree first) or `O=space` (free space first)",
                        ),
                    },
                    _ => match text.parse::<u64>() {
                        Ok(n) if p == Param::Seed => out.design.seed = Some(n),
                        Ok(n) if p == Param::Points && n > MAX_ATTRACTION_POINTS => self.report(
                            StlError::ParamValue {
                                key: p.key(),
                                expected: "a whole number from 0 to 1000000",
                            },
                            vspan,
                            "more attraction points than space-first growth scatters",
                            "write at most `N=1000000` (a million points cost about 100 MB), \
                             or leave `N=` out for one point per L x L of the region",
                        ),
                        Ok(n) if p == Param::Points => out.design.points = Some(n),
                        Ok(n) => out.design.max_stems = Some(n),
                        Err(_) => self.report(
                            StlError::ParamValue {
                                key: p.key(),
                                expected: "a whole number from 0 to 18446744073709551615",
                            },
                            vspan,
                            "not a whole number",
                            &format!("write `{}=` followed by digits", p.key()),
                        ),
                    },
                }
                continue;
            }
            let v = if colour_given { 0.0 } else { self.number(&val) };
            let dv = dec.as_ref().map(|(_, n)| (self.number(n), span_of(n)));
            match Param::from_key(&k) {
                Some(p @ Param::Length) => out.length = self.size(p, v, vspan, dv),
                Some(p @ Param::Broadness) => out.width = self.size(p, v, vspan, dv),
                Some(p @ Param::Angle) => {
                    self.no_decrement(p, dec.map(|(s, _)| s));
                    out.angle = Some(v);
                }
                // Colours and the design keys were read above.
                Some(
                    Param::Stroke
                    | Param::Ground
                    | Param::Order
                    | Param::Seed
                    | Param::MaxStems
                    | Param::Points
                    | Param::Leaf,
                ) => {}
                Some(p @ Param::Reach) => {
                    self.no_decrement(p, dec.map(|(s, _)| s));
                    if v > 0.0 && v.is_finite() {
                        out.design.reach = Some(v);
                    } else {
                        self.report(
                            StlError::ParamValue {
                                key: p.key(),
                                expected: "a distance greater than 0",
                            },
                            vspan,
                            "not a positive distance",
                            "write `Q=` followed by a radius in canvas units, such as 40",
                        );
                    }
                }
                Some(p @ Param::Divergence) => {
                    self.no_decrement(p, dec.map(|(s, _)| s));
                    if self.three_d {
                        out.divergence = Some(v);
                    } else {
                        self.needs_3d(
                            "`D=` (divergence)".into(),
                            kspan.start..vspan.end,
                            "divergence turns about the stem in 3D",
                        );
                    }
                }
                Some(p @ Param::Clearance) => {
                    self.no_decrement(p, dec.map(|(s, _)| s));
                    if v < 0.0 {
                        self.report(
                            StlError::NegativeClearance,
                            vspan,
                            "negative",
                            "write a clearance of 0 or more",
                        );
                    }
                    out.clearance = Some(v);
                }
                None => {
                    let sugg = Param::ALL
                        .iter()
                        .find(|p| p.key().eq_ignore_ascii_case(&k))
                        .map(|p| format!("did you mean `{}`? ", p.key()))
                        .unwrap_or_default();
                    self.report(
                        StlError::UnknownParam { key: k },
                        kspan,
                        "not a stem parameter",
                        &format!("{sugg}the parameters are {}", param_list()),
                    );
                }
            }
        }
        if let Some(w) = whole {
            out.loc = Loc(w);
        }
        out
    }

    /// `L` or `B`: a positive base and a decrement of 0 or more (0 if none
    /// is written).
    fn size(&mut self, p: Param, v: f64, vspan: Span, dec: Option<(f64, Span)>) -> Linear {
        let (key, what) = (p.key(), p.what());
        if v <= 0.0 {
            self.report(
                StlError::StemSizeNotPositive { key, what },
                vspan,
                "zero or negative",
                &format!("write a positive {what}, e.g. `{key}=10(0)`"),
            );
        }
        if let Some((dv, dspan)) = &dec
            && *dv < 0.0
        {
            self.report(
                StlError::NegativeDecrement { key },
                dspan.clone(),
                "negative decrement",
                "stems get shorter and slimmer with order: write a decrement of 0 or more",
            );
        }
        Linear::new(v, dec.map_or(0.0, |(dv, _)| dv))
    }

    /// `A` and `C` take no decrement; `dec` is the span of one written.
    fn no_decrement(&mut self, p: Param, dec: Option<Span>) {
        if let Some(span) = dec {
            self.report(
                StlError::UnexpectedDecrement { key: p.key() },
                span,
                "not allowed here",
                &format!("write `{}=value` without parentheses", p.key()),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_parameter_list_reads_as_prose() {
        assert_eq!(
            param_list(),
            "L (length), B (broadness), A (angle), C (clearance), D (divergence), S (stroke colour), \
             G (background colour), O (growth order), V (seed), M (max stems), N (attraction points), \
             Q (reach) and P (leaf surface)"
        );
        assert_eq!(Param::from_key("B"), Some(Param::Broadness));
        assert_eq!(Param::from_key("b"), None);
    }
}
