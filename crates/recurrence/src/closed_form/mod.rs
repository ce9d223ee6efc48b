//! Closed forms `x_i(s) = sum_l p_l(s) l^s`: the types ([`ClosedForm`] and its parts) and
//! the size estimate. `derive.rs` computes them from the spectral decomposition, `eval.rs`
//! evaluates them exactly; rendering lives in `render.rs` (text, LaTeX, Rust) and `json.rs`.
//!
//! # Design notes (moved from ARCHITECTURE.md)
//!
//! Closed forms (`closed_form/`, `eigen.rs`, `poly.rs`, `field.rs`): `closed_form/mod.rs` holds
//! the types (`ClosedForm`, `ComponentForm`, `Term`, `Coefficient`) and the size estimate,
//! `closed_form/derive.rs` the spectral decomposition, `closed_form/eval.rs` the exact evaluation.
//! `poly.rs` is the one polynomial module: the characteristic polynomial by Faddeev-LeVerrier over
//! `Z`; its square-free factors by Yun's algorithm with gcds computed modulo 62-bit primes, lifted
//! by the Chinese remainder theorem and confirmed by exact division over `Z` (Euclid over `Q` blew
//! up: 8 s for a degree-24 polynomial); roots located by nalgebra's Schur decomposition of each
//! factor's companion matrix (at most `100 max(10, n)` iterations, then Durand-Kerner) and
//! confirmed exactly. Factors of degree one and two (also what is left once the integer roots are
//! divided out) get their roots symbolically, whatever the size of the entries; integer roots are
//! found by exact Newton steps from the estimates and the Cauchy bounds and, for coefficients
//! beyond 2^50, by Sturm-sequence isolation. For an exact eigenvalue `l` of multiplicity `m`
//! (integer or quadratic surd), the spectral parts come fraction-free from the generalized
//! eigenspaces in `Z[sqrt d]`: with `B = c (M - l I)` integral, the right and left kernels `R`,
//! `L` of `B^m` (Bareiss-style Gauss-Jordan, every division exact) give `P = R (L^T R)^-1 L^T`,
//! and every term matrix is one integer matrix over a common denominator, made rational once. Only
//! numeric eigenvalues still go through `h(M)` by Horner in `Complex64`. The fields are plain
//! `num_traits` types; the crate-private `Field` trait adds only division and the embedding of the
//! rationals. `Recurrence::closed_form_cost` bounds the work from the size alone (`n^5 + n^3 w^2`)
//! so callers can refuse before starting.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Zero;

use crate::eigen::{Eigenvalue, EigenvalueInfo};
use crate::field::QuadraticSurd;
use crate::{Complex64, Error, IntMatrix, Result};

mod derive;
mod eval;

pub(crate) use derive::closed_form;
pub(crate) use eval::dot;

/// A coefficient of a closed-form term: exact rational, exact in `Q(sqrt d)`, or numeric.
#[derive(Clone, Debug, PartialEq)]
pub enum Coefficient {
    /// An exact rational.
    Rational(BigRational),
    /// An exact element `a + b*sqrt(d)` of a quadratic field.
    Surd(QuadraticSurd),
    /// A numeric approximation.
    Numeric(Complex64),
}

impl Coefficient {
    /// Whether the coefficient is zero (numeric ones: negligible).
    pub fn is_zero(&self) -> bool {
        match self {
            Coefficient::Rational(r) => r.is_zero(),
            Coefficient::Surd(q) => q.a.is_zero() && q.b.is_zero(),
            Coefficient::Numeric(z) => z.norm() < 1e-9,
        }
    }
}

impl std::fmt::Display for Coefficient {
    /// `p` or `p/q`, `a+b*sqrt(d)`, or a numeric `re+imi`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Coefficient::Rational(r) => write!(f, "{r}"),
            Coefficient::Surd(q) => write!(f, "{q}"),
            Coefficient::Numeric(z) => write!(f, "{z}"),
        }
    }
}

/// One term `(sum_j coefficients[j] * x_j(0)) * s^s_power * eigenvalue^s` of a component.
#[derive(Clone, Debug, PartialEq)]
pub struct Term {
    /// The eigenvalue raised to the power `s`.
    pub eigenvalue: Eigenvalue,
    /// The power of `s` (from Jordan blocks).
    pub s_power: u32,
    /// One coefficient per component of the initial state, in state order.
    pub coefficients: Vec<Coefficient>,
}

/// The value of a component at a level below its `valid_from`, as a combination of the
/// initial values (a row of `M^level`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EarlyLevel {
    /// The level.
    pub level: u64,
    /// One integer coefficient per initial component.
    pub coefficients: Vec<BigInt>,
}

/// The closed form of one component of the state.
#[derive(Clone, Debug, PartialEq)]
pub struct ComponentForm {
    /// The component's name.
    pub name: String,
    /// The least level from which the terms give the component (above `0` only when a zero
    /// eigenvalue contributes to it).
    pub valid_from: u64,
    /// Whether every term is exact (no numeric eigenvalue contributes).
    pub exact: bool,
    /// The terms, largest eigenvalue first, then highest power of `s` first.
    pub terms: Vec<Term>,
    /// The levels below `valid_from`, explicitly.
    pub early_levels: Vec<EarlyLevel>,
}

/// The closed form of every component of a [`Recurrence`](crate::Recurrence).
///
/// Built by [`Recurrence::closed_form`](crate::Recurrence::closed_form); evaluate it with [`ClosedForm::evaluate`], print it
/// with [`ClosedForm::to_text`], [`ClosedForm::to_latex`], [`ClosedForm::to_rust`] or
/// `ClosedForm::to_json` (with the `json` feature).
#[derive(Clone, Debug)]
pub struct ClosedForm {
    names: Vec<String>,
    matrix: IntMatrix,
    eigenvalues: Vec<EigenvalueInfo>,
    components: Vec<ComponentForm>,
    fast: Vec<Option<FastComponent>>,
    powers: Vec<FastEigenvalue>,
    /// The first component and level at which the numeric terms fail to reproduce exact
    /// powering ([`ClosedForm::verify`]).
    inaccurate: Option<(usize, u64)>,
}

/// Precomputed integer data for evaluating one exact component quickly.
#[derive(Clone, Debug)]
pub(crate) struct FastComponent {
    /// Common denominator of the rational coefficients.
    pub(crate) denominator: BigInt,
    /// `(eigenvalue index, s_power, numerators)` for rational eigenvalues.
    pub(crate) rational: Vec<(usize, u32, Vec<BigInt>)>,
    /// `(eigenvalue index, s_power, coefficients)` for surd eigenvalues.
    pub(crate) surd: Vec<(usize, u32, Vec<QuadraticSurd>)>,
    /// The valid_from level and the early rows.
    pub(crate) valid_from: u64,
    pub(crate) early: Vec<Vec<BigInt>>,
}

/// An eigenvalue prepared for fast powering.
#[derive(Clone, Debug)]
pub(crate) enum FastEigenvalue {
    /// An integer; `shift` is `k` when `|value| = 2^k`.
    Integer { value: BigInt, shift: Option<u64> },
    /// A quadratic surd.
    Surd(QuadraticSurd),
    /// Numeric; never evaluated exactly.
    Numeric,
}

impl ClosedForm {
    /// Whether the form holds: exact components always do; a component with numeric terms
    /// was checked against exact powering at a few levels when the form was derived.
    ///
    /// # Errors
    ///
    /// [`Error::InaccurateClosedForm`] naming the first component and level where the
    /// numeric terms miss the exact count (ill-conditioned eigenvalues, such as those of
    /// irreducible cubics with entries beyond `2^53`); such a form must not be shown or
    /// evaluated: power the matrix instead.
    ///
    /// ```
    /// # use recurrence::{Error, IntMatrix, Recurrence};
    /// let cycle = "[[0,0,0,0,1],[1,0,0,0,0],[0,1,0,0,0],[0,0,1,0,0],[0,0,0,1,0]]";
    /// assert!(Recurrence::new(cycle.parse::<IntMatrix>()?).closed_form().verify().is_ok());
    /// let big = "[[9223372036854775807,9223372036854775807,1],[1,0,0],[0,1,0]]";
    /// let form = Recurrence::new(big.parse::<IntMatrix>()?).closed_form();
    /// assert!(matches!(form.verify(), Err(Error::InaccurateClosedForm { .. })));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn verify(&self) -> Result<()> {
        match self.inaccurate {
            None => Ok(()),
            Some((i, level)) => Err(Error::InaccurateClosedForm {
                component: self.names[i].clone(),
                level,
            }),
        }
    }

    /// The component names, in state order.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The matrix the form was derived from.
    pub fn matrix(&self) -> &IntMatrix {
        &self.matrix
    }

    /// The eigenvalues with multiplicities, in the order terms use.
    pub fn eigenvalues(&self) -> &[EigenvalueInfo] {
        &self.eigenvalues
    }

    /// The closed form of each component, in state order.
    pub fn components(&self) -> &[ComponentForm] {
        &self.components
    }

    /// Whether every component's form is exact.
    pub fn is_exact(&self) -> bool {
        self.components.iter().all(|c| c.exact)
    }

    pub(crate) fn fast(&self) -> &[Option<FastComponent>] {
        &self.fast
    }

    pub(crate) fn powers(&self) -> &[FastEigenvalue] {
        &self.powers
    }

    /// An estimate of the size in bits of the largest count at level `s`: `s log2 |l|` for the
    /// largest eigenvalue `l` that appears in a term (coefficients and powers of `s` add only
    /// a few bits). Use it to refuse levels whose counts cannot fit in memory before
    /// computing them; [`summary_at`](Self::summary_at) needs no such guard.
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence};
    /// let form = Recurrence::new("[[1, 1], [0, 4]]".parse::<IntMatrix>()?).closed_form();
    /// assert_eq!(form.estimated_bits(1_000_000), 2_000_000);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn estimated_bits(&self, s: u64) -> u64 {
        (0..self.components.len())
            .map(|i| self.component_bits(i, s))
            .max()
            .unwrap_or(0)
    }

    fn component_bits(&self, i: usize, s: u64) -> u64 {
        let rho = self.components[i]
            .terms
            .iter()
            .map(|t| t.eigenvalue.modulus())
            .fold(1.0f64, f64::max);
        let bits = s as f64 * rho.log2();
        if bits >= u64::MAX as f64 {
            u64::MAX
        } else {
            bits.ceil() as u64
        }
    }
}
