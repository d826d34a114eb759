//! The subcommands, one module each (`check`, `emit`, `render`, `view`, `bench`, `mesh`,
//! `serve`, `shell` for completions and the man page); what two of them share is in `common`, or below
//! in `cli` and `view`. No command imports another.

mod bench;
mod check;
mod common;
mod emit;
mod mesh;
mod render;
mod serve;
mod shell;
mod view;

use crate::cli::{Cli, Command, messages};
use clap::Parser;

/// Runs the command line; returns the exit code (0 ok, 1 user error, 2 a bug in sdfc).
pub fn run() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { 1 } else { 0 };
            let _ = e.print();
            return code;
        }
    };
    messages::configure(cli.message_format, cli.color, cli.quiet);
    match cli.command {
        Command::Completions(args) => shell::completions(args.shell, args.output.as_deref()),
        Command::Man(args) => shell::man(&args),
        Command::Check(args) => check::run(&args),
        Command::Emit(args) => emit::run(&args),
        Command::Render(args) => render::run(&args),
        Command::View(args) => view::run(args),
        Command::Bench(args) => bench::run(&args),
        Command::Mesh(args) => mesh::run(&args),
        Command::Serve(args) => serve::run(&args),
    }
}
