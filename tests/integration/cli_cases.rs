//! The command line as a user types it: the literate cases in
//! `tests/cmd/*.md` and the README's `console` blocks (trycmd), each a command, its exit status and what it
//! prints, read as documentation and run as tests. `TRYCMD=overwrite
//! cargo test cli_cases` rewrites their outputs after a deliberate change
//! (look at the diff before committing it).

#[test]
fn cli_cases() {
    trycmd::TestCases::new()
        .register_bin("stlc", assert_cmd::cargo::cargo_bin("stlc"))
        .env("NO_COLOR", "1")
        .case("tests/cmd/*.md")
        // The README's sessions, run from the crate's root.
        .case("README.md");
}
