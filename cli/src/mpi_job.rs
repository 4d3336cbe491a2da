//! The command line steps on one process. Started as one of several ranks
//! of an MPI job, it would run the whole scene on each and race for the
//! output folder, so it refuses.

/// This process's rank and the size of the MPI job it was started in, from
/// the variables the launchers set (Open MPI's `mpirun`, and the PMI of
/// MPICH and Slurm's `srun`); `None` outside a job.
pub fn job() -> Option<(usize, usize)> {
    let read = |name: &str| std::env::var(name).ok()?.trim().parse::<usize>().ok();
    [
        ("OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"),
        ("PMI_RANK", "PMI_SIZE"),
    ]
    .iter()
    .find_map(|(rank, size)| Some((read(rank)?, read(size)?)))
}

/// The refusal rank 0 prints for a job of `size` processes.
pub fn refusal(size: usize) -> String {
    format!(
        "error: mpdem runs on one process, and this is rank 0 of an MPI job of {size}: \
         start it without mpirun (one scene on several processes is, for now, the \
         library's distributed step: see docs/distributed.md)"
    )
}
