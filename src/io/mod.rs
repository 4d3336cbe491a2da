//! A run's results: CSV time series, VTK files for ParaView, PNG plots and
//! snapshots, and the run-output folder that ties them together.

pub mod csv;
pub mod manifest;
pub mod output;
pub mod plot;
pub mod vtk;

pub use output::RunOutput;
