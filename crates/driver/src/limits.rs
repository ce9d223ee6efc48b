//! The counting guards: refuse (a guard's refusal, exit 4) before materializing counts,
//! tables or closed forms too large for memory or time. Every front end that prints exact
//! counts at a level, a table of levels or a closed form asks these first.

use std::ops::RangeInclusive;

use num_bigint::BigInt;
use schemes::{Counter, CLOSED_FORM_LIMIT};

use crate::error::{Error, Result};

/// The last level real subdivision builds: every rule at least doubles the faces per level,
/// so no later level fits 32-bit indices.
pub const MAX_REAL_LEVELS: u32 = 64;
/// Most threads a front end may ask for (`--threads`, `threads=`; 0 uses every core).
pub const MAX_THREADS: usize = 256;

/// Why a real subdivision to `levels` is refused (a guard's refusal: `--levels`, `levels=`),
/// or `None` up to [`MAX_REAL_LEVELS`]; each front end names its own option before it.
pub fn levels_refusal(levels: u64) -> Option<String> {
    (levels > u64::from(MAX_REAL_LEVELS)).then(|| {
        format!("real subdivision stops at level {MAX_REAL_LEVELS} (every rule at least doubles the faces per level, so no later level fits 32-bit indices)")
    })
}

/// Why `threads` is refused (`--threads`, `threads=`: a usage error), or `None` from 0 (every
/// core) to [`MAX_THREADS`]; each front end names its own option before it.
pub fn threads_refusal(threads: u64) -> Option<String> {
    (threads > MAX_THREADS as u64)
        .then(|| format!("at most {MAX_THREADS} threads (0 uses every core)"))
}

/// Most decimal digits a count may have without `--allow-large`.
pub const MAX_DIGITS: f64 = 1e7;
/// Most decimal digits a table (all rows and columns together) may hold.
pub const MAX_TABLE_DIGITS: f64 = 1e8;
/// Most cells a table may hold.
pub const MAX_TABLE_CELLS: f64 = 1e7;

/// What the digit guard suggests: `at` has `--summary` and `--allow-large`; the commands
/// that print every level (`table`, `plot`, `density`) can only ask for fewer levels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Hint {
    /// One level, printed whole (`at`).
    At,
    /// One level, summarized (`at --summary`).
    AtSummary,
    /// Every level of a range.
    Levels,
}

/// Refuses ([`Error::TooManyDigits`]) counts of more than [`MAX_DIGITS`] decimal digits at level `s`.
pub fn digits(
    counter: &Counter,
    x0: &[BigInt],
    s: u64,
    allow_large: bool,
    hint: Hint,
) -> Result<()> {
    if allow_large {
        return Ok(());
    }
    let worst = counter.estimated_log10(x0, s)?;
    if worst > MAX_DIGITS {
        let bytes = worst * std::f64::consts::LOG2_10 / 8.0;
        let hint = match hint {
            Hint::AtSummary => "--summary works without materializing the counts only with an exact closed form from level 0 (not for periodic or composed schemes, nor irrational eigenvalues at such levels); use --allow-large to try anyway",
            Hint::At => "use --summary, or --allow-large to try anyway",
            Hint::Levels => "ask for lower levels (or use `at --summary` for one huge level)",
        };
        return Err(Error::TooManyDigits {
            level: s,
            digits: worst.ceil(),
            bytes: halfedge::memory::human_bytes(bytes),
            hint,
        });
    }
    Ok(())
}

/// The guard of the commands that hold every level of a range (`table`, `plot`): the largest
/// count, then the whole table (rows times columns times digits), before anything is computed;
/// with `uv`, its `UV` column counts too (one more column, digits the larger estimate).
pub fn table(
    counter: &Counter,
    x0: &[BigInt],
    levels: &RangeInclusive<u64>,
    uv: Option<&schemes::uv::UvCounter>,
) -> Result<()> {
    digits(counter, x0, *levels.end(), false, Hint::Levels)?;
    // Exact for the message (up to 2^64 rows), as a float for the estimate.
    let rows = u128::from(*levels.end() - *levels.start()) + 1;
    let columns = counter.columns().len() + usize::from(uv.is_some());
    let cells = rows as f64 * columns as f64;
    let mut digits = counter.estimated_log10(x0, *levels.end())? + 1.0;
    if let Some(uv) = uv {
        digits = digits.max(uv.estimated_log10(*levels.end())? + 1.0);
    }
    if cells > MAX_TABLE_CELLS || cells * digits > MAX_TABLE_DIGITS {
        return Err(Error::TableTooLarge {
            levels: levels.clone(),
            rows,
            digits: (cells * digits).ceil(),
        });
    }
    Ok(())
}

/// Refuses ([`Error::ClosedFormTooCostly`]) closed forms whose cost estimate exceeds [`CLOSED_FORM_LIMIT`]
/// (every phase of a plan), unless `allow_large`.
pub fn closed_forms(counter: &Counter, allow_large: bool) -> Result<()> {
    if allow_large {
        return Ok(());
    }
    for (phase, r) in counter.form_recurrences() {
        let what = match (counter.plan(), phase) {
            (None, _) => "--matrix".to_string(),
            (Some(plan), None) => format!("scheme `{}`", plan.name()),
            (Some(plan), Some(phase)) => format!("scheme `{}`, {phase}", plan.name()),
        };
        let cost = r.closed_form_cost();
        if cost > CLOSED_FORM_LIMIT {
            return Err(Error::ClosedFormTooCostly {
                what,
                dim: r.dim(),
                cost: cost as f64,
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use recurrence::{IntMatrix, Recurrence};

    /// The closed-form guard never refuses a built-in scheme (their costs are a few thousand
    /// units, far below the limit), and refuses exactly from 21 components for 3-digit
    /// entries: `n^5 + n^3 w^2` with `w = ceil(n (10 + bits(n)) / 64)`.
    #[test]
    fn closed_form_guard_spares_builtins_and_stops_near_20_components() {
        for scheme in schemes::builtins() {
            let counter = Counter::from(scheme.clone());
            for (_, r) in counter.form_recurrences() {
                let cost = r.closed_form_cost();
                assert!(cost < 100_000, "{}: {cost}", scheme.name());
            }
            assert!(closed_forms(&counter, false).is_ok());
        }
        let dense = |n: usize| {
            Counter::from(Recurrence::new(
                IntMatrix::try_from_rows(vec![vec![999; n]; n]).unwrap(),
            ))
        };
        assert!(closed_forms(&dense(20), false).is_ok());
        let refused = closed_forms(&dense(21), false).unwrap_err();
        assert_eq!(refused.kind(), crate::Kind::Guard);
        assert!(closed_forms(&dense(21), true).is_ok());
    }
}
