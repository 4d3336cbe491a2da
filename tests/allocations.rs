//! The step allocates nothing once its buffers are sized (the project's
//! rule for the hot loops): a counting allocator wraps the system one, and
//! each scene takes steps after a warm-up with the count running, on a
//! rayon pool as `mpdem run` does. One test in this binary, so no other
//! test's allocations are counted.

mod common;

use mpdem::prelude::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};

/// The system allocator, counting allocations and reallocations while
/// `COUNTING` is set (on every thread: rayon's workers allocate for the
/// step too).
struct CountingAllocator;

static COUNTING: AtomicBool = AtomicBool::new(false);
static ALLOCATIONS: AtomicU64 = AtomicU64::new(0);

fn count() {
    if COUNTING.load(Ordering::Relaxed) {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
    }
}

// SAFETY: every call is passed unchanged to `System`, which upholds the
// `GlobalAlloc` contract; counting touches only atomics.
unsafe impl GlobalAlloc for CountingAllocator {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: forwarded with the caller's guarantees.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        count();
        // SAFETY: forwarded with the caller's guarantees.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        // SAFETY: forwarded with the caller's guarantees.
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded with the caller's guarantees.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: CountingAllocator = CountingAllocator;

/// Allocations during `steps` steps of `sim`.
fn allocations_in_steps(sim: &mut Simulation, steps: usize) -> u64 {
    ALLOCATIONS.store(0, Ordering::SeqCst);
    COUNTING.store(true, Ordering::SeqCst);
    let mut failure = None;
    for _ in 0..steps {
        if let Err(e) = sim.step() {
            failure = Some(e);
            break;
        }
    }
    COUNTING.store(false, Ordering::SeqCst);
    if let Some(e) = failure {
        panic!("{e}");
    }
    ALLOCATIONS.load(Ordering::SeqCst)
}

/// The scene built and stepped `steps` times.
fn warmed_up(scene: &Scene, steps: usize) -> Simulation {
    let mut sim = Simulation::from_scene(scene).unwrap_or_else(|e| panic!("{e}"));
    for _ in 0..steps {
        sim.step().unwrap_or_else(|e| panic!("{e}"));
    }
    sim
}

#[test]
fn steps_allocate_nothing_once_warmed_up() {
    // One pool for the whole test, its threads started before any count.
    common::with_threads(2, every_scene_steps_without_allocating);
}

fn every_scene_steps_without_allocating() {
    let mut rings = common::load_scene("two_rings.ron");
    for body in &mut rings.bodies {
        body.points_per_cell = 1;
    }
    let mut column = common::load_scene("column_collapse.ron");
    for body in &mut column.bodies {
        body.points_per_cell = 1;
    }
    let mut pile = common::load_scene("pile_penetration.ron");
    pile.grid.cell_size = 0.16;
    pile.grid.cells = (50, 35);
    pile.time.dt = 2e-4;
    let mut driven = Simulation::from_scene(&pile).unwrap_or_else(|e| panic!("{e}"));
    while driven.stage_index().is_some_and(|s| s < 2) {
        driven.step().unwrap_or_else(|e| panic!("{e}"));
    }
    // The same as a body of revolution.
    pile.settings.geometry = mpdem::resources::Geometry::Axisymmetric;
    let mut revolved = Simulation::from_scene(&pile).unwrap_or_else(|e| panic!("{e}"));
    while revolved.stage_index().is_some_and(|s| s < 2) {
        revolved.step().unwrap_or_else(|e| panic!("{e}"));
    }
    // A dynamic block falling in a stage that ends when the kinetic energy
    // (of bodies and dynamic blocks) has settled.
    let drop = common::settling_drop();
    let mut report = Vec::new();
    let mut measure = |name: &str, sim: &mut Simulation, steps: usize| {
        let n = allocations_in_steps(sim, steps);
        report.push(format!("{name}: {n} allocations in {steps} steps"));
    };
    measure(
        "wave_1d",
        &mut warmed_up(&common::load_scene("wave_1d.ron"), 20),
        100,
    );
    // Point-block contacts and a block's neighbour lists.
    measure(
        "sliding_45",
        &mut warmed_up(&common::load_scene("sliding_45.ron"), 50),
        200,
    );
    // Body-body contacts as the rings separate (from 2.2 ms; while contact
    // spreads, the contact buffers may still grow to their largest size: a
    // detection chunk's buffers last grow at step 2170, and the rings'
    // layer window, which a body that leaves it grows, between steps 2200
    // and 2400).
    measure("two_rings", &mut warmed_up(&rings, 2400), 200);
    // Mohr–Coulomb soil, a compound kinematic block, stage conditions.
    measure("pile_penetration", &mut driven, 200);
    measure("pile_penetration, axisymmetric", &mut revolved, 200);
    // Drucker–Prager, a spreading body (after its first energy sample, at
    // step 100, which sizes the sampling's scratch).
    measure("column_collapse", &mut warmed_up(&column, 300), 200);
    // In the fall, before the box reaches the ground (step 1 400). A stage
    // takes its plan out of the world and puts it back each step; a world
    // that kept every removal's record grew it at steps 128 and 256.
    measure("rigid_drop, staged", &mut warmed_up(&drop, 100), 200);
    println!("{}", report.join("\n"));
    assert!(
        report.iter().all(|line| line.contains(": 0 allocations")),
        "{}",
        report.join("\n")
    );
}
