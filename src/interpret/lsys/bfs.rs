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

    /// Streams the word `W(axiom, depth)` depth-first, symbol by symbol,
    /// into `f` (its index and the symbol), with an explicit stack of
    /// `(word, position, remaining depth)` frames: no precomputation, memory
    /// O(depth). The fallback of `dfs` when its program would pass
    /// `program::PROGRAM_CAP`.
    pub(super) fn plain_each(&self, depth: u32, mut f: impl FnMut(u64, u32)) {
        let mut frames: Vec<(&[u32], usize, u32)> = vec![(&self.axiom, 0, depth)];
        let mut i = 0u64;
        while let Some(top) = frames.last_mut() {
            let Some(&s) = top.0.get(top.1) else {
                frames.pop();
                continue;
            };
            top.1 += 1;
            let r = top.2;
            match &self.succ[s as usize] {
                Some(w) if r > 0 => frames.push((w, 0, r - 1)),
                _ => {
                    f(i, s);
                    i += 1;
                }
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
