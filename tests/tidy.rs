//! Tidy checks: every Rust source opens with a one-line `//!` module doc, no trailing whitespace.

#[test]
fn sources_are_tidy() {
    let root = sdfc_tests::root();
    let mut files = Vec::new();
    for dir in ["compiler", "runtime", "tests"] {
        sdfc_tests::rust_files(&root.join(dir), &mut files);
    }
    assert!(files.len() > 10);
    let mut problems = Vec::new();
    for f in files {
        let text = std::fs::read_to_string(&f).unwrap();
        if !text.starts_with("//!") {
            problems.push(format!(
                "{}: does not start with a `//!` module doc",
                f.display()
            ));
        }
        for (i, line) in text.lines().enumerate() {
            if line.ends_with(' ') || line.ends_with('\t') {
                problems.push(format!("{}:{}: trailing whitespace", f.display(), i + 1));
            }
        }
        let lines = text.lines().count();
        if lines > 700 {
            problems.push(format!("{}: {lines} lines; split it", f.display()));
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
