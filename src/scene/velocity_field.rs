//! Initial velocity given as expressions of the point position.

use crate::math::{DVec2, Real};
use exmex::prelude::*;
use exmex::{FloatOpsFactory, MatchLiteral, literal_matcher_from_pattern};

// Numbers as the rest of a scene writes them, with an exponent too
// (2.5e-3), which exmex's own matcher does not read.
literal_matcher_from_pattern!(ExponentNumber, r"^(\.?[0-9]+(\.[0-9]*)?([eE][+-]?[0-9]+)?)");

/// One component's expression: exmex's float operators, numbers with
/// exponents.
type Expression = FlatEx<Real, FloatOpsFactory<Real>, ExponentNumber>;

/// A compiled pair of expressions vx(x, y), vy(x, y), e.g. `x*(1-x)`.
/// Operators and functions are those of the `exmex` crate (+ − * / ^, sin,
/// cos, exp, sqrt, …); the only variables are `x` and `y` (m).
#[derive(Debug)]
pub struct VelocityField {
    components: [Expression; 2],
}

/// Why a velocity field cannot be parsed or evaluated.
#[derive(Debug, thiserror::Error)]
pub enum VelocityFieldError {
    /// An expression does not parse. The parser's own message, which dumps
    /// its internals, is kept as the source, not shown.
    #[error(
        "velocity {axis} = \"{text}\" does not parse: write an expression of x and y with + - * / ^, parentheses, numbers (2.5e-3) and functions such as sin, cos, exp and sqrt"
    )]
    Parse {
        /// The component, `x` or `y`.
        axis: &'static str,
        /// The expression.
        text: String,
        /// What the parser says.
        source: exmex::ExError,
    },
    /// An expression longer than [`LONGEST_EXPRESSION`]: its cost at every
    /// point grows with it, and no field a person writes is that long.
    #[error(
        "velocity {axis}: an expression of {length} characters; at most {LONGEST_EXPRESSION} (a field of a few terms)"
    )]
    TooLong {
        /// The component, `x` or `y`.
        axis: &'static str,
        /// Its length in characters.
        length: usize,
    },
    /// An expression names a variable other than x and y.
    #[error(
        "velocity {axis} = \"{text}\": unknown variable '{variable}' (only x and y are allowed)"
    )]
    Variable {
        /// The component, `x` or `y`.
        axis: &'static str,
        /// The expression.
        text: String,
        /// The unknown variable.
        variable: String,
    },
    /// An expression cannot be evaluated at a point (the evaluator's
    /// message is kept as the source).
    #[error("velocity at {at} cannot be evaluated")]
    Eval {
        /// The point.
        at: DVec2,
        /// What the evaluator says.
        source: exmex::ExError,
    },
    /// A velocity is not finite at a point.
    #[error("velocity at {at} is not finite ({value})")]
    NotFinite {
        /// The point.
        at: DVec2,
        /// The value.
        value: Real,
    },
}

/// Longest expression of a velocity field (characters).
pub const LONGEST_EXPRESSION: usize = 1000;

impl VelocityField {
    /// Parses both expressions; the error names the offending one.
    pub fn parse(x: &str, y: &str) -> Result<Self, VelocityFieldError> {
        for (axis, text) in [("x", x), ("y", y)] {
            let length = text.chars().count();
            if length > LONGEST_EXPRESSION {
                return Err(VelocityFieldError::TooLong { axis, length });
            }
        }
        let compile = |axis: &'static str, text: &str| -> Result<Expression, VelocityFieldError> {
            let expr = Expression::parse(text).map_err(|source| VelocityFieldError::Parse {
                axis,
                text: text.to_owned(),
                source,
            })?;
            if let Some(bad) = expr.var_names().iter().find(|v| *v != "x" && *v != "y") {
                return Err(VelocityFieldError::Variable {
                    axis,
                    text: text.to_owned(),
                    variable: bad.clone(),
                });
            }
            Ok(expr)
        };
        Ok(Self {
            components: [compile("x", x)?, compile("y", y)?],
        })
    }

    /// The velocity at `p`.
    pub fn at(&self, p: DVec2) -> Result<DVec2, VelocityFieldError> {
        let mut v = [0.0; 2];
        for (value, expr) in v.iter_mut().zip(&self.components) {
            // exmex orders variables alphabetically: x before y.
            let args: Vec<Real> = expr
                .var_names()
                .iter()
                .map(|name| if name == "x" { p.x } else { p.y })
                .collect();
            *value = expr
                .eval(&args)
                .map_err(|source| VelocityFieldError::Eval { at: p, source })?;
            if !value.is_finite() {
                return Err(VelocityFieldError::NotFinite {
                    at: p,
                    value: *value,
                });
            }
        }
        Ok(DVec2::from(v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_may_have_exponents() {
        let f = VelocityField::parse("2.5e-3*y + 1E3*x", "1.5e+2 - x*1e2").unwrap();
        let v = f.at(DVec2::new(0.5, 2.0)).unwrap();
        assert!((v.x - (5e-3 + 500.0)).abs() < 1e-12, "{v}");
        assert!((v.y - (150.0 - 50.0)).abs() < 1e-12, "{v}");
        // A trailing dot is a number too, as exmex's own matcher reads it.
        let f = VelocityField::parse("3.", "1./(x + 1)").unwrap();
        assert_eq!(f.at(DVec2::new(1.0, 0.0)).unwrap(), DVec2::new(3.0, 0.5));
        // An exponent needs its digits: "2e" is no number.
        assert!(VelocityField::parse("2e*x", "0").is_err());
    }

    #[test]
    fn evaluates_position_expressions() {
        let f = VelocityField::parse("x*(1-x)", "2*y + x").unwrap();
        let v = f.at(DVec2::new(0.25, 1.0)).unwrap();
        assert!((v.x - 0.1875).abs() < 1e-15 && (v.y - 2.25).abs() < 1e-15);
        assert!(
            VelocityField::parse("z", "0")
                .unwrap_err()
                .to_string()
                .contains("unknown variable 'z'")
        );
    }
}
