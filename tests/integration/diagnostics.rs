//! Rendered diagnostics, as a user sees them on stderr (colour off): one
//! snapshot per file in `tests/cases/errors/`. `.od` files that parse are
//! compiled, so growth errors (root outside, unbounded) are covered too.
//!
//! Review changes with `cargo insta review` (or `INSTA_UPDATE=always`, then
//! read `git diff`); CI never writes snapshots.

use std::fs;

use crate::support::{manifest_path, stlc};

#[test]
fn every_error_case_renders_a_pointed_report() {
    let dir = manifest_path("tests/cases/errors");
    let mut names: Vec<String> = fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert!(names.len() >= 12, "{names:?}");
    for name in names {
        let args: Vec<&str> = if name.ends_with(".od") {
            vec!["compile", &name, "-o", "-", "--color", "never"]
        } else {
            vec!["check", &name, "--color", "never"]
        };
        let out = stlc().current_dir(&dir).args(&args).output().unwrap();
        assert_eq!(out.status.code(), Some(1), "{name} should fail with exit 1");
        assert!(out.stdout.is_empty(), "{name}: nothing on stdout");
        let stderr = String::from_utf8(out.stderr).unwrap();
        // Every report names the file and says how to fix it.
        assert!(stderr.contains(&name), "{name}: {stderr}");
        assert!(stderr.to_lowercase().contains("help"), "{name}: {stderr}");
        insta::assert_snapshot!(name.replace('.', "_"), stderr);
    }
}

/// Every limit an error can name ([`stlc::Bound`]) is raised by a real
/// flag: `render --help` (or `serve --help`) lists it with the value name
/// the hints use, and shows the bound's default as the flag's; and
/// docs/limits.md names the flag.
#[test]
fn every_bound_names_a_real_flag_with_its_default() {
    let help = |command: &str| {
        String::from_utf8(crate::support::stlc_piped(&format!("{command} --help"), "")).unwrap()
    };
    let helps = [help("render"), help("serve")];
    let docs = fs::read_to_string(manifest_path("docs/limits.md")).unwrap();
    for bound in stlc::Bound::ALL {
        let flag = format!("{} <{}>", bound.flag(), bound.value_name());
        let entry = helps
            .iter()
            .find_map(|h| {
                let at = h.find(&format!("      {flag}\n"))?;
                let rest = &h[at + flag.len() + 7..];
                // The flag's entry runs to the next flag.
                Some(&rest[..rest.find("\n  -").unwrap_or(rest.len())])
            })
            .unwrap_or_else(|| panic!("{bound:?}: no `{flag}` in render or serve --help"));
        // --max-stems has no default of its own on the command line: not
        // given, growth stops at the default with a warning.
        if bound != stlc::Bound::Stems {
            let default = stlc::limits::Limits::DEFAULT.get(bound);
            let shown = entry.contains(&format!("[default: {default}]"));
            assert!(
                shown,
                "{bound:?}: {flag} does not default to {default}:\n{entry}"
            );
        }
        let written = format!("`{} {}`", bound.flag(), bound.value_name());
        let holds = docs.contains(&written);
        assert!(holds, "{bound:?}: docs/limits.md lacks {written}");
    }
}
