//! State that user systems keep of their own, carried by checkpoints once
//! it is registered by name, so a resumed run with user systems is still
//! bit-identical: resources (a load controller's integral, a counter;
//! [`crate::Simulation::keep_in_checkpoints`]) and components on the
//! engine's bodies and blocks (a body's own per-point field, a block's
//! controller; [`crate::Simulation::keep_components_in_checkpoints`]).

use bevy_ecs::prelude::*;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};

/// An engine entity that a kept component sits on, named so that a world
/// rebuilt from the same scene finds it again.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Holder {
    /// The body at this index of the scene's `bodies`.
    Body(u32),
    /// The block at this index of the scene's `blocks`.
    Block(u32),
}

/// The bodies and blocks of a world, each with its entity.
pub type Holders = [(Holder, Entity)];

/// Something decoded, ready to be put into a world whose bodies and blocks
/// are `Holders`.
type Insert = Box<dyn FnOnce(&mut World, &Holders)>;

/// Encodes one registered type from the world.
type Encode = fn(&World, &Holders) -> Result<Stored, String>;

/// Decodes one registered type.
type Decode = fn(&Stored) -> Result<Insert, String>;

/// What a checkpoint stores of one registered type.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Stored {
    /// A resource's `postcard` encoding.
    Resource(Vec<u8>),
    /// A component's encoding on every body and block that has it.
    Components(Vec<(Holder, Vec<u8>)>),
}

/// One registered type.
#[derive(Clone)]
struct Kept {
    name: String,
    encode: Encode,
    decode: Decode,
}

/// The user state that checkpoints carry, by name, in the order it was
/// registered.
#[derive(Clone, Default)]
pub struct KeptState {
    kept: Vec<Kept>,
}

/// One registered type stored in a checkpoint: its name and its encoding.
pub type StoredState = (String, Stored);

impl KeptState {
    /// Registers the resource type `R` under `name`, replacing an earlier
    /// registration of that name. Register user resources only: the
    /// engine's own (clock, settings, records) are restored by the
    /// checkpoint itself, and one registered too could be overwritten by
    /// either copy.
    pub fn keep_resource<R: Resource + Serialize + DeserializeOwned>(&mut self, name: &str) {
        self.register(name, encode_resource::<R>, decode_resource::<R>);
    }

    /// Registers the component type `C` under `name`, kept on every body
    /// and block that has it, replacing an earlier registration of that
    /// name. Register user components only.
    pub fn keep_component<C: Component + Serialize + DeserializeOwned>(&mut self, name: &str) {
        self.register(name, encode_component::<C>, decode_component::<C>);
    }

    fn register(&mut self, name: &str, encode: Encode, decode: Decode) {
        let kept = Kept {
            name: name.to_owned(),
            encode,
            decode,
        };
        match self.kept.iter_mut().find(|k| k.name == name) {
            Some(existing) => *existing = kept,
            None => self.kept.push(kept),
        }
    }

    /// Encodes every registered type from `world`, whose bodies and blocks
    /// are `holders`; fails if a registered resource is not in the world.
    pub fn save(&self, world: &World, holders: &Holders) -> Result<Vec<StoredState>, String> {
        self.kept
            .iter()
            .map(|k| {
                let stored = (k.encode)(world, holders)
                    .map_err(|e| format!("user state '{}': {e}", k.name))?;
                Ok((k.name.clone(), stored))
            })
            .collect()
    }

    /// Decodes the `stored` state, ready to be put into a world. The
    /// stored names must be the registered ones: state the run keeps but
    /// the checkpoint lacks, or the reverse, would make the resumed run
    /// differ, and is refused. Components may sit only on the bodies and
    /// blocks of `holders`, the checkpoint's. Nothing is put in here, so a
    /// refusal leaves the world as it was.
    pub fn decode(
        &self,
        stored: Vec<StoredState>,
        holders: &[Holder],
    ) -> Result<DecodedState, String> {
        let mut registered: Vec<&Kept> = self.kept.iter().collect();
        let mut stored = stored;
        registered.sort_unstable_by(|a, b| a.name.cmp(&b.name));
        stored.sort_unstable_by(|a, b| a.0.cmp(&b.0));
        let registered_names: Vec<&str> = registered.iter().map(|k| k.name.as_str()).collect();
        let stored_names: Vec<&str> = stored.iter().map(|(name, _)| name.as_str()).collect();
        if registered_names != stored_names {
            return Err(format!(
                "it holds the user state {stored_names:?} where this run keeps \
                 {registered_names:?} (register it with Simulation::keep_in_checkpoints or \
                 keep_components_in_checkpoints before restoring)"
            ));
        }
        let inserts = registered
            .iter()
            .zip(&stored)
            .map(|(kept, (name, stored))| {
                if let Stored::Components(values) = stored {
                    if let Some((holder, _)) = values.iter().find(|(h, _)| !holders.contains(h)) {
                        return Err(format!(
                            "user state '{name}' is on {holder:?}, which the checkpoint does not hold"
                        ));
                    }
                    if values.windows(2).any(|pair| pair[0].0 >= pair[1].0) {
                        return Err(format!(
                            "user state '{name}' is stored twice on one body or block, or out of order"
                        ));
                    }
                }
                (kept.decode)(stored).map_err(|e| format!("user state '{name}': {e}"))
            })
            .collect::<Result<Vec<Insert>, String>>()?;
        Ok(DecodedState { inserts })
    }
}

/// User state decoded from a checkpoint, to be put into the world once its
/// bodies and blocks are restored.
pub struct DecodedState {
    inserts: Vec<Insert>,
}

impl DecodedState {
    /// Puts every resource into `world`, and every component on its body or
    /// block of `holders`, removing it from those the checkpoint has none
    /// on.
    pub fn insert(self, world: &mut World, holders: &Holders) {
        for insert in self.inserts {
            insert(world, holders);
        }
    }
}

/// Decodes `bytes` wholly as a `T`: bytes left over mean that the type
/// has changed since the checkpoint was written.
fn decode_exactly<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, String> {
    let (value, rest): (T, &[u8]) = postcard::take_from_bytes(bytes).map_err(|e| e.to_string())?;
    if !rest.is_empty() {
        return Err(format!(
            "{} bytes left after it: its type has changed",
            rest.len()
        ));
    }
    Ok(value)
}

fn encode_resource<R: Resource + Serialize>(world: &World, _: &Holders) -> Result<Stored, String> {
    let resource = world.get_resource::<R>().ok_or("it is not in the world")?;
    let bytes = postcard::to_allocvec(resource).map_err(|e| e.to_string())?;
    Ok(Stored::Resource(bytes))
}

fn decode_resource<R: Resource + DeserializeOwned>(stored: &Stored) -> Result<Insert, String> {
    let Stored::Resource(bytes) = stored else {
        return Err("it was stored as a component, and is kept as a resource".into());
    };
    let resource: R = decode_exactly(bytes)?;
    Ok(Box::new(move |world: &mut World, _: &Holders| {
        world.insert_resource(resource);
    }))
}

fn encode_component<C: Component + Serialize>(
    world: &World,
    holders: &Holders,
) -> Result<Stored, String> {
    holders
        .iter()
        .filter_map(|&(holder, entity)| Some((holder, world.get::<C>(entity)?)))
        .map(|(holder, component)| {
            let bytes = postcard::to_allocvec(component).map_err(|e| e.to_string())?;
            Ok((holder, bytes))
        })
        .collect::<Result<_, String>>()
        .map(Stored::Components)
}

fn decode_component<C: Component + DeserializeOwned>(stored: &Stored) -> Result<Insert, String> {
    let Stored::Components(values) = stored else {
        return Err("it was stored as a resource, and is kept as a component".into());
    };
    let decoded = values
        .iter()
        .map(|(holder, bytes)| Ok((*holder, decode_exactly::<C>(bytes)?)))
        .collect::<Result<Vec<(Holder, C)>, String>>()?;
    Ok(Box::new(move |world: &mut World, holders: &Holders| {
        for &(_, entity) in holders {
            world.entity_mut(entity).remove::<C>();
        }
        for (holder, component) in decoded {
            let Some(&(_, entity)) = holders.iter().find(|(h, _)| *h == holder) else {
                panic!("{holder:?} was checked to be in the checkpoint, and is not in the world");
            };
            world.entity_mut(entity).insert(component);
        }
    }))
}
