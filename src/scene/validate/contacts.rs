//! The contact laws between bodies and with blocks.

use super::{Locator, quoted};
use crate::resources::MAX_CONTACT_BODIES;
use crate::scene::{Scene, SceneError};
use std::collections::BTreeSet;

impl Scene {
    /// The laws of pairs with a block: each names a block and a body, or
    /// two blocks; a pair once; valid laws.
    pub(super) fn check_block_contacts(
        &self,
        v: &Locator,
        body_names: &BTreeSet<&str>,
        block_names: &BTreeSet<&str>,
    ) -> Result<(), SceneError> {
        let mut pairs = BTreeSet::new();
        for (k, spec) in self.block_contacts.iter().enumerate() {
            let (a, b) = (spec.between.0.as_str(), spec.between.1.as_str());
            let at = |field: &'static str| -> Vec<&str> {
                std::iter::once("block_contacts")
                    .chain(std::iter::repeat_n(field, k + 1))
                    .collect()
            };
            for name in [a, b] {
                if block_names.contains(name) && body_names.contains(name) {
                    return Err(v.invalid(
                        &at("between"),
                        format!(
                            "block_contacts: '{name}' names a block and a body; rename one so that the law's pair is clear"
                        ),
                    ));
                }
                if !block_names.contains(name) && !body_names.contains(name) {
                    return Err(v.invalid(
                        &at("between"),
                        format!(
                            "block_contacts: unknown block or body '{name}'; expected one of the blocks {block_names:?} or bodies {body_names:?}"
                        ),
                    ));
                }
            }
            if !block_names.contains(a) && !block_names.contains(b) {
                return Err(v.invalid(
                    &at("between"),
                    format!(
                        "block_contacts ('{a}', '{b}'): neither is a block; the law between two bodies goes in body_contacts"
                    ),
                ));
            }
            if a == b {
                return Err(v.invalid(
                    &at("between"),
                    format!("block_contacts ('{a}', '{b}'): a block does not contact itself"),
                ));
            }
            if !pairs.insert((a.min(b), a.max(b))) {
                return Err(v.invalid(
                    &at("between"),
                    format!("block_contacts ('{a}', '{b}'): the pair has two laws"),
                ));
            }
            spec.law.check().map_err(|e| {
                v.invalid(&at("law"), format!("block_contacts ('{a}', '{b}'): {e}"))
            })?;
        }
        Ok(())
    }

    /// The body contact laws and contact groups.
    pub(super) fn check_body_contacts<'s>(
        &'s self,
        v: &Locator,
        body_names: &BTreeSet<&'s str>,
    ) -> Result<(), SceneError> {
        let grid = &self.grid;
        let group_names: BTreeSet<&str> = self
            .bodies
            .iter()
            .filter_map(|b| b.group.as_deref())
            .collect();
        if let Some(b) = self
            .bodies
            .iter()
            .find(|b| b.group.as_deref().is_some_and(|g| body_names.contains(g)))
        {
            return Err(v.invalid(
                &["bodies", &quoted(&b.name), "group"],
                format!(
                    "body '{}': group '{}' has the name of a body; body_contacts could not tell them apart",
                    b.name,
                    b.group.as_deref().unwrap_or_default()
                ),
            ));
        }
        let mut pairs = BTreeSet::new();
        for (k, spec) in self.body_contacts.iter().enumerate() {
            let (a, b) = (&spec.between.0, &spec.between.1);
            // The k-th entry's `between` (and below its `law`).
            let at: Vec<&str> = std::iter::once("body_contacts")
                .chain(std::iter::repeat_n("between", k + 1))
                .collect();
            let members = |name: &str| {
                self.contact_members(name).ok_or_else(|| {
                    v.invalid(
                        &at,
                        format!(
                            "body_contacts: unknown body or group '{name}'; expected one of the bodies {body_names:?} or groups {group_names:?}"
                        ),
                    )
                })
            };
            let (first, second) = (members(a)?, members(b)?);
            let same_layer = |i: usize, j: usize| {
                i == j
                    || self.bodies[i].group.is_some()
                        && self.bodies[i].group == self.bodies[j].group
            };
            for &i in &first {
                for &j in &second {
                    if same_layer(i, j) {
                        return Err(v.invalid(
                            &at,
                            format!(
                                "body_contacts ('{a}', '{b}'): body '{}' would contact '{}', which shares its layer (the same body or contact group): such bodies meet through the grid",
                                self.bodies[i].name, self.bodies[j].name
                            ),
                        ));
                    }
                    if !pairs.insert((i.min(j), i.max(j))) {
                        return Err(v.invalid(
                            &at,
                            format!(
                                "body_contacts ('{a}', '{b}'): the bodies '{}' and '{}' have two laws",
                                self.bodies[i].name, self.bodies[j].name
                            ),
                        ));
                    }
                }
            }
            spec.law.check().map_err(|e| {
                v.invalid(
                    &std::iter::once("body_contacts")
                        .chain(std::iter::repeat_n("law", k + 1))
                        .collect::<Vec<_>>(),
                    format!("body_contacts ('{a}', '{b}'): {e}"),
                )
            })?;
        }
        if !self.body_contacts.is_empty()
            && let Some(b) = self
                .bodies
                .iter()
                .find(|b| b.contact_radius.is_some_and(|r| r > 0.5 * grid.cell_size))
        {
            return Err(v.invalid(
                &["bodies", &quoted(&b.name), "contact_radius"],
                format!(
                    "body '{}': contact_radius {} is more than half a cell ({}): body contacts look for overlapping disks in neighbouring cells only",
                    b.name,
                    b.contact_radius.unwrap_or_default(),
                    0.5 * grid.cell_size
                ),
            ));
        }
        if !self.body_contacts.is_empty() && self.bodies.len() > MAX_CONTACT_BODIES {
            return Err(v.field(
                &["body_contacts"],
                format!(
                    "at most {MAX_CONTACT_BODIES} bodies are supported, the scene has {}",
                    self.bodies.len()
                ),
            ));
        }
        Ok(())
    }
}
