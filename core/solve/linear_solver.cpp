#include "core/solve/linear_solver.hpp"

#include <dlfcn.h>
#include <malloc.h>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/UmfPackSupport>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <vector>

#include "core/solve/petsc_solver.hpp"

namespace stoss::solve {
namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
std::atomic<long> factorizations_in_process{0}, solves_in_process{0}, analyses_in_process{0};
}  // namespace

long LinearSolver::process_factorizations() {
  return factorizations_in_process.load();
}
long LinearSolver::process_solves() {
  return solves_in_process.load();
}
long LinearSolver::process_analyses() {
  return analyses_in_process.load();
}

/// UMFPACK allocates its numeric factors (tens of MB) anew at every factorisation; glibc would map and
/// unmap them each time, and the page faults cost ~10 % of a contact run. Keep such blocks in the heap.
void keep_large_blocks_in_heap() {
  static std::once_flag once;
  std::call_once(once, [] {
    mallopt(M_MMAP_THRESHOLD, 256 << 20);
    mallopt(M_TRIM_THRESHOLD, 512 << 20);
  });
}

/// UMFPACK's dense kernels run on the BLAS behind libblas.so.3. OpenBLAS's serial build keeps unlocked
/// global buffers: two runs factorising at once on two threads race, seen as last-bit differences between
/// a run made alone and beside another (tests/physics/test_concurrent_runs.cpp). deploy/packages.txt
/// installs the pthread build, whose buffers are locked; it is held to one thread per call, since runs
/// and element loops are the parallelism and BLAS threads would only oversubscribe the cores. Should the
/// serial build be the one selected, factorisations and solves take turns instead (blas_turn). Looked up
/// at run time: a BLAS other than OpenBLAS has neither setting and is reentrant.
namespace {
bool configure_blas() {
  using SetThreads = void (*)(int);
  using GetParallel = int (*)();
  if (auto set = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) set(1);
  auto parallel = reinterpret_cast<GetParallel>(dlsym(RTLD_DEFAULT, "openblas_get_parallel"));
  return parallel && parallel() == 0;  // 0: built single-threaded, not reentrant
}

/// A lock held around each BLAS-using call when the BLAS is not reentrant, none otherwise.
std::unique_lock<std::mutex> blas_turn() {
  static const bool needs_turns = configure_blas();
  static std::mutex mutex;
  return needs_turns ? std::unique_lock(mutex) : std::unique_lock<std::mutex>();
}
}  // namespace

/// METIS orders the LU's unknowns (UMFPACK_ORDERING_METIS, below), and Debian's METIS draws its random
/// numbers from the C library's rand(), one generator for the whole process, seeded at every call.
/// Two runs ordering at once on two threads interleave their draws, get other orderings than alone and
/// differ in round-off (tests/physics/test_concurrent_runs.cpp). Orderings therefore take turns.
namespace {
std::mutex& ordering_mutex() {
  static std::mutex mutex;
  return mutex;
}
}  // namespace

struct LinearSolver::Impl {
  Impl() {
    keep_large_blocks_in_heap();
    blas_turn();  // configures the BLAS before its first use
    configure(lu);
  }
  template <class Matrix>
  static void configure(Eigen::UmfPackLU<Matrix>& lu) {
    // No iterative refinement inside UMFPACK: Newton refines the solution itself, and refinement
    // made each solve four times dearer (5.9 ms instead of 1.4 ms on the 4563-dof ball-on-plate system).
    lu.umfpackControl()(UMFPACK_IRSTEP) = 0;
    // Nested dissection: ~8 % less fill than AMD on contact systems of two bodies (AMD if METIS is absent).
    lu.umfpackControl()(UMFPACK_ORDERING) = UMFPACK_ORDERING_METIS;
  }
  Eigen::UmfPackLU<SparseMatrix> lu;
  /// UMFPACK's 64-bit-index variant (umfpack_dl_*), used from the first time the 32-bit one (umfpack_di_*)
  /// runs out of memory: that one sizes its workspace in ints and fails once its estimate passes 2^31, as on
  /// the Hertz example's 52,000-node mesh with 21 GB free (bench/hertz_indentation.py --meshes graded). Not
  /// from the start: its orderings differ in round-off, and every smaller run would change its last bits.
  using WideMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, SuiteSparse_long>;
  std::unique_ptr<Eigen::UmfPackLU<WideMatrix>> wide_lu;
  WideMatrix wide_copy;      ///< the matrix wide_lu factorised, which it refers to
  long status = UMFPACK_OK;  ///< of the last numeric factorisation

  /// Factorises A, analysed by analyze(); on the 32-bit variant's out-of-memory, again with the 64-bit one.
  bool factorize(const SparseMatrix& A) {
    if (!wide_lu) {
      lu.factorize(A);
      status = lu.umfpackFactorizeReturncode();
      if (status != UMFPACK_ERROR_out_of_memory) return lu.info() == Eigen::Success;
      wide_lu = std::make_unique<Eigen::UmfPackLU<WideMatrix>>();
      configure(*wide_lu);
      forget_analysis();
      analyze(A);
    }
    wide_copy = A;
    wide_lu->factorize(wide_copy);
    status = wide_lu->umfpackFactorizeReturncode();
    return wide_lu->info() == Eigen::Success;
  }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const {
    if (wide_lu) return wide_lu->solve(b);
    return lu.solve(b);
  }
  /// The sparsity of the matrix lu's symbolic analysis was made for (empty: none, or not known).
  std::vector<int> analyzed_outer, analyzed_inner;

  /// Whether A has the sparsity lu was analysed for.
  bool analyzed_for(const SparseMatrix& A) const {
    return !analyzed_outer.empty() &&
           std::equal(analyzed_outer.begin(), analyzed_outer.end(), A.outerIndexPtr(),
                      A.outerIndexPtr() + A.outerSize() + 1) &&
           std::equal(analyzed_inner.begin(), analyzed_inner.end(), A.innerIndexPtr(),
                      A.innerIndexPtr() + A.nonZeros());
  }
  /// The symbolic analysis (ordering) of A, unless lu already holds that of A's sparsity: the analysis
  /// (METIS, seeded anew at every call) is a function of the sparsity alone, so keeping it gives the same
  /// factors as redoing it. A pattern rebuilt to the same sparsity (after a checkpoint, or a contact set
  /// that came back) thus costs no analysis (~20 ms on the seed's example).
  void analyze(const SparseMatrix& A) {
    if (analyzed_for(A)) return;
    {
      std::lock_guard ordering(ordering_mutex());
      if (wide_lu) {
        wide_copy = A;
        wide_lu->analyzePattern(wide_copy);
      } else {
        lu.analyzePattern(A);
      }
    }
    ++analyses_in_process;
    analyzed_outer.assign(A.outerIndexPtr(), A.outerIndexPtr() + A.outerSize() + 1);
    analyzed_inner.assign(A.innerIndexPtr(), A.innerIndexPtr() + A.nonZeros());
  }
  /// After lu.compute of another matrix (the Krylov fallback): its analysis is no longer known.
  void forget_analysis() {
    analyzed_outer.clear();
    analyzed_inner.clear();
  }
};

/// The iterative path: a copy of the matrix (Newton may reuse a "factorisation" after the pattern's
/// values moved on) and BiCGSTAB preconditioned by its diagonal. An LU of the copy (Impl) is built
/// only when a Krylov solve fails. Jacobi, not AMG: measured 138 iterations per solve at 1152 hex8 and
/// 234 at 7680 on the tumbling sphere; Eigen's IncompleteLUT (droptol 1e-4, fill 4) took 6.2 and 13.0
/// but its factorisations made the 7680 run 84 s against 46 s with Jacobi and 13.5 s with UMFPACK.
struct LinearSolver::Krylov {
  SparseMatrix A;
  Eigen::BiCGSTAB<SparseMatrix, Eigen::DiagonalPreconditioner<double>> bicgstab;
  bool lu_ready = false;
};

/// The PETSc path (petsc_solver.hpp), loaded on first use; an LU of its matrix only when a solve fails.
struct LinearSolver::Amg {
  explicit Amg(LinearMethod method)
      : solver(method == LinearMethod::petsc_mumps ? make_petsc_lu_solver() : make_petsc_amg_solver()) {}
  std::unique_ptr<AmgSolver> solver;
  bool lu_ready = false;
};

LinearSolver::LinearSolver(LinearMethod method) : impl_(std::make_unique<Impl>()), method_(method) {}
LinearSolver::~LinearSolver() = default;
LinearSolver::LinearSolver(LinearSolver&&) noexcept = default;
LinearSolver& LinearSolver::operator=(LinearSolver&&) noexcept = default;

void LinearSolver::set_method(LinearMethod method) {
  if (method == method_) return;
  method_ = method;
  amg_.reset();  // a PETSc solver of the other kind
  analyzed_generation_ = -1;
  factorized_generation_ = -1;
}

bool LinearSolver::factorize(const BlockPattern& A) {
  if (through_petsc()) return factorize_amg(A);
  const auto t0 = std::chrono::steady_clock::now();
  if (method_ == LinearMethod::iterative) {
    if (!krylov_) krylov_ = std::make_unique<Krylov>();
    krylov_->A = A.matrix();
    krylov_->lu_ready = false;
    krylov_->bicgstab.setTolerance(krylov_tolerance);
    krylov_->bicgstab.setMaxIterations(max_krylov_iterations);
    krylov_->bicgstab.compute(krylov_->A);
    factorization_seconds_ += seconds_since(t0);
    ++factorizations_;
    ++factorizations_in_process;
    const bool ok = krylov_->bicgstab.info() == Eigen::Success;
    factorized_generation_ = ok ? A.generation() : -1;
    return ok;
  }
  if (analyzed_generation_ != A.generation()) {
    impl_->analyze(A.matrix());
    analyzed_generation_ = A.generation();
  }
  bool ok = false;
  {
    const auto turn = blas_turn();
    ok = impl_->factorize(A.matrix());
  }
  factorization_seconds_ += seconds_since(t0);
  ++factorizations_;
  ++factorizations_in_process;
  factorized_generation_ = ok ? A.generation() : -1;
  return ok;
}

std::string LinearSolver::factorization_failure() const {
  if (method_ == LinearMethod::direct && impl_->status == UMFPACK_ERROR_out_of_memory)
    return "the direct solver (UMFPACK) ran out of memory factorising the Jacobian";
  return "singular Jacobian";
}

Eigen::VectorXd LinearSolver::solve(const Eigen::VectorXd& b) const {
  ++solves_in_process;
  if (through_petsc()) return solve_amg(b);
  const auto t0 = std::chrono::steady_clock::now();
  if (method_ == LinearMethod::iterative) {
    // No convergence (an indefinite or badly scaled system, e.g. contact multipliers): this matrix is
    // solved directly rather than handing Newton a poor increment.
    Eigen::VectorXd x = krylov_->bicgstab.solve(b);  // before asking for its iterations and info
    x = checked_krylov(
        std::move(x), int(krylov_->bicgstab.iterations()), krylov_->bicgstab.info() == Eigen::Success,
        [this] { return krylov_->A; }, krylov_->lu_ready, b);
    solve_seconds_ += seconds_since(t0);
    return x;
  }
  Eigen::VectorXd x;
  {
    const auto turn = blas_turn();
    x = impl_->solve(b);
  }
  solve_seconds_ += seconds_since(t0);
  return x;
}

bool LinearSolver::factorize_amg(const BlockPattern& A) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!amg_) amg_ = std::make_unique<Amg>(method_);
  if (amg_tolerance_ > 0) amg_->solver->set_tolerance(amg_tolerance_);
  amg_->lu_ready = false;
  const bool ok = amg_->solver->factorize(A.matrix(), A.generation(), coordinates_);
  factorization_seconds_ += seconds_since(t0);
  ++factorizations_;
  ++factorizations_in_process;
  factorized_generation_ = ok ? A.generation() : -1;
  return ok;
}

Eigen::VectorXd LinearSolver::solve_amg(const Eigen::VectorXd& b) const {
  const auto t0 = std::chrono::steady_clock::now();
  Eigen::VectorXd x;
  const KrylovOutcome outcome = amg_->solver->solve(b, x);
  x = checked_krylov(
      std::move(x), outcome.iterations, outcome.converged, [this] { return amg_->solver->matrix(); },
      amg_->lu_ready, b);
  solve_seconds_ += seconds_since(t0);
  return x;
}

Eigen::VectorXd LinearSolver::checked_krylov(Eigen::VectorXd x, int iterations, bool converged,
                                             const std::function<SparseMatrix()>& matrix, bool& lu_ready,
                                             const Eigen::VectorXd& b) const {
  if (method_ != LinearMethod::petsc_mumps) {  // an LU's one "iteration" is no Krylov statistic
    ++krylov_solves_;
    krylov_iterations_ += iterations;
    krylov_max_iterations_ = std::max(krylov_max_iterations_, iterations);
  }
  if (converged && x.allFinite()) return x;
  ++krylov_fallbacks_;  // Newton gets a solution of this matrix either way
  if (!lu_ready) {
    const SparseMatrix A = matrix();
    impl_->forget_analysis();
    impl_->analyze(A);
    const auto turn = blas_turn();
    impl_->factorize(A);
    impl_->forget_analysis();
    lu_ready = true;
  }
  const auto turn = blas_turn();
  return impl_->solve(b);
}

void LinearSolver::set_krylov_tolerance(double relative) {
  amg_tolerance_ = relative;
  if (amg_) amg_->solver->set_tolerance(relative);
}

std::string LinearSolver::preconditioner_description() const {
  return amg_ && through_petsc() ? amg_->solver->description() : std::string();
}

}  // namespace stoss::solve
