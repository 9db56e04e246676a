//! Regression: the version was written three times — the library's Cargo.toml, the Python
//! crate's and pyproject.toml — and the Python package did not report it at all. It is now
//! written once, `[workspace.package] version` in Cargo.toml, which both crates inherit and
//! maturin puts in the wheel (`dynamic = ["version"]`); `inertance --version` prints it, and so
//! does `inertance.__version__` (`python/tests/test_regression_version_in_three_places.py`).

use std::process::Command;

/// Cargo.toml's `[workspace.package] version`, read as TOML.
fn workspace_version() -> String {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/Cargo.toml")).unwrap();
    let doc: toml_edit::DocumentMut = text.parse().unwrap();
    doc["workspace"]["package"]["version"]
        .as_str()
        .expect("[workspace.package] version")
        .to_string()
}

#[test]
fn the_cli_prints_the_workspace_version() {
    let out = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .arg("--version")
        .output()
        .unwrap();
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8(out.stdout).unwrap(),
        format!("inertance {}\n", workspace_version())
    );
    assert_eq!(inertance::VERSION, workspace_version());
}

/// No other manifest writes a version of its own: both crates inherit the workspace's, and
/// pyproject.toml takes it from the Python crate.
#[test]
fn the_version_is_written_once() {
    let read = |path: &str| -> toml_edit::DocumentMut {
        let file = format!("{}/{path}", env!("CARGO_MANIFEST_DIR"));
        std::fs::read_to_string(&file).unwrap().parse().unwrap()
    };
    for manifest in ["Cargo.toml", "python/Cargo.toml"] {
        let doc = read(manifest);
        assert_eq!(
            doc["package"]["version"]["workspace"].as_bool(),
            Some(true),
            "{manifest}: version.workspace = true"
        );
    }
    let project = read("python/pyproject.toml");
    assert!(project["project"].get("version").is_none());
    let dynamic = project["project"]["dynamic"].as_array().unwrap();
    assert!(dynamic.iter().any(|v| v.as_str() == Some("version")));
}
