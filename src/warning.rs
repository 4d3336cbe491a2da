//! Warnings for the user: a scene that is valid but likely not what was
//! meant, or a run that went somewhere worth a look. Each says what it is
//! about ([`WarningKind`]), the scene field it concerns and what it says;
//! `mpdem check` and `mpdem run` print them alike, and a test matches the
//! kind and the field instead of the words.

use serde::{Deserialize, Serialize};
use std::fmt;

/// What a warning is about.
#[non_exhaustive]
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum WarningKind {
    /// A spelling of an earlier release of the scene format, read as its
    /// present one.
    OldSpelling,
    /// The time step beyond a stability limit: a material's CFL limit, a
    /// contact spring's period, a loose point's wave.
    TimeStep,
    /// A duration or interval that is not a whole number of steps.
    OffStep,
    /// Where bodies and blocks start: at an open edge of the grid, or
    /// overlapping.
    Layout,
    /// An initial stress the material cannot hold.
    InitialStress,
    /// A transfer option likely wrong for the scene's materials.
    Transfer,
    /// Contacts that will not behave as the scene seems to expect.
    Contact,
    /// A probe far from the point it records.
    Probe,
    /// Outputs that will take much room.
    Output,
    /// A stage that ended otherwise than planned, or a load that acts on
    /// nothing.
    Stage,
    /// Raised by a plugin outside the engine.
    Plugin,
}

/// A warning: what it is about, the scene field it concerns (a path such
/// as `time.dt` or `bodies["column"].shape`; empty when it concerns the
/// run as a whole) and what it says. It displays as its message.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Warning {
    /// What it is about.
    pub kind: WarningKind,
    /// The scene field it concerns.
    pub field: String,
    /// What it says, whole: it names the field itself.
    pub message: String,
}

impl Warning {
    /// A warning of `kind` about `field`.
    pub fn new(kind: WarningKind, field: impl Into<String>, message: impl Into<String>) -> Self {
        Self {
            kind,
            field: field.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for Warning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}
