#pragma once
/// @file This process's place in an MPI launch (`mpiexec -n N stoss run`, docs/many_machines.md, "One run on
/// several MPI ranks"), read from the launcher's environment before MPI is initialised: the run decides its
/// output directory, its element threads and its linear solver from it, and MPI itself starts only with PETSc
/// (core/solve/petsc_solver.hpp).

namespace stoss::parallel {

/// Rank and number of ranks: {0, 1} for a process of its own.
struct MpiPlace {
  int rank = 0;
  int size = 1;
  bool several() const { return size > 1; }
};

/// From Open MPI's OMPI_COMM_WORLD_RANK / OMPI_COMM_WORLD_SIZE, else the PMI_RANK / PMI_SIZE of MPICH (and of
/// srun --mpi=pmi2), else the SLURM_PROCID / SLURM_STEP_NUM_TASKS of any task srun starts (srun --mpi=pmix
/// sets no PMI_RANK); {0, 1} when none is set or a pair is not a rank below a size of at least 1.
MpiPlace mpi_place();

}  // namespace stoss::parallel
