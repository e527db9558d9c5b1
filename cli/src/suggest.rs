//! Argument parsing with a second chance at "a similar argument exists": clap's own guess
//! (Jaro similarity above 0.7) misses a swapped pair of letters in a short flag (`--sgv`
//! scores 0.56 against `--svg`), so where it has none, a flag one edit away (insertion,
//! deletion, substitution or two adjacent letters swapped) is suggested.

use clap::error::{ContextKind, ContextValue, ErrorKind};
use clap::{CommandFactory, Parser};

use super::Cli;

/// Parses the process's arguments, exiting with clap's message on an error.
pub fn parse() -> Cli {
    let args: Vec<std::ffi::OsString> = std::env::args_os().collect();
    match Cli::try_parse_from(&args) {
        Ok(cli) => cli,
        Err(e) => with_suggestion(e, &args).exit(),
    }
}

/// `e` with a suggestion of a flag one edit away when it is an unknown argument clap found
/// nothing like.
fn with_suggestion(e: clap::Error, args: &[std::ffi::OsString]) -> clap::Error {
    if e.kind() != ErrorKind::UnknownArgument || e.get(ContextKind::SuggestedArg).is_some() {
        return e;
    }
    let Some(ContextValue::String(bad)) = e.get(ContextKind::InvalidArg) else {
        return e;
    };
    let Some(name) = bad.strip_prefix("--") else {
        return e;
    };
    let top = Cli::command();
    let sub = args
        .iter()
        .skip(1)
        .filter_map(|a| a.to_str())
        .find_map(|a| top.find_subcommand(a));
    let cmd = sub.unwrap_or(&top);
    let near: Vec<String> = cmd
        .get_arguments()
        .chain(top.get_arguments())
        .filter(|a| !a.is_hide_set())
        .filter_map(|a| a.get_long())
        .filter(|l| name.len() >= 3 && one_edit(name, l))
        .map(|l| format!("--{l}"))
        .collect();
    let [flag] = near.as_slice() else {
        return e;
    };
    let mut out = clap::Error::new(ErrorKind::UnknownArgument).with_cmd(cmd);
    out.insert(ContextKind::InvalidArg, ContextValue::String(bad.clone()));
    out.insert(
        ContextKind::SuggestedArg,
        ContextValue::String(flag.clone()),
    );
    if let Some(u) = e.get(ContextKind::Usage) {
        out.insert(ContextKind::Usage, u.clone());
    }
    out
}

/// True when `a` and `b` differ by exactly one edit: a letter inserted, deleted or changed,
/// or two adjacent letters swapped (optimal string alignment distance 1).
fn one_edit(a: &str, b: &str) -> bool {
    let (a, b): (Vec<char>, Vec<char>) = (a.chars().collect(), b.chars().collect());
    let (n, m) = (a.len(), b.len());
    let mut d = vec![vec![0usize; m + 1]; n + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    d[0] = (0..=m).collect();
    for i in 1..=n {
        for j in 1..=m {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = v;
        }
    }
    d[n][m] == 1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_edit_away() {
        assert!(one_edit("sgv", "svg"));
        assert!(one_edit("pnq", "png"));
        assert!(one_edit("jsn", "json"));
        assert!(!one_edit("svg", "svg"));
        assert!(!one_edit("gvs", "svg"));
        assert!(!one_edit("abc", "xyz"));
    }

    #[test]
    fn a_swapped_flag_gets_a_tip() {
        let args: Vec<std::ffi::OsString> = ["kepler", "render", "m.obj", "--sgv", "a.svg"]
            .iter()
            .map(Into::into)
            .collect();
        let e = Cli::try_parse_from(&args).unwrap_err();
        let text = with_suggestion(e, &args).to_string();
        assert!(
            text.contains("a similar argument exists: '--svg'"),
            "{text}"
        );
        assert!(!text.contains("to pass"), "{text}");
    }
}
