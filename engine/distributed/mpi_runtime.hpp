#pragma once
// MPI for the whole program, initialised once by the first piece that needs it. Under mpirun the program
// is one rank of the job; without it Open MPI's singleton mode makes it a job of one rank (also as root,
// since only mpirun refuses root). hypre needs MPI even in a serial run (Debian's libhypre is built against
// Open MPI), so every run starts it. Only the thread that called this calls MPI (MPI_THREAD_FUNNELED): the
// task graph's workers never do. MPI is finalised at exit, after whatever registered its own finalisation
// later (hypre's).
namespace rift {

struct MpiRank {
  int rank = 0;
  int size = 1;
};

// Idempotent; throws Error when MPI_Init_thread fails or grants less than MPI_THREAD_FUNNELED.
MpiRank mpi_runtime_init();

// The rank and size of the job this process was launched in, from the launcher's environment (Open MPI's
// mpirun, Hydra's and Slurm's PMI), without starting MPI: {0, 1} for a process started on its own.
MpiRank launched_rank();

}  // namespace rift
