//! The [`Recurrence`] type: a matrix with named components.

use num_bigint::BigInt;

use crate::power::{checked_power_apply, CheckedRing};
use crate::{ClosedForm, Eigenvalue, EigenvalueInfo, Error, IntMatrix, Polynomial, Result};

/// A linear recurrence `x_s = M x_(s-1)` over named components.
///
/// # Example: the icosahedron under 4:1 subdivision
///
/// ```
/// use num_bigint::BigInt;
/// use recurrence::{IntMatrix, Recurrence};
///
/// let m = IntMatrix::try_from_rows(vec![vec![1, 1, 0], vec![0, 2, 3], vec![0, 0, 4]])?;
/// let r = Recurrence::with_names(m, ["V", "E", "F"])?;
/// let x0 = [12, 30, 20].map(BigInt::from);
/// let v: Vec<BigInt> = (0..4).map(|s| r.state_at(&x0, s).unwrap()[0].clone()).collect();
/// assert_eq!(v, [12, 42, 162, 642].map(BigInt::from));
/// # Ok::<(), recurrence::Error>(())
/// ```
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Recurrence {
    matrix: IntMatrix,
    names: Vec<String>,
}

impl Recurrence {
    /// A recurrence whose components are named `x0`, `x1`, ...
    pub fn new(matrix: IntMatrix) -> Self {
        let names = (0..matrix.dim()).map(|i| format!("x{i}")).collect();
        Recurrence { matrix, names }
    }

    /// A recurrence with the given component names, one per row of the matrix.
    ///
    /// # Errors
    ///
    /// [`Error::NamesMismatch`] when the count differs from the dimension,
    /// [`Error::DuplicateName`] and [`Error::InvalidName`] for unusable names. A valid name
    /// starts with an ASCII letter and continues with ASCII letters, digits or `_`.
    pub fn with_names<I, S>(matrix: IntMatrix, names: I) -> Result<Self>
    where
        I: IntoIterator<Item = S>,
        S: Into<String>,
    {
        let names: Vec<String> = names.into_iter().map(Into::into).collect();
        if names.len() != matrix.dim() {
            return Err(Error::NamesMismatch {
                names: names.len(),
                dim: matrix.dim(),
            });
        }
        for (i, name) in names.iter().enumerate() {
            if !is_valid_name(name) {
                return Err(Error::InvalidName { name: name.clone() });
            }
            if names[..i].contains(name) {
                return Err(Error::DuplicateName { name: name.clone() });
            }
        }
        Ok(Recurrence { matrix, names })
    }

    /// The matrix `M`.
    pub fn matrix(&self) -> &IntMatrix {
        &self.matrix
    }

    /// The component names, in state order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The number of components.
    pub fn dim(&self) -> usize {
        self.matrix.dim()
    }

    /// The position of the component called `name`.
    pub fn index_of(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }

    /// The exact state `M^s x0`, by exponentiation by squaring over big integers.
    ///
    /// # Errors
    ///
    /// [`Error::InitialLength`] when `x0` does not have one value per component.
    pub fn state_at(&self, x0: &[BigInt], s: u64) -> Result<Vec<BigInt>> {
        self.check_len(x0.len())?;
        Ok(checked_power_apply(&self.matrix, x0, s).expect("big integers do not overflow"))
    }

    /// The state `M^s x0` in checked `i128` arithmetic.
    ///
    /// # Errors
    ///
    /// [`Error::Overflow`] when an intermediate or final value does not fit in `i128`
    /// (never a wrapped value), [`Error::InitialLength`] for a wrong-length `x0`.
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence, Error};
    /// let r = Recurrence::new(IntMatrix::try_from_rows(vec![vec![2]])?);
    /// assert_eq!(r.state_at_i128(&[1], 126)?, vec![1i128 << 126]);
    /// assert!(matches!(r.state_at_i128(&[1], 127), Err(Error::Overflow { level: 127, .. })));
    /// # Ok::<(), recurrence::Error>(())
    /// ```
    pub fn state_at_i128(&self, x0: &[i128], s: u64) -> Result<Vec<i128>> {
        self.check_len(x0.len())?;
        checked_power_apply(&self.matrix, x0, s).ok_or(Error::Overflow {
            level: s,
            width: "i128",
        })
    }

    /// The states at levels `0..=last`, by repeated multiplication (one matrix-vector product
    /// per level), which is cheaper than powering when every level is wanted.
    ///
    /// # Errors
    ///
    /// [`Error::InitialLength`] for a wrong-length `x0`.
    pub fn states_up_to(&self, x0: &[BigInt], last: u64) -> Result<Vec<Vec<BigInt>>> {
        self.check_len(x0.len())?;
        let m = self.matrix.map(|&x| BigInt::from(x));
        let mut out = Vec::with_capacity(usize::try_from(last).unwrap_or(0).saturating_add(1));
        let mut x = x0.to_vec();
        for s in 0..=last {
            if s > 0 {
                x = m.checked_apply(&x).expect("big integers do not overflow");
            }
            out.push(x.clone());
        }
        Ok(out)
    }

    /// The matrix `M^s` over any [`CheckedRing`], or `None` on overflow.
    pub fn checked_matrix_power<T: CheckedRing>(&self, s: u64) -> Option<Vec<Vec<T>>> {
        let p = self.matrix.try_map(|&x| T::from_entry(x))?.checked_pow(s)?;
        Some(p.to_rows())
    }

    /// The characteristic polynomial `det(x I - M)`, exact (Faddeev-LeVerrier over the
    /// integers).
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence};
    /// let r = Recurrence::new("[[1, 1, 1], [0, 2, 4], [0, 0, 4]]".parse::<IntMatrix>()?);
    /// assert_eq!(r.characteristic_polynomial().to_string(), "x^3 - 7*x^2 + 14*x - 8");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn characteristic_polynomial(&self) -> Polynomial {
        crate::poly::characteristic_polynomial(&self.matrix)
    }

    /// The distinct eigenvalues with their algebraic multiplicities, largest modulus first.
    ///
    /// Integer eigenvalues and roots of integer quadratic factors are exact; the others are
    /// [`Eigenvalue::Numeric`].
    ///
    /// ```
    /// # use recurrence::{Eigenvalue, IntMatrix, Recurrence};
    /// # use num_rational::BigRational;
    /// let r = Recurrence::new("[[2, 1], [0, 2]]".parse::<IntMatrix>()?);
    /// let e = r.eigenvalues();
    /// assert_eq!(e.len(), 1);
    /// assert_eq!(e[0].eigenvalue, Eigenvalue::Rational(BigRational::from_integer(2.into())));
    /// assert_eq!(e[0].multiplicity, 2);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn eigenvalues(&self) -> Vec<EigenvalueInfo> {
        crate::eigen::eigenvalues(&self.characteristic_polynomial())
    }

    /// The eigenvalue of largest modulus (the growth rate of the counts), or `None` when
    /// every eigenvalue is zero (a nilpotent matrix). Among several of the same modulus, the
    /// one with the largest real part.
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence};
    /// let r = Recurrence::new("[[1, 1], [0, 4]]".parse::<IntMatrix>()?);
    /// assert_eq!(r.dominant_eigenvalue().map(|e| e.to_string()), Some("4".to_string()));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn dominant_eigenvalue(&self) -> Option<Eigenvalue> {
        self.eigenvalues()
            .into_iter()
            .map(|e| e.eigenvalue)
            .find(|e| !e.is_zero())
    }

    /// The exact closed form of every component, from the spectral decomposition of the
    /// matrix (see [`ClosedForm`]). Components with numeric eigenvalues are checked against
    /// exact powering; before showing such a form, call [`ClosedForm::verify`] (or use
    /// [`verified_closed_form`](Self::verified_closed_form)).
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence};
    /// let r = Recurrence::with_names("[[1, 1], [0, 4]]".parse::<IntMatrix>()?, ["V", "E"])?;
    /// let form = r.closed_form();
    /// assert!(form.is_exact());
    /// assert_eq!(form.components()[1].terms.len(), 1);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn closed_form(&self) -> ClosedForm {
        crate::closed_form::closed_form(self)
    }

    /// An upper estimate, in work units (about one machine-word or floating-point operation
    /// each), of what [`closed_form`](Self::closed_form) costs, from the dimension `n` and
    /// the bit length `b` of the largest entry alone (nothing is computed):
    ///
    /// `n^5 + n^3 * w^2` with `w = ceil(n (b + bits(n)) / 64)`.
    ///
    /// The first term bounds the numeric spectral parts (`n^4` per eigenvalue outside `Q`
    /// and `Q(sqrt d)`, at most `n` of them); the second the fraction-free eliminations of
    /// the exact ones (`O(n^3)` operations on integers of up to `n (b + bits(n))` bits, the
    /// size of the minors involved). Use it to refuse matrices whose closed form would take
    /// long before starting: [`closed_form_within`](Self::closed_form_within).
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence};
    /// let r = Recurrence::new("[[1, 1], [0, 4]]".parse::<IntMatrix>()?);
    /// assert_eq!(r.closed_form_cost(), 32 + 8); // 2^5 + 2^3 * 1^2
    /// let big = Recurrence::new(IntMatrix::try_from_rows(vec![vec![1000; 32]; 32])?);
    /// assert_eq!(big.closed_form_cost(), 32u64.pow(5) + 32u64.pow(3) * 8 * 8);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn closed_form_cost(&self) -> u64 {
        let n = self.dim() as u64;
        let b = self
            .matrix
            .rows()
            .flatten()
            .map(|x| u64::from(64 - x.unsigned_abs().leading_zeros()))
            .max()
            .unwrap_or(0)
            .max(1);
        let bits_n = u64::from(64 - n.leading_zeros());
        let w = n.saturating_mul(b + bits_n).div_ceil(64);
        let n3 = n.saturating_mul(n).saturating_mul(n);
        n3.saturating_mul(n)
            .saturating_mul(n)
            .saturating_add(n3.saturating_mul(w.saturating_mul(w)))
    }

    /// The closed form, if its [`closed_form_cost`](Self::closed_form_cost) is at most
    /// `limit`.
    ///
    /// # Errors
    ///
    /// [`Error::ClosedFormTooCostly`] (with the estimate) when the cost exceeds `limit`;
    /// nothing is computed then. [`Error::InaccurateClosedForm`] when the form's numeric
    /// terms miss the exact counts.
    ///
    /// ```
    /// # use recurrence::{Error, IntMatrix, Recurrence};
    /// let r = Recurrence::new("[[1, 1], [0, 4]]".parse::<IntMatrix>()?);
    /// assert!(r.closed_form_within(1000)?.is_exact());
    /// assert!(matches!(
    ///     r.closed_form_within(10),
    ///     Err(Error::ClosedFormTooCostly { dim: 2, cost: 40, limit: 10 })
    /// ));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn closed_form_within(&self, limit: u64) -> Result<ClosedForm> {
        let cost = self.closed_form_cost();
        if cost > limit {
            return Err(Error::ClosedFormTooCostly {
                dim: self.dim(),
                cost,
                limit,
            });
        }
        self.verified_closed_form()
    }

    /// The closed form, if it holds ([`ClosedForm::verify`]).
    ///
    /// # Errors
    ///
    /// [`Error::InaccurateClosedForm`] when numeric terms miss the exact counts.
    pub fn verified_closed_form(&self) -> Result<ClosedForm> {
        let form = self.closed_form();
        form.verify()?;
        Ok(form)
    }

    fn check_len(&self, got: usize) -> Result {
        if got == self.dim() {
            Ok(())
        } else {
            Err(Error::InitialLength {
                got,
                expected: self.dim(),
            })
        }
    }
}

fn is_valid_name(name: &str) -> bool {
    let mut chars = name.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}
