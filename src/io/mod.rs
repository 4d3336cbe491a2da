//! A run's results: CSV time series, VTK files for ParaView, PNG plots and
//! snapshots, and the run-output folder that ties them together.

pub(crate) mod animation;
pub mod csv;
pub mod figure;
pub(crate) mod manifest;
pub(crate) mod output;
pub mod plot;
pub(crate) mod vtk;

pub(crate) use output::RunOutput;
