//! What a command counts: a recurrence (from `--matrix` or a scheme) and an initial state.

use std::ops::RangeInclusive;

use num_bigint::BigInt;
use recurrence::{IntMatrix, Recurrence};

use crate::args::Source;
use crate::failure::{usage, Failure};
use crate::output::Row;

/// The default recurrence: 4:1 triangle subdivision in the (V, E, F) form.
pub(crate) const DEFAULT_MATRIX: &str = "[[1,1,0],[0,2,3],[0,0,4]]";
/// The default initial state: the icosahedron.
pub(crate) const DEFAULT_INIT: [i64; 3] = [12, 30, 20];

/// A recurrence with named components, ready to count.
pub(crate) struct Dynamics {
    pub(crate) recurrence: Recurrence,
}

impl Dynamics {
    /// Builds the recurrence named by the flags, or the default one.
    pub(crate) fn from_source(source: &Source) -> Result<Dynamics, Failure> {
        let matrix_text = source.matrix.as_deref();
        if matrix_text.is_none() && source.names.is_some() {
            return Err(usage!("--names needs --matrix"));
        }
        let matrix: IntMatrix = matrix_text
            .unwrap_or(DEFAULT_MATRIX)
            .parse()
            .map_err(|e| usage!("invalid --matrix: {e}"))?;
        let recurrence = match (&source.names, matrix_text) {
            (Some(names), _) => Recurrence::with_names(matrix, names.iter().map(|n| n.trim()))
                .map_err(|e| usage!("invalid --names: {e}"))?,
            (None, None) => Recurrence::with_names(matrix, ["V", "E", "F"])
                .map_err(|e| usage!("{e}"))?,
            (None, Some(_)) => Recurrence::new(matrix),
        };
        Ok(Dynamics { recurrence })
    }

    /// The component names, in state order.
    pub(crate) fn columns(&self) -> Vec<String> {
        self.recurrence.names().to_vec()
    }

    /// The initial state named by the flags (or the default icosahedron).
    pub(crate) fn initial_state(&self, source: &Source) -> Result<Vec<BigInt>, Failure> {
        let values = match (&source.init, &source.matrix) {
            (Some(text), _) => parse_init(text)?,
            (None, None) => DEFAULT_INIT.iter().map(|&x| BigInt::from(x)).collect(),
            (None, Some(_)) => return Err(usage!("--matrix needs --init with one value per component")),
        };
        if values.len() != self.recurrence.dim() {
            return Err(usage!(
                "--init has {} values but the state has {} components ({})",
                values.len(),
                self.recurrence.dim(),
                self.recurrence.names().join(", ")
            ));
        }
        Ok(values)
    }

    /// The rows for a range of levels: powering to the first, then one step per level.
    pub(crate) fn rows(&self, x0: &[BigInt], levels: RangeInclusive<u64>) -> Vec<Row> {
        let (start, end) = (*levels.start(), *levels.end());
        let first = self.state_at(x0, start);
        let states = self
            .recurrence
            .states_up_to(&first, end - start)
            .expect("the state has the recurrence's dimension");
        states
            .into_iter()
            .enumerate()
            .map(|(i, values)| Row {
                level: start + i as u64,
                values,
            })
            .collect()
    }

    /// The exact state at level `s`.
    pub(crate) fn state_at(&self, x0: &[BigInt], s: u64) -> Vec<BigInt> {
        self.recurrence
            .state_at(x0, s)
            .expect("the state has the recurrence's dimension")
    }
}

/// Parses `12,30,20` (negative values allowed: a recurrence is any integer sequence).
fn parse_init(text: &str) -> Result<Vec<BigInt>, Failure> {
    text.split(',')
        .map(|t| {
            let t = t.trim();
            t.parse::<BigInt>()
                .map_err(|_| usage!("invalid --init: `{t}` is not an integer"))
        })
        .collect()
}

/// An upper estimate of log10 |x_s| for each component, in floating point: powering with
/// renormalization so that no level overflows `f64`. Used only by resource guards.
pub(crate) fn estimate_log10(recurrence: &Recurrence, x0: &[BigInt], s: u64) -> Vec<f64> {
    let n = recurrence.dim();
    let m = recurrence.matrix();
    // |M| entrywise bounds |M^s| entrywise, so this is an upper bound up to rounding.
    let abs: Vec<f64> = m.rows().flatten().map(|&x| (x as f64).abs()).collect();
    let x: Vec<f64> = x0.iter().map(|v| log10_big(v)).collect();
    let max_x = x.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
    // Work with x scaled by 10^-max_x.
    let mut vec: Vec<f64> = x.iter().map(|&l| if l.is_finite() { 10f64.powf(l - max_x) } else { 0.0 }).collect();
    let mut log_scale = if max_x.is_finite() { max_x } else { 0.0 };
    let mut base = abs;
    let mut base_log = 0.0f64;
    let mut s = s;
    let mul = |a: &[f64], b: &[f64]| -> Vec<f64> {
        let mut c = vec![0.0; n * n];
        for i in 0..n {
            for k in 0..n {
                let aik = a[i * n + k];
                if aik == 0.0 {
                    continue;
                }
                for j in 0..n {
                    c[i * n + j] += aik * b[k * n + j];
                }
            }
        }
        c
    };
    let normalize = |v: &mut [f64]| -> f64 {
        let max = v.iter().cloned().fold(0.0, f64::max);
        if max > 0.0 {
            v.iter_mut().for_each(|x| *x /= max);
            max.log10()
        } else {
            0.0
        }
    };
    while s > 0 {
        if s & 1 == 1 {
            let mut next = vec![0.0; n];
            for i in 0..n {
                for j in 0..n {
                    next[i] += base[i * n + j] * vec[j];
                }
            }
            vec = next;
            log_scale += base_log + normalize(&mut vec);
        }
        s >>= 1;
        if s > 0 {
            base = mul(&base, &base);
            base_log = 2.0 * base_log + normalize(&mut base);
        }
    }
    vec.iter()
        .map(|&v| if v > 0.0 { v.log10() + log_scale } else { f64::NEG_INFINITY })
        .collect()
}

fn log10_big(v: &BigInt) -> f64 {
    let bits = v.bits();
    if bits == 0 {
        return f64::NEG_INFINITY;
    }
    let shift = bits.saturating_sub(60);
    let top = (v.magnitude() >> shift).to_string().parse::<f64>().unwrap_or(1.0);
    top.log10() + shift as f64 * std::f64::consts::LOG10_2
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn estimate_tracks_exact_digits() {
        let r = Recurrence::with_names("[[1,1],[0,4]]".parse().unwrap(), ["V", "E"]).unwrap();
        let x0 = [BigInt::from(12), BigInt::from(30)];
        for s in [0u64, 1, 5, 100, 1000] {
            let exact = r.state_at(&x0, s).unwrap();
            let est = estimate_log10(&r, &x0, s);
            for (e, x) in est.iter().zip(&exact) {
                let digits = x.to_string().len() as f64;
                assert!(*e + 1.0 >= digits - 1e-9, "s={s}: estimate {e} below {digits} digits");
                assert!(*e <= digits + 1.0, "s={s}: estimate {e} far above {digits} digits");
            }
        }
        let big = estimate_log10(&r, &x0, 1_000_000_000_000);
        assert!((big[0] - 1e12 * 4f64.log10()).abs() < 1e3);
    }
}
