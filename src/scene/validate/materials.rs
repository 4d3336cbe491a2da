//! The materials: names and parameter ranges.

use super::{Locator, nth_name, quoted};
use crate::rules::{self, ParameterError};
use crate::scene::{Scene, SceneError};
use std::collections::BTreeSet;

impl Scene {
    /// The materials; returns their names.
    pub(super) fn check_materials<'s>(
        &'s self,
        v: &Locator,
    ) -> Result<BTreeSet<&'s str>, SceneError> {
        let mut material_names = BTreeSet::new();
        for (k, m) in self.materials.iter().enumerate() {
            let at = ["materials", &quoted(&m.name)];
            if !material_names.insert(m.name.as_str()) {
                return Err(v.invalid(
                    &nth_name("materials", k),
                    format!("material name '{}' is used twice", m.name),
                ));
            }
            rules::density(m.density).map_err(|e| {
                v.invalid(
                    &[at[0], at[1], "density"],
                    format!("material '{}': density: {e}", m.name),
                )
            })?;
            m.model.check().map_err(|e| {
                // A parameter out of range is placed at its field.
                let field = match &e {
                    ParameterError::Range { field, .. } => Some(*field),
                    ParameterError::Inconsistent(_) => None,
                };
                let anchors: Vec<&str> = at.into_iter().chain(["model"]).chain(field).collect();
                v.invalid(&anchors, format!("material '{}': {e}", m.name))
            })?;
        }
        Ok(material_names)
    }
}
