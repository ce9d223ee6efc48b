//! Custom schemes from TOML text, and the export of any scheme in the same format.
//!
//! A scheme file has these fields (all others are errors):
//!
//! | field | meaning |
//! |---|---|
//! | `name` | the scheme's name (letters, digits, `-`, `_`) |
//! | `description` | optional text |
//! | `state` | the component names, e.g. `["V", "IE", "BE"]`; names equal to a mesh statistic (`V`, `E`, `IE`, `BE`, `NME`, `F`, `H`) bind to the mesh |
//! | `matrix` | the rows of the square matrix applied at every step |
//! | `cycle` | instead of `matrix`: a list of matrices applied in turn (periodic schemes) |
//! | `first_step` | optional matrix applied at step 1 only, before `matrix`/`cycle` take over |
//! | `derive` | optional table giving `V`, `E` or `F` as integer combinations of the state, e.g. `E = { IE = 1, BE = 1 }`; the reserved key `divide_by` divides the combination exactly, e.g. `F = { E = 2, divide_by = 3 }` |
//! | `requires` | optional list of `triangles`, `quads`, `closed`, `manifold` |
//! | `produces` | optional face kind after a step: `triangles`, `quads` or `polygons` (lets a [`Plan`](crate::Plan) chain the scheme) |
//! | `topology` | optional built-in scheme whose real subdivision this matrix counts: `loop`, `loop-boundary`, `midpoint`, `butterfly`, `icosphere`, `catmull-clark`, `sqrt3`, `doo-sabin`, `mid-edge`, `tri-split-N`, ... (its [`Rule`](crate::Rule): `subdivide` runs it, `verify` compares the matrix's counts with it) |
//!
//! Every mistake is an [`Error::SchemeFile`] naming the line and column in the text.
//!
//! # Example
//!
//! ```
//! use num_bigint::BigInt;
//! use schemes::Scheme;
//!
//! let text = r#"
//! name = "fibonacci"
//! state = ["a", "b"]
//! matrix = [[1, 1], [1, 0]]
//! "#;
//! let fib = Scheme::from_toml(text)?;
//! let x = fib.state_at(&[BigInt::from(1), BigInt::from(0)], 90)?;
//! assert_eq!(x[1].to_string(), "2880067194370816120");
//!
//! let err = Scheme::from_toml("name = \"x\"\nstate = [\"a\"]\nmatrix = [[1, 2]]\n").unwrap_err();
//! assert_eq!(err.to_string(), "line 3, column 11: row 1 has 2 entries, but the matrix has 1 row (it must be square)");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::ops::Range;

use recurrence::IntMatrix;
use serde::Deserialize;
use toml::Spanned;

use crate::input::is_identifier;
use crate::scheme::{Component, Derivation, SchemeSpec, StepRule};
use crate::{Error, FaceKind, MeshClass, Result, Scheme, Stat};

type Rows = Vec<Spanned<Vec<i64>>>;
/// `derive`: V, E or F -> (state name or `divide_by` -> coefficient).
type DeriveTable = BTreeMap<Spanned<String>, BTreeMap<Spanned<String>, Spanned<i64>>>;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawScheme {
    name: Spanned<String>,
    description: Option<String>,
    state: Spanned<Vec<Spanned<String>>>,
    matrix: Option<Spanned<Rows>>,
    cycle: Option<Spanned<Vec<Spanned<Rows>>>>,
    first_step: Option<Spanned<Rows>>,
    derive: Option<DeriveTable>,
    requires: Option<Vec<Spanned<String>>>,
    produces: Option<Spanned<String>>,
    topology: Option<Spanned<String>>,
}

/// The reserved key of a `derive` entry that divides the combination.
pub const DIVIDE_BY: &str = "divide_by";

/// The most state components a scheme file may declare.
///
/// Real schemes track a handful of counts; the cap keeps a hostile file (a 300 KB matrix)
/// from starting exact eigen-decompositions and matrix powers whose cost grows steeply with
/// the dimension.
pub const MAX_STATE_COMPONENTS: usize = 32;

struct Located<'a> {
    text: &'a str,
}

impl Located<'_> {
    fn error(&self, span: Range<usize>, message: impl Into<String>) -> Error {
        let offset = span.start.min(self.text.len());
        let before = &self.text[..offset];
        let line = before.matches('\n').count() + 1;
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        let column = self.text[line_start..offset].chars().count() + 1;
        Error::SchemeFile {
            line,
            column,
            message: message.into(),
        }
    }

    fn matrix(&self, rows: &Spanned<Rows>, what: &str, dim: usize) -> Result<IntMatrix> {
        let n = rows.get_ref().len();
        if n == 0 {
            return Err(self.error(rows.span(), format!("{what} is empty")));
        }
        for (i, row) in rows.get_ref().iter().enumerate() {
            if row.get_ref().len() != n {
                return Err(self.error(
                    row.span(),
                    format!(
                        "row {} has {} entr{}, but {what} has {n} row{} (it must be square)",
                        i + 1,
                        row.get_ref().len(),
                        if row.get_ref().len() == 1 { "y" } else { "ies" },
                        if n == 1 { "" } else { "s" }
                    ),
                ));
            }
        }
        if n != dim {
            return Err(self.error(
                rows.span(),
                format!("{what} is {n}x{n}, but the state has {dim} components"),
            ));
        }
        let rows: Vec<Vec<i64>> = rows.get_ref().iter().map(|r| r.get_ref().clone()).collect();
        IntMatrix::try_from_rows(rows).map_err(|e| self.error(0..0, e.to_string()))
    }
}

impl Scheme {
    /// Parses a custom scheme from TOML text (the caller owns the file and its path).
    ///
    /// # Errors
    ///
    /// [`Error::SchemeFile`] with the line and column of the first mistake: TOML syntax, an
    /// unknown or missing field, a non-square matrix or a row of the wrong length, a matrix
    /// whose size differs from the number of state names, duplicate or invalid names, an
    /// empty state or matrix, a state of more than [`MAX_STATE_COMPONENTS`] components, an
    /// entry beyond `i64`, both `matrix` and `cycle`, a `derive`
    /// naming an unknown component, an unknown requirement, or a state the mesh cannot supply
    /// (a non-statistic component in a scheme that declares `requires`).
    pub fn from_toml(text: &str) -> Result<Scheme> {
        let at = Located { text };
        let raw: RawScheme = toml::from_str(text).map_err(|e| {
            // toml's messages may span lines; keep the error on one line.
            let message = e
                .message()
                .lines()
                .map(str::trim)
                .filter(|l| !l.is_empty())
                .collect::<Vec<_>>()
                .join("; ");
            at.error(e.span().unwrap_or(0..0), message)
        })?;
        let name = raw.name.get_ref();
        if name.is_empty()
            || !name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
        {
            return Err(at.error(
                raw.name.span(),
                format!("scheme name `{name}` may only use letters, digits, `-` and `_`"),
            ));
        }
        let state = raw.state.get_ref();
        if state.is_empty() {
            return Err(at.error(raw.state.span(), "the state is empty"));
        }
        if state.len() > MAX_STATE_COMPONENTS {
            return Err(at.error(
                raw.state.span(),
                format!(
                    "the state has {} components; a scheme file may have at most {MAX_STATE_COMPONENTS}",
                    state.len()
                ),
            ));
        }
        let mut names: Vec<String> = Vec::new();
        for n in state {
            let s = n.get_ref();
            if !is_identifier(s) {
                return Err(at.error(
                    n.span(),
                    format!("state name `{s}` is not valid (use letters, digits and `_`, starting with a letter)"),
                ));
            }
            if s == DIVIDE_BY {
                return Err(at.error(n.span(), format!("`{DIVIDE_BY}` is reserved")));
            }
            if names.contains(s) {
                return Err(at.error(n.span(), format!("state name `{s}` is used twice")));
            }
            names.push(s.clone());
        }
        let dim = names.len();
        let cycle = match (&raw.matrix, &raw.cycle) {
            (Some(_), Some(c)) => {
                return Err(at.error(c.span(), "give either `matrix` or `cycle`, not both"))
            }
            (None, None) => {
                return Err(at.error(
                    text.len()..text.len(),
                    "missing `matrix` (or `cycle` for a periodic scheme)",
                ))
            }
            (Some(m), None) => vec![at.matrix(m, "the matrix", dim)?],
            (None, Some(c)) => {
                if c.get_ref().is_empty() {
                    return Err(at.error(c.span(), "the cycle is empty"));
                }
                c.get_ref()
                    .iter()
                    .enumerate()
                    .map(|(i, m)| at.matrix(m, &format!("matrix {} of the cycle", i + 1), dim))
                    .collect::<Result<Vec<_>>>()?
            }
        };
        let first_step = raw
            .first_step
            .as_ref()
            .map(|m| at.matrix(m, "first_step", dim))
            .transpose()?;
        let rule = StepRule::try_new(first_step, cycle)
            .map_err(|e| at.error(raw.name.span(), e.to_string()))?;
        let mut class = MeshClass::ANY;
        let mut requires_given = false;
        for r in raw.requires.iter().flatten() {
            requires_given = true;
            match r.get_ref().as_str() {
                "triangles" | "quads" => {
                    let kind = if r.get_ref() == "triangles" {
                        FaceKind::Triangles
                    } else {
                        FaceKind::Quads
                    };
                    if class.faces != FaceKind::Polygons && class.faces != kind {
                        return Err(
                            at.error(r.span(), "`triangles` and `quads` exclude each other")
                        );
                    }
                    class.faces = kind;
                }
                "closed" => {
                    class.closed = true;
                    class.manifold = true;
                }
                "manifold" => class.manifold = true,
                other => {
                    return Err(at.error(
                        r.span(),
                        format!(
                            "unknown requirement `{other}`; use triangles, quads, closed, manifold"
                        ),
                    ))
                }
            }
        }
        if requires_given {
            for n in state {
                if Stat::from_short_name(n.get_ref()).is_none() {
                    return Err(at.error(
                        n.span(),
                        format!(
                            "state `{}` is not a mesh statistic (V, E, IE, BE, NME, F, H), so a mesh cannot supply it; drop `requires` for a state given by hand",
                            n.get_ref()
                        ),
                    ));
                }
            }
        }
        let produces = match &raw.produces {
            None => None,
            Some(p) => Some(match p.get_ref().as_str() {
                "triangles" => FaceKind::Triangles,
                "quads" => FaceKind::Quads,
                "polygons" => FaceKind::Polygons,
                other => {
                    return Err(at.error(
                        p.span(),
                        format!("unknown face kind `{other}`; use triangles, quads, polygons"),
                    ))
                }
            }),
        };
        let mut derive = Vec::new();
        for (what, terms) in raw.derive.iter().flatten() {
            let stat = match what.get_ref().as_str() {
                "V" => Stat::V,
                "E" => Stat::E,
                "F" => Stat::F,
                other => {
                    return Err(at.error(
                        what.span(),
                        format!("`derive` gives V, E or F, not `{other}`"),
                    ))
                }
            };
            if names.iter().any(|n| n == stat.short_name()) {
                return Err(at.error(
                    what.span(),
                    format!(
                        "{stat} is a state component; `derive` is for V, E, F outside the state"
                    ),
                ));
            }
            let mut coefficients = vec![0i64; dim];
            let mut divisor = 1u64;
            for (key, value) in terms {
                if key.get_ref() == DIVIDE_BY {
                    divisor = u64::try_from(*value.get_ref())
                        .ok()
                        .filter(|d| *d > 0)
                        .ok_or_else(|| at.error(value.span(), "`divide_by` must be positive"))?;
                    continue;
                }
                let Some(i) = names.iter().position(|n| n == key.get_ref()) else {
                    return Err(at.error(
                        key.span(),
                        format!(
                            "`derive.{}` names `{}`, which is not a state component ({})",
                            what.get_ref(),
                            key.get_ref(),
                            names.join(", ")
                        ),
                    ));
                };
                coefficients[i] = *value.get_ref();
            }
            derive.push((stat, Derivation::new(coefficients, divisor)));
        }
        let components = names
            .iter()
            .map(|n| Component {
                name: n.clone(),
                meaning: Stat::from_short_name(n)
                    .map_or("custom component", Stat::meaning)
                    .to_string(),
            })
            .collect();
        let spec = SchemeSpec {
            name: name.clone(),
            description: raw.description.unwrap_or_default(),
            state: components,
            rule,
            requires: class,
            produces,
            derive,
        };
        let scheme =
            Scheme::try_from_spec(spec).map_err(|e| at.error(raw.name.span(), e.to_string()))?;
        match &raw.topology {
            None => Ok(scheme),
            Some(topology) => {
                let rule = crate::builtin(topology.get_ref())
                    .ok()
                    .and_then(|b| b.subdivision_rule())
                    .ok_or_else(|| {
                        at.error(
                            topology.span(),
                            format!(
                                "topology `{}` is not a built-in scheme with a real subdivision \
                                 (use one of: loop, loop-boundary, midpoint, butterfly, icosphere, \
                                 tri-split-N, catmull-clark, sqrt3, sqrt3-boundary, doo-sabin, mid-edge)",
                                topology.get_ref()
                            ),
                        )
                    })?;
                Ok(scheme.with_subdivision_rule(rule))
            }
        }
    }

    /// The scheme in the TOML format read by [`Scheme::from_toml`] (a template for custom
    /// schemes).
    ///
    /// ```
    /// let lb = schemes::builtin("loop-boundary")?;
    /// let text = lb.to_toml();
    /// assert!(text.contains("state = [\"V\", \"IE\", \"BE\"]"));
    /// assert!(text.contains("F = { IE = 2, BE = 1, divide_by = 3 }"));
    /// assert!(text.contains("topology = \"loop\""));
    /// let again = schemes::Scheme::from_toml(&text)?;
    /// assert_eq!(again.matrix(), lb.matrix());
    /// assert_eq!(again.subdivision_rule(), Some(schemes::Rule::Loop));
    /// # Ok::<(), schemes::Error>(())
    /// ```
    pub fn to_toml(&self) -> String {
        let quote = |s: &str| toml::Value::String(s.to_string()).to_string();
        let list = |items: &[&str]| {
            let q: Vec<String> = items.iter().map(|s| quote(s)).collect();
            format!("[{}]", q.join(", "))
        };
        let mut out = String::new();
        let _ = writeln!(out, "# subdivision scheme `{}`", self.canonical_name());
        let _ = writeln!(out, "name = {}", quote(self.canonical_name()));
        if !self.description().is_empty() {
            let _ = writeln!(out, "description = {}", quote(self.description()));
        }
        let names: Vec<&str> = self.state_names().iter().map(String::as_str).collect();
        let _ = writeln!(out, "state = {}", list(&names));
        let keywords = self.mesh_class().keywords();
        if !keywords.is_empty() {
            let _ = writeln!(out, "requires = {}", list(&keywords));
        }
        if let Some(p) = self.produces() {
            let _ = writeln!(out, "produces = {}", quote(p.keyword()));
        }
        if let Some(rule) = self.subdivision_rule() {
            let _ = writeln!(out, "topology = {}", quote(&rule.to_string()));
        }
        let rows = |m: &IntMatrix, indent: &str| -> String {
            let mut s = String::from("[\n");
            for row in m.rows() {
                let entries: Vec<String> = row.iter().map(i64::to_string).collect();
                let _ = writeln!(s, "{indent}  [{}],", entries.join(", "));
            }
            s.push_str(indent);
            s.push(']');
            s
        };
        if let Some(f) = self.first_step() {
            let _ = writeln!(out, "first_step = {}", rows(f, ""));
        }
        if let [m] = self.cycle() {
            let _ = writeln!(out, "matrix = {}", rows(m, ""));
        } else {
            out.push_str("cycle = [\n");
            for m in self.cycle() {
                let _ = writeln!(out, "  {},", rows(m, "  "));
            }
            out.push_str("]\n");
        }
        let derivations = self.derivations();
        if !derivations.is_empty() {
            out.push_str("\n[derive]\n");
            for (stat, d) in derivations {
                let mut terms: Vec<String> = d
                    .coefficients()
                    .iter()
                    .zip(self.state_names())
                    .filter(|(c, _)| **c != 0)
                    .map(|(c, n)| format!("{n} = {c}"))
                    .collect();
                if d.divisor() != 1 {
                    terms.push(format!("{DIVIDE_BY} = {}", d.divisor()));
                }
                let _ = writeln!(out, "{stat} = {{ {} }}", terms.join(", "));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_huge_state_is_refused_before_the_matrix_is_read() {
        let n = MAX_STATE_COMPONENTS + 1;
        let names: Vec<String> = (0..n).map(|i| format!("\"S{i}\"")).collect();
        let row = format!("[{}]", vec!["1"; n].join(", "));
        let text = format!(
            "name = \"big\"\nstate = [{}]\nmatrix = [{}]\n",
            names.join(", "),
            vec![row; n].join(", ")
        );
        let err = Scheme::from_toml(&text).unwrap_err();
        assert_eq!(
            err.to_string(),
            format!("line 2, column 9: the state has {n} components; a scheme file may have at most {MAX_STATE_COMPONENTS}")
        );
        let names: Vec<String> = (0..MAX_STATE_COMPONENTS)
            .map(|i| format!("\"S{i}\""))
            .collect();
        let row = format!("[{}]", vec!["0"; MAX_STATE_COMPONENTS].join(", "));
        let text = format!(
            "name = \"edge\"\nstate = [{}]\nmatrix = [{}]\n",
            names.join(", "),
            vec![row; MAX_STATE_COMPONENTS].join(", ")
        );
        assert_eq!(
            Scheme::from_toml(&text).map(|s| s.dim()).ok(),
            Some(MAX_STATE_COMPONENTS)
        );
    }

    #[test]
    fn topology_names_a_rule_or_is_refused_where_it_stands() {
        let text = "name = \"q\"\nstate = [\"V\", \"E\"]\nmatrix = [[1, 1], [0, 4]]\ntopology = \"butterfly\"\n";
        let s = Scheme::from_toml(text).expect("valid");
        assert_eq!(s.subdivision_rule(), Some(crate::Rule::Butterfly));
        assert!(s.to_toml().contains("topology = \"butterfly\"\n"));
        let bad = text.replace("butterfly", "loopy");
        let err = Scheme::from_toml(&bad).unwrap_err().to_string();
        assert!(
            err.starts_with("line 4, column 12: topology `loopy` is not a built-in scheme with a real subdivision"),
            "{err}"
        );
        let none = text.replace("topology = \"butterfly\"\n", "");
        assert_eq!(
            Scheme::from_toml(&none).expect("valid").subdivision_rule(),
            None
        );
    }
}
