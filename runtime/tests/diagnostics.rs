//! Reports of many diagnostics: one order and one cap in every format — every error before
//! any warning, at most `diag::MAX_SHOWN` shown, the rest counted — and JSON's closing summary
//! object agreeing with the human report's count.

use crate::common::{scratch, sdfc};
use sdfc_compiler::diag::MAX_SHOWN;

/// `sdfc check FILE` in both formats: (exit code, human report, JSON objects).
fn both(file: &str) -> (Option<i32>, String, Vec<serde_json::Value>) {
    let human = sdfc(&["check", file]);
    let json = sdfc(&["check", file, "--message-format", "json"]);
    assert_eq!(human.status.code(), json.status.code());
    let objects = String::from_utf8_lossy(&json.stderr)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect();
    (
        human.status.code(),
        String::from_utf8_lossy(&human.stderr).to_string(),
        objects,
    )
}

/// An error after a thousand warnings is shown, first, in both formats (it was hidden behind
/// the first hundred warnings, with exit 1 and no error printed).
#[test]
fn an_error_behind_many_warnings_is_shown_first() {
    let dir = scratch("diag-order");
    let file = dir.join("scene.sdf");
    let mut source = "sphere(1) |> smooth_union(0.2)\n".repeat(1000);
    source += "sphere(-1)\n";
    std::fs::write(&file, &source).unwrap();
    let (code, human, json) = both(file.to_str().unwrap());
    assert_eq!(code, Some(1));
    assert!(
        human.starts_with("error"),
        "{}",
        &human[..human.len().min(400)]
    );
    assert!(human.contains(":1001:"), "the error's place is not shown");
    let rest = format!(
        "… and {} more (0 errors, {} warnings) not shown",
        1001 - MAX_SHOWN,
        1001 - MAX_SHOWN
    );
    assert!(
        human.contains(&rest),
        "{}",
        &human[human.len().saturating_sub(300)..]
    );
    assert_eq!(json.len(), MAX_SHOWN + 1, "the shown ones and the summary");
    assert_eq!(json[0]["severity"], "error");
    assert_eq!(json[0]["span"]["line"], 1001);
    assert!(
        json[1..MAX_SHOWN]
            .iter()
            .all(|d| d["severity"] == "warning")
    );
    let summary = &json[MAX_SHOWN]["summary"];
    assert_eq!(
        (
            &summary["errors"],
            &summary["warnings"],
            &summary["warnings_shown"]
        ),
        (&1.into(), &1000.into(), &(MAX_SHOWN - 1).into()),
        "{summary}"
    );
}

/// Five thousand errors: both formats show the first hundred and count the rest the same way;
/// JSON no longer prints every one (100 000 errors printed 26 MB in 110 s).
#[test]
fn many_errors_are_capped_alike_in_both_formats() {
    let dir = scratch("diag-cap");
    let file = dir.join("scene.sdf");
    std::fs::write(&file, "sphere(-1)\n".repeat(5000)).unwrap();
    let (code, human, json) = both(file.to_str().unwrap());
    assert_eq!(code, Some(1));
    assert_eq!(
        human.matches("\nerror").count() + 1,
        MAX_SHOWN,
        "{}",
        &human[..300]
    );
    assert!(human.contains(&format!(
        "… and {} more ({} errors, 0 warnings) not shown",
        5000 - MAX_SHOWN,
        5000 - MAX_SHOWN
    )));
    assert_eq!(json.len(), MAX_SHOWN + 1);
    assert_eq!(json[MAX_SHOWN]["summary"]["errors"], 5000);
    assert_eq!(json[MAX_SHOWN]["summary"]["errors_shown"], MAX_SHOWN);
    assert_eq!(json[MAX_SHOWN - 1]["span"]["line"], MAX_SHOWN);
}
