//! The pool of worker threads a run steps on.

/// The most worker threads a run may ask for: far more than any machine's
/// cores (oversubscribing is allowed), far fewer than would exhaust the
/// process's memory or the system's threads.
pub const MAX_THREADS: usize = 1024;

/// Why a pool of worker threads could not be made.
#[derive(Debug, thiserror::Error)]
pub enum ThreadsError {
    /// No thread asked for.
    #[error("the number of threads must be at least 1")]
    None,
    /// More than [`MAX_THREADS`].
    #[error("the number of threads must be at most {MAX_THREADS}, got {0}")]
    TooMany(usize),
    /// The system refused to start them.
    #[error("cannot start {threads} threads: {source}")]
    Start {
        /// The threads asked for (or rayon's default).
        threads: String,
        /// What failed.
        source: rayon::ThreadPoolBuildError,
    },
}

/// A rayon pool of `threads` workers (default: rayon's, one per core or
/// `RAYON_NUM_THREADS`), each with the main thread's usual 8 MiB stack
/// (rayon's default is 2 MiB) for the scene parsing and stepping that run
/// on a worker. Results never depend on the number of threads.
pub fn worker_pool(threads: Option<usize>) -> Result<rayon::ThreadPool, ThreadsError> {
    let mut pool = rayon::ThreadPoolBuilder::new().stack_size(8 << 20);
    match threads {
        None => {}
        Some(0) => return Err(ThreadsError::None),
        Some(n) if n > MAX_THREADS => return Err(ThreadsError::TooMany(n)),
        Some(n) => pool = pool.num_threads(n),
    }
    pool.build().map_err(|source| ThreadsError::Start {
        threads: threads.map_or("the".into(), |n| n.to_string()),
        source,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_pool_takes_one_to_the_most_threads() {
        assert_eq!(worker_pool(Some(2)).unwrap().current_num_threads(), 2);
        assert!(matches!(worker_pool(Some(0)), Err(ThreadsError::None)));
        assert!(matches!(
            worker_pool(Some(MAX_THREADS + 1)),
            Err(ThreadsError::TooMany(1025))
        ));
    }
}
