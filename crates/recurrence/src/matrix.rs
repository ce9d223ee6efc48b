//! Square integer matrices, the input of every recurrence.

use std::fmt;

use crate::{Error, Result};

/// A square matrix of `i64` entries, stored row-major.
///
/// The invariant is that the matrix is square and non-empty; it is checked by
/// [`IntMatrix::try_from_rows`], so every `IntMatrix` in existence satisfies it.
///
/// # Example
///
/// ```
/// use recurrence::IntMatrix;
///
/// let m = IntMatrix::try_from_rows(vec![vec![1, 1], vec![0, 4]])?;
/// assert_eq!(m.dim(), 2);
/// assert_eq!(m.get(0, 1), 1);
/// assert_eq!(m.to_string(), "[[1, 1], [0, 4]]");
/// # Ok::<(), recurrence::Error>(())
/// ```
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct IntMatrix {
    dim: usize,
    entries: Vec<i64>,
}

impl IntMatrix {
    /// Builds a matrix from its rows.
    ///
    /// # Errors
    ///
    /// [`Error::EmptyMatrix`] when there are no rows, [`Error::NotSquare`] naming the first
    /// row whose length differs from the number of rows.
    pub fn try_from_rows(rows: Vec<Vec<i64>>) -> Result<Self> {
        let dim = rows.len();
        if dim == 0 {
            return Err(Error::EmptyMatrix);
        }
        let mut entries = Vec::with_capacity(dim * dim);
        for (row, r) in rows.into_iter().enumerate() {
            if r.len() != dim {
                return Err(Error::NotSquare {
                    row,
                    len: r.len(),
                    expected: dim,
                });
            }
            entries.extend(r);
        }
        Ok(IntMatrix { dim, entries })
    }

    /// The `dim x dim` identity matrix.
    ///
    /// # Panics
    ///
    /// Panics if `dim` is zero.
    pub fn identity(dim: usize) -> Self {
        assert!(dim > 0, "a matrix needs at least one row");
        let mut entries = vec![0; dim * dim];
        for i in 0..dim {
            entries[i * dim + i] = 1;
        }
        IntMatrix { dim, entries }
    }

    /// Number of rows (and columns).
    pub fn dim(&self) -> usize {
        self.dim
    }

    /// The entry in row `i`, column `j`.
    ///
    /// # Panics
    ///
    /// Panics if `i` or `j` is not below [`dim`](Self::dim).
    pub fn get(&self, i: usize, j: usize) -> i64 {
        assert!(i < self.dim && j < self.dim, "index out of range");
        self.entries[i * self.dim + j]
    }

    /// Row `i` as a slice.
    ///
    /// # Panics
    ///
    /// Panics if `i` is not below [`dim`](Self::dim).
    pub fn row(&self, i: usize) -> &[i64] {
        &self.entries[i * self.dim..(i + 1) * self.dim]
    }

    /// Iterates over the rows.
    pub fn rows(&self) -> impl ExactSizeIterator<Item = &[i64]> + '_ {
        self.entries.chunks_exact(self.dim)
    }

    /// The rows as owned vectors (the inverse of [`try_from_rows`](Self::try_from_rows)).
    pub fn to_rows(&self) -> Vec<Vec<i64>> {
        self.rows().map(<[i64]>::to_vec).collect()
    }

    /// The product `self * rhs`, or `None` if an entry overflows `i64` or the dimensions differ.
    ///
    /// Applying `rhs` first and then `self` is the product `self * rhs`.
    pub fn checked_mul(&self, rhs: &IntMatrix) -> Option<IntMatrix> {
        if self.dim != rhs.dim {
            return None;
        }
        let n = self.dim;
        let mut entries = vec![0i64; n * n];
        for i in 0..n {
            for j in 0..n {
                let mut acc: i128 = 0;
                for k in 0..n {
                    acc += i128::from(self.get(i, k)) * i128::from(rhs.get(k, j));
                }
                entries[i * n + j] = i64::try_from(acc).ok()?;
            }
        }
        Some(IntMatrix { dim: n, entries })
    }

    /// Parses the bracketed form `[[1, 1], [0, 4]]` (also what [`Display`](fmt::Display) prints).
    ///
    /// # Errors
    ///
    /// [`ParseMatrixError`] with the byte offset of the first problem.
    ///
    /// ```
    /// use recurrence::IntMatrix;
    /// let m: IntMatrix = "[[1,1,0],[0,2,3],[0,0,4]]".parse()?;
    /// assert_eq!(m.get(1, 2), 3);
    /// assert!("[[1,2],[3]]".parse::<IntMatrix>().is_err());
    /// # Ok::<(), recurrence::ParseMatrixError>(())
    /// ```
    pub fn parse(text: &str) -> std::result::Result<Self, ParseMatrixError> {
        text.parse()
    }
}

impl fmt::Debug for IntMatrix {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

impl fmt::Display for IntMatrix {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("[")?;
        for (i, row) in self.rows().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            f.write_str("[")?;
            for (j, x) in row.iter().enumerate() {
                if j > 0 {
                    f.write_str(", ")?;
                }
                write!(f, "{x}")?;
            }
            f.write_str("]")?;
        }
        f.write_str("]")
    }
}

/// Why a bracketed matrix such as `[[1, 1], [0, 4]]` could not be parsed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ParseMatrixError {
    /// Byte offset into the text where the problem was found, when it is a syntax error.
    pub offset: Option<usize>,
    /// What was wrong, in lowercase without a trailing period.
    pub message: String,
}

impl fmt::Display for ParseMatrixError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.offset {
            Some(offset) => write!(f, "{} at character {offset} of the matrix", self.message),
            None => f.write_str(&self.message),
        }
    }
}

impl std::error::Error for ParseMatrixError {}

impl std::str::FromStr for IntMatrix {
    type Err = ParseMatrixError;

    fn from_str(text: &str) -> std::result::Result<Self, ParseMatrixError> {
        let mut p = Parser { text, pos: 0 };
        let rows = p.matrix()?;
        p.skip_ws();
        if p.pos != text.len() {
            return Err(p.error("unexpected text after the matrix"));
        }
        IntMatrix::try_from_rows(rows).map_err(|e| ParseMatrixError {
            offset: None,
            message: e.to_string(),
        })
    }
}

struct Parser<'a> {
    text: &'a str,
    pos: usize,
}

impl Parser<'_> {
    fn error(&self, message: &str) -> ParseMatrixError {
        ParseMatrixError {
            offset: Some(self.pos),
            message: message.to_string(),
        }
    }

    fn skip_ws(&mut self) {
        while let Some(c) = self.text[self.pos..].chars().next() {
            if c.is_whitespace() {
                self.pos += c.len_utf8();
            } else {
                break;
            }
        }
    }

    fn peek(&mut self) -> Option<char> {
        self.skip_ws();
        self.text[self.pos..].chars().next()
    }

    fn expect(&mut self, c: char) -> std::result::Result<(), ParseMatrixError> {
        if self.peek() == Some(c) {
            self.pos += 1;
            Ok(())
        } else {
            Err(self.error(&format!("expected `{c}`")))
        }
    }

    fn matrix(&mut self) -> std::result::Result<Vec<Vec<i64>>, ParseMatrixError> {
        self.expect('[')?;
        let mut rows = Vec::new();
        if self.peek() == Some(']') {
            self.pos += 1;
            return Ok(rows);
        }
        loop {
            rows.push(self.row()?);
            match self.peek() {
                Some(',') => self.pos += 1,
                Some(']') => {
                    self.pos += 1;
                    return Ok(rows);
                }
                _ => return Err(self.error("expected `,` or `]` after a row")),
            }
        }
    }

    fn row(&mut self) -> std::result::Result<Vec<i64>, ParseMatrixError> {
        self.expect('[')?;
        let mut row = Vec::new();
        if self.peek() == Some(']') {
            self.pos += 1;
            return Ok(row);
        }
        loop {
            row.push(self.integer()?);
            match self.peek() {
                Some(',') => self.pos += 1,
                Some(']') => {
                    self.pos += 1;
                    return Ok(row);
                }
                _ => return Err(self.error("expected `,` or `]` after an entry")),
            }
        }
    }

    fn integer(&mut self) -> std::result::Result<i64, ParseMatrixError> {
        self.skip_ws();
        let start = self.pos;
        let bytes = self.text.as_bytes();
        let mut end = start;
        if end < bytes.len() && (bytes[end] == b'-' || bytes[end] == b'+') {
            end += 1;
        }
        while end < bytes.len() && bytes[end].is_ascii_digit() {
            end += 1;
        }
        let token = &self.text[start..end];
        if token.is_empty() || token == "-" || token == "+" {
            return Err(self.error("expected an integer"));
        }
        match token.parse::<i64>() {
            Ok(v) => {
                self.pos = end;
                Ok(v)
            }
            Err(_) => Err(self.error(&format!("entry `{token}` does not fit in a 64-bit integer"))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parse_round_trips() {
        let m: IntMatrix = " [ [1, -2] ,[3,4] ] ".parse().unwrap();
        assert_eq!(m.to_rows(), vec![vec![1, -2], vec![3, 4]]);
        assert_eq!(m.to_string().parse::<IntMatrix>().unwrap(), m);
    }

    #[test]
    fn parse_errors_say_where() {
        let e = "[[1,2],[3]]".parse::<IntMatrix>().unwrap_err();
        assert_eq!(
            e.to_string(),
            "row 1 of the matrix has 1 entries, expected 2 (the matrix must be square)"
        );
        let e = "[[1,x]]".parse::<IntMatrix>().unwrap_err();
        assert_eq!(e.offset, Some(4));
        assert_eq!(
            e.to_string(),
            "expected an integer at character 4 of the matrix"
        );
        let e = "[[99999999999999999999]]".parse::<IntMatrix>().unwrap_err();
        assert!(e.message.contains("does not fit"), "{e}");
        assert_eq!(
            "[]".parse::<IntMatrix>().unwrap_err().message,
            "the matrix is empty"
        );
    }

    #[test]
    fn checked_mul_reports_overflow() {
        let a = IntMatrix::try_from_rows(vec![vec![i64::MAX, 0], vec![0, 1]]).unwrap();
        assert!(a.checked_mul(&a).is_none());
        let b = IntMatrix::try_from_rows(vec![vec![1, 1], vec![0, 4]]).unwrap();
        assert_eq!(
            b.checked_mul(&b).unwrap().to_rows(),
            vec![vec![1, 5], vec![0, 16]]
        );
    }
}
