//! State that user systems keep in resources of their own (a load
//! controller's integral, a counter), carried by checkpoints once it is
//! registered by name with [`crate::Simulation::keep_in_checkpoints`], so a
//! resumed run with user systems is still bit-identical.

use bevy_ecs::prelude::*;
use serde::Serialize;
use serde::de::DeserializeOwned;

/// Encodes one resource of the world.
type Encode = fn(&World) -> Result<Vec<u8>, String>;

/// Puts a decoded resource into the world.
type Insert = Box<dyn FnOnce(&mut World)>;

/// Decodes one resource, ready to be put into the world.
type Decode = fn(&[u8]) -> Result<Insert, String>;

/// One registered resource type.
#[derive(Clone)]
struct Kept {
    name: String,
    encode: Encode,
    decode: Decode,
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
    /// registration of that name. Register user resources only: the
    /// engine's own (clock, settings, records) are restored by the
    /// checkpoint itself, after the user resources.
    pub fn keep<R: Resource + Serialize + DeserializeOwned>(&mut self, name: &str) {
        let kept = Kept {
            name: name.to_owned(),
            encode: encode::<R>,
            decode: decode::<R>,
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
                    (k.encode)(world).map_err(|e| format!("user resource '{}': {e}", k.name))?;
                Ok((k.name.clone(), bytes))
            })
            .collect()
    }

    /// Puts the `stored` resources into `world`. The stored names must be
    /// the registered ones: a resource the run keeps but the checkpoint
    /// lacks, or one the checkpoint holds but the run does not keep, would
    /// make the resumed run differ, and is refused. Every resource is
    /// decoded before any is put in, so a refusal leaves `world` as it was.
    pub fn load(&self, world: &mut World, stored: Vec<StoredResource>) -> Result<(), String> {
        let mut registered: Vec<&Kept> = self.kept.iter().collect();
        let mut stored = stored;
        registered.sort_unstable_by(|a, b| a.name.cmp(&b.name));
        stored.sort_unstable_by(|a, b| a.0.cmp(&b.0));
        let registered_names: Vec<&str> = registered.iter().map(|k| k.name.as_str()).collect();
        let stored_names: Vec<&str> = stored.iter().map(|(name, _)| name.as_str()).collect();
        if registered_names != stored_names {
            return Err(format!(
                "it holds the user resources {stored_names:?} where this run keeps \
                 {registered_names:?} (register them with Simulation::keep_in_checkpoints \
                 before restoring)"
            ));
        }
        let inserts = registered
            .iter()
            .zip(&stored)
            .map(|(kept, (name, bytes))| {
                (kept.decode)(bytes).map_err(|e| format!("user resource '{name}': {e}"))
            })
            .collect::<Result<Vec<Insert>, String>>()?;
        for insert in inserts {
            insert(world);
        }
        Ok(())
    }
}

fn encode<R: Resource + Serialize>(world: &World) -> Result<Vec<u8>, String> {
    let resource = world.get_resource::<R>().ok_or("it is not in the world")?;
    postcard::to_allocvec(resource).map_err(|e| e.to_string())
}

fn decode<R: Resource + DeserializeOwned>(bytes: &[u8]) -> Result<Insert, String> {
    let (resource, rest): (R, &[u8]) =
        postcard::take_from_bytes(bytes).map_err(|e| e.to_string())?;
    if !rest.is_empty() {
        return Err(format!(
            "{} bytes left after it: the resource's type has changed",
            rest.len()
        ));
    }
    Ok(Box::new(move |world: &mut World| {
        world.insert_resource(resource);
    }))
}
