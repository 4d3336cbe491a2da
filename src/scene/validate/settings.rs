//! The numerical settings.

use super::Locator;
use crate::math::Real;
use crate::rules::shown;

/// Largest gravity a scene may set (m/s²): beyond the 10⁵ g of a
/// geotechnical centrifuge by ten, far past any use; beyond it the run
/// overflows its energies.
pub(super) const MAX_GRAVITY: Real = 1e6;
use crate::scene::axisymmetry::axisymmetry_error;
use crate::scene::{Scene, SceneError};

impl Scene {
    /// Gravity and the numerical settings.
    pub(super) fn check_settings(&self, v: &Locator) -> Result<(), SceneError> {
        if !(self.gravity.is_finite() && self.gravity.length() <= MAX_GRAVITY) {
            return Err(v.invalid(
                &["gravity"],
                format!(
                    "gravity must be finite and at most {MAX_GRAVITY:e} m/s², got ({}, {})",
                    shown(self.gravity.x),
                    shown(self.gravity.y)
                ),
            ));
        }
        self.settings
            .check()
            .map_err(|e| v.field(&["settings"], e))?;
        if let Some((anchors, message)) = axisymmetry_error(self) {
            let anchors: Vec<&str> = anchors.iter().map(String::as_str).collect();
            return Err(v.invalid(&anchors, message));
        }
        if self.settings.xpic_order.is_some() && !self.shared_layers().is_empty() {
            return Err(v.invalid(
                &["settings", "xpic_order"],
                "settings.xpic_order: XPIC is not available with contact groups yet (its projections run per body); use pic_fraction".into(),
            ));
        }
        Ok(())
    }
}
