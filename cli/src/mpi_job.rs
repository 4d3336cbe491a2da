//! mpdem as one of several ranks of an MPI job. Built with the `mpi`
//! feature, `run` steps the scene over the job's ranks and `check` checks
//! on rank 0; `verify` and `bench` run on one process. Built without it,
//! every command refuses: each rank would run the whole scene and race for
//! the output folder.

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

/// Why `command` does not run as rank 0 of a job of `size`, if it does
/// not.
pub fn refusal(command: &str, size: usize) -> Option<String> {
    if !cfg!(feature = "mpi") {
        return Some(format!(
            "error: this mpdem was built without MPI, and this is rank 0 of an MPI job of \
             {size}: build it with `--features mpi` to run a scene over the job's ranks \
             (see docs/distributed.md), or start it without mpirun"
        ));
    }
    matches!(command, "verify" | "bench").then(|| {
        format!(
            "error: mpdem {command} runs on one process, and this is rank 0 of an MPI job \
             of {size}: start it without mpirun"
        )
    })
}

/// The job's transport, its panic hook set: a panic on any rank names the
/// rank and ends the whole job, which would otherwise wait for the rank's
/// messages. Call it once, on the thread that steps the run: it is the
/// one thread that talks to MPI.
#[cfg(feature = "mpi")]
pub fn join() -> Box<dyn mpdem::distributed::Transport> {
    use mpdem::distributed::{MpiRanks, Transport};
    let ranks = MpiRanks::init().expect("MPI is initialized once, here");
    let (rank, size) = (ranks.rank(), ranks.ranks());
    let default_hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        eprintln!("rank {rank} of {size} failed:");
        default_hook(info);
        MpiRanks::abort(101);
    }));
    Box::new(ranks)
}
