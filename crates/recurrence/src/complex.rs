//! [`Complex64`], the crate's own complex number for numeric eigenvalues and coefficients,
//! so that the public API names no dependency's type (nalgebra computes with its own
//! `Complex` inside the crate).

use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

use num_traits::{CheckedAdd, CheckedMul, One, Zero};

/// A complex number in `f64`: a numeric eigenvalue, coefficient or value of a surd.
///
/// Displays as `re` or `re+imi` with 12 significant digits, the form every rendering uses.
/// The arithmetic operators round as `num_complex` does; [`Zero::is_zero`] means negligible
/// (`|z| < 1e-12`).
///
/// ```
/// use recurrence::Complex64;
///
/// let z = Complex64::new(-0.5, 0.866_025_403_784_438_6);
/// assert_eq!(z.to_string(), "-0.5+0.866025403784i");
/// assert!((z.norm() - 1.0).abs() < 1e-12);
/// assert_eq!(Complex64::new(3.0, 0.0).to_string(), "3");
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Complex64 {
    /// The real part.
    pub re: f64,
    /// The imaginary part.
    pub im: f64,
}

impl Complex64 {
    /// `re + im i`.
    pub const fn new(re: f64, im: f64) -> Self {
        Complex64 { re, im }
    }

    /// The modulus `sqrt(re^2 + im^2)`, without overflow in the squares.
    pub fn norm(self) -> f64 {
        self.re.hypot(self.im)
    }

    pub(crate) fn from_nalgebra(z: nalgebra::Complex<f64>) -> Self {
        Complex64::new(z.re, z.im)
    }
}

impl Add for Complex64 {
    type Output = Complex64;
    fn add(self, rhs: Complex64) -> Complex64 {
        Complex64::new(self.re + rhs.re, self.im + rhs.im)
    }
}

impl Sub for Complex64 {
    type Output = Complex64;
    fn sub(self, rhs: Complex64) -> Complex64 {
        Complex64::new(self.re - rhs.re, self.im - rhs.im)
    }
}

impl Mul for Complex64 {
    type Output = Complex64;
    fn mul(self, rhs: Complex64) -> Complex64 {
        Complex64::new(
            self.re * rhs.re - self.im * rhs.im,
            self.re * rhs.im + self.im * rhs.re,
        )
    }
}

impl Div for Complex64 {
    type Output = Complex64;
    /// `self conj(rhs) / |rhs|^2`, rounded as `num_complex` does.
    fn div(self, rhs: Complex64) -> Complex64 {
        let norm_sqr = rhs.re * rhs.re + rhs.im * rhs.im;
        Complex64::new(
            (self.re * rhs.re + self.im * rhs.im) / norm_sqr,
            (self.im * rhs.re - self.re * rhs.im) / norm_sqr,
        )
    }
}

impl Neg for Complex64 {
    type Output = Complex64;
    fn neg(self) -> Complex64 {
        Complex64::new(-self.re, -self.im)
    }
}

impl Zero for Complex64 {
    fn zero() -> Self {
        Complex64::new(0.0, 0.0)
    }

    /// Whether the value is negligible, `|z| < 1e-12`: numeric products skip such entries
    /// as the exact ones skip zeros.
    fn is_zero(&self) -> bool {
        self.norm() < 1e-12
    }
}

impl One for Complex64 {
    fn one() -> Self {
        Complex64::new(1.0, 0.0)
    }
}

impl CheckedAdd for Complex64 {
    /// Always `Some`: floating point saturates to infinity rather than overflowing.
    fn checked_add(&self, rhs: &Self) -> Option<Self> {
        Some(*self + *rhs)
    }
}

impl CheckedMul for Complex64 {
    /// Always `Some`: floating point saturates to infinity rather than overflowing.
    fn checked_mul(&self, rhs: &Self) -> Option<Self> {
        Some(*self * *rhs)
    }
}

impl fmt::Display for Complex64 {
    /// `re`, or `re+imi`, with 12 significant digits.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let re = format_float(self.re);
        if self.im.abs() <= 1e-12 * self.norm().max(1e-300) {
            f.write_str(&re)
        } else if self.im < 0.0 {
            write!(f, "{re}-{}i", format_float(-self.im))
        } else {
            write!(f, "{re}+{}i", format_float(self.im))
        }
    }
}

fn format_float(x: f64) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    let s = format!("{:.11e}", x);
    // Prefer plain notation for moderate magnitudes.
    if (1e-4..1e12).contains(&x.abs()) {
        let digits = 11 - x.abs().log10().floor() as i32;
        let t = format!("{:.*}", digits.max(0) as usize, x);
        let t = if t.contains('.') {
            t.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            t
        };
        return t;
    }
    s
}
