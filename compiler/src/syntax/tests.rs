//! Unit tests of the grammar: keywords, nesting, the scans before and after a parse.

use super::{BLOCK_KEYWORDS, DEFINITION_KEYWORDS, Rule, SdfParser, VALUE_KEYWORDS};
use pest::Parser;

/// Input nested to the limit parses on a thread with Rust's default 2 MiB stack (pest's
/// own stack probe is off: `MAX_NESTING`, checked before parsing, is what bounds the
/// parser's recursion).
#[test]
fn nesting_to_the_limit_parses_on_a_default_stack() {
    let n = super::MAX_NESTING - 2;
    let sources = [
        format!("sphere({}1{})", "(".repeat(n), ")".repeat(n)),
        format!("sphere({}1{})", "sqrt(".repeat(n), ")".repeat(n)),
        format!("{}sphere(1){}", "union { ".repeat(n), " }".repeat(n)),
        format!("sphere(1 + {}1{})", "-(".repeat(n / 2), ")".repeat(n / 2)),
    ];
    for source in sources {
        let ok = std::thread::Builder::new()
            .stack_size(2 << 20)
            .spawn(move || super::parse(&source).is_ok())
            .expect("spawn")
            .join()
            .expect("no stack overflow");
        assert!(ok);
    }
}

/// A file that parses has no bracket open where a statement begins (so `parse_all` looks
/// for them only after a failed parse): random token soups with keywords at line starts.
#[test]
fn open_brackets_at_statements_fail_the_parse() {
    let tokens = [
        "union",
        "{",
        "}",
        "(",
        ")",
        "sphere(1)",
        "\nlet a = 1",
        "\nfn f() = sphere(1)",
        "\ncamera { fov 40deg }",
        "\nbackground #fff",
        "\nimport \"std/gears.sdf\"",
        "\nparam p = 1 in 0..2",
        "\nlight",
        "\nfog",
        ",",
        " at (1, 0, 0)",
        "\n",
        "x",
        "\nmaterial m { color #f00 }",
        "\n  let",
        "// c\n",
        "/* c */",
    ];
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let (mut parsed, mut open) = (0, 0);
    for _ in 0..20_000 {
        let mut text = String::new();
        for _ in 0..1 + (state >> 60) {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            text.push_str(tokens[(state % tokens.len() as u64) as usize]);
            text.push(' ');
        }
        let found = !super::recover::open_at_statements(&text).is_empty();
        if SdfParser::parse(Rule::file, &text).is_ok() {
            parsed += 1;
            assert!(!found, "{text:?}");
        }
        open += usize::from(found);
    }
    // (Both kinds drawn: files that parse, and files with brackets open at a statement.)
    assert!(
        parsed > 1_000 && open > 1_000,
        "{parsed} parsed, {open} open"
    );
}

/// No keyword is a name, and every word that only begins or ends like one, or is one with a
/// letter more or less, is.
#[test]
fn keywords_are_not_names_and_near_misses_are() {
    let is_name = |w: &str| {
        SdfParser::parse(Rule::ident, w).is_ok_and(|mut p| p.next().unwrap().as_str() == w)
    };
    let all = BLOCK_KEYWORDS
        .iter()
        .chain(DEFINITION_KEYWORDS)
        .chain(VALUE_KEYWORDS)
        .chain(&["in", "at"]);
    let mut count = 0;
    for k in all {
        count += 1;
        assert!(!is_name(k), "{k} parsed as a name");
        let near = [
            format!("{k}x"),
            format!("{k}_"),
            format!("{k}2"),
            format!("x{k}"),
            k[..k.len() - 1].to_string(),
            k.to_uppercase(),
        ];
        for w in near.iter().filter(|w| !w.is_empty()) {
            assert!(is_name(w), "{w} (near {k}) is not a name");
        }
    }
    assert_eq!(count, 14);
}

/// The keyword lists are the grammar's: every block keyword in `block_kw`, every statement
/// keyword in its rule, and nothing else in `block_kw`.
#[test]
fn keyword_lists_match_the_grammar() {
    let grammar = include_str!("../../../grammar/sdf.pest");
    let rule = |name: &str| {
        grammar
            .lines()
            .find(|l| l.starts_with(name) && l[name.len()..].trim_start().starts_with('='))
            .unwrap_or_else(|| panic!("rule {name}"))
            .to_string()
    };
    let block_kw = rule("block_kw");
    let quoted = block_kw.matches('"').count() / 2;
    assert_eq!(quoted, BLOCK_KEYWORDS.len(), "{block_kw}");
    for k in BLOCK_KEYWORDS {
        assert!(
            block_kw.contains(&format!("\"{k}\"")),
            "{k} not in {block_kw}"
        );
    }
    for (k, r) in DEFINITION_KEYWORDS.iter().chain(VALUE_KEYWORDS).zip([
        "let_stmt",
        "param_kw",
        "fn_kw",
        "import_kw",
        "value_kw",
    ]) {
        assert!(rule(r).contains(&format!("\"{k}\"")), "{k} not in {r}");
    }
}
