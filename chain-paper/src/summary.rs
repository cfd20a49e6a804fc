//! The summary table, `summary.md`: every number the paper states beside ours and the continuum
//! theory's, one row per [`Row`] of every figure.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::model::{Quality, Row};
use crate::output::{WriteError, write_atomic};

/// The columns of the summary table, in order.
pub const COLUMNS: [&str; 7] =
    ["figure", "quantity", "paper", "ours", "continuum", "relative difference (%)", "note"];

/// The summary table in Markdown: a header, then one line per row, each starting with
/// `| <figure label> |`. A missing continuum value is an empty cell; the last but one column is the
/// row's [`Comparison`](crate::model::Comparison): a percentage, or "not comparable" and why, or
/// empty for a row in words.
pub fn summary_markdown(rows: &[(&'static str, Row)]) -> String {
    let mut table = format!("| {} |\n|{}\n", COLUMNS.join(" | "), " --- |".repeat(COLUMNS.len()));
    for (label, row) in rows {
        let percent = row.comparison.to_string();
        let cells = [
            *label,
            &row.quantity,
            &row.paper,
            &row.ours,
            row.continuum.as_deref().unwrap_or(""),
            &percent,
            &row.note,
        ];
        let cells: Vec<String> = cells.iter().map(|c| cell(c)).collect();
        writeln!(table, "| {} |", cells.join(" | ")).expect("writing to a String");
    }
    table
}

/// The whole `summary.md`: a title, which quality the numbers were computed at, the table, and
/// the figures that failed (`(label, message)`), if any.
pub fn summary_document(rows: &[(&'static str, Row)], quality: Quality, failed: &[(&str, String)]) -> String {
    let mut doc = String::from("# The paper's numbers beside ours\n\n");
    doc.push_str(match quality {
        Quality::Full => "Computed at full resolution (`paper`).\n\n",
        Quality::Quick => {
            "Computed with `paper --quick`: coarse grids and short runs, so the numbers test the \
             pipeline, not the paper.\n\n"
        }
    });
    doc.push_str(&summary_markdown(rows));
    if !failed.is_empty() {
        doc.push_str("\n## Figures that failed\n\n");
        for (label, message) in failed {
            writeln!(doc, "- `{label}`: {}", one_line(message)).expect("writing to a String");
        }
    }
    doc
}

/// Write [`summary_document`] to `dir/summary.md`, atomically. Returns the path written.
pub fn write_summary(
    dir: &Path,
    rows: &[(&'static str, Row)],
    quality: Quality,
    failed: &[(&str, String)],
) -> Result<PathBuf, WriteError> {
    let path = dir.join("summary.md");
    write_atomic(&path, summary_document(rows, quality, failed).as_bytes())?;
    Ok(path)
}

/// A table cell: one line, with `|` escaped so it cannot end the cell.
fn cell(text: &str) -> String {
    one_line(text).replace('|', "\\|")
}

fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_row_is_one_table_line() {
        let rows = [
            (
                "fig:barrier",
                Row::number("PN barrier | n = 60", "0.60", 0.668, Some(0.7), "discreteness\nof the chain"),
            ),
            ("fig:scatter", Row::words("outcome at v0 = 2", "transmitted", "transmitted", "")),
        ];
        let table = summary_markdown(&rows);
        let lines: Vec<&str> = table.lines().collect();
        assert_eq!(lines.len(), 4);
        assert_eq!(
            lines[0],
            "| figure | quantity | paper | ours | continuum | relative difference (%) | note |"
        );
        assert_eq!(
            lines[2],
            "| fig:barrier | PN barrier \\| n = 60 | 0.60 | 0.668 | 0.7 | 11.33 | discreteness of the chain |"
        );
        assert_eq!(lines[3], "| fig:scatter | outcome at v0 = 2 | transmitted | transmitted |  |  |  |");
    }

    #[test]
    fn numbers_that_cannot_be_compared_say_why() {
        let rows = [(
            "fig:longbar",
            Row::number("soft mode", "7.7e-9", 0.020132, None, "")
                .resolution(2.1e-8, "the smallest ω a double-precision ω² resolves"),
        )];
        let table = summary_markdown(&rows);
        let line = table.lines().nth(2).unwrap();
        assert!(
            line.contains("| not comparable: the paper's 7.7e-9 is at or below 2.1e-8, the smallest ω"),
            "{line}"
        );
        assert!(!line.contains("261"), "{line}");
    }

    #[test]
    fn failures_are_listed_after_the_table() {
        let doc = summary_document(&[], Quality::Quick, &[("fig:x", "solver\ndiverged".into())]);
        assert!(doc.contains("paper --quick"));
        assert!(doc.ends_with("## Figures that failed\n\n- `fig:x`: solver diverged\n"), "{doc}");
    }
}
