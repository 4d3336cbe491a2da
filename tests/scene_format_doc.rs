//! `docs/scene-format.md` documents every field and every enum variant a
//! scene file can hold.
//!
//! The names are not listed here: they are traced from the scene types'
//! own `Deserialize` implementations with `serde-reflection`, starting at
//! `mpdem::scene::Scene`, so a field added to any type a scene reaches
//! (settings, materials, shapes, blocks, contact laws, stages, outputs)
//! fails this test until the document names it. Each name must appear as a
//! code span of its own, `` `name` ``, in a table row of the document.
//!
//! Two types validate their input in a way the tracer's made-up values
//! cannot satisfy, and are handled explicitly:
//!
//! * `TimeSpec` is deserialized through a private `TimeInput` and
//!   `TryFrom`, which refuses a time with both `end` and `steps`; the tracer
//!   answers `Some` for every optional field, so it would give both. The
//!   tracer is handed a recorded sample `(dt, end)` for it, and its field
//!   names are read instead from the real type's own field list, which
//!   `FieldNames` below captures as serde hands it to a deserializer.
//! * `MohrCoulomb` checks Poisson's ratio in (−1, 0.5) and the deviatoric
//!   eccentricity in (0.5, 1], which no single made-up number satisfies;
//!   the tracer is handed a valid sample of it, and its field names come
//!   from tracing that sample's serialization (the same derive, the same
//!   names).

use mpdem::materials::MohrCoulomb;
use mpdem::scene::{Scene, TimeSpec};
use serde::Serialize;
use serde::de::{self, Deserialize, Deserializer, Visitor};
use serde_reflection::{ContainerFormat, Registry, Samples, Tracer, TracerConfig, VariantFormat};
use std::collections::BTreeSet;
use std::fmt;

const DOC: &str = "docs/scene-format.md";

/// The tracer's made-up values: every range rule of a scene number holds
/// for 0.25 (> 0, ≥ 0, a Poisson's ratio, a fraction, a damping, an angle
/// in degrees) except the deviatoric eccentricity's (see above); counts
/// must be ≥ 1 (steps, the XPIC order).
fn config() -> TracerConfig {
    TracerConfig::default()
        .record_samples_for_structs(true)
        .default_f64_value(0.25)
        .default_u32_value(1)
        .default_u64_value(1)
}

/// A stand-in that records, under `TimeSpec`'s name, a sample the real
/// `TimeInput` accepts: a step and an end time.
#[derive(Serialize)]
#[serde(rename = "TimeSpec")]
struct TimeSample {
    dt: f64,
    end: f64,
}

/// The samples for the two types the tracer cannot make up (see above).
fn sampled(tracer: &mut Tracer) -> Samples {
    let mut samples = Samples::new();
    tracer
        .trace_value(&mut samples, &TimeSample { dt: 1e-3, end: 1.0 })
        .expect("time sample");
    let mohr_coulomb: MohrCoulomb = ron::from_str(
        "(youngs_modulus: 1e7, poisson_ratio: 0.3, friction_angle: 30.0, deviatoric_eccentricity: Some(0.8), disconnected_above: Some(1.0))",
    )
    .expect("a valid Mohr–Coulomb material");
    tracer
        .trace_value(&mut samples, &mohr_coulomb)
        .expect("Mohr–Coulomb sample");
    samples
}

/// Traces the enum `$ty` through every variant: the tracer explores a
/// list or an option of a type only the first time it meets it, so an enum
/// inside one (a body's shape, a stage's end) shows its first variant only
/// when traced from `Scene`. Rust cannot go from a type's name to the type,
/// so each enum the trace reaches is named here, and
/// [`scene_registry`] fails for one that is not.
macro_rules! enums {
    ($($ty:ty),* $(,)?) => {
        fn trace_enum(tracer: &mut Tracer, samples: &Samples, name: &str) -> bool {
            $(
                if name == stringify!($ty).rsplit("::").next().unwrap() {
                    tracer.trace_type::<$ty>(samples).expect(name);
                    return true;
                }
            )*
            false
        }
    };
}

enums!(
    mpdem::resources::EdgeCondition,
    mpdem::shape_functions::ShapeFunction,
    mpdem::resources::UpdateScheme,
    mpdem::resources::PositionUpdate,
    mpdem::geometry::Geometry,
    mpdem::materials::MaterialModel,
    mpdem::scene::Shape,
    mpdem::scene::InitialVelocity,
    mpdem::scene::InitialStress,
    mpdem::rigid::BlockShape,
    mpdem::scene::MotionSpec,
    mpdem::contact::ForceApplication,
    mpdem::resources::Penetration,
    mpdem::scene::StageEnd,
    mpdem::scene::Side,
    mpdem::scene::AnimatedField,
);

/// The schema of a scene file: `Scene` traced, then every enum it reaches
/// traced through all its variants, until no new enum turns up.
fn scene_registry() -> Registry {
    let mut tracer = Tracer::new(config());
    let samples = sampled(&mut tracer);
    tracer
        .trace_type::<Scene>(&samples)
        .expect("the scene types trace");
    let mut traced: BTreeSet<String> = BTreeSet::new();
    loop {
        // The enums met so far: those of a second tracer that repeats the
        // same steps (the registry can only be read by consuming a tracer).
        let mut probe = Tracer::new(config());
        let probe_samples = sampled(&mut probe);
        probe
            .trace_type::<Scene>(&probe_samples)
            .expect("the scene types trace");
        for name in &traced {
            trace_enum(&mut probe, &probe_samples, name);
        }
        let found: BTreeSet<String> = probe
            .registry_unchecked()
            .into_iter()
            .filter(|(_, format)| matches!(format, ContainerFormat::Enum(_)))
            .map(|(name, _)| name)
            .collect();
        let new: Vec<String> = found.difference(&traced).cloned().collect();
        if new.is_empty() {
            break;
        }
        for name in new {
            assert!(
                trace_enum(&mut tracer, &samples, &name),
                "the scene reaches the enum {name}: add it to `enums!` in this test"
            );
            traced.insert(name);
        }
    }
    tracer
        .registry()
        .expect("every enum of the scene traced through all its variants")
}

/// Every field and variant name of the scene schema, with the type it
/// belongs to.
fn scene_names() -> BTreeSet<(String, String)> {
    let registry = scene_registry();
    let mut names = BTreeSet::new();
    for (container, format) in &registry {
        match format {
            ContainerFormat::Struct(fields) => {
                for field in fields {
                    names.insert((container.clone(), field.name.clone()));
                }
            }
            ContainerFormat::Enum(variants) => {
                for variant in variants.values() {
                    assert!(
                        !matches!(variant.value, VariantFormat::Variable(_)),
                        "{container}::{} was not traced",
                        variant.name
                    );
                    names.insert((container.clone(), variant.name.clone()));
                    if let VariantFormat::Struct(fields) = &variant.value {
                        for field in fields {
                            names.insert((
                                format!("{container}::{}", variant.name),
                                field.name.clone(),
                            ));
                        }
                    }
                }
            }
            _ => {}
        }
    }
    // TimeSpec: the fields of the real type (see the module's comment).
    names.retain(|(container, _)| container != "TimeSpec");
    for field in field_names::<TimeSpec>() {
        names.insert(("TimeSpec".into(), field.to_string()));
    }
    names
}

/// The code spans of the document's table rows: each `` `...` `` of every
/// line that starts with `|`.
fn table_code_spans(doc: &str) -> BTreeSet<String> {
    doc.lines()
        .filter(|line| line.trim_start().starts_with('|'))
        .flat_map(|line| line.split('`').skip(1).step_by(2))
        .map(str::to_string)
        .collect()
}

#[test]
fn the_scene_format_documents_every_field_and_variant() {
    let names = scene_names();
    // The trace reaches the whole schema: a few names from its corners.
    for (container, name) in [
        ("Scene", "stages"),
        ("TimeSpec", "steps"),
        ("Settings", "position_update"),
        ("MohrCoulomb", "deviatoric_eccentricity"),
        ("BlockShape::Compound", "parts"),
        ("StageEnd", "StressChange"),
        ("ForceApplication::Traction", "points"),
        ("CurveSpec", "displacement_label"),
    ] {
        assert!(
            names.contains(&(container.to_string(), name.to_string())),
            "the trace missed {container}.{name}: {names:?}"
        );
    }
    eprintln!("{} scene fields and variants traced", names.len());
    let doc = std::fs::read_to_string(DOC).expect("docs/scene-format.md");
    let documented = table_code_spans(&doc);
    let missing: Vec<String> = names
        .iter()
        .filter(|(_, name)| !documented.contains(name))
        .map(|(container, name)| format!("`{name}` (in {container})"))
        .collect();
    assert!(
        missing.is_empty(),
        "{DOC} does not name these scene fields or variants as a code span in a table row:\n  {}",
        missing.join("\n  ")
    );
}

/// The field names that `T`'s `Deserialize` passes to `deserialize_struct`,
/// read by a deserializer that stops there.
fn field_names<'de, T: Deserialize<'de>>() -> &'static [&'static str] {
    match T::deserialize(FieldNames) {
        Err(Stop(Some(fields))) => fields,
        Err(Stop(None)) => panic!("{} is not read as a struct", std::any::type_name::<T>()),
        Ok(_) => unreachable!("FieldNames yields no value"),
    }
}

/// A deserializer that records the field list of the first struct asked of
/// it and gives up.
struct FieldNames;

/// The end of a [`FieldNames`] deserialization, with the fields if a
/// struct was asked for.
#[derive(Debug)]
struct Stop(Option<&'static [&'static str]>);

impl fmt::Display for Stop {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "stopped at {:?}", self.0)
    }
}

impl std::error::Error for Stop {}

impl de::Error for Stop {
    fn custom<M: fmt::Display>(_: M) -> Self {
        Stop(None)
    }
}

impl<'de> Deserializer<'de> for FieldNames {
    type Error = Stop;

    fn deserialize_any<V: Visitor<'de>>(self, _: V) -> Result<V::Value, Stop> {
        Err(Stop(None))
    }

    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _: &'static str,
        fields: &'static [&'static str],
        _: V,
    ) -> Result<V::Value, Stop> {
        Err(Stop(Some(fields)))
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string
        bytes byte_buf option unit unit_struct newtype_struct seq tuple
        tuple_struct map enum identifier ignored_any
    }
}
