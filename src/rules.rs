//! Range rules for scene values, used twice: while a scene file is parsed
//! (so the error carries the file position) and by [`crate::scene::Scene::validate`]
//! (so scenes built in code are checked by the same rules).

use crate::math::Real;
use serde::{Deserialize, Deserializer, Serialize, Serializer, de::Error};
use std::ops::RangeInclusive;

/// A value outside the range a scene field allows; the message says what
/// was expected and what was given.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum RuleError {
    /// Not a finite value > 0.
    #[error("expected a finite value > 0, got {}", shown(*.0))]
    NotPositive(Real),
    /// Not a finite value ≥ 0.
    #[error("expected a finite value ≥ 0, got {}", shown(*.0))]
    Negative(Real),
    /// Poisson's ratio outside (−1, 0.5).
    #[error("expected Poisson's ratio in (-1, 0.5), got {}", shown(*.0))]
    PoissonRatio(Real),
    /// Outside [0, 1].
    #[error("expected a value in [0, 1], got {}", shown(*.0))]
    NotFraction(Real),
    /// Outside (0, 1].
    #[error("expected a ratio in (0, 1], got {}", shown(*.0))]
    NotRatio(Real),
    /// A damping coefficient outside [0, 1].
    #[error("expected a damping coefficient in [0, 1], got {}", shown(*.0))]
    NotDamping(Real),
    /// An XPIC order outside 1 to 10.
    #[error("expected an XPIC order from 1 to {MAX_XPIC_ORDER}, got {0}")]
    XpicOrder(u32),
    /// An angle outside [0, 90) degrees.
    #[error("expected an angle in [0, 90) degrees, got {}", shown(*.0))]
    Angle(Real),
    /// A deviatoric eccentricity outside (0.5, 1].
    #[error("expected a deviatoric eccentricity in (0.5, 1], got {}", shown(*.0))]
    Eccentricity(Real),
    /// A density outside the range of materials.
    #[error(
        "expected a density from {MIN_DENSITY} to {MAX_DENSITY:e} kg/m³, got {} kg/m³",
        shown(*.0)
    )]
    Density(Real),
    /// An elastic modulus beyond any material's.
    #[error(
        "expected a modulus from {MIN_MODULUS} to {MAX_MODULUS:e} Pa, got {} Pa",
        shown(*.0)
    )]
    Modulus(Real),
    /// A strength or a load (Pa) that is negative or beyond any material's.
    #[error("expected a stress ≥ 0 and at most {MAX_MODULUS:e} Pa, got {} Pa", shown(*.0))]
    Stress(Real),
    /// A contact stiffness beyond any use.
    #[error("expected a stiffness > 0 and at most {MAX_STIFFNESS:e}, got {}", shown(*.0))]
    Stiffness(Real),
    /// A speed beyond any impact's.
    #[error("expected a speed of at most {MAX_SPEED:e} m/s, got {}", shown(*.0))]
    Speed(Real),
    /// A spin beyond any block's.
    #[error("expected a spin of at most {MAX_SPIN:e} rad/s, got {}", shown(*.0))]
    Spin(Real),
    /// A friction coefficient outside [0, 10].
    #[error("expected a friction coefficient from 0 to {MAX_FRICTION}, got {}", shown(*.0))]
    Friction(Real),
    /// An earth pressure coefficient outside [0, 10].
    #[error(
        "expected an earth pressure coefficient from 0 to {MAX_EARTH_PRESSURE_COEFFICIENT}, got {}",
        shown(*.0)
    )]
    EarthPressure(Real),
    /// A viscosity that is negative or beyond any flow's.
    #[error("expected a viscosity ≥ 0 and at most {MAX_VISCOSITY:e} Pa s, got {} Pa s", shown(*.0))]
    Viscosity(Real),
    /// A name that cannot be a file name, and why.
    #[error("{0}")]
    FileName(String),
}

impl RuleError {
    /// This error as that of the parameter `field`.
    pub fn at(self, field: &'static str) -> ParameterError {
        ParameterError::Range { field, rule: self }
    }
}

/// A model's or a law's parameters that a simulation cannot take.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ParameterError {
    /// A parameter outside its range.
    #[error("{field}: {rule}")]
    Range {
        /// The parameter.
        field: &'static str,
        /// Its range, and the value given.
        rule: RuleError,
    },
    /// Parameters that do not fit together, or a value a model refuses, and
    /// why.
    #[error("{0}")]
    Inconsistent(String),
}

/// `x` with the digits that matter: plainly between 1e-4 and 1e7, in
/// scientific notation beyond (1e300, not three hundred digits).
pub fn shown(x: Real) -> String {
    if x == 0.0 || !x.is_finite() || (1e-4..1e7).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A value worked out from the input, as [`shown`] with four significant
/// digits (0.01, not 0.010000000000000002).
pub fn shown_rounded(x: Real) -> String {
    shown(format!("{x:.3e}").parse().unwrap_or(x))
}

/// Most characters of a piece of input a message echoes.
pub const ECHO_CHARACTERS: usize = 80;

/// `text` as a message echoes it: control characters escaped, and cut to
/// [`ECHO_CHARACTERS`] with its length when longer (a 200 MB line of a
/// point file is not printed whole).
pub fn echo(text: &str) -> String {
    let length = text.chars().count();
    let mut shown: String = text
        .chars()
        .take(ECHO_CHARACTERS)
        .flat_map(|c| {
            let escaped: Vec<char> = if c.is_control() {
                c.escape_default().collect()
            } else {
                vec![c]
            };
            escaped
        })
        .collect();
    if length > ECHO_CHARACTERS {
        shown.push_str(&format!("… ({length} characters)"));
    }
    shown
}

/// `value` if it lies in `range` (NaN never does), else `error(value)`.
fn within(
    value: Real,
    range: RangeInclusive<Real>,
    error: fn(Real) -> RuleError,
) -> Result<Real, RuleError> {
    if range.contains(&value) {
        Ok(value)
    } else {
        Err(error(value))
    }
}

/// Lightest density a material or a block may have (kg/m³): below air's
/// (1.2), below any solid's, liquid's or foam's; a smaller value is a unit
/// typed wrong, and makes the time step's limits meaningless.
pub const MIN_DENSITY: Real = 0.1;

/// Heaviest density a material or a block may have (kg/m³): the densest
/// metal (22 600) scaled up 40 000 times for a quasi-static run.
pub const MAX_DENSITY: Real = 1e9;

/// A density within [`MIN_DENSITY`] and [`MAX_DENSITY`].
pub fn density(value: Real) -> Result<Real, RuleError> {
    within(value, MIN_DENSITY..=MAX_DENSITY, RuleError::Density)
}

/// Stiffest elastic modulus a material may have (Pa): ten times
/// diamond's Young's modulus (1.2e12 Pa); beyond it a value is a unit typed
/// wrong, and the time step it needs is below any run's.
pub const MAX_MODULUS: Real = 1e13;

/// Softest elastic modulus a material may have (Pa): a hundredth of the
/// softest gels' (about 100 Pa); below it a value is a unit typed wrong,
/// and the strain energy of any stress overflows.
pub const MIN_MODULUS: Real = 1.0;

/// An elastic modulus within [`MIN_MODULUS`] and [`MAX_MODULUS`].
pub fn modulus(value: Real) -> Result<Real, RuleError> {
    within(value, MIN_MODULUS..=MAX_MODULUS, RuleError::Modulus)
}

/// A strength (cohesion, tension cut-off) or the size of a load (Pa): ≥ 0
/// and at most [`MAX_MODULUS`], as no material's strength or load exceeds
/// its stiffness.
pub fn stress(value: Real) -> Result<Real, RuleError> {
    within(value, 0.0..=MAX_MODULUS, RuleError::Stress)
}

/// Stiffest contact spring a law may have (N/m per metre, or N/m³ by
/// area): 1e8 times the stiffest the verification cases use (1e10), so
/// that the sub-step warning of a stiff law can still be met; beyond it the
/// contact's stable step is below any run's.
pub const MAX_STIFFNESS: Real = 1e18;

/// A contact stiffness: positive, at most [`MAX_STIFFNESS`].
pub fn stiffness(value: Real) -> Result<Real, RuleError> {
    if value > 0.0 && value <= MAX_STIFFNESS {
        Ok(value)
    } else {
        Err(RuleError::Stiffness(value))
    }
}

/// Fastest speed a point or a block may start with (m/s): ten times the
/// fastest hypervelocity impacts (about 10 km/s); beyond it a value is a
/// unit typed wrong, and no time step resolves the motion.
pub const MAX_SPEED: Real = 1e5;

/// A velocity's size: finite, at most [`MAX_SPEED`].
pub fn speed(value: Real) -> Result<Real, RuleError> {
    if value.abs() <= MAX_SPEED {
        Ok(value)
    } else {
        Err(RuleError::Speed(value))
    }
}

/// Fastest spin a block may have (rad/s): a 1 cm block's edge at
/// [`MAX_SPEED`] / 10.
pub const MAX_SPIN: Real = 1e6;

/// A spin's size: finite, at most [`MAX_SPIN`].
pub fn spin(value: Real) -> Result<Real, RuleError> {
    if value.abs() <= MAX_SPIN {
        Ok(value)
    } else {
        Err(RuleError::Spin(value))
    }
}

/// A rigid velocity: its speed within [`MAX_SPEED`] and its spin within
/// [`MAX_SPIN`]; the message names which.
pub fn rigid_velocity(linear: glam::DVec2, angular: Real) -> Result<(), String> {
    speed(linear.length()).map_err(|e| format!("velocity: {e}"))?;
    spin(angular).map_err(|e| format!("angular velocity: {e}"))?;
    Ok(())
}

/// Largest Coulomb friction coefficient (a friction angle of 84°): the
/// roughest interfaces measured (rubber on rough rock) stay below 4.
pub const MAX_FRICTION: Real = 10.0;

/// A friction coefficient in [0, [`MAX_FRICTION`]].
pub fn friction(value: Real) -> Result<Real, RuleError> {
    within(value, 0.0..=MAX_FRICTION, RuleError::Friction)
}

/// Largest earth pressure coefficient at rest K0: above the passive
/// coefficient of any soil (5.8 at φ = 45°) and of heavily overconsolidated
/// clays (about 3).
pub const MAX_EARTH_PRESSURE_COEFFICIENT: Real = 10.0;

/// An earth pressure coefficient in [0, [`MAX_EARTH_PRESSURE_COEFFICIENT`]].
pub fn earth_pressure_coefficient(value: Real) -> Result<Real, RuleError> {
    within(
        value,
        0.0..=MAX_EARTH_PRESSURE_COEFFICIENT,
        RuleError::EarthPressure,
    )
}

/// Largest dynamic viscosity (Pa s): glacier ice's (about 10¹³), the most
/// viscous flow a run of this field meets.
pub const MAX_VISCOSITY: Real = 1e13;

/// A dynamic viscosity in [0, [`MAX_VISCOSITY`]].
pub fn viscosity(value: Real) -> Result<Real, RuleError> {
    within(value, 0.0..=MAX_VISCOSITY, RuleError::Viscosity)
}

/// A value must be finite and strictly positive.
pub fn positive(value: Real) -> Result<Real, RuleError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(RuleError::NotPositive(value))
    }
}

/// A value must be finite and non-negative.
pub fn non_negative(value: Real) -> Result<Real, RuleError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(RuleError::Negative(value))
    }
}

/// Poisson's ratio must lie in (−1, 0.5): 0.5 is incompressible, which
/// explicit MPM cannot integrate (infinite wave speed).
pub fn poisson_ratio(value: Real) -> Result<Real, RuleError> {
    if value > -1.0 && value < 0.5 {
        Ok(value)
    } else {
        Err(RuleError::PoissonRatio(value))
    }
}

/// A fraction in [0, 1] (e.g. the PIC fraction β).
pub fn fraction(value: Real) -> Result<Real, RuleError> {
    within(value, 0.0..=1.0, RuleError::NotFraction)
}

/// A ratio in (0, 1], e.g. of a kinetic energy to its peak: 0 would
/// never be reached, and above 1 the condition holds at once.
pub fn ratio(value: Real) -> Result<Real, RuleError> {
    if value > 0.0 && value <= 1.0 {
        Ok(value)
    } else {
        Err(RuleError::NotRatio(value))
    }
}

/// A local damping coefficient in [0, 1]. At 1 a force that would speed a
/// node or point up is cancelled and one that slows it down is doubled, as
/// the paper's settling stages use it.
pub fn damping(value: Real) -> Result<Real, RuleError> {
    within(value, 0.0..=1.0, RuleError::NotDamping)
}

/// Largest XPIC order: the alternating binomial sum of eq. 12 loses about
/// log10 C(m, m/2) digits (2.4 at m = 10), and the paper's gains flatten
/// well before.
pub const MAX_XPIC_ORDER: u32 = 10;

/// An XPIC order m in [1, MAX_XPIC_ORDER].
pub fn xpic_order(value: u32) -> Result<u32, RuleError> {
    if (1..=MAX_XPIC_ORDER).contains(&value) {
        Ok(value)
    } else {
        Err(RuleError::XpicOrder(value))
    }
}

/// Characters no file name may hold on one of the systems a scene may be
/// run on: path separators, and those Windows reserves.
const NOT_IN_FILE_NAMES: [char; 9] = ['/', '\\', ':', '*', '?', '"', '<', '>', '|'];

/// Names Windows reserves for devices, whatever follows a dot.
const DEVICE_NAMES: [&str; 22] = [
    "con", "prn", "aux", "nul", "com1", "com2", "com3", "com4", "com5", "com6", "com7", "com8",
    "com9", "lpt1", "lpt2", "lpt3", "lpt4", "lpt5", "lpt6", "lpt7", "lpt8", "lpt9",
];

/// A name that becomes a file or folder name in the output (the scene's
/// folder, a curve's files), on any system: not empty, without path
/// separators, Windows' reserved characters (`: * ? " < > |`) or control
/// characters, not starting with `.` (so it can never climb out of the
/// output folder with `..`, name the folder itself or hide a file), not
/// ending with `.` or a space, and not a Windows device name (`CON`,
/// `NUL`, `COM1`, ...).
pub fn file_name(name: &str) -> Result<(), RuleError> {
    const WHY: &str = "names become file names";
    let device = name.split('.').next().unwrap_or("").to_ascii_lowercase();
    if name.is_empty() {
        Err(RuleError::FileName(
            "expected a name, got an empty one".into(),
        ))
    } else if name.starts_with('.') {
        Err(RuleError::FileName(format!(
            "the name '{name}' starts with '.': {WHY}, and such a file would be hidden or name a folder ('.', '..')"
        )))
    } else if let Some(c) = name
        .chars()
        .find(|c| NOT_IN_FILE_NAMES.contains(c) || c.is_control())
    {
        Err(RuleError::FileName(format!(
            "the name '{name}' holds {c:?}: {WHY}, which may not hold path separators, any of : * ? \" < > | or control characters"
        )))
    } else if name.ends_with(['.', ' ']) {
        Err(RuleError::FileName(format!(
            "the name '{name}' ends with '.' or a space: {WHY}, and Windows drops those"
        )))
    } else if DEVICE_NAMES.contains(&device.as_str()) {
        Err(RuleError::FileName(format!(
            "the name '{name}' is a device on Windows: {WHY}; choose another"
        )))
    } else {
        Ok(())
    }
}

/// Longest file name, in bytes, that the usual file systems accept
/// (ext4, XFS, APFS, NTFS: 255).
pub const FILE_NAME_MAX_BYTES: usize = 255;

/// A file name a name becomes (`file`, as written into the output folder)
/// that fits [`FILE_NAME_MAX_BYTES`] also under the temporary name it is
/// written under first ([`crate::files::PARTIAL_PREFIX`] before it), so
/// that a run never fails at its end for a name the scene gave.
pub fn fits_in_file_name(file: &str) -> Result<(), RuleError> {
    let bytes = crate::files::PARTIAL_PREFIX.len() + file.len();
    if bytes > FILE_NAME_MAX_BYTES {
        Err(RuleError::FileName(format!(
            "the name makes the file '{file}', whose temporary name while it is written is {bytes} bytes long, past the {FILE_NAME_MAX_BYTES} that file systems allow: shorten the name by {} bytes",
            bytes - FILE_NAME_MAX_BYTES
        )))
    } else {
        Ok(())
    }
}

/// A name made safe for a file name: every character but ASCII letters,
/// digits, `-` and `_` becomes `_` (probe names, which users write freely,
/// as in "top, left").
pub fn file_safe(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// Applies `rule` to an f64 being deserialized.
fn checked<'de, D: Deserializer<'de>>(
    deserializer: D,
    rule: fn(Real) -> Result<Real, RuleError>,
) -> Result<Real, D::Error> {
    rule(Real::deserialize(deserializer)?).map_err(D::Error::custom)
}

/// `deserialize_with` form of [`density`].
pub fn de_density<'de, D: Deserializer<'de>>(d: D) -> Result<Real, D::Error> {
    checked(d, density)
}

/// `deserialize_with` form of [`modulus`] without its lower bound, which
/// the model's check applies (a parse only refuses what no model takes:
/// a value ≤ 0 or beyond [`MAX_MODULUS`]).
pub fn de_modulus<'de, D: Deserializer<'de>>(d: D) -> Result<Real, D::Error> {
    checked(d, |value| {
        if value > 0.0 && value <= MAX_MODULUS {
            Ok(value)
        } else {
            Err(RuleError::Modulus(value))
        }
    })
}

/// `deserialize_with` form of [`positive`].
pub fn de_positive<'de, D: Deserializer<'de>>(d: D) -> Result<Real, D::Error> {
    checked(d, positive)
}

/// `deserialize_with` form of [`positive`] for an optional field written
/// without `Some` (absent: `None`, with `#[serde(default)]`).
pub fn de_some_positive<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Real>, D::Error> {
    checked(d, positive).map(Some)
}

/// `serialize_with` form of an optional field written without `Some`
/// (read by `de_some_*`): the value itself. Pair it with
/// `skip_serializing_if = "Option::is_none"`, so that `None` is left out.
pub fn ser_some<S: Serializer, T: Serialize>(value: &Option<T>, s: S) -> Result<S::Ok, S::Error> {
    match value {
        Some(v) => v.serialize(s),
        None => s.serialize_none(),
    }
}

/// A number of steps ≥ 1 for an optional field written without `Some`
/// (absent: `None`, with `#[serde(default)]`).
pub fn de_some_step_count<'de, D: Deserializer<'de>>(d: D) -> Result<Option<u64>, D::Error> {
    match u64::deserialize(d)? {
        0 => Err(D::Error::custom("expected a number of steps ≥ 1, got 0")),
        n => Ok(Some(n)),
    }
}

/// `deserialize_with` form of [`stress`].
pub fn de_stress<'de, D: Deserializer<'de>>(d: D) -> Result<Real, D::Error> {
    checked(d, stress)
}

/// `deserialize_with` form of [`non_negative`].
pub fn de_non_negative<'de, D: Deserializer<'de>>(d: D) -> Result<Real, D::Error> {
    checked(d, non_negative)
}

/// `deserialize_with` form of [`viscosity`].
pub fn de_viscosity<'de, D: Deserializer<'de>>(d: D) -> Result<Real, D::Error> {
    checked(d, viscosity)
}

/// `deserialize_with` form of [`fraction`].
pub fn de_fraction<'de, D: Deserializer<'de>>(d: D) -> Result<Real, D::Error> {
    checked(d, fraction)
}

/// `deserialize_with` form of [`xpic_order`] for an optional order. RON
/// writes it `Some(m)` (without the `implicit_some` extension).
pub fn de_xpic_order<'de, D: Deserializer<'de>>(d: D) -> Result<Option<u32>, D::Error> {
    Option::<u32>::deserialize(d)?
        .map(xpic_order)
        .transpose()
        .map_err(D::Error::custom)
}

/// `deserialize_with` form of [`positive`] for an optional value written
/// `Some(x)`.
pub fn de_option_positive<'de, D: Deserializer<'de>>(d: D) -> Result<Option<Real>, D::Error> {
    Option::<Real>::deserialize(d)?
        .map(positive)
        .transpose()
        .map_err(D::Error::custom)
}

/// `deserialize_with` form of [`ratio`].
pub fn de_ratio<'de, D: Deserializer<'de>>(d: D) -> Result<Real, D::Error> {
    checked(d, ratio)
}

/// `deserialize_with` form of [`damping`].
pub fn de_damping<'de, D: Deserializer<'de>>(d: D) -> Result<Real, D::Error> {
    checked(d, damping)
}

/// `deserialize_with` form of [`poisson_ratio`].
pub fn de_poisson_ratio<'de, D: Deserializer<'de>>(d: D) -> Result<Real, D::Error> {
    checked(d, poisson_ratio)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn echoed_input_is_cut_and_escaped_and_numbers_keep_their_digits() {
        assert_eq!(echo("x,y"), "x,y");
        assert_eq!(echo("a\u{1b}[31m"), "a\\u{1b}[31m");
        let long = "1.0, ".repeat(100);
        assert_eq!(
            echo(&long),
            format!("{}… (500 characters)", &long[..ECHO_CHARACTERS])
        );
        assert_eq!(shown(1e300), "1e300");
        assert_eq!(shown(2.5), "2.5");
        assert_eq!(shown(-1e-7), "-1e-7");
        assert_eq!(shown_rounded(0.1 * 0.1), "0.01");
        assert_eq!(shown_rounded(2.0_f64.sqrt() / 20.0), "0.07071");
    }
}
