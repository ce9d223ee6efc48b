//! Initial states from typed counts: [`CountsInput`], [`parse_init`] and the identities that
//! fill in missing statistics.
//!
//! The identities used, and only these (see [`Facts`]):
//!
//! | identity | holds when |
//! |---|---|
//! | `E = IE + BE + NME` | always |
//! | `NME = 0` | the class needs edges of one or two faces (`manifold` or `closed`) |
//! | `BE = 0` | the class is closed |
//! | `H = 2 IE + BE` | `NME = 0` (each interior edge has two face sides, a boundary edge one) |
//! | `H = 3F` | all faces are triangles |
//! | `H = 4F` | all faces are quads |
//!
//! Together they give the familiar shortcuts: on triangles with edges of one or two faces
//! `IE = 3F - E` and `BE = 2E - 3F`; on pure quads `H = 4F`; on closed meshes `BE = 0`,
//! `IE = E`.

use std::fmt;
use std::str::FromStr;

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use crate::{Error, FaceKind, MeshClass, MeshCounts, Result, Stat};

/// Counts typed in by a user, e.g. `V=12,E=30,F=20`: keys are [`Stat`] short names or state
/// component names of the scheme they are meant for, in any order.
///
/// # Example
///
/// ```
/// use num_bigint::BigInt;
/// use schemes::CountsInput;
///
/// let c: CountsInput = "V=12, E=30,F=20".parse()?;
/// assert_eq!(c.get("E"), Some(&BigInt::from(30)));
/// assert_eq!(c.to_string(), "V=12,E=30,F=20");
/// assert!("V=12,V=13".parse::<CountsInput>().is_err());
/// assert!("V=-1".parse::<CountsInput>().is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct CountsInput {
    entries: Vec<(String, BigInt)>,
}

impl CountsInput {
    /// Parses `KEY=VALUE` pairs separated by commas (spaces allowed around each part).
    ///
    /// # Errors
    ///
    /// [`Error::CountsSyntax`] for bad syntax or an empty text, [`Error::NegativeCount`] for a
    /// negative value, [`Error::DuplicateKey`] for a key given twice. Unknown keys are reported
    /// later, by [`Scheme::state_from_input`](crate::Scheme::state_from_input), which knows
    /// the scheme's state names.
    pub fn parse(text: &str) -> Result<CountsInput> {
        let syntax = |reason: String| Error::CountsSyntax {
            text: text.to_string(),
            reason,
        };
        if text.trim().is_empty() {
            return Err(syntax(
                "no counts given (expected e.g. V=12,E=30,F=20)".into(),
            ));
        }
        let mut out = CountsInput::default();
        for (i, part) in text.split(',').enumerate() {
            let n = i + 1;
            let part = part.trim();
            let Some((key, value)) = part.split_once('=') else {
                return Err(syntax(format!(
                    "item {n} `{part}` is not of the form KEY=VALUE"
                )));
            };
            let (key, value) = (key.trim(), value.trim());
            if !is_identifier(key) {
                return Err(syntax(format!(
                    "item {n}: `{key}` is not a name (letters, digits and `_`, starting with a letter)"
                )));
            }
            let v = decimal_integer(value).ok_or_else(|| {
                syntax(format!(
                    "item {n}: value `{value}` of {key} is not an integer"
                ))
            })?;
            if v.is_negative() {
                return Err(Error::NegativeCount {
                    key: key.to_string(),
                    value: value.to_string(),
                });
            }
            out.insert(key, v)?;
        }
        Ok(out)
    }

    /// Adds one count.
    ///
    /// # Errors
    ///
    /// [`Error::DuplicateKey`] if `key` is already present, [`Error::NegativeCount`] for a
    /// negative value.
    pub fn insert(&mut self, key: &str, value: BigInt) -> Result {
        if self.get(key).is_some() {
            return Err(Error::DuplicateKey {
                key: key.to_string(),
            });
        }
        if value.is_negative() {
            return Err(Error::NegativeCount {
                key: key.to_string(),
                value: value.to_string(),
            });
        }
        self.entries.push((key.to_string(), value));
        Ok(())
    }

    /// The value given for `key`.
    pub fn get(&self, key: &str) -> Option<&BigInt> {
        self.entries.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }

    /// The counts in the order given.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &BigInt)> + '_ {
        self.entries.iter().map(|(k, v)| (k.as_str(), v))
    }

    /// Whether no count is given.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// All seven linear statistics of a mesh.
    pub fn from_mesh_counts(counts: &MeshCounts) -> CountsInput {
        CountsInput {
            entries: Stat::ALL
                .iter()
                .map(|s| (s.short_name().to_string(), BigInt::from(counts.get(*s))))
                .collect(),
        }
    }
}

impl FromStr for CountsInput {
    type Err = Error;

    fn from_str(text: &str) -> Result<CountsInput> {
        CountsInput::parse(text)
    }
}

impl fmt::Display for CountsInput {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, (k, v)) in self.entries.iter().enumerate() {
            if i > 0 {
                f.write_str(",")?;
            }
            write!(f, "{k}={v}")?;
        }
        Ok(())
    }
}

/// Parses a plain initial state in state order: integers separated by commas, `12,30`
/// (spaces around each value are ignored). This is the grammar of `subcount --init`.
///
/// Values may be negative (a custom recurrence need not count anything).
///
/// # Errors
///
/// [`Error::InitSyntax`] naming the first value that is not an integer (an empty value
/// included, so `12,,30` and the empty text are refused).
///
/// ```
/// use num_bigint::BigInt;
/// assert_eq!(schemes::parse_init("12, -30")?, vec![BigInt::from(12), BigInt::from(-30)]);
/// assert_eq!(
///     schemes::parse_init("12,x").unwrap_err().to_string(),
///     "initial state `12,x`: `x` is not an integer"
/// );
/// # Ok::<(), schemes::Error>(())
/// ```
pub fn parse_init(text: &str) -> Result<Vec<BigInt>> {
    text.split(',')
        .map(|item| {
            let item = item.trim();
            item.parse::<BigInt>().map_err(|_| Error::InitSyntax {
                text: text.to_string(),
                item: item.to_string(),
            })
        })
        .collect()
}

pub(crate) fn is_identifier(name: &str) -> bool {
    let mut chars = name.chars();
    matches!(chars.next(), Some(c) if c.is_ascii_alphabetic())
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_')
}

/// What is known about a mesh beyond its numbers: which identities hold.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Facts {
    /// The kind of every face, when fixed.
    pub faces: Option<FaceKind>,
    /// No boundary edges and no non-manifold edges.
    pub closed: bool,
    /// No non-manifold edges.
    pub manifold: bool,
}

impl Facts {
    /// The facts a scheme's mesh class guarantees.
    pub fn of_class(class: &MeshClass) -> Facts {
        Facts {
            faces: match class.faces {
                FaceKind::Polygons => None,
                k => Some(k),
            },
            closed: class.closed,
            manifold: class.needs_manifold(),
        }
    }

    fn describe(&self) -> String {
        let noun = match self.faces {
            Some(FaceKind::Triangles) => "triangle mesh",
            Some(FaceKind::Quads) => "quad mesh",
            _ => "polygon mesh",
        };
        if self.closed {
            format!("closed {noun}")
        } else if self.manifold {
            format!("{noun} with edges of one or two faces")
        } else {
            noun.to_string()
        }
    }
}

struct Identity {
    lhs: Stat,
    rhs: Vec<(i64, Stat)>,
}

impl fmt::Display for Identity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} = ", self.lhs)?;
        if self.rhs.is_empty() {
            return f.write_str("0");
        }
        for (i, (c, s)) in self.rhs.iter().enumerate() {
            if i > 0 {
                f.write_str(" + ")?;
            }
            if *c != 1 {
                write!(f, "{c}")?;
            }
            write!(f, "{s}")?;
        }
        Ok(())
    }
}

fn identities(facts: &Facts, nme_zero: bool) -> Vec<Identity> {
    use Stat::*;
    let mut out = vec![Identity {
        lhs: E,
        rhs: vec![(1, IE), (1, BE), (1, NME)],
    }];
    if facts.manifold || facts.closed {
        out.push(Identity {
            lhs: NME,
            rhs: vec![],
        });
    }
    if facts.closed {
        out.push(Identity {
            lhs: BE,
            rhs: vec![],
        });
    }
    if facts.manifold || facts.closed || nme_zero {
        out.push(Identity {
            lhs: H,
            rhs: vec![(2, IE), (1, BE)],
        });
    }
    match facts.faces {
        Some(FaceKind::Triangles) => out.push(Identity {
            lhs: H,
            rhs: vec![(3, F)],
        }),
        Some(FaceKind::Quads) => out.push(Identity {
            lhs: H,
            rhs: vec![(4, F)],
        }),
        _ => {}
    }
    out
}

/// Fills in the statistics that `given` and the identities allowed by `facts` determine.
///
/// Returns one entry per [`Stat::ALL`], `None` where still unknown.
pub(crate) fn solve(given: &[Option<BigInt>; 7], facts: &Facts) -> Result<[Option<BigInt>; 7]> {
    let nme_zero = given[Stat::NME.index()].as_ref().is_some_and(Zero::is_zero);
    let ids = identities(facts, nme_zero);
    let id_text: Vec<String> = ids.iter().map(ToString::to_string).collect();
    // Columns: unknowns first (pivot candidates), then knowns. Each row: sum c_j x_j = 0.
    let unknown: Vec<usize> = (0..7).filter(|&i| given[i].is_none()).collect();
    let known: Vec<usize> = (0..7).filter(|&i| given[i].is_some()).collect();
    let order: Vec<usize> = unknown.iter().chain(known.iter()).copied().collect();
    let mut rows: Vec<Vec<BigRational>> = ids
        .iter()
        .map(|id| {
            let mut row = vec![BigRational::zero(); 7];
            row[order_pos(&order, id.lhs.index())] += BigRational::one();
            for (c, s) in &id.rhs {
                row[order_pos(&order, s.index())] -= BigRational::from_integer(BigInt::from(*c));
            }
            row
        })
        .collect();
    // Reduced row echelon form, pivoting in the unknown columns only.
    let mut pivots: Vec<(usize, usize)> = Vec::new();
    let mut r = 0;
    for col in 0..unknown.len() {
        let Some(p) = (r..rows.len()).find(|&i| !rows[i][col].is_zero()) else {
            continue;
        };
        rows.swap(r, p);
        let inv = rows[r][col].recip();
        for x in rows[r].iter_mut() {
            *x *= &inv;
        }
        let pivot_row = rows[r].clone();
        for (i, row) in rows.iter_mut().enumerate() {
            if i != r && !row[col].is_zero() {
                let factor = row[col].clone();
                for (x, p) in row.iter_mut().zip(&pivot_row) {
                    *x -= &factor * p;
                }
            }
        }
        pivots.push((r, col));
        r += 1;
    }
    let value_of = |row: &[BigRational]| -> BigRational {
        let mut acc = BigRational::zero();
        for (k, &stat) in known.iter().enumerate() {
            let c = &row[unknown.len() + k];
            if !c.is_zero() {
                acc += c * BigRational::from_integer(given[stat].clone().unwrap_or_default());
            }
        }
        acc
    };
    let ident_list = id_text.join(", ");
    // Rows without unknowns are constraints among the given values.
    for row in &rows[r..] {
        if !value_of(row).is_zero() {
            return Err(Error::Contradiction {
                detail: format!(
                    "{} (identities for a {}: {ident_list})",
                    describe_constraint(row, &order, given),
                    facts.describe()
                ),
            });
        }
    }
    let mut out: [Option<BigInt>; 7] = given.clone();
    for &(row, col) in &pivots {
        let determined = rows[row][..unknown.len()]
            .iter()
            .enumerate()
            .all(|(j, c)| j == col || c.is_zero());
        if !determined {
            continue;
        }
        let stat = Stat::ALL[unknown[col]];
        let value = -value_of(&rows[row]);
        let formula = formula_text(&rows[row], unknown.len(), &known);
        if !value.is_integer() || value.is_negative() {
            return Err(Error::ImpossibleDerived {
                name: stat.to_string(),
                formula,
                value: value.to_string(),
                class: facts.describe(),
            });
        }
        out[unknown[col]] = Some(value.to_integer());
    }
    Ok(out)
}

fn order_pos(order: &[usize], stat: usize) -> usize {
    order.iter().position(|&s| s == stat).unwrap_or(0)
}

/// `x = formula` for a determined unknown, from its reduced row `x + sum c_k known_k = 0`.
fn formula_text(row: &[BigRational], n_unknown: usize, known: &[usize]) -> String {
    let terms: Vec<(BigRational, String)> = known
        .iter()
        .enumerate()
        .filter(|(k, _)| !row[n_unknown + k].is_zero())
        .map(|(k, &s)| (-row[n_unknown + k].clone(), Stat::ALL[s].to_string()))
        .collect();
    linear_text(&terms)
}

pub(crate) fn linear_text(terms: &[(BigRational, String)]) -> String {
    if terms.is_empty() {
        return "0".into();
    }
    let mut s = String::new();
    for (i, (c, name)) in terms.iter().enumerate() {
        let mag = c.abs();
        if i == 0 {
            if c.is_negative() {
                s.push('-');
            }
        } else if c.is_negative() {
            s.push_str(" - ");
        } else {
            s.push_str(" + ");
        }
        if mag.is_one() {
            s.push_str(name);
        } else if mag.is_integer() {
            s.push_str(&format!("{mag}{name}"));
        } else {
            s.push_str(&format!("({}/{}){name}", mag.numer(), mag.denom()));
        }
    }
    s
}

/// `2E = 60 but 3F = 63` for a violated constraint among given values.
fn describe_constraint(
    row: &[BigRational],
    order: &[usize],
    given: &[Option<BigInt>; 7],
) -> String {
    let lcm = row.iter().fold(BigInt::one(), |acc, c| acc.lcm(c.denom()));
    let mut ints: Vec<(BigInt, usize)> = row
        .iter()
        .enumerate()
        .filter(|(_, c)| !c.is_zero())
        .map(|(j, c)| {
            (
                (c * BigRational::from_integer(lcm.clone())).to_integer(),
                order[j],
            )
        })
        .collect();
    let g = ints.iter().fold(BigInt::zero(), |acc, (c, _)| acc.gcd(c));
    let first_negative = ints.first().is_some_and(|(c, _)| c.is_negative());
    for (c, _) in ints.iter_mut() {
        *c = &*c / &g;
        if first_negative {
            *c = -&*c;
        }
    }
    let side = |positive: bool| -> (String, BigInt) {
        let terms: Vec<(BigRational, String)> = ints
            .iter()
            .filter(|(c, _)| c.is_positive() == positive)
            .map(|(c, s)| {
                (
                    BigRational::from_integer(c.abs()),
                    Stat::ALL[*s].to_string(),
                )
            })
            .collect();
        let value: BigInt = ints
            .iter()
            .filter(|(c, _)| c.is_positive() == positive)
            .map(|(c, s)| c.abs() * given[*s].clone().unwrap_or_default())
            .sum();
        (linear_text(&terms), value)
    };
    let (l, lv) = side(true);
    let (r, rv) = side(false);
    if r == "0" {
        format!("{l}={lv} given but must be 0")
    } else if ints.iter().filter(|(c, _)| c.is_positive()).count() == 1
        && ints.iter().any(|(c, _)| c.is_one())
    {
        format!("{l}={lv} given but {r} = {rv}")
    } else {
        format!("{l} = {lv} but {r} = {rv}")
    }
}

/// `text` as an integer when it is written in decimal digits, after an optional `-` (no `+`,
/// no spaces, no `_`: what `BigInt`'s parser would accept beyond that is refused).
fn decimal_integer(text: &str) -> Option<BigInt> {
    let digits = text.strip_prefix('-').unwrap_or(text);
    let decimal = !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit());
    decimal.then(|| text.parse().ok()).flatten()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn given(pairs: &[(Stat, i64)]) -> [Option<BigInt>; 7] {
        let mut g: [Option<BigInt>; 7] = Default::default();
        for (s, v) in pairs {
            g[s.index()] = Some(BigInt::from(*v));
        }
        g
    }

    fn get(x: &[Option<BigInt>; 7], s: Stat) -> Option<i64> {
        x[s.index()].as_ref().map(|v| i64::try_from(v).unwrap())
    }

    const TRI: Facts = Facts {
        faces: Some(FaceKind::Triangles),
        closed: false,
        manifold: true,
    };

    #[test]
    fn triangles_fill_ie_and_be() {
        // A triangle strip of 4 triangles: E = 9, F = 4 -> IE = 3F - E = 3, BE = 2E - 3F = 6.
        let x = solve(&given(&[(Stat::E, 9), (Stat::F, 4)]), &TRI).unwrap();
        assert_eq!(get(&x, Stat::IE), Some(3));
        assert_eq!(get(&x, Stat::BE), Some(6));
        assert_eq!(get(&x, Stat::H), Some(12));
        assert_eq!(get(&x, Stat::NME), Some(0));
        assert_eq!(get(&x, Stat::V), None);
    }

    #[test]
    fn contradictions_name_both_values() {
        let closed = Facts {
            closed: true,
            ..TRI
        };
        let err = solve(
            &given(&[(Stat::E, 30), (Stat::IE, 29), (Stat::BE, 2)]),
            &TRI,
        )
        .unwrap_err();
        assert!(
            err.to_string().contains("E=30 given but IE + BE = 31"),
            "{err}"
        );
        let err = solve(&given(&[(Stat::E, 30), (Stat::F, 21)]), &closed).unwrap_err();
        assert!(err.to_string().contains("2E = 60 but 3F = 63"), "{err}");
        let err = solve(&given(&[(Stat::BE, 2)]), &closed).unwrap_err();
        assert!(
            err.to_string().contains("BE=2 given but must be 0"),
            "{err}"
        );
    }

    #[test]
    fn impossible_values_are_refused() {
        // E = 31, F = 20 on triangles: BE = 2E - 3F = 2, fine; E = 29: BE = -2.
        let err = solve(&given(&[(Stat::E, 29), (Stat::F, 20)]), &TRI).unwrap_err();
        assert_eq!(
            err.to_string(),
            "BE = 2E - 3F = -2 is not a count (the counts do not describe a triangle mesh with edges of one or two faces)"
        );
        // Quads, closed: E = 7 -> F = E/2 is not an integer.
        let quads = Facts {
            faces: Some(FaceKind::Quads),
            closed: true,
            manifold: true,
        };
        let err = solve(&given(&[(Stat::E, 7)]), &quads).unwrap_err();
        assert!(err.to_string().starts_with("F = (1/2)E = 7/2"), "{err}");
    }

    #[test]
    fn counts_input_errors() {
        assert!(matches!(
            CountsInput::parse("V=1,V=2"),
            Err(Error::DuplicateKey { key }) if key == "V"
        ));
        assert!(matches!(
            CountsInput::parse("V=-3"),
            Err(Error::NegativeCount { key, .. }) if key == "V"
        ));
        assert_eq!(
            CountsInput::parse("V=12,E").unwrap_err().to_string(),
            "counts `V=12,E`: item 2 `E` is not of the form KEY=VALUE"
        );
        assert_eq!(
            CountsInput::parse("V=1x").unwrap_err().to_string(),
            "counts `V=1x`: item 1: value `1x` of V is not an integer"
        );
        assert!(CountsInput::parse(" ").is_err());
        let big = CountsInput::parse("V=123456789012345678901234567890").unwrap();
        assert_eq!(
            big.get("V").unwrap().to_string(),
            "123456789012345678901234567890"
        );
    }
}
