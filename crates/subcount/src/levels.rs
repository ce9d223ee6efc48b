//! Parsing of levels: `--level N`, a range `--levels N` (meaning `0..=N`), `A..=B` or `A..B`,
//! and a number of levels (`subdivide --levels N`). Every message names the flag.

use std::ops::RangeInclusive;

use crate::failure::{usage, Failure};

/// A whole number in `T`, trimmed; `Err(true)` when it is negative, `Err(false)` otherwise.
/// Every level parser reads its numbers here and words the error for its flag.
fn whole<T: std::str::FromStr>(text: &str) -> Result<T, bool> {
    text.trim()
        .parse()
        .map_err(|_| text.trim().starts_with('-'))
}

/// Parses `--level`: a whole number from 0 to `u64::MAX`.
pub(crate) fn parse_level(text: &str) -> Result<u64, Failure> {
    let t = text.trim();
    whole(t).map_err(|negative| {
        if negative {
            usage!("invalid --level: `{t}` is negative; levels start at 0")
        } else {
            usage!(
                "invalid --level: `{t}` is not a whole number from 0 to {}",
                u64::MAX
            )
        }
    })
}

/// Parses the number of levels of `subdivide` and `verify` (`--levels`).
pub(crate) fn parse_levels_count(text: &str) -> Result<u32, Failure> {
    let t = text.trim();
    whole(t).map_err(|negative| {
        if negative {
            usage!("invalid --levels: `{t}` is negative")
        } else {
            usage!("invalid --levels: `{t}` is not a whole number of levels")
        }
    })
}

/// Parses a level range. The result is never empty.
pub(crate) fn parse_levels(text: &str) -> Result<RangeInclusive<u64>, String> {
    let text = text.trim();
    let number = |t: &str| -> Result<u64, String> {
        let t = t.trim();
        whole(t).map_err(|negative| {
            if negative {
                format!("level `{t}` is negative; levels start at 0")
            } else {
                format!(
                    "`{t}` is not a level (a whole number from 0 to {})",
                    u64::MAX
                )
            }
        })
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
