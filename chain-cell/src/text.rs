//! The TOML cell format (issue 33) read into the unvalidated form [`Raw`], every value with its
//! line. Unknown keys and wrong types are reported by the TOML reader at their line; everything
//! else (missing keys, ranges, names) by [`super::validate`].

use super::validate::{Raw, RawBond, RawLaw, RawNode, Val};
use crate::error::CellError;
use serde::Deserialize;
use toml::Spanned;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    dimension: Option<Spanned<i64>>,
    lattice: Option<Spanned<Vec<Vec<f64>>>>,
    law: Option<Spanned<toml::Value>>,
    #[serde(default)]
    node: Vec<Spanned<NodeTable>>,
    #[serde(default)]
    bond: Vec<Spanned<BondTable>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NodeTable {
    name: Option<Spanned<String>>,
    kind: Option<Spanned<String>>,
    position: Option<Spanned<Vec<f64>>>,
    pivot: Option<Spanned<Vec<f64>>>,
    length: Option<Spanned<f64>>,
    angle: Option<Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct BondTable {
    from: Option<Spanned<String>>,
    to: Option<Spanned<String>>,
    cell: Option<Spanned<Vec<i64>>>,
    k: Option<Spanned<f64>>,
    rest_length: Option<Spanned<f64>>,
    law: Option<Spanned<toml::Value>>,
}

/// A `law` value as written: a name, or a table `{ polynomial = [numbers] }`; anything else is
/// kept as its description for the validation's error.
fn raw_law(value: toml::Value) -> RawLaw {
    match value {
        toml::Value::String(name) => RawLaw::Name(name),
        toml::Value::Table(table) if table.len() == 1 && table.contains_key("polynomial") => {
            match &table["polynomial"] {
                toml::Value::Array(items) => {
                    let numbers: Option<Vec<f64>> = items
                        .iter()
                        .map(|v| match v {
                            toml::Value::Float(x) => Some(*x),
                            toml::Value::Integer(i) => Some(*i as f64),
                            _ => None,
                        })
                        .collect();
                    numbers
                        .map_or_else(|| RawLaw::Other("a list with a non-number".into()), RawLaw::Polynomial)
                }
                other => RawLaw::Other(format!("`polynomial = ` a {}", other.type_str())),
            }
        }
        other => RawLaw::Other(format!("a {}", other.type_str())),
    }
}

/// The byte offsets where the lines of a text start, found once, so that each of a file's
/// many values finds its line by a binary search (a scan of the text before each value made
/// reading a cell of n nodes O(n^2): 25 s for 10 000 nodes).
struct Lines(Vec<usize>);

impl Lines {
    fn new(text: &str) -> Self {
        Self(core::iter::once(0).chain(text.match_indices('\n').map(|(i, _)| i + 1)).collect())
    }

    /// 1-based line and column of byte `offset` (clamped to the text).
    fn line_column(&self, text: &str, offset: usize) -> (usize, usize) {
        let offset = offset.min(text.len());
        // Lines starting at or before `offset`: at least the first.
        let line = self.0.partition_point(|&start| start <= offset);
        (line, offset - self.0[line - 1] + 1)
    }
}

/// Parse the text of a cell file.
pub(crate) fn parse(text: &str) -> Result<Raw, CellError> {
    let lines = Lines::new(text);
    let file: File = toml::from_str(text).map_err(|e| {
        let (line, column) = match e.span() {
            Some(span) => {
                let (l, c) = lines.line_column(text, span.start);
                (Some(l), Some(c))
            }
            None => (None, None),
        };
        CellError::Syntax { line, column, message: e.message().trim_end().to_owned() }
    })?;
    let line = |start: usize| Some(lines.line_column(text, start).0);
    fn val<T>(s: Spanned<T>, line: &dyn Fn(usize) -> Option<usize>) -> Val<T> {
        let l = line(s.span().start);
        Val { value: s.into_inner(), line: l }
    }
    Ok(Raw {
        dimension: file.dimension.map(|v| val(v, &line)),
        lattice: file.lattice.map(|v| val(v, &line)),
        law: file.law.map(|v| {
            let v = val(v, &line);
            Val { value: raw_law(v.value), line: v.line }
        }),
        line: Some(1),
        nodes: file
            .node
            .into_iter()
            .map(|t| {
                let l = line(t.span().start);
                let t = t.into_inner();
                RawNode {
                    line: l,
                    name: t.name.map(|v| val(v, &line)),
                    kind: t.kind.map(|v| val(v, &line)),
                    position: t.position.map(|v| val(v, &line)),
                    pivot: t.pivot.map(|v| val(v, &line)),
                    length: t.length.map(|v| val(v, &line)),
                    angle: t.angle.map(|v| val(v, &line)),
                }
            })
            .collect(),
        bonds: file
            .bond
            .into_iter()
            .map(|t| {
                let l = line(t.span().start);
                let t = t.into_inner();
                RawBond {
                    line: l,
                    from: t.from.map(|v| val(v, &line)),
                    to: t.to.map(|v| val(v, &line)),
                    cell: t.cell.map(|v| val(v, &line)),
                    k: t.k.map(|v| val(v, &line)),
                    rest_length: t.rest_length.map(|v| val(v, &line)),
                    law: t.law.map(|v| {
                        let v = val(v, &line);
                        Val { value: raw_law(v.value), line: v.line }
                    }),
                }
            })
            .collect(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_columns_are_one_based() {
        let text = "a = 1\nbb = 2\n";
        let lines = Lines::new(text);
        assert_eq!(lines.line_column(text, 0), (1, 1));
        assert_eq!(lines.line_column(text, 5), (1, 6));
        assert_eq!(lines.line_column(text, 6), (2, 1));
        assert_eq!(lines.line_column(text, 8), (2, 3));
        // The end of the text and past it: the line after the last newline.
        assert_eq!(lines.line_column(text, 13), (3, 1));
        assert_eq!(lines.line_column(text, 99), (3, 1));
        let lines = Lines::new("");
        assert_eq!(lines.line_column("", 0), (1, 1));
    }
}
