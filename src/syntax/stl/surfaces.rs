//! The organs of an OD or a BED (`stl-language.md` section 13): the
//! `SURFACES ... ENDSURFACES` block, each line `surface X { word }` read as
//! the `.lsys` key is (src/syntax/lsys/organs.rs), and the `P=X` of the
//! header checked against it.

use pest::iterators::Pair;

use super::super::Rule;
use super::builder::{Builder, not_in_grammar, span_of};
use crate::diag::{Diagnostic, StlError};
use crate::model::{Loc, StemParams, SurfaceBlock};

impl Builder<'_> {
    /// `SURFACES ... ENDSURFACES`.
    pub(super) fn surfaces(&mut self, p: Pair<'_, Rule>) -> SurfaceBlock {
        let span = span_of(&p);
        let (mut kw, mut closed) = (None, false);
        let mut read = (Vec::new(), Vec::new());
        for c in p.into_inner() {
            match c.as_rule() {
                Rule::stl_kw_surfaces => kw = Some(span_of(&c)),
                Rule::stl_kw_endsurfaces => closed = true,
                Rule::stl_surfaces_text => {
                    read = crate::syntax::lsys::surface_block(
                        c.as_str(),
                        c.as_span().start(),
                        &mut self.diags,
                    );
                }
                other => not_in_grammar("stl_surfaces", other),
            }
        }
        if !closed {
            self.err(
                Diagnostic::error(StlError::UnclosedSection {
                    open: "SURFACES",
                    close: "ENDSURFACES",
                })
                .with_span(kw.expect("grammar: stl_surfaces starts with `SURFACES`"))
                .with_label("this section is never closed")
                .with_help("end the surfaces with `ENDSURFACES`, before `LAYOUT`"),
            );
        }
        SurfaceBlock {
            surfaces: read.0,
            lines: read.1,
            loc: Loc(span),
        }
    }

    /// `P=X` names a surface of the block.
    pub(super) fn check_leaf(&mut self, params: &StemParams, block: Option<&SurfaceBlock>) {
        let Some((name, loc)) = &params.leaf else {
            return;
        };
        let defined = block.is_some_and(|b| b.surfaces.iter().any(|s| s.name == *name));
        // A surface the block failed to read is reported there; its name
        // is not also called undefined.
        let failed = block.is_some_and(|b| {
            let within =
                |s: &std::ops::Range<usize>| s.start >= b.loc.0.start && s.end <= b.loc.0.end;
            self.diags
                .0
                .iter()
                .any(|d| d.span.as_ref().is_some_and(within))
        });
        if !defined && !failed {
            let known: Vec<String> = block
                .iter()
                .flat_map(|b| b.surfaces.iter().map(|s| format!("`{}`", s.name)))
                .collect();
            let help = if known.is_empty() {
                format!(
                    "define it before LAYOUT: `SURFACES surface {name} {{ [{{.+f.-f.-f.+f.}}] }} ENDSURFACES`"
                )
            } else {
                format!("the file defines {}", known.join(", "))
            };
            self.report(
                StlError::UnknownSurface {
                    name: name.to_string(),
                },
                loc.0.clone(),
                "no such surface",
                &help,
            );
        }
    }
}
