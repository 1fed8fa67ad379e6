#pragma once
/// @file The PETSc path of LinearSolver: GMRES preconditioned by PETSc's smoothed-aggregation
/// algebraic multigrid (GAMG), with the rigid-body modes of the nodes as near-null space.
///
/// The PETSc code lives in a module of its own (core/solve/petsc/, `libstoss_petsc.so`), loaded with
/// dlopen on first use: PETSc and MPI cost ~40 ms of dynamic loading per process, which every run
/// that does not ask for this path would pay otherwise.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/solve/block_pattern.hpp"

namespace stoss::solve {

/// One Krylov solve: converged (relative residual ≤ the tolerance) in `iterations` iterations.
struct KrylovOutcome {
  bool converged = false;
  int iterations = 0;
};

/// A Krylov solver with an algebraic multigrid preconditioner on one matrix at a time.
///
/// Unknowns: the first `positions.size()` rows are node positions (3 per node, x y z); the rows after
/// them (contact multipliers and mixed contact unknowns) form a second field. With no such rows the
/// preconditioner is GAMG on the whole matrix (block size 3). With them it is a Schur-complement
/// field split (lower factorisation): GAMG on the position block, and an LU of the approximate Schur
/// complement S ≈ A₁₁ − A₁₀ diag(A₀₀)⁻¹ A₀₁ for the contact unknowns (PETSc's "selfp").
class AmgSolver {
 public:
  virtual ~AmgSolver() = default;
  /// Takes A (values copied; the pattern kept while `generation` stays the same) and sets up the
  /// preconditioner. `positions` gives the rigid-body modes (MatNullSpaceCreateRigidBody); when
  /// empty, GAMG uses its default near-null space (translations). Returns false on a PETSc error.
  virtual bool factorize(const SparseMatrix& A, int generation, const Eigen::VectorXd& positions) = 0;
  /// Relative residual ‖b − A x‖ / ‖b‖ a solve stops at (amg_default_tolerance until set).
  virtual void set_tolerance(double relative) = 0;
  /// Solves A x = b with GMRES (right preconditioned, so the test is on ‖b − A x‖ / ‖b‖).
  virtual KrylovOutcome solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) = 0;
  /// The matrix of the last factorize() (for a direct fallback).
  virtual SparseMatrix matrix() const = 0;
  /// One line: the Krylov method, how many setups used GAMG on the whole matrix and how many the field
  /// split, with the GAMG levels of the last of each.
  virtual std::string description() const = 0;
};

/// Relative residual a solve stops at by default: Newton is the outer iteration and corrects the rest
/// (an inexact Newton step). On the tumbling sphere (7680 hex8) 1e-4 left Newton's iterations per
/// step unchanged against 1e-10 (8.5) and cut GMRES's from 12.8 to 4.6 per solve; 1e-2 added one
/// Newton iteration per step.
constexpr double amg_default_tolerance = 1e-4;
/// Iterations a solve may take; then LinearSolver falls back to LU.
constexpr int amg_max_iterations = 200;

/// Loads the PETSc module (initialising PETSc and MPI once per process) and makes a solver.
/// Throws std::runtime_error naming the module path and the loader's message if it cannot.
std::unique_ptr<AmgSolver> make_petsc_amg_solver();

/// The same interface over MUMPS's LU through PETSc (KSPPREONLY + PCLU): every factorize() factorises, every
/// solve() is exact. The direct solver of a run on several ranks (LinearMethod::petsc_mumps). Throws as
/// make_petsc_amg_solver.
std::unique_ptr<AmgSolver> make_petsc_lu_solver();

/// Starts PETSc and MPI (through the module) and returns once every rank of the launch has called it: a run
/// on several ranks (core/parallel/mpi_place.hpp) calls it before its first step, so that a rank resuming
/// reads the checkpoint rank 0 reads. One process of its own returns at once. Throws as
/// make_petsc_amg_solver.
void synchronize_ranks();

/// Sums `count` doubles over every rank of the launch in place, the same bits on every rank (a reduction to
/// rank 0 and a broadcast); after synchronize_ranks. A run on several ranks sums with it the residual's
/// position rows, each from its owner, and the strain energy and stresses (core/parallel/element_share.hpp).
void sum_over_ranks(double* values, long count);

/// The rank that owns each node: PETSc's partitioner (PT-Scotch) on the nodes' graph in CSR (`offsets` of
/// node count + 1, `neighbours`), computed on rank 0 and sent to every rank, which all call it at once. The
/// module keeps it: each rank passes PETSc the position rows of its nodes. Throws when PETSc fails, and as
/// make_petsc_amg_solver.
std::vector<int> partition_nodes(const std::vector<int>& offsets, const std::vector<int>& neighbours);

/// {rank, number of ranks} of this process as MPI says, starting PETSc and MPI (through the module) if need
/// be: a job's ranks take their place from it, so any launcher that starts MPI processes will do (mpiexec,
/// srun with whichever PMI). Throws as make_petsc_amg_solver.
std::pair<int, int> world_place();

}  // namespace stoss::solve
