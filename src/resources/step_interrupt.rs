//! A request to cut the step in progress short, for a stop that cannot
//! wait for a long step to end.

use bevy_ecs::prelude::*;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// The flag that, once raised, makes the step in progress skip its
/// remaining sets (checked before each of them), and whether it did.
///
/// A step cut short leaves the state half updated: the simulation refuses
/// further steps, and its state is neither checkpointed nor hashed by the
/// runner. The diagnostics and the last hook run only for a whole step, so
/// the records end at the last whole step.
#[derive(Resource, Debug)]
pub struct StepInterrupt {
    request: Arc<AtomicBool>,
    cut_short: AtomicBool,
}

impl StepInterrupt {
    /// Watches `request`.
    pub fn new(request: Arc<AtomicBool>) -> Self {
        Self {
            request,
            cut_short: AtomicBool::new(false),
        }
    }

    /// Whether a step was cut short.
    pub fn cut_short(&self) -> bool {
        self.cut_short.load(Ordering::SeqCst)
    }

    /// Whether the step goes on into the next set: false from the first
    /// set the request was seen before.
    pub(crate) fn goes_on(&self) -> bool {
        if self.cut_short() {
            return false;
        }
        if self.request.load(Ordering::SeqCst) {
            self.cut_short.store(true, Ordering::SeqCst);
            return false;
        }
        true
    }
}
