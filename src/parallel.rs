//! How finely the per-point and per-node loops are split between threads.
//! The splits never change the results (sums are formed in a fixed order,
//! see [`crate::scatter`]); they only trade task overhead against balance.

/// Fewest points one parallel task handles in the per-point loops: below
/// this, splitting costs more (thread wake-ups) than it gains, and small
/// bodies run on one thread.
pub const MIN_POINTS_PER_TASK: usize = 1024;

/// Fewest nodes one parallel task handles in the per-node loops: a node
/// update is a few flops, so smaller tasks cost more to hand out than they
/// save (measured on the standard bench: no gain below 4096).
pub const MIN_NODES_PER_TASK: usize = 4096;
