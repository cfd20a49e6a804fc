//! What one grid point yields, as CSV fields: the [`Record`] trait and the field helpers.
//!
//! The CSV is written and read by hand (about forty lines here) rather than with the `csv` and
//! `serde` crates: the sweep needs each point written as one whole line in one `write_all`, and on
//! resume needs the byte offset of every line to cut off a half-written last one. Both are
//! natural with lines and awkward through a buffered CSV writer and reader.

use std::borrow::Cow;
use std::str::FromStr;

/// A field or line that cannot be read back.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ParseError {
    #[error("expected {expected} fields, found {found}")]
    /// A line with the wrong number of columns.
    FieldCount {
        /// Columns expected.
        expected: usize,
        /// Columns found.
        found: usize,
    },
    #[error("column `{column}`: cannot read `{value}`: {reason}")]
    /// A column that cannot be read.
    Field {
        /// The column.
        column: String,
        /// The text in it.
        value: String,
        /// Why it cannot be read.
        reason: String,
    },
    #[error("unterminated quoted field")]
    /// A quoted field that is not closed.
    Unterminated,
}

/// The outcome of one grid point, stored as a fixed list of CSV columns.
///
/// `to_fields` and `from_fields` must round-trip; write floats with [`format_f64`] so they do
/// exactly. Column names must be distinct, non-empty, and free of `,`, `"` and line breaks.
pub trait Record: Sized {
    /// The column names, in order.
    fn header() -> &'static [&'static str];
    /// One field per column of [`Record::header`].
    fn to_fields(&self) -> Vec<String>;
    /// Read back what [`Record::to_fields`] wrote (unquoted, one `&str` per column), or, from a
    /// file written before the last [`Record::optional_columns`] columns existed, the fields
    /// before them.
    fn from_fields(fields: &[&str]) -> Result<Self, ParseError>;
    /// How many of the last columns of [`Record::header`] were added after files were written
    /// without them (default 0): such a file's header lacks them, and it still reads (its
    /// points' fields stop before them); a sweep resumes only a file with every column.
    fn optional_columns() -> usize {
        0
    }
}

/// The shortest text that parses back to exactly `value` (Rust's `Debug` for `f64`: `0.1`,
/// `1e-12`, `NaN`, `inf`), so a record survives a round trip through the file bit for bit.
pub fn format_f64(value: f64) -> String {
    format!("{value:?}")
}

/// Read field `index` of `fields` as a `T`, naming the column in the error.
pub fn parse_field<T>(fields: &[&str], index: usize, column: &str) -> Result<T, ParseError>
where
    T: FromStr,
    T::Err: std::fmt::Display,
{
    let value =
        fields.get(index).ok_or(ParseError::FieldCount { expected: index + 1, found: fields.len() })?;
    value.parse().map_err(|e: T::Err| ParseError::Field {
        column: column.to_owned(),
        value: (*value).to_owned(),
        reason: e.to_string(),
    })
}

/// `fields` must have exactly `expected` entries.
pub fn expect_fields(fields: &[&str], expected: usize) -> Result<(), ParseError> {
    if fields.len() == expected {
        Ok(())
    } else {
        Err(ParseError::FieldCount { expected, found: fields.len() })
    }
}

/// Append `field` to `line` as one CSV field: quoted (RFC 4180, `"` doubled) if it holds `,` or
/// `"`. Line breaks become spaces, because one line of the file must be one point.
pub(crate) fn push_field(line: &mut String, field: &str) {
    let field: Cow<str> = if field.contains(['\n', '\r']) {
        Cow::Owned(field.replace(['\n', '\r'], " "))
    } else {
        Cow::Borrowed(field)
    };
    if field.contains([',', '"']) {
        line.push('"');
        line.push_str(&field.replace('"', "\"\""));
        line.push('"');
    } else {
        line.push_str(&field);
    }
}

/// Split one line (without its newline) into fields, undoing [`push_field`]'s quoting.
pub(crate) fn split_fields(line: &str) -> Result<Vec<Cow<'_, str>>, ParseError> {
    let mut fields = Vec::new();
    let mut rest = line;
    loop {
        if let Some(quoted) = rest.strip_prefix('"') {
            let mut field = String::new();
            let mut chars = quoted.char_indices();
            let end = loop {
                match chars.next() {
                    None => return Err(ParseError::Unterminated),
                    Some((k, '"')) if quoted[k + 1..].starts_with('"') => {
                        field.push('"');
                        chars.next();
                    }
                    Some((k, '"')) => break k + 1,
                    Some((_, c)) => field.push(c),
                }
            };
            fields.push(Cow::Owned(field));
            rest = &quoted[end..];
            match rest.strip_prefix(',') {
                Some(after) => rest = after,
                None if rest.is_empty() => return Ok(fields),
                None => {
                    return Err(ParseError::Field {
                        column: format!("#{}", fields.len()),
                        value: rest.to_owned(),
                        reason: "text after a closing quote".to_owned(),
                    });
                }
            }
        } else {
            match rest.split_once(',') {
                Some((field, after)) => {
                    fields.push(Cow::Borrowed(field));
                    rest = after;
                }
                None => {
                    fields.push(Cow::Borrowed(rest));
                    return Ok(fields);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line_of(fields: &[&str]) -> String {
        let mut line = String::new();
        for (k, f) in fields.iter().enumerate() {
            if k > 0 {
                line.push(',');
            }
            push_field(&mut line, f);
        }
        line
    }

    #[test]
    fn fields_round_trip_through_quoting() {
        let fields = ["plain", "", "a,b", "say \"hi\"", "\"", ",", "x\"y,z\"", "two\nlines"];
        let line = line_of(&fields);
        assert!(!line.contains('\n'));
        let back = split_fields(&line).unwrap();
        let mut expected = fields.map(str::to_owned);
        expected[7] = "two lines".to_owned();
        assert_eq!(back, expected);
        assert_eq!(split_fields("").unwrap(), [""]);
        assert_eq!(split_fields(",").unwrap(), ["", ""]);
    }

    #[test]
    fn malformed_quotes_are_errors() {
        assert_eq!(split_fields("a,\"open"), Err(ParseError::Unterminated));
        assert!(matches!(split_fields("\"x\"y,z"), Err(ParseError::Field { .. })));
    }

    #[test]
    fn floats_round_trip_exactly() {
        for v in [0.1, 1.0 / 3.0, -0.0, 1e-300, 6.02e23, f64::MAX, f64::INFINITY, f64::MIN_POSITIVE] {
            let back: f64 = parse_field(&[&format_f64(v)], 0, "v").unwrap();
            assert_eq!(back.to_bits(), v.to_bits(), "{v}");
        }
        assert!(parse_field::<f64>(&[&format_f64(f64::NAN)], 0, "v").unwrap().is_nan());
    }

    #[test]
    fn field_errors_name_the_column() {
        let err = parse_field::<usize>(&["3", "x"], 1, "kinks_final").unwrap_err();
        assert!(err.to_string().starts_with("column `kinks_final`: cannot read `x`"), "{err}");
        assert_eq!(
            parse_field::<usize>(&["3"], 1, "k"),
            Err(ParseError::FieldCount { expected: 2, found: 1 })
        );
        assert_eq!(expect_fields(&["a"], 2), Err(ParseError::FieldCount { expected: 2, found: 1 }));
    }
}
