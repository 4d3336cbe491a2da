//! The verdicts of a verify run, counted: what `mpdem verify` says at its
//! end and whether it passed.

use crate::report::counted;
use crate::{CaseReport, Verdict};
use std::fmt;

/// The checks of a set of case reports, counted by verdict, and the cases
/// that could not be measured.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Tally {
    /// Cases run.
    pub cases: usize,
    /// Checks that met their target.
    pub met: usize,
    /// Checks that missed their target.
    pub missed: usize,
    /// Checks reported without a verdict.
    pub reported: usize,
    /// The cases that could not be measured.
    pub failed: Vec<&'static str>,
}

impl Tally {
    /// Counts the checks of `reports`.
    pub fn of(reports: &[CaseReport]) -> Self {
        let count = |verdict| {
            reports
                .iter()
                .flat_map(|r| r.checks())
                .filter(|c| c.verdict == verdict)
                .count()
        };
        Self {
            cases: reports.len(),
            met: count(Verdict::Met),
            missed: count(Verdict::Missed),
            reported: count(Verdict::Reported),
            failed: reports
                .iter()
                .filter(|r| r.outcome.is_err())
                .map(|r| r.case)
                .collect(),
        }
    }

    /// Every case measured and no check missed.
    pub fn passed(&self) -> bool {
        self.missed == 0 && self.failed.is_empty()
    }

    /// What a run that did not pass says of itself: the checks missed and
    /// the cases that could not be run; empty if it passed.
    pub fn problems(&self) -> String {
        let mut problems = Vec::new();
        if self.missed > 0 {
            let target = if self.missed == 1 {
                "its target"
            } else {
                "their targets"
            };
            problems.push(format!("{} missed {target}", counted(self.missed, "check")));
        }
        if !self.failed.is_empty() {
            problems.push(format!(
                "these cases could not be run: {}",
                self.failed.join(", ")
            ));
        }
        problems.join("; ")
    }
}

/// "3 cases; 10 checks met, 0 missed, 2 reported; 0 cases could not be
/// measured".
impl fmt::Display for Tally {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(
            f,
            "{}; {} met, {} missed, {} reported; {} could not be measured",
            counted(self.cases, "case"),
            counted(self.met, "check"),
            self.missed,
            self.reported,
            counted(self.failed.len(), "case"),
        )
    }
}
