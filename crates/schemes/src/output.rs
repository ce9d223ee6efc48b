//! Rendering of count tables and single-level results as text, JSON and CSV (the layout of
//! the command line's output).
//!
//! JSON is one line per object, `{"level": 0, "V": 12}` (a space after `:` and `,`): serde
//! values through [`Spaced`], and counts as decimal JSON integers of any size ([`Field::Count`]:
//! no quotes, floats or exponents, so the object stays exact for a program that reads big
//! integers). Their digits come from [`decimal::Decimal`], which streams a 600,000-digit
//! count in a fraction of the time num-bigint's quadratic `to_string` takes (same text).

use std::io::{self, Write};

use decimal::Decimal;
use num_bigint::BigInt;
use serde::Serialize;
use serde_json::Value;

/// One row of a table: a level and one value per column.
pub use crate::Row;

/// The JSON layout of every command: compact, with a space after `:` and after `,`.
pub struct Spaced;

impl serde_json::ser::Formatter for Spaced {
    fn begin_array_value<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        if first {
            Ok(())
        } else {
            w.write_all(b", ")
        }
    }

    fn begin_object_key<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        self.begin_array_value(w, first)
    }

    fn begin_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        w.write_all(b": ")
    }
}

/// Writes `value` in the [`Spaced`] layout.
pub fn write_json(out: &mut impl Write, value: &impl Serialize) -> io::Result<()> {
    let mut ser = serde_json::Serializer::with_formatter(out, Spaced);
    value.serialize(&mut ser).map_err(io::Error::other)
}

/// `value` in the [`Spaced`] layout, as a string.
pub fn json_text(value: &impl Serialize) -> String {
    let mut buf = Vec::new();
    // Writing to a `Vec` fails only for values serde_json cannot represent (none here).
    let _ = write_json(&mut buf, value);
    String::from_utf8_lossy(&buf).into_owned()
}

/// One member of a JSON object written by [`write_object`].
pub enum Field<'a> {
    /// Any serde value.
    Json(Value),
    /// A count of any size, or `null`.
    Count(Option<&'a BigInt>),
}

/// Writes the object `{"key": value, ...}` (no trailing newline) in the [`Spaced`] layout.
pub fn write_object(out: &mut impl Write, fields: &[(&str, Field<'_>)]) -> io::Result<()> {
    write!(out, "{{")?;
    for (i, (key, field)) in fields.iter().enumerate() {
        if i > 0 {
            write!(out, ", ")?;
        }
        write_json(out, key)?;
        write!(out, ": ")?;
        match field {
            Field::Json(v) => write_json(out, v)?,
            Field::Count(Some(v)) => write!(out, "{}", Decimal::from(*v))?,
            Field::Count(None) => write!(out, "null")?,
        }
    }
    write!(out, "}}")
}

/// The members `"level": s, "V": ..., ...` of a row, to extend and pass to [`write_object`].
pub fn row_fields<'a>(columns: &'a [String], row: &'a Row) -> Vec<(&'a str, Field<'a>)> {
    std::iter::once(("level", Field::Json(row.level.into())))
        .chain(
            columns
                .iter()
                .zip(&row.values)
                .map(|(name, v)| (name.as_str(), Field::Count(v.as_ref()))),
        )
        .collect()
}

/// One bare object `{"level": s, "V": .., ...}` without a trailing newline.
pub fn write_row_json(out: &mut impl Write, columns: &[String], row: &Row) -> io::Result<()> {
    write_object(out, &row_fields(columns, row))
}

/// Rows of counts under their column names (after `level`), written as JSON, CSV or text.
pub struct Table<'a> {
    /// The column names, after `level`.
    pub columns: &'a [String],
    /// One row per level.
    pub rows: &'a [Row],
}

impl Table<'_> {
    /// `[{"level": 0, "V": 12, ...}, ...]`, one object per line.
    pub fn write_json(&self, out: &mut impl Write) -> io::Result<()> {
        let (columns, rows) = (self.columns, self.rows);
        writeln!(out, "[")?;
        for (i, row) in rows.iter().enumerate() {
            write_row_json(out, columns, row)?;
            writeln!(out, "{}", if i + 1 < rows.len() { "," } else { "" })?;
        }
        writeln!(out, "]")
    }

    /// `level,V,E,F` then one line per level.
    pub fn write_csv(&self, out: &mut impl Write) -> io::Result<()> {
        let (columns, rows) = (self.columns, self.rows);
        write!(out, "level")?;
        for c in columns {
            write!(out, ",{c}")?;
        }
        writeln!(out)?;
        for row in rows {
            write!(out, "{}", row.level)?;
            for v in &row.values {
                match v {
                    Some(v) => write!(out, ",{}", Decimal::from(v))?,
                    None => write!(out, ",")?,
                }
            }
            writeln!(out)?;
        }
        Ok(())
    }

    /// A right-aligned plain-text table with a header line.
    pub fn write_text(&self, out: &mut impl Write) -> io::Result<()> {
        let (columns, rows) = (self.columns, self.rows);
        let cells: Vec<Vec<String>> = rows
            .iter()
            .map(|r| {
                std::iter::once(r.level.to_string())
                    .chain(r.values.iter().map(|v| {
                        v.as_ref()
                            .map_or_else(|| "-".to_string(), decimal::to_decimal)
                    }))
                    .collect()
            })
            .collect();
        let header: Vec<&str> = std::iter::once("level")
            .chain(columns.iter().map(String::as_str))
            .collect();
        let widths: Vec<usize> = (0..header.len())
            .map(|j| {
                cells
                    .iter()
                    .map(|r| r[j].len())
                    .chain(std::iter::once(header[j].len()))
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        let line = |out: &mut dyn Write, items: &[&str]| -> io::Result<()> {
            for (j, item) in items.iter().enumerate() {
                if j > 0 {
                    write!(out, "  ")?;
                }
                write!(out, "{item:>w$}", w = widths[j])?;
            }
            writeln!(out)
        };
        line(out, &header)?;
        for r in &cells {
            let items: Vec<&str> = r.iter().map(String::as_str).collect();
            line(out, &items)?;
        }
        Ok(())
    }
}

/// A summary of a big count: its number of decimal digits, first and last digits.
pub use recurrence::DigitSummary;

/// `{"digits": n, "leading": "...", "trailing": "..."}` (plus `"negative": true` if so).
pub fn summary_json(d: &DigitSummary) -> Value {
    let mut v = serde_json::json!({
        "digits": d.digits,
        "leading": d.leading,
        "trailing": d.trailing,
    });
    if d.negative {
        v["negative"] = Value::Bool(true);
    }
    v
}

/// `602062 digits: 19604598754139134831...31093324874142187520`, or the whole number when
/// it is short.
pub fn summary_text(d: &DigitSummary) -> String {
    let sign = if d.negative { "-" } else { "" };
    if (d.leading.len() as u64) >= d.digits {
        format!("{} digits: {sign}{}", d.digits, d.leading)
    } else {
        format!("{} digits: {sign}{}...{}", d.digits, d.leading, d.trailing)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rows() -> Vec<Row> {
        vec![
            Row {
                level: 0,
                values: vec![Some(12.into()), Some(30.into())],
            },
            Row {
                level: 1,
                values: vec![Some(42.into()), Some(120.into())],
            },
        ]
    }

    #[test]
    fn json_csv_text() {
        let (cols, rows) = (vec!["V".to_string(), "E".to_string()], rows());
        let table = Table {
            columns: &cols,
            rows: &rows,
        };
        type Writer = fn(&Table<'_>, &mut Vec<u8>) -> io::Result<()>;
        let cases: [(Writer, &str); 3] = [
            (
                |t, out| t.write_json(out),
                "[\n{\"level\": 0, \"V\": 12, \"E\": 30},\n{\"level\": 1, \"V\": 42, \"E\": 120}\n]\n",
            ),
            (|t, out| t.write_csv(out), "level,V,E\n0,12,30\n1,42,120\n"),
            (
                |t, out| t.write_text(out),
                "level   V    E\n    0  12   30\n    1  42  120\n",
            ),
        ];
        for (write, expected) in cases {
            let mut out = Vec::new();
            write(&table, &mut out).unwrap();
            assert_eq!(String::from_utf8(out).unwrap(), expected);
        }
    }

    #[test]
    fn digit_summary() {
        let n: BigInt = "123456789012345678901234567890".parse().unwrap();
        let d = recurrence::digit_summary(&n, 5);
        assert_eq!(d.digits, 30);
        assert_eq!(summary_text(&d), "30 digits: 12345...67890");
        assert_eq!(
            json_text(&summary_json(&d)),
            "{\"digits\": 30, \"leading\": \"12345\", \"trailing\": \"67890\"}"
        );
        let small = recurrence::digit_summary(&BigInt::from(42), 20);
        assert_eq!(summary_text(&small), "2 digits: 42");
    }
}
