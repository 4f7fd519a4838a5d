//! Mutation smoke test on stable Rust: the fuzz targets' bodies
//! (`fuzz/bodies/`) over random mutations of their committed seeds, without
//! nightly, libFuzzer or coverage guidance. Blunter than `cargo fuzz`, but
//! it runs anywhere in seconds; it found the first three bugs the bodies
//! caught (docs/fuzzing.md).
//!
//! ```text
//! cargo run --release --example fuzz_smoke -- TARGET [RUNS] [SEED]
//! ```
//! TARGET: `lsys_parse`, `lsys_render`, `od_compile`, `stl_parse` or `all`;
//! RUNS per target (default 10,000); SEED of the mutations (default 1).
//! Each input that breaks a promise is written to
//! `fuzz/artifacts/smoke/<target>-<n>`; the exit status is 1 if any did.

#[path = "../fuzz/bodies/lsys_parse.rs"]
mod lsys_parse;
#[path = "../fuzz/bodies/lsys_render.rs"]
mod lsys_render;
#[path = "../fuzz/bodies/od_compile.rs"]
mod od_compile;
#[path = "../fuzz/bodies/stl_parse.rs"]
mod stl_parse;

use std::path::{Path, PathBuf};

/// Pieces of the languages a mutation may insert: probabilities, dotted
/// names, repeats, roots, keys, extreme numbers.
const TOKENS: &[&str] = &[
    "(0.5)",
    "(1)",
    "(0)",
    "(1e9)",
    "R1.1",
    "R1.9",
    "R1",
    "R2",
    "[I 3 R1]",
    "[I 0 F]",
    "[I 2 R1.1]",
    "(1, 2)",
    "(5,5) (6,6)",
    "{",
    "}",
    ",",
    "[",
    "]",
    "SEED\n",
    "ENDSEED\n",
    "RULE\n",
    "F",
    "+",
    "-",
    ".",
    "\n",
    " -> ",
    " (0.3): ",
    "9999999999",
    "rule F (0.5) -> F[+F]F\n",
    "seed 18446744073709551615\n",
    "generations 30\n",
    "width 1e300\n",
    "angle 1e-300\n",
    "R1 (0.5): [+F]\n",
    "R1.1 (0.5): [-F]\n",
    "B=1e12(0)",
    "L=1e-300(0)",
    "L=10(10)",
    "A=1e300",
    "C=1e300",
    "(clRed) Ellipse (0,0), 1e300, 5\n",
];

/// A target's body: returns, or panics on a broken promise.
type Body = fn(&[u8]);

/// xorshift64*: a small deterministic generator, so a SEED replays.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// One to five edits: insert a token, delete a few bytes, duplicate a
/// line, or overwrite a byte with printable ASCII.
fn mutate(rng: &mut Rng, seed: &[u8]) -> Vec<u8> {
    let mut data = seed.to_vec();
    for _ in 0..1 + rng.below(5) {
        let at = rng.below(data.len() + 1);
        match rng.below(20) {
            0..=8 => {
                let t = TOKENS[rng.below(TOKENS.len())].as_bytes();
                data.splice(at..at, t.iter().copied());
            }
            9..=13 if !data.is_empty() => {
                let end = (at + 1 + rng.below(8)).min(data.len());
                data.drain(at.min(end)..end);
            }
            14..=16 => {
                let mut lines: Vec<&[u8]> = data.split(|&b| b == b'\n').collect();
                let i = rng.below(lines.len());
                lines.insert(i, lines[i]);
                data = lines.join(&b'\n');
            }
            _ if at < data.len() => data[at] = 32 + rng.below(95) as u8,
            _ => {}
        }
    }
    data
}

fn seeds(root: &Path, target: &str) -> Vec<Vec<u8>> {
    let dir = root.join("fuzz/corpus").join(target);
    let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.expect("a directory entry").path())
        .filter(|p| {
            p.file_name()
                .is_some_and(|n| n.to_string_lossy().starts_with("seed-"))
        })
        .collect();
    files.sort();
    files
        .iter()
        .map(|f| std::fs::read(f).expect("a corpus seed"))
        .collect()
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let which = args.first().map_or("all", String::as_str);
    let runs: usize = args.get(1).map_or(10_000, |r| r.parse().expect("RUNS"));
    let seed: u64 = args.get(2).map_or(1, |s| s.parse().expect("SEED"));
    let targets: [(&str, Body); 4] = [
        ("lsys_parse", lsys_parse::run),
        ("lsys_render", lsys_render::run),
        ("od_compile", od_compile::run),
        ("stl_parse", stl_parse::run),
    ];
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let out = root.join("fuzz/artifacts/smoke");
    let mut broken = 0;
    for (name, body) in targets {
        if which != "all" && which != name {
            continue;
        }
        let corpus = seeds(root, name);
        let mut rng = Rng(seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1);
        let start = std::time::Instant::now();
        let mut found = 0;
        for n in 0..runs {
            let pick = rng.below(corpus.len());
            let data = mutate(&mut rng, &corpus[pick]);
            if std::panic::catch_unwind(|| body(&data)).is_err() {
                std::fs::create_dir_all(&out).expect("fuzz/artifacts/smoke");
                let path = out.join(format!("{name}-{n}"));
                std::fs::write(&path, &data).expect("an artifact");
                println!("{name}: broke a promise: {}", path.display());
                found += 1;
            }
        }
        println!(
            "{name}: {runs} inputs from {} seeds, {found} broken, {:.1} s",
            corpus.len(),
            start.elapsed().as_secs_f64()
        );
        broken += found;
    }
    if broken > 0 {
        std::process::exit(1);
    }
}
