//! The one walk over a rule body, and the one expander of fixed figures.
//!
//! Every pass over a description (growth, BED expansion `dfs` and `bfs`,
//! measuring, validation, the writer) sees a rule body as the same sequence
//! of [`Step`]s: runs of drawing components, fixed figures, and each branch
//! as an [`Step::Open`], its pieces, and a [`Step::Tip`] where its slot
//! grows before the closing `]`. A fixed figure `[I n w]` is expanded by
//! [`FixedWord`] alone, a rule repeat `[I n X]` by [`Levels`] alone. The
//! one walk over a seed is [`super::seed_walk`].

use super::{Body, BodyItem, Branch, DrawRun, Fixed, Piece};

/// One step of a rule body, in drawing order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Step<'a> {
    /// Drawing components, trunk or inside a branch (nested brackets are
    /// drawing too).
    Run(&'a DrawRun),
    /// A fixed figure `[I n w]`, drawn at the current order.
    Fixed(&'a Fixed),
    /// The `[` opening branch number `index` (0-based, written order).
    Open {
        /// Which branch: the slot number of the rule's terms.
        index: usize,
        /// The branch.
        branch: &'a Branch,
    },
    /// The tip of branch `index`: what grows in slot `index` goes here,
    /// then the branch's closing `]`. In an OD the branch's successor (or
    /// the rule itself) grows here.
    Tip {
        /// Which branch.
        index: usize,
        /// The branch.
        branch: &'a Branch,
    },
}

/// The steps of `body`, in drawing order.
pub fn steps(body: &Body) -> Steps<'_> {
    Steps {
        items: &body.items,
        item: 0,
        piece: None,
        branch: 0,
    }
}

/// Iterator of [`steps`].
#[derive(Debug, Clone)]
pub struct Steps<'a> {
    items: &'a [BodyItem],
    /// Next item.
    item: usize,
    /// Inside a branch (opened, not yet at its tip): its next piece.
    piece: Option<usize>,
    /// Branches opened so far.
    branch: usize,
}

impl<'a> Iterator for Steps<'a> {
    type Item = Step<'a>;

    fn next(&mut self) -> Option<Step<'a>> {
        let item = self.items.get(self.item)?;
        match (item, self.piece) {
            (BodyItem::Draw(r), _) => {
                self.item += 1;
                Some(Step::Run(r))
            }
            (BodyItem::Fixed(f), _) => {
                self.item += 1;
                Some(Step::Fixed(f))
            }
            (BodyItem::Branch(b), None) => {
                self.piece = Some(0);
                Some(Step::Open {
                    index: self.branch,
                    branch: b,
                })
            }
            (BodyItem::Branch(b), Some(i)) => match b.pieces.get(i) {
                Some(p) => {
                    self.piece = Some(i + 1);
                    Some(match p {
                        Piece::Draw(r) => Step::Run(r),
                        Piece::Fixed(f) => Step::Fixed(f),
                    })
                }
                None => {
                    let index = self.branch;
                    self.piece = None;
                    self.item += 1;
                    self.branch += 1;
                    Some(Step::Tip { index, branch: b })
                }
            },
        }
    }
}

/// The drawing components of a fixed figure `[I n w]`: `F` rewritten by
/// `w`, `n` times, streamed with an explicit stack of depth `n`. So
/// `[I 1 w]` is `w`, `[I 2 w]` is `w` with each `F` replaced by `w`, and
/// `[I 0 w]` is a single `F` (no rewriting at all). The brackets of
/// `[I n w]` are syntax: the figure does not save and restore the turtle
/// around itself. Components are bytes of `w` (ASCII drawing letters).
#[derive(Debug, Clone)]
pub struct FixedWord<'a> {
    word: &'a [u8],
    /// (rewritings left at this level, next index into `word`).
    stack: Vec<(u32, usize)>,
    /// `[I 0 w]`: the single `F` is still to come.
    single_f: bool,
}

impl<'a> FixedWord<'a> {
    /// The components of `f`.
    pub fn new(f: &'a Fixed) -> Self {
        FixedWord::of(&f.word, f.count)
    }

    /// The components of `[I count word]`.
    pub fn of(word: &'a str, count: u32) -> Self {
        FixedWord {
            word: word.as_bytes(),
            stack: if count > 0 {
                vec![(count, 0)]
            } else {
                Vec::new()
            },
            single_f: count == 0,
        }
    }

    /// Starts over on `f`, keeping the stack's memory: a pass that meets
    /// fixed figures again and again (the BED `dfs` streamer) reuses one
    /// expander instead of allocating a stack per figure.
    pub fn restart(&mut self, f: &'a Fixed) {
        self.word = f.word.as_bytes();
        self.stack.clear();
        if f.count > 0 {
            self.stack.push((f.count, 0));
        }
        self.single_f = f.count == 0;
    }
}

impl Iterator for FixedWord<'_> {
    type Item = u8;

    fn next(&mut self) -> Option<u8> {
        if self.single_f {
            self.single_f = false;
            return Some(b'F');
        }
        loop {
            let (level, i) = self.stack.last_mut()?;
            let Some(&c) = self.word.get(*i) else {
                self.stack.pop();
                continue;
            };
            *i += 1;
            if c == b'F' && *level > 1 {
                let next = *level - 1;
                self.stack.push((next, 0));
                continue;
            }
            return Some(c);
        }
    }
}

/// How many components `[I count word]` expands to, and how many of them
/// are `F`, without expanding it (saturating at `u64::MAX`). Agrees with
/// [`FixedWord`] component for component.
pub fn fixed_counts(word: &str, count: u32) -> (u64, u64) {
    if count == 0 {
        return (1, 1);
    }
    let len = word.len() as u64;
    let fs = word.bytes().filter(|&b| b == b'F').count() as u64;
    let others = len - fs;
    let (mut symbols, mut stems) = (len, fs);
    for _ in 1..count {
        let next = (
            others.saturating_add(symbols.saturating_mul(fs)),
            stems.saturating_mul(fs),
        );
        if next == (symbols, stems) {
            break;
        }
        (symbols, stems) = next;
    }
    (symbols, stems)
}

/// The levels of a rule repeat `[I n X]`, X a rule: the one expander of
/// rule repeats. `[I n X]` is the growth point rewritten by X `n` times:
/// X applied here with `[I n-1 X]` in every slot, `n` levels in all. So
/// `[I 1 X]` is X with its slots empty and `[I 0 X]` applies nothing (an
/// empty slot), as `[I 0 w]` rewrites nothing ([`FixedWord`]). Measuring
/// ([`repeat_counts`]), BED expansion and growth all step through these.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Levels(u32);

impl Levels {
    /// The levels of `[I count X]`: `None` for `count = 0`, nothing applied.
    pub fn of(count: u32) -> Option<Levels> {
        (count > 0).then_some(Levels(count))
    }

    /// How many levels, from this one down (at least 1).
    pub fn get(self) -> u32 {
        self.0
    }

    /// What grows in every slot of this level's application: the next
    /// level, or `None` (slots empty) below the last.
    pub fn next(self) -> Option<Levels> {
        Levels::of(self.0 - 1)
    }
}

/// How many symbols and stems `[I count X]` expands to (saturating at
/// `u64::MAX`), given what one application of X draws itself (`own`, its
/// slots aside) and X's branch count. Agrees with [`Levels`]: `count = 0`
/// is nothing.
pub fn repeat_counts(own: (u64, u64), branches: usize, count: u32) -> (u64, u64) {
    let Some(levels) = Levels::of(count) else {
        return (0, 0);
    };
    let m = branches as u64;
    let mut s = own;
    for _ in 1..levels.get() {
        let next = (
            own.0.saturating_add(s.0.saturating_mul(m)),
            own.1.saturating_add(s.1.saturating_mul(m)),
        );
        if next == s {
            break;
        }
        s = next;
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Loc, RuleId, RuleRef};

    use super::testing::{fixed, run};

    fn expand(count: u32, word: &str) -> String {
        FixedWord::of(word, count).map(char::from).collect()
    }

    /// `F [+F f [I 2 F-F] R2] [-F]`, written out by hand.
    #[test]
    fn steps_visit_trunk_branches_and_tips_in_drawing_order() {
        let body = Body {
            items: vec![
                BodyItem::Draw(run("F")),
                BodyItem::Branch(Branch {
                    pieces: vec![Piece::Draw(run("+Ff")), Piece::Fixed(fixed(2, "F-F"))],
                    successor: Some(RuleRef {
                        rule: RuleId(1),
                        loc: Loc::default(),
                    }),
                    loc: Loc::default(),
                }),
                BodyItem::Branch(Branch {
                    pieces: vec![Piece::Draw(run("-F"))],
                    successor: None,
                    loc: Loc::default(),
                }),
            ],
        };
        let shown: Vec<String> = steps(&body)
            .map(|s| match s {
                Step::Run(r) => format!("run {}", r.text),
                Step::Fixed(f) => format!("fixed {} {}", f.count, f.word),
                Step::Open { index, .. } => format!("open {index}"),
                Step::Tip { index, branch } => {
                    format!(
                        "tip {index} {:?}",
                        branch.successor.as_ref().map(|s| s.rule)
                    )
                }
            })
            .collect();
        assert_eq!(
            shown,
            [
                "run F",
                "open 0",
                "run +Ff",
                "fixed 2 F-F",
                "tip 0 Some(RuleId(1))",
                "open 1",
                "run -F",
                "tip 1 None",
            ]
        );
        assert_eq!(steps(&Body { items: vec![] }).count(), 0);
    }

    #[test]
    fn fixed_figures_rewrite_f_n_times_and_zero_times_is_one_f() {
        assert_eq!(expand(0, "F+F"), "F");
        assert_eq!(expand(1, "F+F"), "F+F");
        assert_eq!(expand(2, "F+F"), "F+F+F+F");
        assert_eq!(expand(3, "F-f"), "F-f-f-f");
        assert_eq!(expand(2, "F[+F]F"), "F[+F]F[+F[+F]F]F[+F]F");
        assert_eq!(expand(5, "+-"), "+-");
        assert_eq!(expand(3, ""), "");
        assert_eq!(FixedWord::new(&fixed(2, "FF")).count(), 4);
        // Restarting mid-figure forgets the rest of the old one.
        let (a, b) = (fixed(3, "F+F"), fixed(0, "F-F"));
        let mut w = FixedWord::new(&a);
        w.next();
        w.restart(&b);
        assert_eq!(w.by_ref().map(char::from).collect::<String>(), "F");
        w.restart(&a);
        assert_eq!(w.map(char::from).collect::<String>(), expand(3, "F+F"));
    }

    /// The counts agree with the expansion, component by component.
    #[test]
    fn fixed_counts_agree_with_the_expansion() {
        for word in ["F", "F+F", "F[+F]F[-F]F", "+-f", "", "fF|F"] {
            for count in 0..6 {
                let e = expand(count, word);
                let fs = e.bytes().filter(|&b| b == b'F').count() as u64;
                assert_eq!(
                    fixed_counts(word, count),
                    (e.len() as u64, fs),
                    "[I {count} {word}]"
                );
            }
        }
        assert_eq!(fixed_counts("FF", 200), (u64::MAX, u64::MAX));
    }

    /// `[I n X]` is `n` levels: the counts follow the levels, and
    /// `[I 0 X]` is nothing.
    #[test]
    fn repeat_levels_and_counts() {
        assert_eq!(Levels::of(0), None);
        let three = Levels::of(3).unwrap();
        let below: Vec<u32> = std::iter::successors(Some(three), |l| l.next())
            .map(Levels::get)
            .collect();
        assert_eq!(below, [3, 2, 1]);
        // X draws 11 symbols and 3 stems itself and has 2 branches:
        // `2^n - 1` applications.
        for n in 0..10 {
            let k = (1u64 << n) - 1;
            assert_eq!(repeat_counts((11, 3), 2, n), (11 * k, 3 * k), "n = {n}");
        }
        assert_eq!(repeat_counts((4, 1), 1, 5), (20, 5));
        assert_eq!(repeat_counts((4, 1), 0, 5), (4, 1));
        assert_eq!(repeat_counts((1, 1), 2, 200), (u64::MAX, u64::MAX));
    }
}

/// Builders the walk and expansion tests share.
#[cfg(test)]
pub(crate) mod testing {
    use crate::model::{DrawRun, Fixed};

    /// Drawing components at no place in the text.
    pub fn run(text: &str) -> DrawRun {
        DrawRun::new(text)
    }

    /// `[I count word]` at no place in the text.
    pub fn fixed(count: u32, word: &str) -> Fixed {
        Fixed::new(count, word)
    }
}
