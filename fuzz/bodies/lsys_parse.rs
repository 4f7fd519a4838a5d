//! Bytes -> `precheck` -> `.lsys` parser. Any input must give an `LSystem`
//! or a `Diagnostics` with at least one error, never a panic, hang or
//! unbounded allocation.

use stlc::limits::Limits;
use stlc::syntax::{lsys, precheck};

/// The defaults, tightened so every input runs in milliseconds.
const LIMITS: Limits = Limits {
    max_input_bytes: 1 << 16,
    max_nesting: 1_000,
    max_depth: 16,
    max_repeat: 16,
    max_symbols: 1_000_000,
    max_word: 1_000_000,
    max_stems: 10_000,
    max_rule_parts: 1_000,
    max_layout_shapes: 100,
    ..Limits::DEFAULT
};

/// One input: returns normally, or panics on a broken promise.
pub fn run(data: &[u8]) {
    let Ok(text) = precheck(data, &LIMITS) else {
        return;
    };
    match lsys::parse(text, &LIMITS) {
        Ok(sys) => {
            // What the parser promises about a system it accepts.
            assert!(sys.angle.is_finite(), "angle {}", sys.angle);
            assert!(sys.length.is_finite(), "length {}", sys.length);
            assert!(sys.width.is_finite(), "width {}", sys.width);
            assert!(sys.generations.is_none_or(|g| g <= LIMITS.max_depth));
            assert!(!sys.axiom.is_empty(), "an accepted axiom is not empty");
            let balanced = |w: &[char]| {
                let mut d = 0i64;
                w.iter().all(|&c| {
                    d += match c {
                        '[' => 1,
                        ']' => -1,
                        _ => 0,
                    };
                    d >= 0
                }) && d == 0
            };
            assert!(balanced(&sys.axiom), "unbalanced axiom accepted");
            for ps in sys.rules.values() {
                for p in ps {
                    assert!(balanced(&p.successor), "unbalanced successor accepted");
                }
                // Several rules for a symbol only with probabilities, each a
                // finite number above 0, together 1 within the tolerance.
                if ps.len() > 1 || ps[0].probability.is_some() {
                    let p: Vec<f64> = ps
                        .iter()
                        .map(|p| p.probability.expect("all have one"))
                        .collect();
                    assert!(p.iter().all(|p| p.is_finite() && *p > 0.0), "{p:?}");
                    let sum: f64 = p.iter().sum();
                    assert!((sum - 1.0).abs() <= stlc::choice::SUM_TOLERANCE, "{p:?}");
                }
            }
        }
        Err(e) => {
            assert!(e.has_errors(), "an Err without an error: {e:?}");
            for d in e.iter() {
                if let Some(s) = &d.span {
                    assert!(
                        s.start <= s.end && s.end <= text.len(),
                        "span {s:?} outside the text"
                    );
                    assert!(text.is_char_boundary(s.start) && text.is_char_boundary(s.end));
                }
            }
        }
    }
}
