//! Numbers in emitted code that real shader compilers take: none beyond f32's range, in any
//! text target (issue 30: Chrome's WGSL compiler refused `f32::MAX` as naga prints it).

use sdfc_compiler::emit::{self, Output, Target};
use sdfc_compiler::lower::{Entry, tracer::Options};

/// Numbers in `code` whose value lies beyond f32's range (what a real shader compiler refuses
/// or reads as infinity), with their text.
fn numbers_beyond_f32(code: &str) -> Vec<String> {
    let bytes = code.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < bytes.len() {
        let starts = bytes[i].is_ascii_digit()
            && (i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_'));
        if !starts {
            i += 1;
            continue;
        }
        let mut j = i;
        while j < bytes.len() && (bytes[j].is_ascii_digit() || bytes[j] == b'.') {
            j += 1;
        }
        if j < bytes.len() && (bytes[j] == b'e' || bytes[j] == b'E') {
            let mut k = j + 1;
            if k < bytes.len() && (bytes[k] == b'+' || bytes[k] == b'-') {
                k += 1;
            }
            if k < bytes.len() && bytes[k].is_ascii_digit() {
                j = k;
                while j < bytes.len() && bytes[j].is_ascii_digit() {
                    j += 1;
                }
            }
        }
        let text = &code[i..j];
        if let Ok(v) = text.parse::<f64>()
            && v > f32::MAX as f64
        {
            out.push(text.to_string());
        }
        i = j.max(i + 1);
    }
    out
}

/// No number in any emitted text module lies beyond f32's range: every example × WGSL, GLSL,
/// MSL, HLSL × compute, fragment, library and trace entries, with the default bounding
/// volumes and with every union's tree (`--bvh`). Chrome's WGSL compiler refused
/// `340282350000000000000000000000000000000f` (f32::MAX as naga prints it, a union's first
/// running minimum) in five examples (issue 30). SPIR-V carries bit patterns, not text.
#[test]
fn no_number_in_emitted_code_is_beyond_f32() {
    assert_eq!(
        numbers_beyond_f32("d = 340282350000000000000000000000000000000f; x = 3.4028235e38;"),
        ["340282350000000000000000000000000000000", "3.4028235e38"]
    );
    assert!(numbers_beyond_f32("a = 1e30; b = 3.4028234e38; v_1e99 = 2.0;").is_empty());
    let mut modules = 0;
    let mut bad = Vec::new();
    for path in sdfc_tests::examples() {
        let scene = sdfc_tests::example(&path);
        for trees in [
            sdfc_compiler::lower::tracer::BoundingVolumes::Large,
            sdfc_compiler::lower::tracer::BoundingVolumes::All,
        ] {
            let mut options = Options::from_scene(&scene);
            options.bounding_volumes = trees;
            for entry in [
                Entry::Compute,
                Entry::Fragment,
                Entry::Library,
                Entry::Trace,
            ] {
                let (m, info) =
                    emit::module(&scene, entry, &options).unwrap_or_else(|e| panic!("{}", e.0));
                for target in [Target::Wgsl, Target::Glsl, Target::Msl, Target::Hlsl] {
                    let Output::Text(code) =
                        emit::write(&m, &info, target, entry).unwrap_or_else(|e| panic!("{}", e.0))
                    else {
                        unreachable!("text target")
                    };
                    modules += 1;
                    for n in numbers_beyond_f32(&code) {
                        bad.push(format!(
                            "{} {target:?} {entry:?} {trees:?}: {n}",
                            path.display()
                        ));
                    }
                }
            }
        }
    }
    let examples = sdfc_tests::examples().len();
    assert!(
        examples >= 16 && modules == examples * 2 * 4 * 4,
        "{modules} modules"
    );
    assert!(
        bad.is_empty(),
        "{} numbers beyond f32:\n{}",
        bad.len(),
        bad.join("\n")
    );
}
