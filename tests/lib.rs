//! Shared helpers for the integration tests: loading examples, compiling with a large stack.

use sdfc_compiler::check::{self, Checked};
use sdfc_compiler::diag;
use sdfc_compiler::scene::Scene;
use std::path::{Path, PathBuf};

pub mod scenes;

/// The workspace root.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root")
        .to_path_buf()
}

/// Every `examples/*.sdf`, sorted.
pub fn examples() -> Vec<PathBuf> {
    let mut v: Vec<PathBuf> = std::fs::read_dir(root().join("examples"))
        .expect("examples folder")
        .map(|e| e.expect("dir entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "sdf"))
        .collect();
    v.sort();
    v
}

/// Writes SPIR-V words to a file (little-endian), for `spirv-val`.
pub fn write_spirv(path: &Path, words: &[u32]) {
    let bytes: Vec<u8> = words.iter().flat_map(|w| w.to_le_bytes()).collect();
    std::fs::write(path, bytes).expect("write SPIR-V");
}

/// Runs `f` on a thread with a large stack, as the command line does.
pub fn with_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(f)
        .expect("spawn")
        .join()
        .expect("no panic")
}

/// Compiles a source that must be valid; panics with the rendered diagnostics otherwise.
pub fn scene(name: &str, source: &str) -> Scene {
    let Checked {
        scene, diagnostics, ..
    } = check::compile(source);
    match scene {
        Some(s) => s,
        None => panic!(
            "{name} did not compile:\n{}",
            diag::render(&diagnostics, name, source)
        ),
    }
}

/// Compiles an example file by path.
pub fn example(path: &Path) -> Scene {
    let source = std::fs::read_to_string(path).expect("read example");
    scene(&path.display().to_string(), &source)
}

/// A number from the environment variable `name`, if it is set and parses.
pub fn env_number<T: std::str::FromStr>(name: &str) -> Option<T> {
    std::env::var(name).ok()?.parse().ok()
}

/// Cases per fuzzing property: `default` in CI, `SDFC_FUZZ_CASES` for longer runs by hand.
pub fn fuzz_cases(default: u32) -> u32 {
    env_number("SDFC_FUZZ_CASES").unwrap_or(default)
}

/// The fuzzers' seed: `SDFC_FUZZ_SEED` (a number) if set; in CI (`CI` set) a new one each run,
/// written to the real-clients log with how to run it again, so that every CI run explores
/// new inputs within the same budget; else `default` (the same inputs every local run). A
/// failure prints the input, which then becomes a test.
pub fn fuzz_seed(default: u64) -> u64 {
    if let Some(s) = env_number::<u64>("SDFC_FUZZ_SEED") {
        return s ^ default;
    }
    if std::env::var_os("CI").is_none() {
        return default;
    }
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(1, |d| d.as_nanos() as u64);
    let s = now % 1_000_000_007;
    report(&format!(
        "fuzz seed {s} for the fuzzer seeded {default:#x}: rerun with SDFC_FUZZ_SEED={s}"
    ));
    s ^ default
}

/// A small deterministic generator (xorshift) for the fuzzers and samplers; the seed comes from
/// proptest or a fixed constant, so runs repeat.
pub struct Rng(pub u64);

impl Rng {
    /// A generator from `seed` (0 is replaced: xorshift needs a non-zero state).
    pub fn new(seed: u64) -> Rng {
        Rng(seed.max(1))
    }
    /// The next 64 random bits.
    pub fn bits(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    /// A number in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.bits() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// A number in [lo, hi).
    pub fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    /// A whole number below `n` (0 for n = 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.bits() % n.max(1) as u64) as usize
    }
    /// One of `items`.
    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// A random operator of the catalog applied to children, as source text: `name(args) { … }`,
/// with `args` writing its arguments and `child` each child (shared by the fuzzers).
pub fn operator_block(
    r: &mut Rng,
    args: impl Fn(&mut Rng, &sdfc_compiler::catalog::Operator) -> String,
    mut child: impl FnMut(&mut Rng) -> String,
) -> String {
    use sdfc_compiler::catalog::{Arity, OPERATORS};
    // `extrude` and `revolve` take 2D shapes: made by `solid_of_2d` where one is drawn.
    let op = loop {
        let op = r.pick(OPERATORS);
        // A bake samples its shape at hundreds of points when checked: drawn a quarter as
        // often, so that the fuzzers' time goes mostly to the field.
        if op.traits.bakes && r.below(4) != 0 {
            continue;
        }
        if !matches!(
            op.traits.plane,
            sdfc_compiler::catalog::traits::Plane::Makes
        ) {
            break op;
        }
    };
    let n = match op.arity {
        Arity::Exactly(k) => k,
        Arity::AtLeast(k) => k + r.below(3),
    };
    let children: Vec<String> = (0..n).map(|_| child(r)).collect();
    format!(
        "{}({}) {{\n{}\n}}",
        op.name,
        args(r, op),
        children.join("\n")
    )
}

/// A 2D shape `shape` (source text) made a solid: extruded or revolved with a random height or
/// radius, sometimes after a union with a second copy moved in its plane (shared by the
/// fuzzers).
pub fn solid_of_2d(r: &mut Rng, shape: String) -> String {
    let moved = format!(
        "{shape} at ({:.3}, {:.3}, 0)",
        r.range(-0.8, 0.8),
        r.range(-0.8, 0.8)
    );
    // 2D operators too: a union, a smooth blend, a turn in the plane, a mirror across a
    // plane through the z axis, a rounding.
    let shape = match r.below(7) {
        0 => format!("union {{ {shape}  {moved} }}"),
        1 => format!(
            "smooth_union({:.3}) {{ {shape}  {moved} }}",
            r.range(0.0, 0.5)
        ),
        2 => format!("{moved} |> rotate(z, {}deg)", r.below(360)),
        3 => format!(
            "mirror(({:.3}, {:.3}, 0)) {{ {moved} }}",
            r.range(-1.0, 1.0),
            r.range(0.1, 1.0)
        ),
        4 => format!("{shape} |> round({:.3})", r.range(0.0, 0.3)),
        _ => shape,
    };
    if r.below(2) == 0 {
        format!("extrude(height = {:.3}) {{ {shape} }}", r.range(0.0, 2.0))
    } else {
        format!("revolve(radius = {:.3}) {{ {shape} }}", r.range(-0.5, 1.5))
    }
}

/// Whether an external tool is installed; says so loudly when it is not.
pub fn have(tool: &str) -> bool {
    let ok = std::process::Command::new(tool)
        .arg("--version")
        .output()
        .is_ok();
    if !ok {
        eprintln!(
            "\n*** {tool} is not installed: its checks are SKIPPED (`.ci/run` installs it) ***\n"
        );
    }
    ok
}

/// Appends `line` to `target/real-clients.log`, the tally of every module each real compiler
/// or client accepted, which `.ci/run` prints after the tests (the test harness hides a
/// passing test's output).
pub fn report(line: &str) {
    use std::io::Write;
    println!("{line}");
    let path = root().join("target/real-clients.log");
    if let Ok(mut f) = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)
    {
        let _ = writeln!(f, "{line}");
    }
}

/// Runs `tool` on `file` with `args`; fails the test with its output if it refuses.
pub fn run_tool(tool: &str, args: &[&str], file: &Path, what: &str) {
    let out = std::process::Command::new(tool)
        .args(args)
        .arg(file)
        .output()
        .expect("run validator");
    assert!(
        out.status.success(),
        "{tool} rejected {what}:\n{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A scratch directory of this process for files handed to external tools.
pub fn tempdir() -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("sdfc-emit-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Every `.rs` file under `dir`, appended to `out` (build output, hidden folders and snapshots
/// left out): what the tidy and house checks read.
pub fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_name().unwrap().to_string_lossy().to_string();
        if path.is_dir() && name != "target" && !name.starts_with('.') && name != "snapshots" {
            rust_files(&path, out);
        } else if name.ends_with(".rs") {
            out.push(path);
        }
    }
}
