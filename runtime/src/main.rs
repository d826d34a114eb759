//! The `sdfc` command line: check, emit, render, view and bench scene files. Its layers, each
//! using only those below: `cmd` (one module per subcommand) over `view` (the live window) over
//! `cli` (the arguments, messages and scene input), all on the runtime library (`sdfc`).

/// `eprintln!` that never panics: a full or closed standard error (`2>/dev/full`) drops the
/// message instead of ending the command with a panic.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

/// `eprint!` that never panics (see `say!`).
macro_rules! say_raw {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = write!(std::io::stderr(), $($arg)*);
    }};
}

mod cli;
mod cmd;
mod view;

/// mimalloc instead of the C library's allocator: it maps memory in large pieces (transparent
/// huge pages where the kernel allows them), so a large scene's compile is not paced by
/// page faults. `sdfc emit` of the 10 001-node scene of `scripts/emit_time.py`: 9 824 page
/// faults and 32-42 ms of system time with glibc's malloc, 343-475 faults and 4-13 ms with this
/// (median of 25 alternating runs: 159 ms against 127 ms; issue 14).
#[global_allocator]
static GLOBAL: mimalloc::MiMalloc = mimalloc::MiMalloc;

/// Tells the allocator to keep the memory freed from here on for reuse rather than give it back
/// to the system: a large mesh frees and allocates its tables step after step, and every page
/// given back came back zeroed by the kernel — a fifth to a third of `sdfc mesh`'s profile
/// (`clear_page`). The box less a ball at 215 cells to the measuring step: median 1.03 s, 0.94
/// s with this (8 runs each, alternating), the peak memory about 3 % higher. For commands that
/// end when their work does (`sdfc mesh`).
pub fn keep_freed_memory() {
    // mimalloc's `mi_option_purge_delay`: its place in `mi_option_e`, the same in mimalloc 2
    // and 3 (the enum keeps retired options' places); −1: never purge.
    const PURGE_DELAY: std::ffi::c_int = 15;
    unsafe extern "C" {
        fn mi_option_set(option: std::ffi::c_int, value: std::ffi::c_long);
    }
    // SAFETY: mimalloc is linked (the global allocator above); setting an option only stores a
    // value its later purges read.
    unsafe { mi_option_set(PURGE_DELAY, -1) };
}

fn main() {
    // Mesa's drivers complain on every start when this is unset; nothing else reads it here.
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        // SAFETY: no other thread exists yet.
        unsafe { std::env::set_var("XDG_RUNTIME_DIR", std::env::temp_dir()) };
    }
    // The front end recurses over the syntax tree; a large stack keeps pathological input (which
    // it rejects past its nesting limits) from overflowing before it is rejected.
    // Baked volumes outlive the process in the cache folder.
    if let Some(store) = sdfc::bake_store::DiskStore::open() {
        sdfc_compiler::bake::cache::set_store(Some(Box::new(store)));
    }
    // Large bakes are sampled on the GPU.
    sdfc_compiler::check::sampler::set_sampler(Some(Box::new(sdfc::bake_gpu::GpuSampler::new())));
    let code = std::thread::Builder::new()
        .stack_size(256 << 20)
        .spawn(cmd::run)
        .map(|h| h.join().unwrap_or(2))
        .unwrap_or(2);
    std::process::exit(code);
}
