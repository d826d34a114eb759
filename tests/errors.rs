//! Data-driven diagnostics: every `tests/errors/*.sdf` (and `tests/warnings/*.sdf`) is checked and its rendered diagnostics
//! are snapshotted exactly as the user sees them.

use sdfc_compiler::{check, diag, syntax};

/// Checks a case as `sdfc check` does: named by its path relative to this crate (the working
/// directory of tests), so its imports are read beside it (`errors/lib/…`).
fn compile(name: &str, source: String) -> check::Checked {
    let name = name.to_string();
    sdfc_tests::with_stack(move || {
        check::compile_file(&name, &source, &Default::default(), &syntax::FsLoader)
    })
}

#[test]
fn error_snapshots() {
    let mut count = 0;
    insta::glob!("errors/*.sdf", |path| {
        let source = std::fs::read_to_string(path).expect("read");
        let name = format!("errors/{}", path.file_name().unwrap().to_string_lossy());
        let checked = compile(&name, source);
        assert!(checked.scene.is_none(), "{name} compiled but should not");
        let errors = checked.diagnostics.iter().filter(|d| d.is_error()).count();
        assert!(errors > 0, "{name}: no error reported");
        insta::assert_snapshot!(diag::render_sources(
            &checked.diagnostics,
            &checked.sources,
            false
        ));
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
        let checked = compile(&name, source);
        assert!(checked.scene.is_some(), "{name} should compile");
        assert!(!checked.diagnostics.is_empty(), "{name}: no warning");
        insta::assert_snapshot!(diag::render_sources(
            &checked.diagnostics,
            &checked.sources,
            false
        ));
        count += 1;
    });
    assert!(count >= 1);
}
