//! The worker threads a simulation steps on.

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

/// The engine's pool of `threads` workers (default: one per core), as the
/// CLI's; a count out of range is a `ValueError`.
pub fn thread_pool(threads: Option<usize>) -> PyResult<rayon::ThreadPool> {
    use mpdem::threads::{ThreadsError, worker_pool};
    worker_pool(threads).map_err(|e| match e {
        ThreadsError::Start { .. } => PyRuntimeError::new_err(e.to_string()),
        _ => PyValueError::new_err(format!("threads: {e}")),
    })
}
