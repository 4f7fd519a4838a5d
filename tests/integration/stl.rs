//! `.od`/`.bed`: parsing, diagnostics, the canonical writer and expansion.

use stlc::bed::write::write;
use stlc::interpret::Strategy;
use stlc::interpret::bed::{draw_into, expand};
use stlc::limits::Limits;
use stlc::progress::NoProgress;
use stlc::syntax::ast::{Description, Format};
use stlc::syntax::stl::parse;
use stlc::turtle::Recorder;

fn bed(src: &str) -> Description {
    match parse(src, Format::Bed, &Limits::default()) {
        Ok(d) => d,
        Err(e) => panic!("{e}"),
    }
}

fn expanded(d: &Description, strategy: Strategy) -> String {
    let mut out = Vec::new();
    expand(d, strategy, &Limits::default(), &mut out, &mut NoProgress).unwrap();
    String::from_utf8(out).unwrap()
}

#[test]
fn the_papers_worked_expansion() {
    let d = bed("Rn (0, 0) L=10(0) B=1(0)
        RULE R1 = [F][+F][-F]  R2 = [++F][-F]
        SEED R1{R1{,,},R2{,},R1{,,}} ENDSEED");
    for s in [Strategy::Dfs, Strategy::Bfs] {
        assert_eq!(
            expanded(&d, s),
            "[F[F][+F][-F]][+F[++F][-F]][-F[F][+F][-F]]\n"
        );
    }
    println!("{}", write(&d));
}
