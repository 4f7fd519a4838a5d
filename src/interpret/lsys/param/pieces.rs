//! The distinct pieces of a parametric word (memo.rs, memo3.rs): a piece
//! is a module (its symbol and parameter values, bit for bit) expanded
//! `r` more times. They are interned from the axiom down, a node per
//! module and depth, each one's successor as nodes one level down, so a
//! memo can compose what each does bottom-up, level by level.

use std::collections::HashMap;

use super::{Deriver, Word};
use crate::diag::Diagnostics;
use crate::model::lsys::LSystem;
use crate::model::param::{Parametric, eval};

/// Most pieces one memo may hold (about 200 bytes each).
pub const PARAM_NODES: usize = 1 << 17;

/// Most successor entries all pieces together may hold.
pub(super) const PARAM_SUCC: usize = 1 << 22;

/// The pieces of one system at one depth.
pub(super) struct Pieces {
    pub sym: Vec<char>,
    /// `off[i]..off[i + 1]`: node `i`'s parameters in `vals`.
    off: Vec<u32>,
    vals: Vec<f64>,
    /// A node's successor, as nodes one level down (`None`: a module no
    /// rule rewrites, or at depth 0).
    pub succ: Vec<Option<Vec<u32>>>,
    pub axiom: Vec<u32>,
    /// Per remaining depth, its nodes (a module no rule rewrites at 0):
    /// level by level from 0 up, children come before their parents.
    pub levels: Vec<Vec<u32>>,
    pub depth: u32,
    /// Successor entries of all pieces together.
    pub entries: usize,
}

/// A node's interning key: symbol, parameters' bits, remaining depth.
type NodeKey = (char, Vec<u64>, u32);

impl Pieces {
    /// The pieces of `sys` to `depth` (the caller has checked the system
    /// is one whose equal modules expand alike), `None` past
    /// [`PARAM_NODES`] or [`PARAM_SUCC`]; an error where deriving would
    /// fail (a non-finite parameter).
    pub fn new(sys: &LSystem, p: &Parametric, depth: u32) -> Result<Option<Pieces>, Diagnostics> {
        let d = Deriver::new(sys, p);
        let mut m = Pieces {
            sym: Vec::new(),
            off: vec![0],
            vals: Vec::new(),
            succ: Vec::new(),
            axiom: Vec::new(),
            levels: Vec::new(),
            depth,
            entries: 0,
        };
        let mut index: HashMap<NodeKey, u32> = HashMap::new();
        // Per level, the nodes first met there, in the order met.
        let mut levels: Vec<Vec<u32>> = vec![Vec::new(); depth as usize + 1];
        let mut axiom = Vec::with_capacity(p.axiom.len());
        for md in &p.axiom {
            let vals: Vec<f64> = md.args.iter().map(|e| eval(e, &[])).collect();
            match m.intern(&d, &mut index, &mut levels, md.symbol, &vals, depth) {
                Some(id) => axiom.push(id),
                None => return Ok(None),
            }
        }
        m.axiom = axiom;
        let (mut one, mut out, mut bind) = (Word::new(), Word::new(), Vec::new());
        for r in (1..=depth).rev() {
            let level = std::mem::take(&mut levels[r as usize]);
            for &id in &level {
                one.clear();
                one.push(
                    m.sym[id as usize],
                    m.params(id),
                    crate::choice::Key::root(0),
                );
                out.clear();
                d.rewrite(&one, &[], 0, depth - r + 1, &mut out, &mut bind)?;
                m.entries += out.len();
                if m.entries > PARAM_SUCC {
                    return Ok(None);
                }
                let mut kids = Vec::with_capacity(out.len());
                for j in 0..out.len() {
                    match m.intern(
                        &d,
                        &mut index,
                        &mut levels,
                        out.syms[j],
                        out.params(j),
                        r - 1,
                    ) {
                        Some(k) => kids.push(k),
                        None => return Ok(None),
                    }
                }
                m.succ[id as usize] = Some(kids);
            }
            levels[r as usize] = level;
        }
        m.levels = levels;
        Ok(Some(m))
    }

    /// Node `id`'s parameters.
    pub fn params(&self, id: u32) -> &[f64] {
        &self.vals[self.off[id as usize] as usize..self.off[id as usize + 1] as usize]
    }

    /// How many nodes.
    pub fn len(&self) -> usize {
        self.sym.len()
    }

    /// The node of module `sym(vals)` at remaining depth `r` (depth 0 for
    /// a module no rule rewrites: it is the same at every depth), new ones
    /// queued on their level; `None` past [`PARAM_NODES`].
    fn intern(
        &mut self,
        d: &Deriver,
        index: &mut HashMap<NodeKey, u32>,
        levels: &mut [Vec<u32>],
        sym: char,
        vals: &[f64],
        r: u32,
    ) -> Option<u32> {
        let mut key: NodeKey = (sym, vals.iter().map(|v| v.to_bits()).collect(), r);
        if let Some(&id) = index.get(&key) {
            return Some(id);
        }
        if r > 0 && !d.applies(sym, vals) {
            key.2 = 0;
            if let Some(&id) = index.get(&key) {
                return Some(id);
            }
        }
        let r = key.2;
        if self.sym.len() >= PARAM_NODES {
            return None;
        }
        let id = self.sym.len() as u32;
        self.sym.push(sym);
        self.vals.extend_from_slice(vals);
        self.off.push(self.vals.len() as u32);
        self.succ.push(None);
        index.insert(key, id);
        levels[r as usize].push(id);
        Some(id)
    }
}
