//! docs/commands.md cannot drift from the command line: every flag of every command's
//! `--help` (clap's own description of the commands, walked recursively) must appear there.

use super::Cli;
use clap::CommandFactory;

/// `(command path, --flag)` for every long flag of every command and subcommand, except
/// clap's own `--help` and `--version`.
fn flags() -> Vec<(String, String)> {
    fn walk(cmd: &clap::Command, path: &str, out: &mut Vec<(String, String)>) {
        for arg in cmd.get_arguments() {
            if arg.is_hide_set() {
                continue;
            }
            if let Some(long) = arg.get_long() {
                if long != "help" && long != "version" {
                    out.push((path.to_string(), format!("--{long}")));
                }
            }
        }
        for sub in cmd.get_subcommands() {
            walk(sub, &format!("{path} {}", sub.get_name()), out);
        }
    }
    let mut out = Vec::new();
    walk(&Cli::command(), "platoonsim", &mut out);
    out
}

/// The flags of `flags` that `doc` does not name (as `--flag` followed by anything but a
/// letter, digit or `-`, so that `--trips` is not found inside `--trips-foo`).
fn undocumented(flags: &[(String, String)], doc: &str) -> Vec<String> {
    flags
        .iter()
        .filter(|(_, flag)| {
            !doc.match_indices(flag.as_str()).any(|(i, _)| {
                doc[i + flag.len()..]
                    .chars()
                    .next()
                    .is_none_or(|c| !(c.is_ascii_alphanumeric() || c == '-'))
            })
        })
        .map(|(cmd, flag)| format!("{cmd} {flag}"))
        .collect()
}

#[test]
fn every_flag_of_every_command_is_in_docs_commands_md() {
    let doc = include_str!("../../../../docs/commands.md");
    let flags = flags();
    // The walk sees the nested commands (`import sumo`, each experiment) too.
    assert!(flags
        .iter()
        .any(|(c, f)| c == "platoonsim run" && f == "--trips"));
    assert!(flags.iter().any(|(c, _)| c == "platoonsim import sumo"));
    assert!(flags.len() > 60, "{}", flags.len());
    let missing = undocumented(&flags, doc);
    assert!(
        missing.is_empty(),
        "flags missing in docs/commands.md:\n{}",
        missing.join("\n")
    );
}

#[test]
fn a_flag_is_found_only_as_a_whole_word() {
    let flags = [("platoonsim run".to_string(), "--trips".to_string())];
    assert!(undocumented(&flags, "use `--trips` here").is_empty());
    assert!(undocumented(&flags, "ends with --trips").is_empty());
    assert_eq!(
        undocumented(&flags, "only --trips-x and --tripsy"),
        ["platoonsim run --trips"]
    );
}
