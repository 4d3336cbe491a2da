//! Checkpoints: the whole changing state of a run in one file, so that a
//! long run can be resumed after a stop, or carried on to a later end
//! time, and continue bit-identically to a run that never stopped.
//!
//! A checkpoint holds what the steps change: the clock, every body's
//! points (and the energy damping has taken from it), every block present
//! (pose, velocity, reaction, neighbour list, contacts with their
//! tangential springs), and the state that the features and user systems
//! registered by name: the settings, gravity and grid edges as the
//! stages left them, the springs between bodies and between blocks, where
//! the run is in its stages, and every record the outputs are written
//! from. What the scene fixes (shapes, materials, laws, the grid) is
//! rebuilt from the scene, so a checkpoint resumes only the scene it was
//! written for: its name, `time.end` and `output` (but `output.fronts`) may change, nothing
//! else. Scratch buffers and the layers' node windows are not kept: they
//! do not change the results. State that user systems keep, in resources
//! or in components on the bodies and blocks, is carried once registered
//! ([`crate::Simulation::keep_in_checkpoints`],
//! [`crate::Simulation::keep_components_in_checkpoints`], or a plugin's
//! [`crate::plugins::PluginSetup`]); components on entities of their own
//! are not.
//!
//! The file is binary: eight magic bytes, the layout's number (`u32`,
//! little-endian), the state's length in bytes (`u64`) and its CRC-32
//! (`u32`, both little-endian), then the state (`postcard`), every real
//! number stored exactly. A file whose length or checksum does not match
//! (a flipped bit, a partial copy) is refused before anything is read
//! from it.

use crate::components::{
    BlockContacts, BlockId, BlockTemplate, DampedEnergy, MaterialPoints, NeighbourList,
    PartReactions, Pose, Reaction, RigidMotion, RigidVelocity, StepTravel, bodies_in_scene_order,
};
mod kept_state;
mod state_hash;

pub use kept_state::Holder;
pub use kept_state::{Checkpointed, Problem, StateError, TimeRecord};
pub(crate) use kept_state::{KeptState, StoredState};
pub(crate) use state_hash::StateHasher;

use crate::math::Real;
use crate::resources::{Clock, Sampling, StagePlan};
use crate::scene::{OutputSpec, Scene, SceneError, Shape};
use bevy_ecs::prelude::*;
use serde::{Deserialize, Serialize};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::{Path, PathBuf};

/// The file's first bytes.
const MAGIC: &[u8; 8] = b"MPDEMCK\0";

/// The bytes before the state: magic, layout, length and checksum.
const HEADER_BYTES: usize = 8 + 4 + 8 + 4;

/// The state after the layout's number, once its length and CRC-32 match
/// those stored before it; otherwise what does not match.
fn checked_payload(stored: &[u8]) -> Result<&[u8], Damage> {
    let Some((length, stored)) = stored.split_first_chunk::<8>() else {
        return Err(Damage::NoLength);
    };
    let Some((checksum, payload)) = stored.split_first_chunk::<4>() else {
        return Err(Damage::NoChecksum);
    };
    let header = u64::from_le_bytes(*length);
    if header != payload.len() as u64 {
        return Err(Damage::Length {
            found: payload.len(),
            header,
        });
    }
    let (header, computed) = (u32::from_le_bytes(*checksum), crc32fast::hash(payload));
    if header != computed {
        return Err(Damage::Checksum { computed, header });
    }
    Ok(payload)
}

/// How a checkpoint's state fails its header.
#[derive(Debug, thiserror::Error)]
pub enum Damage {
    /// The file ends before the state's length.
    #[error("it ends before its length")]
    NoLength,
    /// The file ends before the state's checksum.
    #[error("it ends before its checksum")]
    NoChecksum,
    /// The state's length is not the header's.
    #[error("{found} bytes of state where its header says {header}")]
    Length {
        /// The state's length.
        found: usize,
        /// The header's.
        header: u64,
    },
    /// The state's CRC-32 is not the header's.
    #[error("CRC-32 {computed:08x} where its header says {header:08x}")]
    Checksum {
        /// The state's.
        computed: u32,
        /// The header's.
        header: u32,
    },
}

/// Why a file is not a checkpoint of this scene that this version can read.
#[derive(Debug, thiserror::Error)]
pub enum FormatProblem {
    /// It does not start with the magic bytes.
    #[error("it does not start as one")]
    NotACheckpoint,
    /// It ends within its header.
    #[error("it ends after its first bytes")]
    Truncated,
    /// It has another layout.
    #[error(
        "layout {found} where this version reads {FORMAT}: written by another version of mpdem, or damaged"
    )]
    Layout {
        /// The file's layout.
        found: u32,
    },
    /// Its state cannot be decoded.
    #[error("its state cannot be read: {0}")]
    Unreadable(postcard::Error),
    /// Bytes follow its state.
    #[error("{0} bytes follow its state")]
    BytesLeft(usize),
    /// Its bodies are not the scene's.
    #[error("its bodies are not the scene's")]
    OtherBodies,
    /// It has a block the scene does not.
    #[error("it has a block {0} the scene does not")]
    UnknownBlock(usize),
    /// It has a block absent at the start that no stage adds.
    #[error("it has block {0}, which no stage adds")]
    NotAdded(usize),
    /// A block could not be spawned again.
    #[error("block {0} could not be spawned")]
    NotSpawned(u32),
    /// Its kept state does not fit the run's.
    #[error(transparent)]
    State(#[from] StateError),
}

/// The layout of the stored state; a checkpoint of another layout is
/// refused rather than misread (CHANGELOG.md names what each changed).
const FORMAT: u32 = 20;

impl CheckpointError {
    /// The error, naming the checkpoint file `path` where it names a file.
    fn at(self, path: &Path) -> Self {
        let path = path.to_path_buf();
        match self {
            Self::Encode { source, .. } => Self::Encode { path, source },
            Self::EncodeWhole { source, .. } => Self::EncodeWhole { path, source },
            other => other,
        }
    }
}

/// Why a checkpoint could not be written or resumed.
#[derive(Debug, thiserror::Error)]
pub enum CheckpointError {
    /// Reading or writing the file failed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The checkpoint file.
        path: PathBuf,
        /// What failed.
        source: std::io::Error,
    },
    /// The kept state could not be encoded.
    #[error("{}: cannot encode the run's state: {source}", path.display())]
    Encode {
        /// The checkpoint file.
        path: PathBuf,
        /// What failed.
        source: StateError,
    },
    /// The whole state could not be encoded.
    #[error("{}: cannot encode the run's state: {source}", path.display())]
    EncodeWhole {
        /// The checkpoint file.
        path: PathBuf,
        /// What failed.
        source: postcard::Error,
    },
    /// The file's state does not match its length or checksum.
    #[error("{}: the checkpoint is damaged ({damage}); it is left as it is", path.display())]
    Damaged {
        /// The checkpoint file.
        path: PathBuf,
        /// What did not match.
        damage: Damage,
    },
    /// The file is not a checkpoint this version can read.
    #[error("{}: not a checkpoint of this mpdem ({problem})", path.display())]
    Format {
        /// The checkpoint file.
        path: PathBuf,
        /// What was wrong.
        problem: FormatProblem,
    },
    /// The checkpoint was written for another scene.
    #[error(
        "{}: written for a different scene ({changes}); between a run and its resumption only the scene's name, time.end and output (but output.fronts) may change",
        path.display()
    )]
    OtherScene {
        /// The checkpoint file.
        path: PathBuf,
        /// What differs in the scene from the one the checkpoint was
        /// written for.
        changes: String,
    },
    /// The scene itself could not be built.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The simulation's last step was cut short: its state is half updated
    /// and is not written.
    #[error(
        "{}: not written: the step in progress was cut short, so the state is half updated",
        path.display()
    )]
    CutShort {
        /// The checkpoint file.
        path: PathBuf,
    },
    /// A checkpoint was to be restored into a simulation that cannot take
    /// it (one that has stepped, or was built from another scene).
    #[error("cannot restore {}: {reason}", path.display())]
    Restore {
        /// The checkpoint file.
        path: PathBuf,
        /// Why.
        reason: &'static str,
    },
}

/// Everything a checkpoint stores.
#[derive(Serialize, Deserialize)]
struct RunState {
    scene: SceneFingerprint,
    step: u64,
    /// Every body in scene order: its entity (bodies are spawned first and
    /// never removed, so a rebuilt world gives them the same entities,
    /// which the neighbour lists and loads refer to), its points and how
    /// far they moved in the last step (the neighbour lists' next
    /// rebuild depends on it) and the energy damping has taken from it.
    bodies: Vec<(Entity, MaterialPoints, StepTravel, DampedEnergy)>,
    /// The blocks present, in scene order.
    blocks: Vec<BlockState>,
    /// The steps between samples of the run that wrote the checkpoint: a
    /// sample at its step off that interval was taken because the run
    /// ended there.
    sample_every: u64,
    /// The state the features and user systems registered, by name.
    kept: Vec<StoredState>,
}

/// One block's changing state.
#[derive(Serialize, Deserialize)]
struct BlockState {
    index: u32,
    pose: Pose,
    velocity: RigidVelocity,
    motion: RigidMotion,
    reaction: Reaction,
    parts: PartReactions,
    neighbours: NeighbourList,
    contacts: BlockContacts,
}

/// A scene as a checkpoint identifies it, up to what a resumed run may
/// change (its name, `time.end` and `output` but `output.fronts`, whose
/// record from the start the checkpoint holds or not): a hash of each of
/// its parts, in scene order, so that a refusal can say which parts differ.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub(crate) struct SceneFingerprint {
    /// Each part's label, as a user would name it, and its hash.
    parts: Vec<(String, u64)>,
}

impl SceneFingerprint {
    /// The fingerprint of `scene`.
    pub(crate) fn of(scene: &Scene) -> Self {
        let mut fixed = scene.clone();
        fixed.name = None;
        fixed.time.end = 0.0;
        fixed.output = OutputSpec::default();
        // A point list's line numbers are for messages: a comment added to
        // the file does not make another scene.
        for body in &mut fixed.bodies {
            if let Shape::Points { points, .. } = &mut body.shape {
                points.iter_mut().for_each(|p| p.line = 0);
            }
        }
        let mut parts = vec![
            part("`grid`", &fixed.grid),
            part("`time`", &fixed.time),
            part("`gravity`", &fixed.gravity),
            part("`settings`", &fixed.settings),
            part("`contact`", &fixed.contact),
            part("`output.fronts`", &scene.output.fronts),
        ];
        parts.extend(named_parts("material", &fixed.materials, |m| &m.name));
        parts.extend(named_parts("body", &fixed.bodies, |b| &b.name));
        parts.extend(named_parts("block", &fixed.blocks, |b| &b.name));
        parts.extend(named_parts("probe", &fixed.probes, |p| &p.name));
        parts.extend(named_parts("stage", &fixed.stages, |s| &s.name));
        parts.extend(listed_parts("body_contacts", &fixed.body_contacts));
        parts.extend(listed_parts("block_contacts", &fixed.block_contacts));
        Self { parts }
    }

    /// What differs in `self` from `earlier`, for a message: the parts
    /// changed, added or removed, or, when each part is the same, their
    /// order.
    fn changes_since(&self, earlier: &Self) -> String {
        let hash_in = |fingerprint: &Self, label: &str| {
            let mut parts = fingerprint.parts.iter();
            parts.find(|(l, _)| l == label).map(|(_, hash)| *hash)
        };
        let mut changes: Vec<String> = Vec::new();
        for (label, hash) in &self.parts {
            match hash_in(earlier, label) {
                None => changes.push(format!("{label} added")),
                Some(before) if before != *hash => changes.push(format!("{label} changed")),
                Some(_) => {}
            }
        }
        for (label, _) in &earlier.parts {
            if hash_in(self, label).is_none() {
                changes.push(format!("{label} removed"));
            }
        }
        if changes.is_empty() {
            "the order of its parts changed".into()
        } else {
            changes.join(", ")
        }
    }
}

/// The parts of a list of named entries, each labelled `kind "name"`.
fn named_parts<'a, T: std::fmt::Debug>(
    kind: &'a str,
    entries: &'a [T],
    name: impl Fn(&T) -> &str + 'a,
) -> impl Iterator<Item = (String, u64)> + 'a {
    entries
        .iter()
        .map(move |e| part(&format!("{kind} \"{}\"", name(e)), e))
}

/// The parts of a list of unnamed entries, each labelled by its place in
/// the scene's `field`, from 1.
fn listed_parts<'a, T: std::fmt::Debug>(
    field: &'a str,
    entries: &'a [T],
) -> impl Iterator<Item = (String, u64)> + 'a {
    let label = move |k: usize| format!("`{field}` entry {}", k + 1);
    entries
        .iter()
        .enumerate()
        .map(move |(k, e)| part(&label(k), e))
}

/// A part of a scene's fingerprint: its label and the hash of its value.
fn part(label: &str, value: &impl std::fmt::Debug) -> (String, u64) {
    let mut hasher = StateHasher::default();
    // Writing into the hasher cannot fail.
    let _ = write!(hasher, "{value:?}");
    (label.to_string(), hasher.finish())
}

/// The world's state as a checkpoint stores it (`postcard`), without the
/// file's header; an encoding error names no file.
pub(crate) fn encoded_state(
    world: &mut World,
    fingerprint: &SceneFingerprint,
    kept: &KeptState,
) -> Result<Vec<u8>, CheckpointError> {
    let holders = holders(world);
    let stored = kept
        .save(world, &holders)
        .map_err(|source| CheckpointError::Encode {
            path: PathBuf::new(),
            source,
        })?;
    let state = capture(world, fingerprint, stored);
    postcard::to_stdvec(&state).map_err(|source| CheckpointError::EncodeWhole {
        path: PathBuf::new(),
        source,
    })
}

/// Writes the world's state to `path`, through a temporary file renamed
/// into place, so a stop while writing leaves the previous checkpoint.
pub(crate) fn write_checkpoint(
    world: &mut World,
    fingerprint: &SceneFingerprint,
    kept: &KeptState,
    path: &Path,
) -> Result<(), CheckpointError> {
    let payload = encoded_state(world, fingerprint, kept).map_err(|e| e.at(path))?;
    let mut bytes = Vec::with_capacity(HEADER_BYTES + payload.len());
    bytes.extend_from_slice(MAGIC);
    bytes.extend_from_slice(&FORMAT.to_le_bytes());
    bytes.extend_from_slice(&(payload.len() as u64).to_le_bytes());
    bytes.extend_from_slice(&crc32fast::hash(&payload).to_le_bytes());
    bytes.extend_from_slice(&payload);
    // Named like the outputs' temporary files, so a new run into the
    // folder removes one that a killed run left.
    let partial = crate::files::partial_path(path);
    let write = || -> std::io::Result<()> {
        let mut file = std::fs::File::create(&partial)?;
        file.write_all(&bytes)?;
        file.sync_all()
    };
    write().map_err(|source| {
        std::fs::remove_file(&partial).ok();
        CheckpointError::Io {
            path: partial.clone(),
            source,
        }
    })?;
    std::fs::rename(&partial, path).map_err(|source| CheckpointError::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// Puts the state stored in `path` into `world`, freshly spawned from the
/// scene whose fingerprint is `fingerprint`, with the user state of
/// `kept`.
pub(crate) fn restore_checkpoint(
    world: &mut World,
    scene: &Scene,
    fingerprint: &SceneFingerprint,
    kept: &KeptState,
    path: &Path,
) -> Result<(), CheckpointError> {
    let format_error = |problem: FormatProblem| CheckpointError::Format {
        path: path.to_path_buf(),
        problem,
    };
    let bytes = std::fs::read(path).map_err(|source| CheckpointError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let Some(stored) = bytes.strip_prefix(MAGIC) else {
        return Err(format_error(FormatProblem::NotACheckpoint));
    };
    let Some((format, stored)) = stored.split_first_chunk::<4>() else {
        return Err(format_error(FormatProblem::Truncated));
    };
    let format = u32::from_le_bytes(*format);
    if format != FORMAT {
        return Err(format_error(FormatProblem::Layout { found: format }));
    }
    let stored = checked_payload(stored).map_err(|damage| CheckpointError::Damaged {
        path: path.to_path_buf(),
        damage,
    })?;
    let (state, rest): (RunState, &[u8]) = postcard::take_from_bytes(stored)
        .map_err(|e| format_error(FormatProblem::Unreadable(e)))?;
    if !rest.is_empty() {
        return Err(format_error(FormatProblem::BytesLeft(rest.len())));
    }
    if state.scene != *fingerprint {
        return Err(CheckpointError::OtherScene {
            path: path.to_path_buf(),
            changes: fingerprint.changes_since(&state.scene),
        });
    }
    let bodies = bodies_in_scene_order(world);
    if bodies.len() != state.bodies.len()
        || bodies.iter().zip(&state.bodies).any(|(e, s)| *e != s.0)
    {
        return Err(format_error(FormatProblem::OtherBodies));
    }
    apply(world, scene, state, kept).map_err(format_error)
}

fn capture(world: &mut World, fingerprint: &SceneFingerprint, kept: Vec<StoredState>) -> RunState {
    let bodies = bodies_in_scene_order(world)
        .into_iter()
        .filter_map(|e| {
            let travel = world.get::<StepTravel>(e).copied().unwrap_or_default();
            let damped = world.get::<DampedEnergy>(e).copied().unwrap_or_default();
            Some((e, world.get::<MaterialPoints>(e)?.clone(), travel, damped))
        })
        .collect();
    let mut blocks: Vec<BlockState> = world
        .query::<(
            &BlockId,
            &Pose,
            &RigidVelocity,
            &RigidMotion,
            &Reaction,
            &PartReactions,
            &NeighbourList,
            &BlockContacts,
        )>()
        .iter(world)
        .map(
            |(id, pose, velocity, motion, reaction, parts, neighbours, contacts)| BlockState {
                index: id.index,
                pose: *pose,
                velocity: *velocity,
                motion: *motion,
                reaction: *reaction,
                parts: parts.clone(),
                neighbours: neighbours.clone(),
                contacts: contacts.clone(),
            },
        )
        .collect();
    blocks.sort_unstable_by_key(|b| b.index);
    RunState {
        scene: fingerprint.clone(),
        step: world.resource::<Clock>().step,
        bodies,
        blocks,
        sample_every: sample_every(world),
        kept,
    }
}

fn apply(
    world: &mut World,
    scene: &Scene,
    state: RunState,
    kept: &KeptState,
) -> Result<(), FormatProblem> {
    // First what can be refused without having changed the world: the
    // kept state, all decoded before any is put in, once the blocks are.
    // A block the scene lacks is found after the points are in: a world
    // whose restore failed is to be discarded.
    let stored_holders: Vec<Holder> = (0..state.bodies.len() as u32)
        .map(Holder::Body)
        .chain(state.blocks.iter().map(|b| Holder::Block(b.index)))
        .collect();
    let decoded = kept.decode(state.kept, &stored_holders)?;
    {
        let mut clock = world.resource_mut::<Clock>();
        clock.step = state.step;
        clock.time = state.step as Real * clock.dt;
    }
    // The bodies were checked to be the world's, in order.
    for (entity, points, travel, damped) in state.bodies {
        world.entity_mut(entity).insert((points, travel, damped));
    }
    restore_blocks(world, scene, state.blocks)?;
    let holders = holders(world);
    decoded.insert(world, &holders);
    kept.run_after_restore(world);
    drop_the_end_sample(world, kept, state.sample_every);
    Ok(())
}

/// The steps between two samples of the records.
fn sample_every(world: &World) -> u64 {
    world.get_resource::<Sampling>().map_or(1, |s| s.every)
}

/// A run samples its last step even off its sampling interval (`stored`
/// steps). If the resumed run goes on past that step and its own interval
/// does not sample it either, a run of the resumed scene that never stopped
/// has no sample there: it is taken back from every record.
fn drop_the_end_sample(world: &mut World, kept: &KeptState, stored: u64) {
    let clock = *world.resource::<Clock>();
    let every = sample_every(world).max(1);
    let sampled_as_the_end = !clock.step.is_multiple_of(stored.max(1));
    if clock.finished() || !sampled_as_the_end || clock.step.is_multiple_of(every) {
        return;
    }
    kept.forget_from(world, clock.time - 0.5 * clock.dt);
}

/// The world's bodies and blocks, each named by its index in the scene.
fn holders(world: &mut World) -> Vec<(Holder, Entity)> {
    let bodies = bodies_in_scene_order(world);
    let mut holders: Vec<(Holder, Entity)> = (0..)
        .map(Holder::Body)
        .zip(bodies)
        .chain(
            world
                .query::<(Entity, &BlockId)>()
                .iter(world)
                .map(|(e, id)| (Holder::Block(id.index), e)),
        )
        .collect();
    holders.sort_unstable_by_key(|&(holder, _)| holder);
    holders
}

/// Makes the blocks present those of the checkpoint (stages may have added
/// or removed some), then gives each its stored state.
fn restore_blocks(
    world: &mut World,
    scene: &Scene,
    blocks: Vec<BlockState>,
) -> Result<(), FormatProblem> {
    let present = |world: &mut World| -> Vec<(Entity, u32)> {
        world
            .query::<(Entity, &BlockId)>()
            .iter(world)
            .map(|(e, id)| (e, id.index))
            .collect()
    };
    for (entity, index) in present(world) {
        if !blocks.iter().any(|b| b.index == index) {
            world.despawn(entity);
        }
    }
    let spawned = present(world);
    // A block absent now was added by a stage: its template is the plan's.
    let absent: Vec<BlockTemplate> = world
        .get_resource::<StagePlan>()
        .map(|plan| plan.absent_blocks.clone())
        .unwrap_or_default();
    for block in &blocks {
        let index = block.index as usize;
        if index >= scene.blocks.len() {
            return Err(FormatProblem::UnknownBlock(index));
        }
        if !spawned.iter().any(|(_, i)| *i == block.index) {
            let template = absent
                .iter()
                .find(|t| t.id.index == block.index)
                .ok_or(FormatProblem::NotAdded(index))?;
            template.spawn(world);
        }
    }
    let present = present(world);
    for block in blocks {
        let Some(&(entity, _)) = present.iter().find(|(_, i)| *i == block.index) else {
            return Err(FormatProblem::NotSpawned(block.index));
        };
        world.entity_mut(entity).insert((
            block.pose,
            block.velocity,
            block.motion,
            block.reaction,
            block.parts,
            block.neighbours,
            block.contacts,
        ));
    }
    Ok(())
}
