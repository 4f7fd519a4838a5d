//! The library's files import one another one way (docs/architecture.md,
//! "Imports run one way"): no two files import each other, directly or
//! round a loop. A `mod.rs` declaring its children (`mod x;`) and
//! re-exporting their items (`pub use x::Y;`) is its table of contents, not
//! an import; anything else it uses of a child is.
//!
//! The loops that stood when the rule came are listed in [`KNOWN_LOOPS`],
//! each a debt: the test fails on a new loop, and on a listed one that is
//! gone (strike it from the list), so the list only shrinks.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use crate::support;

/// Loops that still stand, each as its files' modules, sorted and joined
/// by spaces. Every one is a `mod.rs` whose children use its items while
/// it calls theirs: moving the shared items into a leaf file of their own
/// (as `grow/options.rs` did for `grow`) breaks it.
const KNOWN_LOOPS: &[&str] = &[];

/// A file's module path: `grow/grower` for `src/grow/grower.rs`, `grow`
/// for `src/grow/mod.rs`, `` for `lib.rs` and `main.rs`.
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    parts
}

/// The code of a file as the graph reads it: no comment lines, nothing
/// from the first `#[cfg(test)]` on, no `pub use` statements.
fn code(text: &str) -> String {
    let text = text.split("#[cfg(test)]").next().unwrap_or("");
    let mut out = String::new();
    let mut in_pub_use = false;
    for line in text.lines() {
        let t = line.trim_start();
        if t.starts_with("//") {
            continue;
        }
        if t.starts_with("pub use ") || t.starts_with("pub(crate) use ") {
            in_pub_use = true;
        }
        if !in_pub_use {
            out.push_str(line);
            out.push('\n');
        }
        if in_pub_use && line.contains(';') {
            in_pub_use = false;
        }
    }
    out
}

/// The paths `code` names from `root` (`crate`, `super` or a child
/// module's name) on: each `a::b::c`, and each item of a `{...}` group.
fn paths_from(code: &str, root: &str) -> Vec<Vec<String>> {
    let needle = format!("{root}::");
    let mut found = Vec::new();
    let mut rest = code;
    while let Some(at) = rest.find(&needle) {
        let whole =
            at == 0 || !rest[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_' || c == ':');
        rest = &rest[at + needle.len()..];
        if !whole {
            continue;
        }
        let head: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
            .collect();
        let mut prefix: Vec<String> = head
            .split("::")
            .filter(|s| !s.is_empty())
            .map(str::to_string)
            .collect();
        let after = &rest[head.len()..];
        // Past the whole path: `super::super::x` is one path, not two.
        let next = rest.len() - after.len();
        if let Some(group) = after.strip_prefix('{') {
            let end = group.find('}').unwrap_or(group.len());
            for item in group[..end].split(',') {
                let mut path = prefix.clone();
                path.extend(
                    item.split("::")
                        .map(|s| {
                            s.trim()
                                .split(|c: char| !(c.is_alphanumeric() || c == '_'))
                                .next()
                                .unwrap_or("")
                        })
                        .filter(|s| !s.is_empty() && *s != "self")
                        .map(str::to_string),
                );
                found.push(path);
            }
        } else if !prefix.is_empty() {
            found.push(std::mem::take(&mut prefix));
        }
        rest = &rest[next..];
    }
    found
}

/// Module → the modules (files) it imports.
fn graph(src: &Path) -> BTreeMap<Vec<String>, BTreeSet<Vec<String>>> {
    let files = super::architecture::rust_files(src);
    let modules: BTreeSet<Vec<String>> = files.iter().map(|f| module_of(src, f)).collect();
    let mut edges = BTreeMap::new();
    for file in &files {
        let me = module_of(src, file);
        let text = std::fs::read_to_string(file).unwrap();
        let code = code(&text);
        let kids: Vec<String> = code
            .lines()
            .filter_map(|l| {
                let l = l.trim_start();
                let l = l
                    .strip_prefix("pub ")
                    .or(l.strip_prefix("pub(crate) "))
                    .unwrap_or(l);
                l.strip_prefix("mod ")?
                    .strip_suffix(';')
                    .map(str::to_string)
            })
            .collect();
        let mut full_paths = Vec::new();
        for p in paths_from(&code, "crate") {
            full_paths.push(p);
        }
        for p in paths_from(&code, "super") {
            // `super` is the module's parent, a `mod.rs`'s too.
            let mut base = me.clone();
            let mut rest = p.as_slice();
            base.pop();
            while rest.first().is_some_and(|s| s == "super") {
                base.pop();
                rest = &rest[1..];
            }
            base.extend(rest.iter().cloned());
            full_paths.push(base);
        }
        for kid in &kids {
            for p in paths_from(&code, kid) {
                let mut base = me.clone();
                base.push(kid.clone());
                base.extend(p);
                full_paths.push(base);
            }
        }
        let targets: &mut BTreeSet<Vec<String>> = edges.entry(me.clone()).or_default();
        for path in full_paths {
            // The longest prefix that is a file of its own.
            if let Some(target) = (1..=path.len())
                .rev()
                .map(|k| path[..k].to_vec())
                .find(|m| modules.contains(m))
                && target != me
            {
                targets.insert(target);
            }
        }
    }
    edges
}

/// The loops of `edges`: its strongly connected components of more than one
/// module (Tarjan's algorithm), each sorted.
fn loops(edges: &BTreeMap<Vec<String>, BTreeSet<Vec<String>>>) -> Vec<Vec<Vec<String>>> {
    struct T<'a> {
        edges: &'a BTreeMap<Vec<String>, BTreeSet<Vec<String>>>,
        index: BTreeMap<&'a Vec<String>, (usize, usize)>,
        stack: Vec<&'a Vec<String>>,
        next: usize,
        found: Vec<Vec<Vec<String>>>,
    }
    fn visit<'a>(t: &mut T<'a>, v: &'a Vec<String>) {
        t.index.insert(v, (t.next, t.next));
        t.next += 1;
        t.stack.push(v);
        for w in t.edges.get(v).into_iter().flatten() {
            if !t.index.contains_key(w) {
                visit(t, w);
                let low = t.index[w].1.min(t.index[v].1);
                t.index.get_mut(v).unwrap().1 = low;
            } else if t.stack.contains(&w) {
                let low = t.index[w].0.min(t.index[v].1);
                t.index.get_mut(v).unwrap().1 = low;
            }
        }
        if t.index[v].0 == t.index[v].1 {
            let mut component = Vec::new();
            while let Some(w) = t.stack.pop() {
                component.push(w.clone());
                if w == v {
                    break;
                }
            }
            if component.len() > 1 {
                component.sort();
                t.found.push(component);
            }
        }
    }
    let mut t = T {
        edges,
        index: BTreeMap::new(),
        stack: Vec::new(),
        next: 0,
        found: Vec::new(),
    };
    for v in edges.keys() {
        if !t.index.contains_key(v) {
            visit(&mut t, v);
        }
    }
    t.found
}

fn name(component: &[Vec<String>]) -> String {
    component
        .iter()
        .map(|m| m.join("/"))
        .collect::<Vec<_>>()
        .join(" ")
}

#[test]
fn the_graph_reader_sees_crate_super_and_child_paths() {
    let code = code(
        "mod kid;\npub use kid::Shown;\nuse super::{a::B, c};\nuse crate::x::y::Z;\n\
         // crate::not::this\nfn f() { kid::run(); }\n#[cfg(test)]\nuse crate::tests_only;\n",
    );
    assert_eq!(paths_from(&code, "crate"), [vec!["x", "y", "Z"]]);
    assert_eq!(paths_from(&code, "super"), [vec!["a", "B"], vec!["c"]]);
    assert_eq!(paths_from(&code, "kid"), [vec!["run"]]);
    // `super::super::x` is one path.
    let up = paths_from("use super::super::x::Y;", "super");
    assert_eq!(up, [vec!["super", "x", "Y"]]);
    // A loop of three and a tail: Tarjan finds the three.
    let m = |s: &str| vec![s.to_string()];
    let mut edges = BTreeMap::new();
    edges.insert(m("a"), BTreeSet::from([m("b")]));
    edges.insert(m("b"), BTreeSet::from([m("c")]));
    edges.insert(m("c"), BTreeSet::from([m("a"), m("d")]));
    edges.insert(m("d"), BTreeSet::new());
    let found: Vec<String> = loops(&edges).iter().map(|c| name(c)).collect();
    assert_eq!(found, ["a b c"]);
}

#[test]
fn no_two_files_import_each_other_round_a_loop() {
    let edges = graph(&support::manifest_path("src"));
    assert!(edges.len() >= 100, "only {} files read", edges.len());
    let found: BTreeSet<String> = loops(&edges).iter().map(|c| name(c)).collect();
    let known: BTreeSet<String> = KNOWN_LOOPS.iter().map(|s| s.to_string()).collect();
    let new: Vec<&String> = found.difference(&known).collect();
    let round = "files that import each other round a loop";
    assert!(new.is_empty(), "{round}: {new:#?}");
    let gone: Vec<&String> = known.difference(&found).collect();
    let strike = "these loops are gone: strike them from KNOWN_LOOPS";
    assert!(gone.is_empty(), "{strike}: {gone:#?}");
}
