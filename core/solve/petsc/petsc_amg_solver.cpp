// The PETSc module (libstoss_petsc.so) behind core/solve/petsc_solver.hpp; loaded with dlopen.
#include <petscksp.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/solve/petsc_solver.hpp"

namespace stoss::solve {
namespace {

using RowMajorMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;
constexpr PetscErrorCode success = 0;  // PETSC_SUCCESS arrives with PETSc 3.19

/// PETSc (and MPI, as a singleton) for the rest of the process. No signal handlers: the job process
/// turns SIGTERM into a cancel and a crash must stay a crash. PETSC_OPTIONS still applies.
void initialize_petsc() {
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  if (initialized) return;
  static char name[] = "stoss", no_handler[] = "-no_signal_handler", left[] = "-options_left", no[] = "no";
  static char* arguments[] = {name, no_handler, left, no, nullptr};
  static int argc = 4;
  static char** argv = arguments;
  // Scotch 7 partitions with threads unless told otherwise, and then not the same way twice: one thread, so
  // that a run on several ranks repeats itself to the bit (partition_graph).
  setenv("SCOTCH_PTHREAD_NUMBER", "1", 0);
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0)
    throw std::runtime_error("PetscInitialize failed");
  std::atexit([] { PetscFinalize(); });
}

/// The MPI ranks of this run (`mpiexec -n N stoss run`, docs/many_machines.md): 1 for a process of its own.
int world_size() {
  PetscMPIInt size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}
int world_rank() {
  PetscMPIInt rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank;
}

/// The run's partition of the nodes among the ranks (partition_graph): every solver of the process numbers
/// its rows by it.
std::vector<int>& node_partition() {
  static std::vector<int> parts;
  return parts;
}

/// The part of each of `nodes` nodes: PT-Scotch (PETSc's MatPartitioning) on the nodes' graph in CSR, as many
/// parts as ranks. Rank 0 computes it and every rank receives it, so that all agree.
PetscErrorCode partition_graph(int nodes, const int* offsets, const int* neighbours,
                               std::vector<int>& parts) {
  parts.assign(nodes, 0);
  if (world_rank() == 0 && nodes > 0) {
    PetscInt *ia = nullptr, *ja = nullptr;  // MatCreateMPIAdj takes them (PetscMalloc'ed)
    PetscCall(PetscMalloc1(nodes + 1, &ia));
    PetscCall(PetscMalloc1(std::max(offsets[nodes], 1), &ja));
    std::copy(offsets, offsets + nodes + 1, ia);
    std::copy(neighbours, neighbours + offsets[nodes], ja);
    Mat graph;
    MatPartitioning partitioning;
    IS part_of;
    PetscCall(MatCreateMPIAdj(PETSC_COMM_SELF, nodes, nodes, ia, ja, nullptr, &graph));
    PetscCall(MatPartitioningCreate(PETSC_COMM_SELF, &partitioning));
    PetscCall(MatPartitioningSetAdjacency(partitioning, graph));
    PetscCall(MatPartitioningSetNParts(partitioning, world_size()));
    PetscCall(MatPartitioningSetType(partitioning, MATPARTITIONINGPTSCOTCH));
    PetscCall(MatPartitioningApply(partitioning, &part_of));
    const PetscInt* indices = nullptr;
    PetscCall(ISGetIndices(part_of, &indices));
    std::copy(indices, indices + nodes, parts.begin());
    PetscCall(ISRestoreIndices(part_of, &indices));
    PetscCall(ISDestroy(&part_of));
    PetscCall(MatPartitioningDestroy(&partitioning));
    PetscCall(MatDestroy(&graph));
  }
  MPI_Bcast(parts.data(), nodes, MPI_INT, 0, PETSC_COMM_WORLD);
  return success;
}

/// Sets an option of this solver unless the user set it already (PETSC_OPTIONS="-stoss_...").
PetscErrorCode default_option(const std::string& name, const char* value) {
  PetscBool set = PETSC_FALSE;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, name.c_str(), &set));
  if (!set) PetscCall(PetscOptionsSetValue(nullptr, name.c_str(), value));
  return success;
}

/// GAMG for elasticity: the graph of the non-symmetric tangent symmetrised, weak couplings (< 1 %)
/// dropped, the interpolation kept while the pattern stays (a refactorisation redoes only the Galerkin
/// products). Smoothing stays PETSc's Chebyshev/Jacobi: SOR took half the GMRES iterations on the
/// tumbling sphere at 7,680 hex8, but at 27,648 its inode kernel met singular diagonal blocks on a
/// coarse level (aggregates with fewer nodes than rigid-body modes), and Jacobi treats a zero diagonal.
PetscErrorCode default_gamg_options(const std::string& prefix) {
  PetscCall(default_option(prefix + "pc_gamg_sym_graph", "true"));
  PetscCall(default_option(prefix + "pc_gamg_threshold", "0.01"));
  PetscCall(default_option(prefix + "pc_gamg_reuse_interpolation", "true"));
  return success;
}

constexpr const char* prefix = "stoss_";

/// The preconditioner of the last setup is kept for new values of the same pattern (Newton iterations,
/// later steps) while GMRES needs at most this factor times, plus `reuse_slack`, the iterations it needed
/// right after that setup (docs/measurements.md, "Linear solvers"): the setup (the Galerkin products
/// PᵀAP on every level) cost about a third of a tumbling-sphere step at 27,648 hex8, and the tangent
/// of one step hardly changes the preconditioner's quality.
constexpr double reuse_growth = 1.5;
constexpr int reuse_slack = 5;

PetscErrorCode set_default_options() {
  PetscCall(default_gamg_options(std::string("-") + prefix));
  PetscCall(default_gamg_options(std::string("-") + prefix + "fieldsplit_0_"));
  PetscCall(default_option(std::string("-") + prefix + "fieldsplit_0_ksp_type", "preonly"));
  PetscCall(default_option(std::string("-") + prefix + "fieldsplit_0_pc_type", "gamg"));
  PetscCall(default_option(std::string("-") + prefix + "fieldsplit_1_ksp_type", "preonly"));
  PetscCall(default_option(std::string("-") + prefix + "fieldsplit_1_pc_type", "lu"));
  // The contact block is indefinite (multiplier rows): an LU that pivots (PETSc's own does not). UMFPACK is
  // sequential; on several ranks the block is distributed and MUMPS factorises it.
  PetscCall(default_option(std::string("-") + prefix + "fieldsplit_1_pc_factor_mat_solver_type",
                           world_size() > 1 ? "mumps" : "umfpack"));
  return success;
}

void check(PetscErrorCode code, const char* what) {
  if (code != success) throw std::runtime_error(std::string("PETSc: ") + what + " failed");
}

class PetscAmgSolver final : public AmgSolver {
 public:
  /// `lu`: MUMPS's LU of the whole matrix (KSPPREONLY + PCLU), the direct solver on several ranks, instead of
  /// GMRES + GAMG.
  explicit PetscAmgSolver(bool lu = false) : lu_(lu) {
    initialize_petsc();
    ranks_ = world_size();
    check(set_default_options(), "setting the default options");
  }
  ~PetscAmgSolver() override { destroy(); }

  bool factorize(const SparseMatrix& A, int generation, const Eigen::VectorXd& positions) override {
    if (ranks_ > 1) return factorize_matrix(A, generation, positions);  // its own rows read in place
    const RowMajorMatrix R = A;                                         // PETSc's AIJ is CSR
    return factorize_matrix(R, generation, positions);
  }

  void set_tolerance(double relative) override {
    tolerance_ = relative;
    if (ksp_)
      check(KSPSetTolerances(ksp_, tolerance_, 1e-300, PETSC_DEFAULT, amg_max_iterations),
            "KSPSetTolerances");
  }

  KrylovOutcome solve(const Eigen::VectorXd& b, Eigen::VectorXd& x) override {
    KrylovOutcome outcome;
    x.resize(b.size());
    if (run(b, x, outcome) != success) outcome.converged = false;
    return outcome;
  }

  SparseMatrix matrix() const override {
    if (ranks_ > 1) return gathered_matrix();
    PetscInt n = 0;
    const PetscInt *ia = nullptr, *ja = nullptr;
    PetscBool done = PETSC_FALSE;
    const PetscScalar* values = nullptr;
    check(MatGetRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done), "MatGetRowIJ");
    check(MatSeqAIJGetArrayRead(A_, &values), "MatSeqAIJGetArrayRead");
    std::vector<int> outer(ia, ia + n + 1), inner(ja, ja + ia[n]);
    const SparseMatrix copy =
        Eigen::Map<const RowMajorMatrix>(n, n, ia[n], outer.data(), inner.data(), values);
    check(MatSeqAIJRestoreArrayRead(A_, &values), "MatSeqAIJRestoreArrayRead");
    check(MatRestoreRowIJ(A_, 0, PETSC_FALSE, PETSC_FALSE, &n, &ia, &ja, &done), "MatRestoreRowIJ");
    return copy;
  }

  std::string description() const override {
    if (lu_)
      return "MUMPS LU through PETSc, " + std::to_string(whole_setups_) + " factorisations" +
             (ranks_ > 1 ? "; on " + std::to_string(ranks_) + " MPI ranks" : "");
    char rtol[16];
    std::snprintf(rtol, sizeof rtol, "%.0e", tolerance_);
    std::string text = std::string("GMRES(100), right-preconditioned, rtol ") + rtol;
    if (whole_setups_ > 0) text += "; " + std::to_string(whole_setups_) + " setups of " + whole_;
    if (split_setups_ > 0)
      text += "; " + std::to_string(split_setups_) + " setups of " + split_ + " (the last)";
    if (reuses_ > 0) text += "; the preconditioner reused for " + std::to_string(reuses_) + " more matrices";
    if (ranks_ > 1) text += "; on " + std::to_string(ranks_) + " MPI ranks";
    return text;
  }

 private:
  /// factorize on M: A itself on several ranks (each reads its own rows out of it), A in row order on one.
  template <class Matrix>
  bool factorize_matrix(const Matrix& M, int generation, const Eigen::VectorXd& positions) {
    const int m = positions.size() % 3 == 0 && positions.size() <= M.rows() ? int(positions.size()) : 0;
    if (generation != generation_ || M.rows() != rows_ || M.nonZeros() != nonzeros_ || m != positions_) {
      destroy();
      if (create(M, positions.head(m)) != success) return destroy(), false;
      generation_ = generation;
    } else if (refill(M) != success) {
      return false;
    } else if (!lu_ && preconditioner_still_good()) {
      ++reuses_;
      return KSPSetReusePreconditioner(ksp_, PETSC_TRUE) == success;
    }
    return setup() == success;
  }

  /// Counts a setup and describes it (GAMG levels exist only once set up).
  void describe_setup() {
    const std::string smoother = finest_sor_ ? ", SOR on the finest level" : "";
    if (!split()) {
      ++whole_setups_;
      whole_ = "GAMG (" + levels_of(gamg()) + " levels" + smoother + ")" +
               (near_null_ ? " with 6 rigid-body modes" : "");
      return;
    }
    ++split_setups_;
    split_ = "a Schur field split (lower): GAMG (" + levels_of(gamg()) + " levels" + smoother +
             ", rigid-body modes) on " + std::to_string(positions_) +
             " position dofs, LU of the selfp Schur complement on " + std::to_string(rows_ - positions_) +
             " contact unknowns";
  }

  /// Whether the contact unknowns make the preconditioner a field split (GAMG on the positions).
  bool split() const { return positions_ > 0 && positions_ < rows_; }

  PC pc() const {
    PC pc = nullptr;
    KSPGetPC(ksp_, &pc);
    return pc;
  }

  /// The Krylov object whose preconditioner is GAMG: the whole solver's, or the field split's on the
  /// positions (null before setup).
  KSP gamg_ksp() const {
    if (!split()) return ksp_;
    KSP* sub = nullptr;
    PetscInt count = 0;
    KSP positions = nullptr;
    if (PCFieldSplitGetSubKSP(pc(), &count, &sub) == success && count > 0) {
      positions = sub[0];
      PetscFree(sub);
    }
    return positions;
  }

  PC gamg() const {
    PC gamg = nullptr;
    if (KSP ksp = gamg_ksp()) KSPGetPC(ksp, &gamg);
    return gamg;
  }

  /// One symmetric SOR sweep (Richardson) instead of Chebyshev/Jacobi on GAMG's finest level, unless the
  /// user chose the levels' smoothers (PETSC_OPTIONS). Measured on the tumbling sphere at 27,648 hex8: 14.7
  /// GMRES iterations per solve instead of 23.6, linear solver 10.9 s instead of 11.9 s over 3 steps
  /// (docs/measurements.md, "Linear solvers"). Only the finest level: its matrix has the inertia on its
  /// diagonal, while coarse levels can carry zero diagonals (aggregates whose rotations hold no energy) that
  /// SOR cannot divide by. Kept by later setups of the same preconditioner.
  PetscErrorCode smooth_finest_level_with_sor() {
    KSP positions = gamg_ksp();
    // The split sets up its blocks' solvers at its first use; GAMG's levels are needed now.
    if (split() && positions) PetscCall(KSPSetUp(positions));
    PC multigrid = nullptr;
    if (positions) PetscCall(KSPGetPC(positions, &multigrid));
    PetscInt levels = 0;
    PetscBool user_set = PETSC_FALSE;
    const std::string levels_prefix =
        std::string("-") + prefix + (split() ? "fieldsplit_0_" : "") + "mg_levels_";
    PetscCall(PetscOptionsHasName(nullptr, nullptr, (levels_prefix + "pc_type").c_str(), &user_set));
    if (!multigrid || user_set || PCMGGetLevels(multigrid, &levels) != success || levels < 2) return success;
    KSP smoother = nullptr;
    PC sor = nullptr;
    PetscCall(PCMGGetSmoother(multigrid, levels - 1, &smoother));
    PetscCall(KSPGetPC(smoother, &sor));
    PetscBool already = PETSC_FALSE;
    PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(sor), PCSOR, &already));
    if (!already) {
      PetscCall(KSPSetType(smoother, KSPRICHARDSON));
      PetscCall(KSPSetTolerances(smoother, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 1));
      PetscCall(PCSetType(sor, PCSOR));
      PetscCall(KSPSetUp(smoother));
    }
    finest_sor_ = true;
    return success;
  }

  static std::string levels_of(PC pc) {
    PetscInt levels = 0;
    if (!pc || PCMGGetLevels(pc, &levels) != success) return "?";
    return std::to_string(levels);
  }

  /// One process: PETSC_COMM_SELF and sequential objects. Several MPI ranks: each rank passes PETSc its own
  /// rows (own_rows), the only rows its element loop makes whole (core/parallel/element_share.hpp).
  MPI_Comm communicator() const { return ranks_ > 1 ? PETSC_COMM_WORLD : PETSC_COMM_SELF; }

  /// This rank's rows [first_, last_) of PETSc's numbering. One process: the matrix's own rows. Several
  /// ranks: the nodes in the run's partition (node_partition), the one by which the element loop is shared,
  /// numbered part by part (order_), so that each rank owns its part's position rows, with the contact
  /// unknowns after them on the last rank (the field split's second block, MUMPS's there).
  PetscErrorCode own_rows() {
    first_ = 0;
    last_ = rows_;
    if (ranks_ == 1) return success;
    const int nodes = positions_ / 3, rank = world_rank();
    const std::vector<int>& parts = node_partition();
    if (int(parts.size()) != nodes)
      SETERRQ(PETSC_COMM_SELF, PETSC_ERR_ARG_WRONGSTATE,
              "several ranks: the nodes have no partition (stoss_partition_nodes, core/run/ranks.cpp)");
    std::vector<int> count(ranks_, 0);
    for (int part : parts) ++count[part];
    order_.resize(rows_);
    std::vector<int> next(ranks_, 0);  // the first new node of each part
    for (int k = 1; k < ranks_; ++k) next[k] = next[k - 1] + count[k - 1];
    first_ = 3 * next[rank];
    last_ = rank == ranks_ - 1 ? rows_ : first_ + 3 * count[rank];
    for (int node = 0; node < nodes; ++node) {  // each part's nodes in their order
      const int slot = next[parts[node]]++;
      for (int c = 0; c < 3; ++c) order_[3 * slot + c] = 3 * node + c;
    }
    for (int row = positions_; row < rows_; ++row) order_[row] = row;
    renumbered_.resize(rows_);
    for (int row = 0; row < rows_; ++row) renumbered_[order_[row]] = row;
    return success;
  }

  int owned_positions() const { return std::max(0, std::min(last_, positions_) - first_); }
  /// The matrix's row (or unknown) that row `row` of PETSc's numbering is.
  int original(int row) const { return order_.empty() ? row : order_[row]; }

  /// One process: R's pattern, for the preallocation only.
  void local_csr(const RowMajorMatrix& R) {
    const int* outer = R.outerIndexPtr();
    local_ia_.assign(outer, outer + rows_ + 1);
    local_ja_.assign(R.innerIndexPtr(), R.innerIndexPtr() + outer[rows_]);
  }

  /// Several ranks: this rank's rows of A in CSR with PETSc's columns, sorted, and where each value is in A
  /// (kept for refill). Read out of A's columns in place, since only this rank's rows of A are whole
  /// (core/parallel/element_share.hpp) and a row-ordered copy would cost 12 bytes per entry.
  void local_csr(const SparseMatrix& A) {
    const auto local_row = [&](Eigen::Index row) { return renumbered_[row] - first_; };  // < 0 or ≥: not ours
    const int local = last_ - first_;
    local_ia_.assign(local + 1, 0);
    for (Eigen::Index col = 0; col < A.outerSize(); ++col)
      for (SparseMatrix::InnerIterator it(A, col); it; ++it)
        if (const int k = local_row(it.row()); k >= 0 && k < local) ++local_ia_[k + 1];
    for (int k = 0; k < local; ++k) local_ia_[k + 1] += local_ia_[k];
    std::vector<std::pair<PetscInt, int>> entries(local_ia_[local]);  // (PETSc's column, place in A)
    std::vector<PetscInt> next(local_ia_.begin(), local_ia_.end() - 1);
    for (Eigen::Index col = 0; col < A.outerSize(); ++col)
      for (SparseMatrix::InnerIterator it(A, col); it; ++it)
        if (const int k = local_row(it.row()); k >= 0 && k < local)
          entries[next[k]++] = {renumbered_[col], int(&it.valueRef() - A.valuePtr())};
    local_ja_.resize(entries.size());
    value_from_.resize(entries.size());
    for (int k = 0; k < local; ++k) {
      std::sort(entries.begin() + local_ia_[k], entries.begin() + local_ia_[k + 1]);
      for (PetscInt e = local_ia_[k]; e < local_ia_[k + 1]; ++e)
        local_ja_[e] = entries[e].first, value_from_[e] = entries[e].second;
    }
  }

  /// Several ranks: the whole matrix on every rank, gathered from the ranks' rows. Only the LU fallback
  /// asks for it, on every rank at once (whether GMRES converged is one answer for all), so no rank keeps a
  /// copy of the whole matrix meanwhile.
  SparseMatrix gathered_matrix() const {
    const int local_rows = last_ - first_, local_entries = int(local_ja_.size());
    std::vector<int> rows_of(ranks_), entries_of(ranks_);
    MPI_Allgather(&local_rows, 1, MPI_INT, rows_of.data(), 1, MPI_INT, PETSC_COMM_WORLD);
    MPI_Allgather(&local_entries, 1, MPI_INT, entries_of.data(), 1, MPI_INT, PETSC_COMM_WORLD);
    std::vector<int> row_at(ranks_, 0), entry_at(ranks_, 0);
    for (int k = 1; k < ranks_; ++k) {
      row_at[k] = row_at[k - 1] + rows_of[k - 1];
      entry_at[k] = entry_at[k - 1] + entries_of[k - 1];
    }
    std::vector<int> lengths(local_rows), columns(local_entries);
    for (int k = 0; k < local_rows; ++k) lengths[k] = int(local_ia_[k + 1] - local_ia_[k]);
    for (int e = 0; e < local_entries; ++e) columns[e] = original(int(local_ja_[e]));
    std::vector<int> all_lengths(rows_), all_columns(entry_at.back() + entries_of.back());
    std::vector<double> all_values(all_columns.size());
    MPI_Allgatherv(lengths.data(), local_rows, MPI_INT, all_lengths.data(), rows_of.data(), row_at.data(),
                   MPI_INT, PETSC_COMM_WORLD);
    MPI_Allgatherv(columns.data(), local_entries, MPI_INT, all_columns.data(), entries_of.data(),
                   entry_at.data(), MPI_INT, PETSC_COMM_WORLD);
    const std::vector<PetscScalar> values = own_values();
    MPI_Allgatherv(values.data(), local_entries, MPI_DOUBLE, all_values.data(), entries_of.data(),
                   entry_at.data(), MPI_DOUBLE, PETSC_COMM_WORLD);
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(all_values.size());
    for (int row = 0, e = 0; row < rows_; ++row)  // PETSc's rows, rank by rank
      for (int k = 0; k < all_lengths[row]; ++k, ++e)
        entries.emplace_back(original(row), all_columns[e], all_values[e]);
    SparseMatrix whole(rows_, rows_);
    whole.setFromTriplets(entries.begin(), entries.end());
    return whole;
  }

  /// Several ranks: this rank's values of A in local_csr's order.
  /// Held only while PETSc copies them: GAMG's setup, which follows, finds the memory free.
  std::vector<PetscScalar> local_values(const SparseMatrix& A) const {
    std::vector<PetscScalar> values(value_from_.size());
    for (std::size_t k = 0; k < value_from_.size(); ++k) values[k] = A.valuePtr()[value_from_[k]];
    return values;
  }

  /// Several ranks: this rank's values as PETSc holds them, in local_ia_/local_ja_'s order (both sorted by
  /// column within a row).
  std::vector<PetscScalar> own_values() const {
    std::vector<PetscScalar> values(local_ja_.size());
    for (int k = 0; k < last_ - first_; ++k) {
      PetscInt count = 0;
      const PetscScalar* row = nullptr;
      check(MatGetRow(A_, first_ + k, &count, nullptr, &row), "MatGetRow");
      const bool same = count == local_ia_[k + 1] - local_ia_[k];
      if (same) std::copy(row, row + count, values.begin() + local_ia_[k]);
      check(MatRestoreRow(A_, first_ + k, &count, nullptr, &row), "MatRestoreRow");
      if (!same) throw std::runtime_error("PETSc: a row of the matrix changed its length");
    }
    return values;
  }

  template <class Matrix>
  PetscErrorCode create(const Matrix& M, const Eigen::VectorXd& positions) {
    rows_ = int(M.rows());
    nonzeros_ = M.nonZeros();
    positions_ = int(positions.size());
    PetscCall(own_rows());
    const int local = last_ - first_;
    PetscCall(MatCreate(communicator(), &A_));
    PetscCall(MatSetSizes(A_, local, local, rows_, rows_));
    PetscCall(MatSetType(A_, ranks_ > 1 ? MATMPIAIJ : MATSEQAIJ));
    if (positions_ == rows_) PetscCall(MatSetBlockSize(A_, 3));
    local_csr(M);
    if constexpr (std::is_same_v<Matrix, SparseMatrix>) {
      PetscCall(MatMPIAIJSetPreallocationCSR(A_, local_ia_.data(), local_ja_.data(), local_values(M).data()));
    } else {
      PetscCall(MatSeqAIJSetPreallocationCSR(A_, local_ia_.data(), local_ja_.data(), M.valuePtr()));
      std::vector<PetscInt>().swap(local_ia_);  // PETSc copied the pattern; refill copies values only
      std::vector<PetscInt>().swap(local_ja_);
    }
    // No node (inode) kernels for this matrix: measured on the tumbling sphere at 27,648 hex8 (3 steps,
    // quiet machine), its products and sweeps took the linear solver from 11.9 s without them to 18.5 s.
    PetscCall(MatSetOption(A_, MAT_USE_INODES, PETSC_FALSE));
    if (ranks_ > 1) {
      PetscCall(VecCreateMPI(PETSC_COMM_WORLD, local, rows_, &b_));
      PetscCall(VecDuplicate(b_, &x_));
      PetscCall(VecScatterCreateToAll(x_, &gather_, &all_));  // every rank gets the whole solution
    } else {
      PetscCall(VecCreateSeq(PETSC_COMM_SELF, rows_, &b_));
      PetscCall(VecDuplicate(b_, &x_));
    }
    if (positions_ > 0) PetscCall(rigid_body_modes(positions));

    PetscCall(KSPCreate(communicator(), &ksp_));
    PetscCall(KSPSetOptionsPrefix(ksp_, prefix));
    if (lu_) return direct();
    PetscCall(KSPSetType(ksp_, KSPGMRES));
    PetscCall(KSPGMRESSetRestart(ksp_, 100));
    PetscCall(KSPSetPCSide(ksp_, PC_RIGHT));
    PetscCall(KSPSetTolerances(ksp_, tolerance_, 1e-300, PETSC_DEFAULT, amg_max_iterations));
    PetscCall(KSPSetOperators(ksp_, A_, A_));
    if (!split()) {
      if (near_null_) PetscCall(MatSetNearNullSpace(A_, near_null_));
      PetscCall(PCSetType(pc(), PCGAMG));
    } else {
      PetscCall(field_split());
    }
    PetscCall(KSPSetFromOptions(ksp_));
    return success;
  }

  /// MUMPS's LU of the whole matrix, which pivots (contact multiplier rows have zero diagonals).
  PetscErrorCode direct() {
    PetscCall(KSPSetType(ksp_, KSPPREONLY));
    PetscCall(KSPSetOperators(ksp_, A_, A_));
    PetscCall(PCSetType(pc(), PCLU));
    PetscCall(PCFactorSetMatSolverType(pc(), MATSOLVERMUMPS));
    PetscCall(KSPSetFromOptions(ksp_));
    return success;
  }

  /// Translations and rotations about the origin of the current positions (block size 3).
  PetscErrorCode rigid_body_modes(const Eigen::VectorXd& positions) {
    Vec coordinates;
    if (ranks_ > 1)
      PetscCall(VecCreateMPI(PETSC_COMM_WORLD, owned_positions(), positions_, &coordinates));
    else
      PetscCall(VecCreateSeq(PETSC_COMM_SELF, positions_, &coordinates));
    PetscCall(VecSetBlockSize(coordinates, 3));
    PetscScalar* p = nullptr;
    PetscCall(VecGetArray(coordinates, &p));
    for (int k = 0; k < owned_positions(); ++k) p[k] = positions[original(first_ + k)];
    PetscCall(VecRestoreArray(coordinates, &p));
    PetscCall(MatNullSpaceCreateRigidBody(coordinates, &near_null_));
    PetscCall(VecDestroy(&coordinates));
    return success;
  }

  /// Positions first (GAMG with the rigid-body modes, attached to the split's index set so the
  /// extracted block carries them), then the contact unknowns (LU of the selfp Schur complement).
  PetscErrorCode field_split() {
    PetscCall(ISCreateStride(communicator(), owned_positions(), first_, 1, &fields_[0]));
    PetscCall(ISSetBlockSize(fields_[0], 3));
    if (near_null_)
      PetscCall(PetscObjectCompose((PetscObject)fields_[0], "nearnullspace", (PetscObject)near_null_));
    const int contact_first = std::max(first_, positions_);
    PetscCall(
        ISCreateStride(communicator(), std::max(0, last_ - contact_first), contact_first, 1, &fields_[1]));
    PC split = pc();
    PetscCall(PCSetType(split, PCFIELDSPLIT));
    PetscCall(PCFieldSplitSetIS(split, "0", fields_[0]));
    PetscCall(PCFieldSplitSetIS(split, "1", fields_[1]));
    PetscCall(PCFieldSplitSetType(split, PC_COMPOSITE_SCHUR));
    // Lower: one GAMG cycle per application where full takes two (before and after the Schur solve). On the
    // seed's example refined to 28,160 hex8, 3 steps: 20.0 GMRES iterations per solve against 18.1, wall 20.0
    // s against 30.0 s; the seed's example 7.1 against 8.5 s (docs/measurements.md, "Linear solvers").
    PetscCall(PCFieldSplitSetSchurFactType(split, PC_FIELDSPLIT_SCHUR_FACT_LOWER));
    PetscCall(PCFieldSplitSetSchurPre(split, PC_FIELDSPLIT_SCHUR_PRE_SELFP, nullptr));
    return success;
  }

  /// Same pattern: the values only, in PETSc's CSR order (both sorted by column within a row).
  PetscErrorCode refill(const SparseMatrix& A) {
    const int local = last_ - first_;
    PetscCall(MatUpdateMPIAIJWithArrays(A_, local, local, rows_, rows_, local_ia_.data(), local_ja_.data(),
                                        local_values(A).data()));
    PetscCall(KSPSetOperators(ksp_, A_, A_));
    return success;
  }
  PetscErrorCode refill(const RowMajorMatrix& R) {
    PetscScalar* values = nullptr;
    PetscCall(MatSeqAIJGetArray(A_, &values));
    std::copy(R.valuePtr(), R.valuePtr() + nonzeros_, values);
    PetscCall(MatSeqAIJRestoreArray(A_, &values));
    PetscCall(KSPSetOperators(ksp_, A_, A_));
    return success;
  }

  bool preconditioner_still_good() const {
    return fresh_iterations_ >= 0 && last_iterations_ <= reuse_growth * fresh_iterations_ + reuse_slack;
  }

  PetscErrorCode setup() {
    PetscCall(KSPSetReusePreconditioner(ksp_, PETSC_FALSE));
    PetscCall(KSPSetUp(ksp_));
    if (lu_) {
      ++whole_setups_;
      return success;
    }
    PetscCall(smooth_finest_level_with_sor());
    fresh_iterations_ = -1;  // set by the next solve
    describe_setup();
    return success;
  }

  PetscErrorCode run(const Eigen::VectorXd& b, Eigen::VectorXd& x, KrylovOutcome& outcome) {
    PetscScalar* p = nullptr;
    PetscCall(VecGetArray(b_, &p));
    for (int k = first_; k < last_; ++k) p[k - first_] = b[original(k)];
    PetscCall(VecRestoreArray(b_, &p));
    PetscCall(KSPSolve(ksp_, b_, x_));
    KSPConvergedReason reason;
    PetscInt iterations = 0;
    PetscCall(KSPGetConvergedReason(ksp_, &reason));
    PetscCall(KSPGetIterationNumber(ksp_, &iterations));
    outcome.converged = reason > 0;
    outcome.iterations = int(iterations);
    last_iterations_ =
        outcome.converged ? outcome.iterations : amg_max_iterations + 1;  // not converged: rebuild
    if (fresh_iterations_ < 0) fresh_iterations_ = last_iterations_;
    Vec whole = x_;
    if (ranks_ > 1) {
      PetscCall(VecScatterBegin(gather_, x_, all_, INSERT_VALUES, SCATTER_FORWARD));
      PetscCall(VecScatterEnd(gather_, x_, all_, INSERT_VALUES, SCATTER_FORWARD));
      whole = all_;
    }
    const PetscScalar* q = nullptr;
    PetscCall(VecGetArrayRead(whole, &q));
    for (Eigen::Index k = 0; k < x.size(); ++k) x[original(int(k))] = q[k];
    PetscCall(VecRestoreArrayRead(whole, &q));
    return success;
  }

  void destroy() {
    KSPDestroy(&ksp_);
    ISDestroy(&fields_[0]);
    ISDestroy(&fields_[1]);
    MatNullSpaceDestroy(&near_null_);
    VecDestroy(&b_);
    VecDestroy(&x_);
    VecScatterDestroy(&gather_);
    VecDestroy(&all_);
    MatDestroy(&A_);
    generation_ = rows_ = positions_ = -1;
    finest_sor_ = false;
    nonzeros_ = -1;
    fresh_iterations_ = last_iterations_ = -1;
  }

  Mat A_ = nullptr;
  KSP ksp_ = nullptr;
  Vec b_ = nullptr, x_ = nullptr;
  VecScatter gather_ = nullptr;  ///< several ranks: x_ to all_ on every rank
  Vec all_ = nullptr;
  int ranks_ = 1;                              ///< MPI ranks, after PETSc's initialisation
  int first_ = 0, last_ = 0;                   ///< this rank's rows (own_rows)
  std::vector<PetscInt> local_ia_, local_ja_;  ///< this rank's rows of the pattern, PETSc's columns
  std::vector<int> value_from_;                ///< several ranks: where each of this rank's values is in A
  std::vector<int> order_, renumbered_;        ///< several ranks: PETSc's row → R's row, and back
  IS fields_[2] = {nullptr, nullptr};
  MatNullSpace near_null_ = nullptr;
  int generation_ = -1, rows_ = -1, positions_ = -1;
  Eigen::Index nonzeros_ = -1;
  double tolerance_ = amg_default_tolerance;
  int whole_setups_ = 0, split_setups_ = 0, reuses_ = 0;
  int fresh_iterations_ = -1;  ///< GMRES iterations of the first solve after the last setup
  int last_iterations_ = -1;   ///< of the last solve
  std::string whole_, split_;  ///< the last setup of each kind, described
  bool finest_sor_ = false;    ///< SOR smooths GAMG's finest level (smooth_finest_level_with_sor)
  bool lu_ = false;            ///< MUMPS's LU instead of GMRES + GAMG
};

}  // namespace
}  // namespace stoss::solve

extern "C" stoss::solve::AmgSolver* stoss_make_petsc_amg_solver() {
  return new stoss::solve::PetscAmgSolver();
}

extern "C" stoss::solve::AmgSolver* stoss_make_petsc_lu_solver() {
  return new stoss::solve::PetscAmgSolver(true);
}

/// Starts PETSc and MPI and waits for every rank (core/solve/petsc_solver.hpp, synchronize_ranks).
extern "C" void stoss_synchronize_ranks() {
  stoss::solve::initialize_petsc();
  MPI_Barrier(PETSC_COMM_WORLD);
}

/// This process's rank and the number of ranks, as MPI says once started: whatever launched them (mpiexec,
/// srun with any PMI), and whatever their environment says (core/solve/petsc_solver.hpp, world_place).
extern "C" void stoss_world_place(int* rank, int* size) {
  stoss::solve::initialize_petsc();
  *rank = stoss::solve::world_rank();
  *size = stoss::solve::world_size();
}

/// Partitions the nodes' graph among the ranks and keeps the partition for the solvers' rows; every rank
/// gets the same `parts` (core/solve/petsc_solver.hpp, partition_nodes). False when PETSc failed.
extern "C" bool stoss_partition_nodes(int nodes, const int* offsets, const int* neighbours, int* parts) {
  stoss::solve::initialize_petsc();
  std::vector<int>& kept = stoss::solve::node_partition();
  if (stoss::solve::partition_graph(nodes, offsets, neighbours, kept) != 0) return false;
  std::copy(kept.begin(), kept.end(), parts);
  return true;
}

/// Sums `count` doubles over every rank in place: reduced to rank 0 and broadcast, so every rank gets the
/// same bits (core/solve/petsc_solver.hpp, sum_over_ranks).
extern "C" void stoss_sum_over_ranks(double* values, long count) {
  // An event of its own, so that -log_view counts the element loop's sums beside PETSc's own messages.
  static PetscLogEvent sum_event = [] {
    PetscLogEvent event = 0;
    PetscClassId id = 0;
    PetscClassIdRegister("Stoss", &id);
    PetscLogEventRegister("StossSumRanks", id, &event);
    return event;
  }();
  PetscLogEventBegin(sum_event, 0, 0, 0, 0);
  const bool root = stoss::solve::world_rank() == 0;
  for (long done = 0; done < count;) {
    const int part = static_cast<int>(std::min<long>(count - done, 1L << 30));
    if (root)
      MPI_Reduce(MPI_IN_PLACE, values + done, part, MPI_DOUBLE, MPI_SUM, 0, PETSC_COMM_WORLD);
    else
      MPI_Reduce(values + done, nullptr, part, MPI_DOUBLE, MPI_SUM, 0, PETSC_COMM_WORLD);
    MPI_Bcast(values + done, part, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
    done += part;
  }
  PetscLogEventEnd(sum_event, 0, 0, 0, 0);
}
