//! The worker threads a simulation steps on.

use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

/// A pool of `threads` workers (default: one per core), each with the
/// main thread's usual 8 MiB stack, as the CLI's.
pub fn thread_pool(threads: Option<usize>) -> PyResult<rayon::ThreadPool> {
    let mut pool = rayon::ThreadPoolBuilder::new().stack_size(8 << 20);
    match threads {
        Some(0) => return Err(PyValueError::new_err("threads must be at least 1")),
        Some(n) => pool = pool.num_threads(n),
        None => {}
    }
    pool.build()
        .map_err(|e| PyRuntimeError::new_err(format!("cannot start the worker threads: {e}")))
}
