//! State that user systems keep in resources of their own (a load
//! controller's integral, a counter), carried by checkpoints once it is
//! registered by name with [`crate::Simulation::keep_in_checkpoints`], so a
//! resumed run with user systems is still bit-identical.

use bevy_ecs::prelude::*;
use serde::Serialize;
use serde::de::DeserializeOwned;

/// Encodes one resource of the world.
type Save = fn(&World) -> Result<Vec<u8>, String>;

/// Decodes one resource and puts it into the world.
type Load = fn(&mut World, &[u8]) -> Result<(), String>;

/// One registered resource type.
#[derive(Clone)]
struct Kept {
    name: String,
    save: Save,
    load: Load,
}

/// The user resources that checkpoints carry, by name, in the order they
/// were registered.
#[derive(Clone, Default)]
pub struct KeptResources {
    kept: Vec<Kept>,
}

/// A resource stored in a checkpoint: its registered name and its
/// `postcard` encoding.
pub type StoredResource = (String, Vec<u8>);

impl KeptResources {
    /// Registers the resource type `R` under `name`, replacing an earlier
    /// registration of that name.
    pub fn keep<R: Resource + Serialize + DeserializeOwned>(&mut self, name: &str) {
        let kept = Kept {
            name: name.to_owned(),
            save: save::<R>,
            load: load::<R>,
        };
        match self.kept.iter_mut().find(|k| k.name == name) {
            Some(existing) => *existing = kept,
            None => self.kept.push(kept),
        }
    }

    /// Encodes every registered resource; fails if one is not in `world`.
    pub fn save(&self, world: &World) -> Result<Vec<StoredResource>, String> {
        self.kept
            .iter()
            .map(|k| {
                let bytes =
                    (k.save)(world).map_err(|e| format!("user resource '{}': {e}", k.name))?;
                Ok((k.name.clone(), bytes))
            })
            .collect()
    }

    /// Puts the `stored` resources into `world`. The stored names must be
    /// the registered ones: a resource the run keeps but the checkpoint
    /// lacks, or one the checkpoint holds but the run does not keep, would
    /// make the resumed run differ, and is refused.
    pub fn load(&self, world: &mut World, stored: Vec<StoredResource>) -> Result<(), String> {
        let mut registered: Vec<&str> = self.kept.iter().map(|k| k.name.as_str()).collect();
        let mut in_file: Vec<&str> = stored.iter().map(|(name, _)| name.as_str()).collect();
        registered.sort_unstable();
        in_file.sort_unstable();
        if registered != in_file {
            return Err(format!(
                "it holds the user resources {in_file:?} where this run keeps {registered:?} \
                 (register them with Simulation::keep_in_checkpoints before restoring)"
            ));
        }
        for kept in &self.kept {
            if let Some((_, bytes)) = stored.iter().find(|(name, _)| *name == kept.name) {
                (kept.load)(world, bytes)
                    .map_err(|e| format!("user resource '{}': {e}", kept.name))?;
            }
        }
        Ok(())
    }
}

fn save<R: Resource + Serialize>(world: &World) -> Result<Vec<u8>, String> {
    let resource = world.get_resource::<R>().ok_or("it is not in the world")?;
    postcard::to_allocvec(resource).map_err(|e| e.to_string())
}

fn load<R: Resource + DeserializeOwned>(world: &mut World, bytes: &[u8]) -> Result<(), String> {
    let resource: R = postcard::from_bytes(bytes).map_err(|e| e.to_string())?;
    world.insert_resource(resource);
    Ok(())
}
