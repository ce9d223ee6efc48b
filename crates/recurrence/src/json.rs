//! The JSON rendering of closed forms, behind the `json` feature (the only use of
//! `serde_json` in this crate).

use serde_json::{json, Map, Value};

use crate::ClosedForm;

impl ClosedForm {
    /// The closed forms as JSON: an array with one object per component,
    /// `{"component", "valid_from", "exact", "terms", "early_levels"}`. Each term is
    /// `{"eigenvalue", "s_power", "coefficients": {name: "p/q", ...}}`; the component equals
    /// the sum over terms of (sum of coefficient * initial value) * s^s_power *
    /// eigenvalue^s for every `s >= valid_from`. Surds read `a+b*sqrt(d)`.
    ///
    /// Needs the `json` feature.
    ///
    /// ```
    /// # use recurrence::{IntMatrix, Recurrence};
    /// let r = Recurrence::with_names("[[1, 1], [0, 4]]".parse::<IntMatrix>()?, ["V", "E"])?;
    /// let json = r.closed_form().to_json();
    /// assert_eq!(json[0]["terms"][0]["eigenvalue"], "4");
    /// assert_eq!(json[0]["terms"][0]["coefficients"]["E"], "1/3");
    /// assert_eq!(json[0]["terms"][1]["coefficients"]["E"], "-1/3");
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_json(&self) -> Value {
        let names = self.names();
        Value::Array(
            self.components()
                .iter()
                .map(|c| {
                    let terms: Vec<Value> = c
                        .terms
                        .iter()
                        .map(|t| {
                            json!({
                                "eigenvalue": t.eigenvalue.to_string(),
                                "s_power": t.s_power,
                                "coefficients": by_name(names, &t.coefficients),
                            })
                        })
                        .collect();
                    let early: Vec<Value> = c
                        .early_levels
                        .iter()
                        .map(|l| {
                            json!({"level": l.level, "coefficients": by_name(names, &l.coefficients)})
                        })
                        .collect();
                    json!({
                        "component": c.name,
                        "valid_from": c.valid_from,
                        "exact": c.exact,
                        "terms": terms,
                        "early_levels": early,
                    })
                })
                .collect(),
        )
    }
}

/// `{name: "value", ...}`: one coefficient per initial component, as strings.
fn by_name<T: std::fmt::Display>(names: &[String], values: &[T]) -> Map<String, Value> {
    names
        .iter()
        .zip(values)
        .map(|(n, c)| (n.clone(), Value::String(c.to_string())))
        .collect()
}
