//! [`Matrix`], the crate's one dense matrix type (its `i64` instance [`IntMatrix`] is the
//! input of every recurrence), and the bracketed text form `[[1, 1], [0, 4]]`.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Exact linear recurrences over `IntMatrix`. `matrix.rs` holds the crate's one dense matrix type,
//! `Matrix<T>` (`IntMatrix` is `Matrix<i64>`, square and non-empty from every public constructor),
//! and writes its arithmetic once over `num_traits` bounds: `checked_mul`, `checked_apply`,
//! `checked_pow` need `Zero + CheckedAdd + CheckedMul` (and `One`), so `i64` and `i128` report
//! overflow while `BigInt`, the rationals, `QuadraticSurd`, `Z[sqrt d]` and `Complex64` never do.
//! Powering (`power.rs`, `CheckedRing` adds only the conversion of `i64` entries), the
//! characteristic polynomial, Horner's rule in a field, the fraction-free spectra and the early
//! levels of a closed form all multiply through it; nalgebra's `DMatrix` is used only for the
//! Schur decomposition of companion matrices (`eigen.rs`).

use std::fmt;

use num_traits::{CheckedAdd, CheckedMul, One, Zero};

use crate::{Error, Result};

/// A dense matrix over any ring, stored row-major: the one matrix type of the crate.
///
/// Every public constructor builds a square, non-empty matrix ([`Matrix::try_from_rows`]
/// checks it), and products of square matrices are square, so a `Matrix` from outside the
/// crate is square; inside it, the fraction-free eliminations multiply rectangular blocks
/// with the same type.
///
/// The arithmetic is written once over `num_traits` bounds: [`checked_mul`](Self::checked_mul),
/// [`checked_apply`](Self::checked_apply) and [`checked_pow`](Self::checked_pow) need
/// `Zero + CheckedAdd + CheckedMul` (and `One` for powers), so `i64` and `i128` report
/// overflow with `None` while `BigInt` and the exact fields never do.
///
/// # Example
///
/// ```
/// use num_bigint::BigInt;
/// use recurrence::{IntMatrix, Matrix};
///
/// let m = IntMatrix::try_from_rows(vec![vec![1, 1], vec![0, 4]])?;
/// assert_eq!(m.dim(), 2);
/// assert_eq!(m.get(0, 1), 1);
/// assert_eq!(m.to_string(), "[[1, 1], [0, 4]]");
/// let big: Matrix<BigInt> = m.map(|&x| BigInt::from(x));
/// let p = big.checked_pow(40).expect("big integers do not overflow");
/// assert_eq!(p.get(1, 1), BigInt::from(4).pow(40));
/// assert_eq!(m.checked_pow(40), None); // 4^40 does not fit in i64
/// # Ok::<(), recurrence::Error>(())
/// ```
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Matrix<T> {
    nrows: usize,
    ncols: usize,
    entries: Vec<T>,
}

/// A square matrix of `i64` entries, the input of every recurrence.
pub type IntMatrix = Matrix<i64>;

impl<T> Matrix<T> {
    /// Builds a square matrix from its rows.
    ///
    /// # Errors
    ///
    /// [`Error::EmptyMatrix`] when there are no rows, [`Error::NotSquare`] naming the first
    /// row whose length differs from the number of rows.
    pub fn try_from_rows(rows: Vec<Vec<T>>) -> Result<Self> {
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
        Ok(Matrix {
            nrows: dim,
            ncols: dim,
            entries,
        })
    }

    /// The `dim x dim` matrix whose entry in row `i`, column `j` is `f(i, j)`.
    ///
    /// # Panics
    ///
    /// Panics if `dim` is zero.
    pub fn from_fn(dim: usize, mut f: impl FnMut(usize, usize) -> T) -> Self {
        assert!(dim > 0, "a matrix needs at least one row");
        let entries = (0..dim * dim).map(|k| f(k / dim, k % dim)).collect();
        Matrix {
            nrows: dim,
            ncols: dim,
            entries,
        }
    }

    /// A `nrows x ncols` block from its row-major entries (inside the crate only).
    pub(crate) fn from_vec(nrows: usize, ncols: usize, entries: Vec<T>) -> Self {
        debug_assert_eq!(entries.len(), nrows * ncols, "entries fill the block");
        Matrix {
            nrows,
            ncols,
            entries,
        }
    }

    /// Number of rows (and columns).
    pub fn dim(&self) -> usize {
        self.nrows
    }

    /// Number of columns (equal to [`dim`](Self::dim) outside the crate).
    pub(crate) fn ncols(&self) -> usize {
        self.ncols
    }

    /// A reference to the entry in row `i`, column `j`.
    ///
    /// # Panics
    ///
    /// Panics if `i` or `j` is out of range.
    pub fn entry(&self, i: usize, j: usize) -> &T {
        assert!(i < self.nrows && j < self.ncols, "index out of range");
        &self.entries[i * self.ncols + j]
    }

    /// Row `i` as a slice.
    ///
    /// # Panics
    ///
    /// Panics if `i` is not below [`dim`](Self::dim).
    pub fn row(&self, i: usize) -> &[T] {
        &self.entries[i * self.ncols..(i + 1) * self.ncols]
    }

    /// Iterates over the rows.
    pub fn rows(&self) -> impl ExactSizeIterator<Item = &[T]> + '_ {
        self.entries.chunks_exact(self.ncols)
    }

    /// The entries, row by row.
    pub fn entries(&self) -> &[T] {
        &self.entries
    }

    /// The entries, row by row, for changes in place.
    pub(crate) fn entries_mut(&mut self) -> &mut [T] {
        &mut self.entries
    }

    /// The matrix with `f` applied to every entry.
    pub fn map<U>(&self, f: impl FnMut(&T) -> U) -> Matrix<U> {
        Matrix {
            nrows: self.nrows,
            ncols: self.ncols,
            entries: self.entries.iter().map(f).collect(),
        }
    }

    /// The matrix with `f` applied to every entry, or `None` if `f` fails for one.
    pub fn try_map<U>(&self, f: impl FnMut(&T) -> Option<U>) -> Option<Matrix<U>> {
        Some(Matrix {
            nrows: self.nrows,
            ncols: self.ncols,
            entries: self.entries.iter().map(f).collect::<Option<Vec<U>>>()?,
        })
    }
}

impl<T: Clone> Matrix<T> {
    /// The entry in row `i`, column `j`.
    ///
    /// # Panics
    ///
    /// Panics if `i` or `j` is not below [`dim`](Self::dim).
    pub fn get(&self, i: usize, j: usize) -> T {
        self.entry(i, j).clone()
    }

    /// The rows as owned vectors (the inverse of [`try_from_rows`](Self::try_from_rows)).
    pub fn to_rows(&self) -> Vec<Vec<T>> {
        self.rows().map(<[T]>::to_vec).collect()
    }

    /// The transpose.
    pub(crate) fn transpose(&self) -> Self {
        let entries = (0..self.nrows * self.ncols)
            .map(|k| self.entries[(k % self.nrows) * self.ncols + k / self.nrows].clone())
            .collect();
        Matrix {
            nrows: self.ncols,
            ncols: self.nrows,
            entries,
        }
    }
}

impl<T: Clone + Zero> Matrix<T> {
    /// The `nrows x ncols` zero block.
    pub(crate) fn zeros(nrows: usize, ncols: usize) -> Self {
        Matrix::from_vec(nrows, ncols, vec![T::zero(); nrows * ncols])
    }

    /// `c I`, `dim x dim`.
    pub(crate) fn scalar(dim: usize, c: &T) -> Self {
        let mut m = Matrix::zeros(dim, dim);
        for i in 0..dim {
            m.entries[i * dim + i] = c.clone();
        }
        m
    }
}

impl<T: Clone + Zero + One> Matrix<T> {
    /// The `dim x dim` identity matrix.
    ///
    /// # Panics
    ///
    /// Panics if `dim` is zero.
    pub fn identity(dim: usize) -> Self {
        assert!(dim > 0, "a matrix needs at least one row");
        Matrix::scalar(dim, &T::one())
    }
}

impl<T: Clone + Zero + CheckedAdd + CheckedMul> Matrix<T> {
    /// The product `self * rhs`, or `None` if an operation overflows (a partial sum
    /// included) or the dimensions do not match.
    ///
    /// Applying `rhs` first and then `self` is the product `self * rhs`. Zero entries are
    /// skipped.
    pub fn checked_mul(&self, rhs: &Matrix<T>) -> Option<Matrix<T>> {
        if self.ncols != rhs.nrows {
            return None;
        }
        let (n, inner, m) = (self.nrows, self.ncols, rhs.ncols);
        let mut entries = Vec::with_capacity(n * m);
        for i in 0..n {
            for j in 0..m {
                let mut acc = T::zero();
                for k in 0..inner {
                    let a = &self.entries[i * inner + k];
                    let b = &rhs.entries[k * m + j];
                    if a.is_zero() || b.is_zero() {
                        continue;
                    }
                    acc = acc.checked_add(&a.checked_mul(b)?)?;
                }
                entries.push(acc);
            }
        }
        Some(Matrix::from_vec(n, m, entries))
    }

    /// The vector `self x`, or `None` on overflow or when `x` has the wrong length.
    pub fn checked_apply(&self, x: &[T]) -> Option<Vec<T>> {
        if x.len() != self.ncols {
            return None;
        }
        self.rows()
            .map(|row| {
                row.iter().zip(x).try_fold(T::zero(), |acc, (a, xk)| {
                    if a.is_zero() || xk.is_zero() {
                        Some(acc)
                    } else {
                        acc.checked_add(&a.checked_mul(xk)?)
                    }
                })
            })
            .collect()
    }

    /// The entrywise sum, or `None` on overflow or when the shapes differ.
    pub(crate) fn checked_add(&self, rhs: &Matrix<T>) -> Option<Matrix<T>> {
        if (self.nrows, self.ncols) != (rhs.nrows, rhs.ncols) {
            return None;
        }
        let entries = self
            .entries
            .iter()
            .zip(&rhs.entries)
            .map(|(a, b)| a.checked_add(b))
            .collect::<Option<Vec<T>>>()?;
        Some(Matrix::from_vec(self.nrows, self.ncols, entries))
    }

    /// `q(self)` for a polynomial with coefficients lowest degree first, by Horner's rule,
    /// or `None` on overflow.
    pub(crate) fn checked_eval_poly(&self, coeffs: &[T]) -> Option<Matrix<T>> {
        let mut acc = Matrix::zeros(self.nrows, self.ncols);
        for c in coeffs.iter().rev() {
            acc = acc.checked_mul(self)?.checked_add_scalar(c)?;
        }
        Some(acc)
    }

    /// `self + c I`, or `None` on overflow.
    pub(crate) fn checked_add_scalar(&self, c: &T) -> Option<Matrix<T>> {
        let mut out = self.clone();
        for i in 0..self.nrows.min(self.ncols) {
            let e = &mut out.entries[i * self.ncols + i];
            *e = e.checked_add(c)?;
        }
        Some(out)
    }
}

impl<T: Clone + Zero + One + CheckedAdd + CheckedMul> Matrix<T> {
    /// `self^s` by squaring, or `None` on overflow (or for a matrix that is not square).
    pub fn checked_pow(&self, mut s: u64) -> Option<Matrix<T>> {
        if self.nrows != self.ncols {
            return None;
        }
        let mut result = Matrix::identity(self.nrows);
        let mut base = self.clone();
        while s > 0 {
            if s & 1 == 1 {
                result = result.checked_mul(&base)?;
            }
            s >>= 1;
            if s > 0 {
                base = base.checked_mul(&base)?;
            }
        }
        Some(result)
    }
}

impl Matrix<i64> {
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

impl<T: fmt::Display> fmt::Debug for Matrix<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Display::fmt(self, f)
    }
}

impl<T: fmt::Display> fmt::Display for Matrix<T> {
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
        self.list(Self::row, "a row")
    }

    fn row(&mut self) -> std::result::Result<Vec<i64>, ParseMatrixError> {
        self.list(Self::integer, "an entry")
    }

    /// `[item, item, ...]` (possibly empty); `what` names an item in the error.
    fn list<T>(
        &mut self,
        mut item: impl FnMut(&mut Self) -> std::result::Result<T, ParseMatrixError>,
        what: &str,
    ) -> std::result::Result<Vec<T>, ParseMatrixError> {
        self.expect('[')?;
        let mut items = Vec::new();
        if self.peek() == Some(']') {
            self.pos += 1;
            return Ok(items);
        }
        loop {
            items.push(item(self)?);
            match self.peek() {
                Some(',') => self.pos += 1,
                Some(']') => {
                    self.pos += 1;
                    return Ok(items);
                }
                _ => return Err(self.error(&format!("expected `,` or `]` after {what}"))),
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

    #[test]
    fn generic_powers_agree_with_repeated_products() {
        use num_bigint::BigInt;

        let m = IntMatrix::try_from_rows(vec![vec![1, 1, 0], vec![0, 2, 3], vec![-1, 0, 4]])
            .unwrap()
            .map(|&x| BigInt::from(x));
        let mut product = Matrix::<BigInt>::identity(3);
        for s in 0..40u64 {
            assert_eq!(m.checked_pow(s).unwrap(), product, "level {s}");
            product = product.checked_mul(&m).unwrap();
        }
        let x = [1, -2, 5].map(BigInt::from);
        let step = m.checked_apply(&x).unwrap();
        assert_eq!(step, [-1, 11, 19].map(BigInt::from));
        assert_eq!(m.checked_apply(&x[..2]), None);
        // i128 reports overflow where BigInt keeps going.
        let two = IntMatrix::try_from_rows(vec![vec![2]]).unwrap();
        let wide = two.map(|&x| i128::from(x));
        assert_eq!(wide.checked_pow(126).unwrap().get(0, 0), 1i128 << 126);
        assert_eq!(wide.checked_pow(127), None);
    }

    #[test]
    fn rectangular_blocks_multiply_and_transpose() {
        let a = Matrix::from_vec(2, 3, vec![1i64, 2, 3, 4, 5, 6]);
        let t = a.transpose();
        assert_eq!((t.dim(), t.ncols()), (3, 2));
        assert_eq!(t.entries(), &[1, 4, 2, 5, 3, 6]);
        let g = a.checked_mul(&t).unwrap();
        assert_eq!(g.to_rows(), vec![vec![14, 32], vec![32, 77]]);
        assert_eq!(a.checked_mul(&a), None, "2x3 times 2x3 does not multiply");
        assert_eq!(
            Matrix::from_fn(2, |i, j| i64::try_from(10 * i + j).unwrap()).to_rows(),
            vec![vec![0, 1], vec![10, 11]]
        );
    }
}
