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

/// `sdfc man`: the man page in roff (sdfc's, a subcommand's, or all of them into a folder),
/// or a subcommand's synopsis as text; the exit code.
pub fn man(args: &crate::cli::ManArgs) -> i32 {
    let top = Cli::command();
    if let Some(dir) = &args.dir {
        let made = std::fs::create_dir_all(dir).and_then(|()| every_page(top, dir));
        return match made {
            Ok(()) => {
                say!("wrote the man pages into {}", dir.display());
                0
            }
            Err(e) => {
                say!(
                    "error: cannot write the man pages into `{}`: {e}",
                    dir.display()
                );
                1
            }
        };
    }
    let cmd = match &args.subcommand {
        None => top,
        Some(name) => {
            let Some(sub) = top.find_subcommand(name) else {
                let names: Vec<&str> = top.get_subcommands().map(|c| c.get_name()).collect();
                say!(
                    "error: `sdfc {name}` is no subcommand\nnote: the subcommands are {}",
                    names.join(", ")
                );
                return 1;
            };
            page_of(sub, name)
        }
    };
    let mut bytes = Vec::new();
    if args.synopsis {
        bytes = (synopsis(&cmd) + "\n").into_bytes();
    } else if let Err(e) = clap_mangen::Man::new(cmd).render(&mut bytes) {
        say!("error: cannot write the man page: {e}");
        return 1;
    }
    write_output(args.output.as_deref(), &bytes, false)
}

/// The subcommand `sub` named as sdfc(1) names its page: `sdfc render` is sdfc-render(1).
fn page_of(sub: &clap::Command, name: &str) -> clap::Command {
    sub.clone()
        .name(format!("sdfc-{name}"))
        .bin_name(format!("sdfc {name}"))
}

/// sdfc.1 and a page for every subcommand sdfc(1) names — `help` included, which clap's own
/// `generate_to` leaves out — into `dir`.
fn every_page(mut top: clap::Command, dir: &Path) -> std::io::Result<()> {
    top.build();
    let mut bytes = Vec::new();
    clap_mangen::Man::new(top.clone()).render(&mut bytes)?;
    std::fs::write(dir.join("sdfc.1"), &bytes)?;
    for sub in top.get_subcommands() {
        let name = sub.get_name();
        let mut bytes = Vec::new();
        clap_mangen::Man::new(page_of(sub, name)).render(&mut bytes)?;
        std::fs::write(dir.join(format!("sdfc-{name}.1")), &bytes)?;
    }
    Ok(())
}

/// A subcommand's synopsis from its definition: its name and positional arguments, then each
/// option as `[--name VALUE]` (its choices, `a|b|c`, when it has a few) or `[--flag]`, wrapped
/// at 100 columns under the first option.
fn synopsis(cmd: &clap::Command) -> String {
    // (Built, as clap builds it to parse: required arguments marked.)
    let mut cmd = cmd.clone();
    cmd.build();
    let cmd = &cmd;
    let bin = cmd.get_bin_name().unwrap_or(cmd.get_name()).to_string();
    let mut head = bin.clone();
    for a in cmd.get_positionals() {
        let name = a
            .get_value_names()
            .and_then(|v| v.first())
            .map_or(a.get_id().to_string(), |v| v.to_string());
        head += &format!(" {name}");
    }
    let indent = " ".repeat(bin.len() + 1);
    let mut lines = vec![head];
    for a in cmd
        .get_arguments()
        .filter(|a| !a.is_positional() && !a.is_hide_set())
    {
        let Some(long) = a.get_long() else { continue };
        if matches!(long, "help" | "version") {
            continue;
        }
        let flag = match a.get_short() {
            Some(s) => format!("-{s}/--{long}"),
            None => format!("--{long}"),
        };
        let takes = a.get_num_args().is_none_or(|n| n.takes_values());
        let choices: Vec<String> = a
            .get_possible_values()
            .iter()
            .filter(|v| !v.is_hide_set())
            .map(|v| v.get_name().to_string())
            .collect();
        let token = if !takes
            || matches!(
                a.get_action(),
                clap::ArgAction::SetTrue | clap::ArgAction::Count
            ) {
            flag
        } else if !choices.is_empty() && choices.len() <= 6 {
            format!("{flag} {}", choices.join("|"))
        } else {
            let value = a
                .get_value_names()
                .and_then(|v| v.first())
                .map_or(long.to_uppercase(), |v| v.to_string());
            format!("{flag} {value}")
        };
        let token = match a.is_required_set() {
            true => token,
            false => format!("[{token}]"),
        };
        let last = lines.last_mut().expect("a line");
        if last.len() + 1 + token.len() > 100 {
            lines.push(format!("{indent}{token}"));
        } else {
            last.push(' ');
            last.push_str(&token);
        }
    }
    lines.join("\n")
}
