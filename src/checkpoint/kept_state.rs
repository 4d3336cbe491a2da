//! The registry of the state that checkpoints carry, by name: what each
//! feature of the engine keeps (registered by its plugin, see
//! [`crate::plugins::PluginSetup`]) and what user systems keep of their
//! own, so a resumed run is bit-identical: resources (a record, a load
//! controller's integral; [`crate::Simulation::keep_in_checkpoints`]) and
//! components on the engine's bodies and blocks (a body's own per-point
//! field, a block's controller;
//! [`crate::Simulation::keep_components_in_checkpoints`]).

use crate::math::Real;
use bevy_ecs::component::Mutable;
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
type Encode = fn(&World, &Holders) -> Result<Stored, Problem>;

/// Decodes one registered type.
type Decode = fn(&Stored) -> Result<Insert, Problem>;

/// Forgets a time record's samples from a time on.
type Forget = fn(&mut World, Real);

/// Why the state registered under a name could not be stored or put back.
#[derive(Debug, thiserror::Error)]
pub enum StateError {
    /// What went wrong with the state of one name.
    #[error("state '{name}': {problem}")]
    Named {
        /// The registered name.
        name: String,
        /// What went wrong.
        problem: Problem,
    },
    /// The checkpoint holds other names than the run registered.
    #[error(
        "its user state differs from this run's: it holds {extra:?} that this run does not keep, \
         and lacks {missing:?} that it keeps (register state with \
         Simulation::keep_in_checkpoints or keep_components_in_checkpoints, or add its plugin, \
         before restoring)"
    )]
    OtherNames {
        /// Names the checkpoint holds and the run does not keep.
        extra: Vec<String>,
        /// Names the run keeps and the checkpoint lacks.
        missing: Vec<String>,
    },
}

/// What went wrong with the state of one registered name.
#[derive(Debug, thiserror::Error)]
pub enum Problem {
    /// A registered resource is not in the world.
    #[error("it is not in the world")]
    NotInTheWorld,
    /// `postcard` could not encode or decode it.
    #[error(transparent)]
    Postcard(#[from] postcard::Error),
    /// Bytes were left after decoding it.
    #[error("{0} bytes left after it: its type has changed")]
    BytesLeft(usize),
    /// It was stored as a resource and is kept as a component, or the
    /// reverse.
    #[error("it was stored as a {stored}, and is kept as a {kept}")]
    OtherKind {
        /// How the checkpoint stored it.
        stored: &'static str,
        /// How the run keeps it.
        kept: &'static str,
    },
    /// A component sits on a body or block the checkpoint does not hold.
    #[error("it is on {0:?}, which the checkpoint does not hold")]
    UnknownHolder(Holder),
    /// A component is stored twice on one holder, or out of order.
    #[error("it is stored twice on one body or block, or out of order")]
    Unordered,
}

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

/// A resource that a plugin builds with the world and whose changing part
/// checkpoints carry: restoring puts that part back into the resource the
/// rebuilt world already holds (a record keeps the room reserved for the
/// whole run, so recording never allocates inside a step).
pub trait Checkpointed: Resource + Component<Mutability = Mutable> {
    /// The part a checkpoint stores.
    type Stored: Serialize + DeserializeOwned + 'static;

    /// The part to store, as it is now.
    fn stored(&self) -> Self::Stored;

    /// Puts a stored part back.
    fn restore(&mut self, stored: Self::Stored);
}

/// A record of samples in time, taken on the steps the probes are
/// (`Probes::due`), whose checkpoint may hold one sample too many: the one
/// a run takes at its last step, off its sampling interval, which a run
/// that goes on past that step does not take.
pub trait TimeRecord: Checkpointed {
    /// Forgets the samples taken at `time` or later.
    fn forget_from(&mut self, time: Real);
}

/// The state that checkpoints carry, by name, in the order it was
/// registered, with what restoring it then does.
#[derive(Clone, Default)]
pub struct KeptState {
    kept: Vec<Kept>,
    /// The time records, to forget a sample a run that never stopped
    /// would not have taken.
    records: Vec<(String, Forget)>,
    /// How many of the first entries are the engine's, whose names the
    /// user's may not take.
    sealed: usize,
    /// What features do once the whole state is back.
    after_restore: Vec<fn(&mut World)>,
}

/// One registered type stored in a checkpoint: its name and its encoding.
pub type StoredState = (String, Stored);

impl KeptState {
    /// Registers the resource type `R` under `name`, stored whole and
    /// inserted whole on restoring, replacing an earlier registration of
    /// that name.
    pub fn keep_resource<R: Resource + Serialize + DeserializeOwned>(&mut self, name: &str) {
        self.register(name, encode_resource::<R>, decode_resource::<R>);
    }

    /// Registers the part of the resource `R` that it stores (see
    /// [`Checkpointed`]) under `name`, replacing an earlier registration of
    /// that name.
    pub fn keep_checkpointed<R: Checkpointed>(&mut self, name: &str) {
        self.register(name, encode_checkpointed::<R>, decode_checkpointed::<R>);
    }

    /// Registers the time record `R` under `name`, as
    /// [`KeptState::keep_checkpointed`], and forgets its samples from a
    /// resumed run that a run that never stopped would not have.
    pub fn keep_record<R: TimeRecord>(&mut self, name: &str) {
        self.keep_checkpointed::<R>(name);
        self.records.retain(|(n, _)| n != name);
        self.records.push((name.to_owned(), forget_from::<R>));
    }

    /// Adds `hook`, run once the whole state of a checkpoint is restored
    /// (to rebuild what a feature derives from it).
    pub fn after_restore(&mut self, hook: fn(&mut World)) {
        self.after_restore.push(hook);
    }

    /// Runs the hooks of [`KeptState::after_restore`].
    pub(crate) fn run_after_restore(&self, world: &mut World) {
        for hook in &self.after_restore {
            hook(world);
        }
    }

    /// Forgets the samples of every time record taken at `time` or later.
    pub(crate) fn forget_from(&self, world: &mut World, time: Real) {
        for (_, forget) in &self.records {
            forget(world, time);
        }
    }

    /// Registers the component type `C` under `name`, kept on every body
    /// and block that has it, replacing an earlier registration of that
    /// name. Register components of bodies and blocks only.
    pub fn keep_component<C: Component + Serialize + DeserializeOwned>(&mut self, name: &str) {
        self.register(name, encode_component::<C>, decode_component::<C>);
    }

    /// Registers `name`, replacing an earlier registration of it unless
    /// that one is the engine's.
    ///
    /// # Panics
    /// If `name` is one the engine keeps (see [`KeptState::seal`]): taking
    /// it would drop the engine's state from checkpoints.
    fn register(&mut self, name: &str, encode: Encode, decode: Decode) {
        let kept = Kept {
            name: name.to_owned(),
            encode,
            decode,
        };
        match self.kept.iter().position(|k| k.name == name) {
            Some(k) if k < self.sealed => panic!(
                "the checkpointed state '{name}' is the engine's: keep yours under another name"
            ),
            Some(k) => {
                self.records.retain(|(n, _)| n != name);
                self.kept[k] = kept;
            }
            None => self.kept.push(kept),
        }
    }

    /// Marks every name registered so far as the engine's.
    pub(crate) fn seal(&mut self) {
        self.sealed = self.kept.len();
    }

    /// Encodes every registered type from `world`, whose bodies and blocks
    /// are `holders`; fails if a registered resource is not in the world.
    pub fn save(&self, world: &World, holders: &Holders) -> Result<Vec<StoredState>, StateError> {
        self.kept
            .iter()
            .map(|k| {
                let stored = (k.encode)(world, holders).map_err(|problem| StateError::Named {
                    name: k.name.clone(),
                    problem,
                })?;
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
    ) -> Result<DecodedState, StateError> {
        let mut registered: Vec<&Kept> = self.kept.iter().collect();
        let mut stored = stored;
        registered.sort_unstable_by(|a, b| a.name.cmp(&b.name));
        stored.sort_unstable_by(|a, b| a.0.cmp(&b.0));
        let registered_names: Vec<&str> = registered.iter().map(|k| k.name.as_str()).collect();
        let stored_names: Vec<&str> = stored.iter().map(|(name, _)| name.as_str()).collect();
        if registered_names != stored_names {
            let not_in = |names: &[&str], other: &[&str]| -> Vec<String> {
                names
                    .iter()
                    .filter(|n| !other.contains(n))
                    .map(|n| n.to_string())
                    .collect()
            };
            return Err(StateError::OtherNames {
                extra: not_in(&stored_names, &registered_names),
                missing: not_in(&registered_names, &stored_names),
            });
        }
        let inserts = registered
            .iter()
            .zip(&stored)
            .map(|(kept, (name, stored))| {
                check_holders(stored, holders)
                    .and_then(|()| (kept.decode)(stored))
                    .map_err(|problem| StateError::Named {
                        name: name.clone(),
                        problem,
                    })
            })
            .collect::<Result<Vec<Insert>, StateError>>()?;
        Ok(DecodedState { inserts })
    }
}

/// Components may sit only on the checkpoint's bodies and blocks, once
/// each, in order.
fn check_holders(stored: &Stored, holders: &[Holder]) -> Result<(), Problem> {
    let Stored::Components(values) = stored else {
        return Ok(());
    };
    if let Some(&(holder, _)) = values.iter().find(|(h, _)| !holders.contains(h)) {
        return Err(Problem::UnknownHolder(holder));
    }
    if values.windows(2).any(|pair| pair[0].0 >= pair[1].0) {
        return Err(Problem::Unordered);
    }
    Ok(())
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
fn decode_exactly<T: DeserializeOwned>(bytes: &[u8]) -> Result<T, Problem> {
    let (value, rest): (T, &[u8]) = postcard::take_from_bytes(bytes)?;
    if !rest.is_empty() {
        return Err(Problem::BytesLeft(rest.len()));
    }
    Ok(value)
}

const RESOURCE: &str = "resource";
const COMPONENT: &str = "component";

fn encode_resource<R: Resource + Serialize>(world: &World, _: &Holders) -> Result<Stored, Problem> {
    let resource = world.get_resource::<R>().ok_or(Problem::NotInTheWorld)?;
    Ok(Stored::Resource(postcard::to_allocvec(resource)?))
}

fn decode_resource<R: Resource + DeserializeOwned>(stored: &Stored) -> Result<Insert, Problem> {
    let Stored::Resource(bytes) = stored else {
        return Err(Problem::OtherKind {
            stored: COMPONENT,
            kept: RESOURCE,
        });
    };
    let resource: R = decode_exactly(bytes)?;
    Ok(Box::new(move |world: &mut World, _: &Holders| {
        world.insert_resource(resource);
    }))
}

fn encode_checkpointed<R: Checkpointed>(world: &World, _: &Holders) -> Result<Stored, Problem> {
    let resource = world.get_resource::<R>().ok_or(Problem::NotInTheWorld)?;
    Ok(Stored::Resource(postcard::to_allocvec(&resource.stored())?))
}

fn decode_checkpointed<R: Checkpointed>(stored: &Stored) -> Result<Insert, Problem> {
    let Stored::Resource(bytes) = stored else {
        return Err(Problem::OtherKind {
            stored: COMPONENT,
            kept: RESOURCE,
        });
    };
    let part: R::Stored = decode_exactly(bytes)?;
    Ok(Box::new(move |world: &mut World, _: &Holders| {
        // The registering feature built the resource with the world.
        world.resource_mut::<R>().restore(part);
    }))
}

fn forget_from<R: TimeRecord>(world: &mut World, time: Real) {
    world.resource_mut::<R>().forget_from(time);
}

fn encode_component<C: Component + Serialize>(
    world: &World,
    holders: &Holders,
) -> Result<Stored, Problem> {
    holders
        .iter()
        .filter_map(|&(holder, entity)| Some((holder, world.get::<C>(entity)?)))
        .map(|(holder, component)| Ok((holder, postcard::to_allocvec(component)?)))
        .collect::<Result<_, Problem>>()
        .map(Stored::Components)
}

fn decode_component<C: Component + DeserializeOwned>(stored: &Stored) -> Result<Insert, Problem> {
    let Stored::Components(values) = stored else {
        return Err(Problem::OtherKind {
            stored: RESOURCE,
            kept: COMPONENT,
        });
    };
    let decoded = values
        .iter()
        .map(|(holder, bytes)| Ok((*holder, decode_exactly::<C>(bytes)?)))
        .collect::<Result<Vec<(Holder, C)>, Problem>>()?;
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
