//! The documentation runs: every command in `README.md` and in the guide (`guide/*.md`) is a
//! `console` block that this test executes with the binary just built, comparing its output
//! (stdout then stderr) and exit status with what the page shows — so a stale number fails CI.
//! Elided output is marked `...` (whole lines) or `[..]` (part of a line); `? 2` gives a
//! status other than 0. Blocks in other languages (`sh`, `toml`, `text`, `python`) are not run
//! here: the Python chapter's `>>>` examples run under `python/test.sh` (pytest's doctests).
//!
//! After changing an output on purpose, `TRYCMD=overwrite cargo test --test docs` rewrites the
//! pages' blocks with the new output; review the diff before committing.

#[test]
fn readme_and_guide_commands_print_what_they_show() {
    trycmd::TestCases::new()
        .register_bin("inertance", trycmd::cargo::cargo_bin("inertance"))
        .case("README.md")
        .case("guide/*.md");
}
