//! A warning about a velocity transfer that granular bodies do not
//! survive.

use crate::scene::Scene;
use crate::warning::{Warning, WarningKind};

/// A warning when the scene starts under `affine_transfer` with pure FLIP
/// (no PIC share, no XPIC, no granular relaxation) and has a
/// Drucker–Prager or Mohr–Coulomb body:
/// the affine part then feeds isolated points of a granular flow, which run
/// away from it until one leaves the grid (a granular column collapse
/// does, `docs/cases.md`). Taylor PIC (`pic_fraction: 1.0` with the affine
/// transfer) keeps them. Elastic bodies under the same transfer are not
/// concerned (the toppling blocks use it).
pub fn granular_transfer_warning(scene: &Scene) -> Option<Warning> {
    let settings = &scene.settings;
    let pure_flip = settings.xpic_order.is_none()
        && settings.pic_fraction == 0.0
        && settings.granular_relaxation.is_none();
    let granular = scene.bodies.iter().find(|body| {
        scene
            .materials
            .iter()
            .any(|m| m.name == body.material && m.model.as_model().granular())
    })?;
    (settings.affine_transfer && pure_flip).then(|| {
        Warning::new(WarningKind::Transfer, "settings.affine_transfer", format!(
            "settings.affine_transfer under pure FLIP (pic_fraction 0, granular_relaxation None) lets isolated points of a granular flow run away until one leaves the grid (body '{}' is granular: Drucker–Prager or Mohr–Coulomb); use it with pic_fraction: 1.0 (Taylor PIC), or leave affine_transfer out",
            granular.name
        ))
    })
}
