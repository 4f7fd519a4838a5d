//! `bfs`: Saupe's string rewriting. The whole word is built level by level
//! (one byte per symbol when the alphabet has at most 256 symbols), then
//! handed over symbol by symbol.

use super::Alphabet;

impl Alphabet {
    /// Saupe's string rewriting: builds the word level by level, then calls
    /// `f(index, symbol id)` for each symbol of the final one, in order.
    pub(super) fn bfs_each(&self, depth: u32, mut f: impl FnMut(usize, u32)) {
        if self.chars.len() <= 256 {
            for (i, s) in self.rewrite::<u8>(depth).into_iter().enumerate() {
                f(i, u32::from(s));
            }
        } else {
            for (i, s) in self.rewrite::<u32>(depth).into_iter().enumerate() {
                f(i, s);
            }
        }
    }

    fn rewrite<S: SymId>(&self, depth: u32) -> Vec<S> {
        let succ: Vec<Option<Vec<S>>> = self
            .succ
            .iter()
            .map(|s| {
                s.as_ref()
                    .map(|w| w.iter().map(|&c| S::from_id(c)).collect())
            })
            .collect();
        let mut word: Vec<S> = self.axiom.iter().map(|&c| S::from_id(c)).collect();
        for _ in 0..depth {
            let mut next = Vec::with_capacity(word.len());
            for &s in &word {
                match &succ[s.id() as usize] {
                    Some(w) => next.extend_from_slice(w),
                    None => next.push(s),
                }
            }
            word = next;
        }
        word
    }
}

/// A compact symbol id for the `bfs` word.
trait SymId: Copy {
    fn from_id(id: u32) -> Self;
    fn id(self) -> u32;
}

impl SymId for u8 {
    fn from_id(id: u32) -> Self {
        id as u8
    }
    fn id(self) -> u32 {
        u32::from(self)
    }
}

impl SymId for u32 {
    fn from_id(id: u32) -> Self {
        id
    }
    fn id(self) -> u32 {
        self
    }
}
