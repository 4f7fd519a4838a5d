//! The Branch-Expansion Description: the contract between `compile` and
//! `render`.
//!
//! A [`Bed`] is a [`Description`] that has been validated and measured:
//! [`Bed::new`] checks what the grammar cannot see ([`validate`]) and
//! computes what the BED draws (symbols and stems) exactly, saturating at
//! `u64::MAX`, without expanding it ([`measure`]). The interpreter takes a
//! [`Bed`], so a BED is validated and measured once per run.

pub mod write;

use std::collections::BTreeMap;

use crate::diag::{BedError, Diagnostic, Diagnostics, RuleError};
use crate::limits::{Bound, Limits};
use crate::model::seed_walk::{SeedStep, SeedWalk};
use crate::model::walk::{self, Step};
use crate::model::{Description, Fixed, RuleId, Seed, StemParams};

/// What a description's seed expands to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Size {
    /// Turtle operations in the expansion (drawing components, plus one
    /// `Enter` and one `Leave` per rule application), saturating.
    pub symbols: u64,
    /// Stems drawn (`F`s in the expansion), saturating.
    pub stems: u64,
}

impl Size {
    fn add(&mut self, o: Size) {
        self.symbols = self.symbols.saturating_add(o.symbols);
        self.stems = self.stems.saturating_add(o.stems);
    }
}

/// Size of drawing components as written.
fn draw_size(text: &str) -> Size {
    Size {
        symbols: text.len() as u64,
        stems: text.bytes().filter(|&b| b == b'F').count() as u64,
    }
}

/// Size of `[I n w]` (see [`walk::fixed_counts`]).
fn fixed_size(f: &Fixed) -> Size {
    let (symbols, stems) = walk::fixed_counts(&f.word, f.count);
    Size { symbols, stems }
}

/// Per-rule sizes, computed once.
struct Sizer<'a> {
    desc: &'a Description,
    /// What one application of each rule draws itself (`Enter`/`Leave`
    /// included, slots excluded).
    own: Vec<Size>,
    repeats: BTreeMap<(usize, u32), Size>,
}

impl<'a> Sizer<'a> {
    fn new(desc: &'a Description) -> Self {
        let own = desc
            .rules
            .iter()
            .map(|r| {
                // `Enter` and `Leave`.
                let mut s = Size {
                    symbols: 2,
                    stems: 0,
                };
                for step in walk::steps(&r.body) {
                    match step {
                        Step::Run(d) => s.add(draw_size(&d.text)),
                        Step::Fixed(f) => s.add(fixed_size(f)),
                        // A branch's `[` and its `]`.
                        Step::Open { .. } | Step::Tip { .. } => {
                            s.symbols = s.symbols.saturating_add(1);
                        }
                    }
                }
                s
            })
            .collect();
        Sizer {
            desc,
            own,
            repeats: BTreeMap::new(),
        }
    }

    /// Size of `[I n X]` (see [`walk::repeat_counts`]; `[I 0 X]` is
    /// nothing).
    fn repeat(&mut self, rule: RuleId, n: u32) -> Size {
        if let Some(s) = self.repeats.get(&(rule.0, n)) {
            return *s;
        }
        let own = self.own.get(rule.0).copied().unwrap_or_default();
        let m = self.desc.rules.get(rule.0).map_or(0, |r| r.branch_count());
        let (symbols, stems) = walk::repeat_counts((own.symbols, own.stems), m, n);
        let s = Size { symbols, stems };
        self.repeats.insert((rule.0, n), s);
        s
    }
}

/// Computes what `seed` (of `desc`) expands to, exactly or saturated.
pub fn measure_seed(desc: &Description, seed: &Seed) -> Size {
    let mut total = Size::default();
    item_sizes(desc, seed, |_, s| total.add(s));
    total
}

/// Calls `each` with the index and size of every item of `seed`, in order
/// (one at a time: a generated seed can hold millions of items).
fn item_sizes(desc: &Description, seed: &Seed, mut each: impl FnMut(usize, Size)) {
    let mut z = Sizer::new(desc);
    for i in 0..seed.items.len() {
        let mut total = Size::default();
        for step in SeedWalk::item(seed, i) {
            match step {
                SeedStep::Run(d) => total.add(draw_size(&d.text)),
                SeedStep::Fixed(f) => total.add(fixed_size(f)),
                SeedStep::Repeat { repeat: r, .. } => total.add(z.repeat(r.rule, r.count)),
                SeedStep::Term { term, .. } => {
                    total.add(z.own.get(term.rule().0).copied().unwrap_or_default());
                }
                _ => {}
            }
        }
        each(i, total);
    }
}

/// The span of the seed item that alone expands past `max_symbols`, if
/// one does (the one to point at); else `None`.
fn item_over(desc: &Description, seed: &Seed, max_symbols: u64) -> Option<crate::diag::Span> {
    let mut biggest: Option<(usize, u64)> = None;
    item_sizes(desc, seed, |i, s| {
        if biggest.is_none_or(|(_, b)| s.symbols > b) {
            biggest = Some((i, s.symbols));
        }
    });
    let (i, symbols) = biggest?;
    if symbols <= max_symbols {
        return None;
    }
    let span = seed.item_span(&seed.items[i]);
    (span.end > span.start).then_some(span)
}

/// Computes what the description's seeds in force expand to (all trees of
/// a forest together).
pub fn measure(desc: &Description) -> Size {
    let mut total = Size::default();
    for (_, seed) in desc.trees() {
        if let Some(seed) = seed {
            total.add(measure_seed(desc, &seed));
        }
    }
    total
}

/// A validated, measured Branch-Expansion Description.
#[derive(Debug, Clone, PartialEq)]
pub struct Bed {
    desc: Description,
    size: Size,
}

impl Bed {
    /// Validates `desc` (see [`validate`]) and measures it.
    pub fn new(desc: Description, limits: &Limits) -> Result<Bed, Diagnostics> {
        let size = validate(&desc, limits)?;
        Ok(Bed { desc, size })
    }

    /// The description.
    pub fn description(&self) -> &Description {
        &self.desc
    }

    /// What its seed expands to.
    pub fn size(&self) -> Size {
        self.size
    }

    /// The description, given back.
    pub fn into_description(self) -> Description {
        self.desc
    }
}

/// Checks what the grammar cannot: every term names a rule and has one slot
/// per branch, every rule application's order leaves its stems a positive
/// length and width, counts are within `limits.max_repeat`, and the whole
/// expansion stays within `limits.max_symbols`. Returns the measured size.
///
/// A forest's trees are checked one by one and measured together.
pub fn validate(desc: &Description, limits: &Limits) -> Result<Size, Diagnostics> {
    let mut total = Size::default();
    for (_, seed) in desc.trees() {
        if let Some(seed) = seed {
            total.add(validate_seed(desc, &seed, limits)?);
        }
    }
    if total.symbols > limits.max_symbols {
        return Err(Bound::Symbols
            .exceeded_by(
                "symbols in the expansion of the forest",
                total.symbols,
                limits.max_symbols,
            )
            .with_help(Bound::Symbols.raise() + ", or grow fewer trees")
            .into());
    }
    Ok(total)
}

/// [`validate`] for one tree's seed.
fn validate_seed(desc: &Description, seed: &Seed, limits: &Limits) -> Result<Size, Diagnostics> {
    let mut diags = Diagnostics::new();
    let p = &desc.params;
    let mut order_reported = false;
    let mut check_order =
        |order: u32, span: &crate::diag::Span, what: &str, diags: &mut Diagnostics| {
            if order_reported || p.can_grow_at(order) {
                return;
            }
            order_reported = true;
            diags.push(order_error(p, order, span.clone(), what));
        };
    let check_count = |count: u32, span: &crate::diag::Span, diags: &mut Diagnostics| {
        if count > limits.max_repeat {
            diags.push(
                Bound::Repeat
                    .exceeded(count, limits.max_repeat.into())
                    .with_span(span.clone()),
            );
        }
    };
    for r in &desc.rules {
        for step in walk::steps(&r.body) {
            if let Step::Fixed(f) = step {
                check_count(f.count, &f.loc.0, &mut diags);
            }
        }
    }
    let mut walk = SeedWalk::written(seed);
    while let Some(step) = walk.next() {
        match step {
            SeedStep::Fixed(f) => check_count(f.count, &f.loc.0, &mut diags),
            SeedStep::Repeat {
                repeat: r, order, ..
            } => {
                check_count(r.count, &r.loc.0, &mut diags);
                if desc.rules.get(r.rule.0).is_none() {
                    diags.push(unknown_id(r.rule, &r.loc.0));
                } else {
                    // Its last level's order.
                    let deepest = (order - 1).saturating_add(r.count);
                    check_order(deepest, &r.loc.0, &rule_name(desc, r.rule), &mut diags);
                }
            }
            SeedStep::Term { term: t, order, .. } => {
                let Some(rule) = desc.rules.get(t.rule().0) else {
                    diags.push(unknown_id(t.rule(), &t.loc()));
                    walk.step_over();
                    continue;
                };
                let m = rule.branch_count();
                if t.slot_count() != m {
                    diags.push(
                        Diagnostic::error(RuleError::SlotCount {
                            rule: rule.full_name().into_owned(),
                            expected: m,
                            found: t.slot_count(),
                        })
                        .with_span(t.loc())
                        .with_help("write one slot per branch"),
                    );
                }
                check_order(order, &t.loc(), &rule.full_name(), &mut diags);
            }
            _ => {}
        }
    }
    if diags.has_errors() {
        return Err(diags);
    }
    let size = measure_seed(desc, seed);
    if size.symbols > limits.max_symbols {
        diags.push(
            Bound::Symbols
                .exceeded(
                    if size.symbols == u64::MAX {
                        format!("more than {}", u64::MAX - 1)
                    } else {
                        size.symbols.to_string()
                    },
                    limits.max_symbols,
                )
                .with_span(item_over(desc, seed, limits.max_symbols).unwrap_or(seed.loc.0.clone()))
                .with_help(Bound::Symbols.raise() + ", or lower the counts"),
        );
    }
    diags.into_result(size)
}

fn rule_name(desc: &Description, id: RuleId) -> String {
    desc.rules
        .get(id.0)
        .map_or_else(|| format!("#{}", id.0), |r| r.full_name().into_owned())
}

fn unknown_id(id: RuleId, span: &crate::diag::Span) -> Diagnostic {
    Diagnostic::error(RuleError::UnknownRule {
        name: format!("#{}", id.0),
    })
    .with_span(span.clone())
    .with_help("the description refers to a rule it does not declare")
}

fn order_error(p: &StemParams, order: u32, span: crate::diag::Span, rule: &str) -> Diagnostic {
    Diagnostic::error(BedError::OrderTooDeep {
        rule: rule.to_string(),
        order,
        length: p.length.at(order),
        width: p.width.at(order),
    })
    .with_span(span)
    .with_label("stems of this order cannot exist")
    .with_help("stems need a positive length and width: lower the decrements of `L` and `B`, or remove the deeper terms")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::ErrorKind;

    use crate::model::Loc;
    use crate::num::Linear;

    /// The message is the BED writer's numbers in a fixed sentence.
    #[test]
    fn order_errors_name_the_rule_order_length_and_width() {
        let p = StemParams {
            length: Linear::new(10.0, 5.0),
            width: Linear::new(1.0, 0.3),
            angle: None,
            clearance: None,
            divergence: None,
            stroke: None,
            stroke_end: None,
            leaf: None,
            background: None,
            design: Default::default(),
            loc: Loc::default(),
        };
        let d = order_error(&p, 4, 3..7, "R1");
        assert_eq!(
            d.kind,
            ErrorKind::Bed(BedError::OrderTooDeep {
                rule: "R1".into(),
                order: 4,
                length: -10.0,
                width: 1.0 - 4.0 * 0.3
            })
        );
        assert_eq!(d.span, Some(3..7));
        assert_eq!(
            d.kind.to_string(),
            "`R1` is applied at order 4, where stems have length -10 and width -0.2"
        );
    }

    fn fixed(count: u32, word: &str) -> Fixed {
        Fixed {
            count,
            word: word.into(),
            loc: Loc::default(),
        }
    }

    #[test]
    fn fixed_sizes_follow_the_rewriting() {
        // [I 1 F+F] = F+F; [I 2 F+F] = F+F+F+F (7 symbols, 4 stems).
        let size = |count, word| fixed_size(&fixed(count, word));
        assert_eq!(
            size(1, "F+F"),
            Size {
                symbols: 3,
                stems: 2
            }
        );
        assert_eq!(
            size(2, "F+F"),
            Size {
                symbols: 7,
                stems: 4
            }
        );
        assert_eq!(
            size(3, "F+F"),
            Size {
                symbols: 15,
                stems: 8
            }
        );
        // saturates instead of overflowing
        assert_eq!(size(200, "FF").stems, u64::MAX);
    }
}
