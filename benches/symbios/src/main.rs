//! Parametric derivation, stlc against the `symbios` crate, on the same
//! systems: Honda's monopodial tree (ABOP Fig. 2.6a,
//! `examples/abop-2.6a.lsys`) and Anabaena catenula with heterocysts
//! (ABOP Fig. 1.35, `examples/abop-1.35.lsys`), written for symbios in
//! its own syntax below.
//!
//! ```text
//! symbios-bench ENGINE SYSTEM DEPTH      # ENGINE: symbios | stlc
//! symbios-bench counts SYSTEM DEPTH      # modules per generation, both engines
//! symbios-bench words SYSTEM DEPTH       # every generation's words, both engines, compared
//! symbios-bench show SYSTEM DEPTH        # both words at DEPTH, printed
//! ```
//!
//! `ENGINE SYSTEM DEPTH` reads the system, derives it to DEPTH and prints
//! `modules seconds modules_per_second`: the time of the derivation
//! alone (wall clock, in-process, after parsing; the word is not
//! written). stlc's derivation is the one `expand`, `stats` and `render`
//! use (`interpret::lsys::param::Deriver`, dfs, which streams Honda's
//! context-free tree and derives Anabaena's contexts level by level);
//! symbios rewrites its word level by level (`System::derive`).
//! `benches/symbios.sh` runs it under GNU time for CPU seconds and peak
//! memory.

use std::process::ExitCode;
use std::time::Instant;

use stlc::interpret::Derivation;
use stlc::interpret::lsys::param::{self, Deriver};
use stlc::pipeline::{InputKind, Loaded, load};
use stlc::{Limits, model::lsys::LSystem};
use symbios::System;

/// The examples' paths, from this crate's directory.
const HONDA: &str = include_str!("../../../examples/abop-2.6a.lsys");
const ANABAENA: &str = include_str!("../../../examples/abop-1.35.lsys");

/// Honda's tree in symbios's syntax: multi-letter symbols, so modules
/// are separated by spaces. The same constants and rules as
/// `examples/abop-2.6a.lsys` (symbios's own `examples/monopodial_tree.rs`
/// has `l*r1` in A's branch where ABOP and stlc have `l*r2`).
fn honda() -> Result<System, String> {
    let mut s = System::new();
    for d in [
        "#define r1 0.9",
        "#define r2 0.6",
        "#define a0 45",
        "#define a2 45",
        "#define d 137.5",
        "#define wr 0.707",
    ] {
        s.add_directive(d).map_err(|e| e.to_string())?;
    }
    for r in [
        "A(l,w) -> !(w) F(l) [ &(a0) B(l*r2,w*wr) ] /(d) A(l*r1,w*wr)",
        "B(l,w) -> !(w) F(l) [ -(a2) $ C(l*r2,w*wr) ] C(l*r1,w*wr)",
        "C(l,w) -> !(w) F(l) [ +(a2) $ B(l*r2,w*wr) ] B(l*r1,w*wr)",
    ] {
        s.add_rule(r).map_err(|e| e.to_string())?;
    }
    s.set_axiom("A(1,10)").map_err(|e| e.to_string())?;
    Ok(s)
}

/// Anabaena in symbios's syntax. stlc applies the first matching rule in
/// file order (language section 12); symbios chooses at random among all
/// the rules that match. A growing cell that divides (`t==1 && s>=6`)
/// also satisfies the third rule's condition (`s>ST`), so the third rule
/// says `!(s>=6 & (t==1 | t==2))` to leave it to the division rules, as
/// file order does in stlc: the same rule applies to every module in
/// both. symbios spells `&&` and `||` as `&` and `|`, and its comparisons
/// call numbers within a relative 1e-8 of each other equal (a cell of
/// length 5.999999999999993 is `>= 6` there, not in stlc, and divides a
/// generation early): each comparison of a length or a concentration is
/// written as the sign of the difference times 1e9, which rounding keeps
/// exact (`x - y` is zero only when `x == y` and has its sign) and no
/// difference of these parameters brings within symbios's absolute
/// 2.2e-14 of 0, so symbios compares as stlc does.
fn anabaena() -> Result<System, String> {
    let mut s = System::new();
    for d in [
        "#define CH 900",
        "#define CT 0.4",
        "#define ST 3.9",
        "#ignore: f ~ H",
    ] {
        s.add_directive(d).map_err(|e| e.to_string())?;
    }
    for r in [
        "F(s,t,c) : t==1 & (s-6)*1e9>=0 -> F(s/3*2,2,c) f(1) F(s/3,1,c)",
        "F(s,t,c) : t==2 & (s-6)*1e9>=0 -> F(s/3,2,c) f(1) F(s/3*2,1,c)",
        "F(h,i,k) < F(s,t,c) > F(o,p,r) : ((s-ST)*1e9>0 | (c-CT)*1e9>0) & !((s-6)*1e9>=0 & (t==1 | t==2)) -> F(s+0.1,t,c+0.25*(k+r-3*c))",
        "F(h,i,k) < F(s,t,c) > F(o,p,r) : !((s-ST)*1e9>0 | (c-CT)*1e9>0) -> F(0,0,CH) H(1)",
        "H(s) : (s-3)*1e9<0 -> H(s*1.1)",
    ] {
        s.add_rule(r).map_err(|e| e.to_string())?;
    }
    s.set_axiom("-(90) F(0,0,CH) F(4,1,CH) F(0,0,CH)")
        .map_err(|e| e.to_string())?;
    Ok(s)
}

fn symbios_system(name: &str) -> Result<System, String> {
    let mut s = match name {
        "honda" => honda()?,
        "anabaena" => anabaena()?,
        _ => return Err(format!("unknown system {name} (honda, anabaena)")),
    };
    // The default refuses past 10^6 modules; Honda's depth 18 has 1.8 M.
    s.max_capacity = usize::MAX;
    Ok(s)
}

fn stlc_system(name: &str) -> Result<LSystem, String> {
    let text = match name {
        "honda" => HONDA,
        "anabaena" => ANABAENA,
        _ => return Err(format!("unknown system {name} (honda, anabaena)")),
    };
    match load(text.as_bytes(), InputKind::Lsys, &Limits::DEFAULT) {
        Ok(Loaded::Lsys(sys)) => Ok(sys),
        Ok(_) => Err("not an L-system".into()),
        Err(e) => Err(format!("{e:?}")),
    }
}

/// The word in stlc's `expand` notation: `A(0.9,7.07)`, each number the
/// shortest that reads back (Rust's `{}` of an f64), no spaces.
fn module(out: &mut String, sym: &str, params: &[f64]) {
    use std::fmt::Write as _;
    out.push_str(sym);
    if !params.is_empty() {
        out.push('(');
        for (i, v) in params.iter().enumerate() {
            if i > 0 {
                out.push(',');
            }
            let _ = write!(out, "{v}");
        }
        out.push(')');
    }
}

fn symbios_word(s: &System) -> String {
    let mut out = String::new();
    for i in 0..s.state.len() {
        let v = s.state.get_view(i).expect("a module in range");
        module(&mut out, s.interner.resolve(v.sym).unwrap_or("?"), v.params);
    }
    out
}

/// stlc's derivation to `depth`: the number of modules, and the word
/// when `word` is given.
fn stlc_derive(sys: &LSystem, depth: u32, mut word: Option<&mut String>) -> Result<u64, String> {
    let p = param::of(sys).ok_or("not a parametric system")?;
    let limits = Limits {
        max_depth: 100_000,
        ..Limits::DEFAULT
    };
    Deriver::new(sys, p)
        .each(depth, Derivation::Dfs, &limits, |c, ps| {
            if let Some(w) = word.as_deref_mut() {
                let mut b = [0u8; 4];
                module(w, c.encode_utf8(&mut b), ps);
            }
        })
        .map_err(|e| format!("{e:?}"))
}

fn run(args: &[String]) -> Result<(), String> {
    let [mode, name, depth] = args else {
        return Err("usage: symbios-bench symbios|stlc|counts|words|show SYSTEM DEPTH".into());
    };
    let depth: u32 = depth.parse().map_err(|_| "DEPTH: a whole number")?;
    match mode.as_str() {
        "symbios" => {
            let mut s = symbios_system(name)?;
            let t = Instant::now();
            s.derive(depth as usize).map_err(|e| e.to_string())?;
            let secs = t.elapsed().as_secs_f64();
            let n = s.state.len();
            println!("{n} {secs:.6} {:.0}", n as f64 / secs);
        }
        "stlc" => {
            let sys = stlc_system(name)?;
            let t = Instant::now();
            let n = stlc_derive(&sys, depth, None)?;
            let secs = t.elapsed().as_secs_f64();
            println!("{n} {secs:.6} {:.0}", n as f64 / secs);
        }
        "counts" => {
            let sys = stlc_system(name)?;
            let mut s = symbios_system(name)?;
            let mut same = true;
            for g in 0..=depth {
                if g > 0 {
                    s.derive(1).map_err(|e| e.to_string())?;
                }
                let a = stlc_derive(&sys, g, None)?;
                let b = s.state.len() as u64;
                same &= a == b;
                println!("{g} {a} {b}{}", if a == b { "" } else { " differ" });
            }
            if !same {
                return Err("module counts differ".into());
            }
        }
        "words" => {
            let sys = stlc_system(name)?;
            let mut s = symbios_system(name)?;
            let mut first = None;
            for g in 0..=depth {
                if g > 0 {
                    s.derive(1).map_err(|e| e.to_string())?;
                }
                let mut a = String::new();
                stlc_derive(&sys, g, Some(&mut a))?;
                if a != symbios_word(&s) && first.is_none() {
                    first = Some(g);
                }
            }
            match first {
                None => println!("the words agree at every generation 0..={depth}"),
                Some(g) => return Err(format!("the words differ first at generation {g}")),
            }
        }
        "show" => {
            let sys = stlc_system(name)?;
            let mut s = symbios_system(name)?;
            s.derive(depth as usize).map_err(|e| e.to_string())?;
            let mut a = String::new();
            stlc_derive(&sys, depth, Some(&mut a))?;
            println!("stlc    {a}\nsymbios {}", symbios_word(&s));
        }
        _ => return Err(format!("unknown mode {mode}")),
    }
    Ok(())
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("symbios-bench: {e}");
            ExitCode::FAILURE
        }
    }
}
