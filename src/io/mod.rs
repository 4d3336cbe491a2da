//! Everything that leaves the engine: CSV time series, VTK files for
//! ParaView, PNG plots and snapshots, the state hash, checkpoints to resume
//! a run from (with the user state they carry), and the run-output
//! folder that ties them together.

pub mod checkpoint;
pub mod csv;
pub mod kept_state;
pub mod manifest;
pub mod output;
pub mod plot;
pub mod state_hash;
pub mod vtk;

pub use output::RunOutput;
