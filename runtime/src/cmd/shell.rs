//! Shell completions and the man page, generated from the command line's own definition
//! (`clap_complete`, `clap_mangen`), so that they cannot drift from it.

use super::common::write_output;
use crate::cli::Cli;
use clap::CommandFactory;
use std::path::Path;

/// `sdfc completions SHELL`: the completion script; the exit code.
pub fn completions(shell: clap_complete::Shell, output: Option<&Path>) -> i32 {
    let mut bytes = Vec::new();
    clap_complete::generate(shell, &mut Cli::command(), "sdfc", &mut bytes);
    write_output(output, &bytes, false)
}

/// `sdfc man`: the man page in roff; the exit code.
pub fn man(output: Option<&Path>) -> i32 {
    let mut bytes = Vec::new();
    if let Err(e) = clap_mangen::Man::new(Cli::command()).render(&mut bytes) {
        say!("error: cannot write the man page: {e}");
        return 1;
    }
    write_output(output, &bytes, false)
}
