//! One source for every quoted number (issue 34): the numbers the guides quote from the `paper`
//! run are that run's.
//!
//! The source is `docs/figures/summary.md`, the `summary.md` of the full run whose figures are
//! committed beside it. Three checks:
//! - docs/paper.md's table is that file's table, line for line;
//! - every figure's rows in it, but those of the slowest figure (`fig:phasediagram`: 6 s in
//!   release, 62 s in this debug build against 6 s for all the others), are what the figure
//!   computes now at full resolution: a stale file fails;
//! - each number another guide quotes from the run appears, as the same digits, in the rows of the
//!   figure the guide names.

use std::path::Path;

use chain_paper::Quality;
use chain_paper::figures::{self, Params};
use chain_paper::summary::summary_markdown;

/// The figure too slow to recompute at full resolution in a debug test (its rows are checked by
/// the full run that writes the file).
const SLOW: [&str; 1] = ["fig:phasediagram"];

fn read(path: &str) -> String {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    std::fs::read_to_string(root.join(path)).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// The table lines of `text` (those starting with `|`).
fn table(text: &str) -> Vec<&str> {
    text.lines().filter(|l| l.starts_with('|')).collect()
}

/// The committed summary's rows of `label`.
fn rows_of<'a>(summary: &'a str, label: &str) -> Vec<&'a str> {
    let start = format!("| {label} |");
    table(summary).into_iter().filter(|l| l.starts_with(&start)).collect()
}

/// The section of `text` from the heading `heading` to the next heading of its level.
fn section<'a>(text: &'a str, heading: &str) -> &'a str {
    let start = text.find(heading).unwrap_or_else(|| panic!("no heading {heading}"));
    let rest = &text[start + heading.len()..];
    &rest[..rest.find("\n## ").unwrap_or(rest.len())]
}

/// The first `count` numbers (digits, with a decimal point and more digits) after `marker`.
fn numbers_after<'a>(text: &'a str, marker: &str, count: usize) -> Vec<&'a str> {
    let start = text.find(marker).unwrap_or_else(|| panic!("no `{marker}`")) + marker.len();
    let mut found = Vec::new();
    let mut rest = &text[start..];
    while found.len() < count {
        let Some(begin) = rest.find(|c: char| c.is_ascii_digit()) else { break };
        let digits = |s: &str| s.find(|c: char| !c.is_ascii_digit()).unwrap_or(s.len());
        let mut end = begin + digits(&rest[begin..]);
        if let Some(fraction) = rest[end..].strip_prefix('.').filter(|f| digits(f) > 0) {
            end += 1 + digits(fraction);
        }
        found.push(&rest[begin..end]);
        rest = &rest[end..];
    }
    found
}

/// Whether `number` stands in `line` as a whole number (not part of a longer one: no digit or
/// point before it, no digit or decimal part after it).
fn stands_in(line: &str, number: &str) -> bool {
    line.match_indices(number).any(|(k, _)| {
        let before = line[..k].chars().next_back().is_some_and(|c| c.is_ascii_digit() || c == '.');
        let after = &line[k + number.len()..];
        let more = after.starts_with(|c: char| c.is_ascii_digit())
            || after.strip_prefix('.').is_some_and(|a| a.starts_with(|c: char| c.is_ascii_digit()));
        !before && !more
    })
}

#[test]
fn the_papers_table_is_the_committed_summary_of_a_full_run() {
    let summary = read("docs/figures/summary.md");
    assert!(summary.contains("Computed at full resolution (`paper`)."), "not a full run's summary");
    let paper = read("docs/paper.md");
    let ours = table(section(&paper, "## Our numbers beside the paper's"));
    assert_eq!(ours, table(&summary), "docs/paper.md's table is not docs/figures/summary.md's");
    // Every figure of the run has its rows there, and no other figure does.
    let labels: Vec<&str> = figures::all().into_iter().map(|(label, _)| label).collect();
    for line in &table(&summary)[2..] {
        assert!(labels.iter().any(|l| line.starts_with(&format!("| {l} |"))), "{line}");
    }
}

#[test]
fn every_fast_figures_rows_are_what_it_computes_now() {
    let summary = read("docs/figures/summary.md");
    let params = Params::default();
    for (label, figure) in figures::all() {
        if SLOW.contains(&label) {
            continue;
        }
        let computed = figure(&params, Quality::Full).unwrap_or_else(|e| panic!("{label}: {e}"));
        let rows: Vec<(&'static str, _)> = computed.rows.into_iter().map(|row| (label, row)).collect();
        let now = summary_markdown(&rows);
        assert_eq!(
            table(&now)[2..],
            rows_of(&summary, label)[..],
            "{label}: docs/figures/summary.md is stale (run `paper --out DIR` and copy DIR/summary.md and the figures)"
        );
    }
}

#[test]
fn numbers_the_guides_quote_are_the_runs() {
    let summary = read("docs/figures/summary.md");
    // (guide, text just before the quoted numbers, how many, the figure whose rows hold them)
    let quotes = [
        ("docs/statics.md", "falls by ", 1, "fig:logvpn-size"),
        ("docs/statics.md", "1/\\xi =\n", 1, "fig:logvpn-size"),
        ("docs/statics.md", "hence its ", 2, "fig:orbit"),
        ("docs/dynamics.md", "(found) | **", 1, "fig:akpntrapprofile"),
        ("docs/dynamics.md", "**14.8 (rotor ", 1, "fig:akpntrapprofile"),
        (
            "docs/dynamics.md",
            "so its closest approaches in\n[`figures/summary.md`](figures/summary.md), ",
            2,
            "fig:orbit",
        ),
        ("docs/dynamics.md", "it moves at ", 1, "fig:akpntrapprofile"),
        ("docs/dynamics.md", "the phonon band of the uniform chain\nspans ", 2, "fig:akpntrapprofile"),
    ];
    for (guide, marker, count, label) in quotes {
        let text = read(guide);
        let numbers = numbers_after(&text, marker, count);
        assert_eq!(numbers.len(), count, "{guide}: `{marker}`");
        let rows = rows_of(&summary, label);
        assert!(!rows.is_empty(), "no rows of {label}");
        for number in numbers {
            assert!(
                rows.iter().any(|row| stands_in(row, number)),
                "{guide} quotes {number} after `{marker}` from {label}, whose rows do not have it: {rows:#?}"
            );
        }
    }
    // The checker itself: a number with other digits, or one inside a longer one, is not found.
    let row = "| fig:x | a | b | exponential, 1.454 per rotor | 1.460 per rotor |";
    assert!(stands_in(row, "1.454") && !stands_in(row, "1.45") && !stands_in(row, "1.464"));
    assert_eq!(numbers_after("t = 20.32 near rotor 35.2.", "t = ", 2), ["20.32", "35.2"]);
}
