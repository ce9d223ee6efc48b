//! Parsing of levels: `--level N`, a range `--levels N` (meaning `0..=N`), `A..=B` or `A..B`,
//! and a number of levels (`subdivide --levels N`). Every message names the flag.

use std::ops::RangeInclusive;

use crate::failure::{usage, Failure};

/// A whole number in `T`, trimmed, or the message for its flag: `negative` when it starts
/// with `-`, `other` otherwise (each given the trimmed text). Every level parser reads its
/// numbers here.
fn whole<T: std::str::FromStr>(
    text: &str,
    negative: impl FnOnce(&str) -> String,
    other: impl FnOnce(&str) -> String,
) -> Result<T, String> {
    let t = text.trim();
    t.parse().map_err(|_| {
        if t.starts_with('-') {
            negative(t)
        } else {
            other(t)
        }
    })
}

/// Parses `--level`: a whole number from 0 to `u64::MAX`.
pub(crate) fn parse_level(text: &str) -> Result<u64, Failure> {
    whole(
        text,
        |t| format!("invalid --level: `{t}` is negative; levels start at 0"),
        |t| {
            format!(
                "invalid --level: `{t}` is not a whole number from 0 to {}",
                u64::MAX
            )
        },
    )
    .map_err(|m| usage!("{m}"))
}

/// Parses the number of levels of `subdivide` and `verify` (`--levels`).
pub(crate) fn parse_levels_count(text: &str) -> Result<u32, Failure> {
    whole(
        text,
        |t| format!("invalid --levels: `{t}` is negative"),
        |t| format!("invalid --levels: `{t}` is not a whole number of levels"),
    )
    .map_err(|m| usage!("{m}"))
}

/// Parses a level range. The result is never empty.
pub(crate) fn parse_levels(text: &str) -> Result<RangeInclusive<u64>, String> {
    let text = text.trim();
    let number = |t: &str| -> Result<u64, String> {
        whole(
            t,
            |t| format!("level `{t}` is negative; levels start at 0"),
            |t| {
                format!(
                    "`{t}` is not a level (a whole number from 0 to {})",
                    u64::MAX
                )
            },
        )
    };
    let (start, end) = if let Some((a, b)) = text.split_once("..=") {
        (number(a)?, number(b)?)
    } else if let Some((a, b)) = text.split_once("..") {
        let (a, b) = (number(a)?, number(b)?);
        if b <= a {
            return Err(format!("the level range `{text}` is empty"));
        }
        (a, b - 1)
    } else {
        (0, number(text)?)
    };
    if end < start {
        return Err(format!(
            "the level range `{text}` is inverted (it starts at {start} but ends at {end})"
        ));
    }
    Ok(start..=end)
}

#[cfg(test)]
mod tests {
    use super::parse_levels;

    #[test]
    fn forms() {
        assert_eq!(parse_levels("8"), Ok(0..=8));
        assert_eq!(parse_levels("2..=5"), Ok(2..=5));
        assert_eq!(parse_levels("2..5"), Ok(2..=4));
        assert_eq!(parse_levels(" 0..=0 "), Ok(0..=0));
    }

    /// Ranges up to `u64::MAX` parse exactly; one past it is not a level.
    #[test]
    fn ranges_reach_u64_max() {
        let max = u64::MAX;
        assert_eq!(parse_levels(&format!("0..={max}")), Ok(0..=max));
        assert_eq!(parse_levels(&format!("{max}..={max}")), Ok(max..=max));
        assert_eq!(parse_levels(&format!("{max}")), Ok(0..=max));
        assert_eq!(parse_levels(&format!("5..{max}")), Ok(5..=max - 1));
        assert_eq!(
            parse_levels(&format!("{max}..{max}")).unwrap_err(),
            format!("the level range `{max}..{max}` is empty")
        );
        assert_eq!(
            parse_levels("0..=18446744073709551616").unwrap_err(),
            format!("`18446744073709551616` is not a level (a whole number from 0 to {max})")
        );
    }

    #[test]
    fn errors() {
        assert_eq!(
            parse_levels("5..=2").unwrap_err(),
            "the level range `5..=2` is inverted (it starts at 5 but ends at 2)"
        );
        assert_eq!(
            parse_levels("3..3").unwrap_err(),
            "the level range `3..3` is empty"
        );
        assert_eq!(
            parse_levels("-1").unwrap_err(),
            "level `-1` is negative; levels start at 0"
        );
        assert!(parse_levels("x..=3")
            .unwrap_err()
            .contains("`x` is not a level"));
    }
}
