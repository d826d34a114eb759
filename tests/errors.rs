//! Data-driven diagnostics: every `tests/errors/*.sdf` (and `tests/warnings/*.sdf`) is checked and its rendered diagnostics
//! are snapshotted exactly as the user sees them.

use sdfc_compiler::{check, diag};

#[test]
fn error_snapshots() {
    let mut count = 0;
    insta::glob!("errors/*.sdf", |path| {
        let source = std::fs::read_to_string(path).expect("read");
        let name = format!("errors/{}", path.file_name().unwrap().to_string_lossy());
        let checked = sdfc_tests::with_stack(move || check::compile(&source));
        assert!(checked.scene.is_none(), "{name} compiled but should not");
        let errors = checked.diagnostics.iter().filter(|d| d.is_error()).count();
        assert!(errors > 0, "{name}: no error reported");
        let source = std::fs::read_to_string(path).expect("read");
        insta::assert_snapshot!(diag::render(&checked.diagnostics, &name, &source));
        count += 1;
    });
    assert!(count >= 30, "only {count} error cases");
}

/// Every `tests/warnings/*.sdf` compiles, with at least one warning, snapshotted.
#[test]
fn warning_snapshots() {
    let mut count = 0;
    insta::glob!("warnings/*.sdf", |path| {
        let source = std::fs::read_to_string(path).expect("read");
        let name = format!("warnings/{}", path.file_name().unwrap().to_string_lossy());
        let checked = sdfc_tests::with_stack(move || check::compile(&source));
        assert!(checked.scene.is_some(), "{name} should compile");
        assert!(!checked.diagnostics.is_empty(), "{name}: no warning");
        let source = std::fs::read_to_string(path).expect("read");
        insta::assert_snapshot!(diag::render(&checked.diagnostics, &name, &source));
        count += 1;
    });
    assert!(count >= 1);
}
