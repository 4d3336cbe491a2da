//! The native part of the Python package `mpdem`: scenes, simulations
//! stepped from Python with their fields as NumPy arrays, and runs that
//! write what the CLI writes. The package's `mpdem/__init__.py` re-exports
//! it and adds the series as NumPy record arrays and pandas frames.

mod ctrl_c;
mod errors;
mod fields;
mod key_path;
mod run;
mod scene;
mod simulation;
mod threads;

use pyo3::prelude::*;

/// Material point method with DEM-enriched contact: build scenes, run them,
/// and read every field as NumPy arrays.
#[pymodule]
fn _mpdem(module: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(module)?;
    module.add_class::<scene::PyScene>()?;
    module.add_class::<simulation::PySimulation>()?;
    module.add_class::<fields::Body>()?;
    module.add_class::<fields::Block>()?;
    module.add_class::<run::RunSummary>()?;
    module.add_function(wrap_pyfunction!(run::run, module)?)?;
    module.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
