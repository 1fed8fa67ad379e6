#include "server/jobs/running/job_process.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <new>
#include <system_error>
#include <thread>
#include <tuple>
#include <vector>

#include "core/parallel/mpi_place.hpp"
#include "core/run/ranks.hpp"
#include "core/scene/scene.hpp"
#include "core/solve/petsc_solver.hpp"
#include "server/common/stop_signals.hpp"
#include "server/jobs/job_files.hpp"
#include "server/jobs/running/inprocess_executor.hpp"
#include "server/jobs/running/job_protocol.hpp"
#include "server/jobs/running/launcher.hpp"

namespace stoss::server::jobs {

namespace {

/// The child's cancel flag, set by SIGTERM.
std::atomic<bool> child_cancel{false};

/// Writes all of `text` to `fd` (EINTR retried); false when the reader is gone.
bool write_all(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    done += static_cast<std::size_t>(n);
  }
  return true;
}

void append_log(const std::filesystem::path& log, const std::string& line) {
  std::ofstream out(log, std::ios::app);
  out << line << '\n' << std::flush;
}

std::string memory_limit_reason(std::size_t memory) {
  return "exceeded memory limit " + std::to_string(memory) + " bytes (--job-memory)";
}

/// The process's own set-up: it dies with the server (a job whose server is gone is rerun by another one
/// after its lease expires), the memory limit, a lower priority. False when the parent is already gone.
bool enter_job_process(const JobProcessOptions& options) {
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (options.parent > 0 && getppid() != options.parent) return false;
  if (options.memory > 0) {
    const rlimit limit{options.memory, options.memory};
    setrlimit(RLIMIT_AS, &limit);
  }
  // Batch work yields to the API: on a busy machine status polls keep their latency, and a job loses
  // nothing when the CPU is idle otherwise.
  if (nice(5) == -1 && errno != 0) errno = 0;
  return true;
}

/// Runs the attempt with `executor`, reporting progress to `report`; `recorded` says whether the executor
/// wrote outcome.json itself.
Outcome run_attempt(const JobProcessOptions& options, InProcessExecutor& executor,
                    const AttemptFiles& attempt, const ProgressSink& report, bool& recorded) {
  recorded = false;
  try {
    const Job job = read_job_request(attempt.dir());
    Outcome outcome = executor.run(job, child_cancel, report);
    recorded = true;
    if (outcome.status == Status::failed && options.memory > 0 && outcome.error &&
        outcome.error->find("bad_alloc") != std::string::npos) {
      outcome.error = memory_limit_reason(options.memory);
      append_log(attempt.log(), "failed: " + *outcome.error);
      recorded = false;
    }
    return outcome;
  } catch (const std::bad_alloc&) {
    return {Status::failed, std::nullopt, memory_limit_reason(options.memory)};
  } catch (const std::exception& e) {
    return {Status::failed, std::nullopt, std::string("cannot run the job: ") + e.what()};
  }
}

/// Writes `outcome` unless the executor did; the exit code of the process.
int record(const AttemptFiles& attempt, const Outcome& outcome, bool recorded) {
  try {
    if (!recorded) attempt.write_outcome(outcome);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stoss run-job: %s\n", e.what());
    return 3;
  }
  return 0;
}

/// The attempt's outcome `reason`, also in its log, when it cannot run at all; the exit code.
int record_failure(const AttemptFiles& attempt, const std::string& reason) {
  append_log(attempt.log(), "failed: " + reason);
  return record(attempt, {Status::failed, std::nullopt, reason}, false);
}

// ---- A job on several ranks ----

/// The command every rank of the launch runs: this executable's run-job for the attempt, with its share of
/// the memory limit.
std::vector<std::string> rank_command(const JobProcessOptions& o) {
  std::vector<std::string> command{this_executable().string(),
                                   "run-job",
                                   std::filesystem::absolute(o.data).string(),
                                   o.id.str(),
                                   "--attempt",
                                   std::to_string(o.attempt),
                                   "--ranks",
                                   std::to_string(o.ranks),
                                   "--launched"};
  if (o.memory > 0) command.insert(command.end(), {"--memory", std::to_string(o.memory / o.ranks)});
  return command;
}

/// Makes fd `target` append to `path`; throws std::system_error when it cannot.
void append_fd_to(int target, const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0 || ::dup2(fd, target) < 0)
    throw std::system_error(errno, std::generic_category(), "cannot open " + path.string());
  ::close(fd);
}

/// Replaces this process by the launcher; the exit code when it cannot (the attempt failed with the reason).
int launch_ranks(const JobProcessOptions& options) {
  JobProcessOptions launcher = options;
  launcher.memory = 0;  // each rank has its share (rank_command)
  if (!enter_job_process(launcher)) return 3;
  const AttemptFiles attempt = JobFiles{options.data}.attempt(options.id, options.attempt);
  std::string reason;
  try {
    const auto command = launcher_command(options.launcher, options.ranks, rank_command(options));
    // stdout: the progress pipe, where the launcher passes rank 0's stdout on; stderr: the launcher's
    // messages and every rank's, the reason of a launch that failed.
    if (::dup2(progress_fd, STDOUT_FILENO) < 0)
      throw std::system_error(errno, std::generic_category(), "dup2");
    ::close(progress_fd);
    append_fd_to(STDERR_FILENO, attempt.dir() / launcher_log_file);
    sigset_t none;  // the spawn blocked SIGTERM, which the launcher must receive
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    reason = exec_command(command);
  } catch (const std::exception& e) {
    reason = e.what();
  }
  return record_failure(attempt,
                        "cannot start the job's " + std::to_string(options.ranks) + " ranks: " + reason);
}

/// Sets the cancel flag once the parent wrote the attempt's cancel file (the cancel of a launch), looking
/// every 100 ms while it lives.
class CancelFileWatch {
 public:
  explicit CancelFileWatch(std::filesystem::path file)
      : thread_([this, file = std::move(file)] {
          for (std::error_code error; !done_; std::this_thread::sleep_for(std::chrono::milliseconds(100)))
            if (std::filesystem::exists(file, error)) child_cancel.store(true);
        }) {}
  ~CancelFileWatch() {
    done_ = true;
    thread_.join();
  }
  CancelFileWatch(const CancelFileWatch&) = delete;
  CancelFileWatch& operator=(const CancelFileWatch&) = delete;

 private:
  std::atomic<bool> done_{false};
  std::thread thread_;
};

/// Rank 0's word to every rank: a sum over the ranks to which only rank 0 adds.
bool word_of_rank_zero(parallel::MpiPlace place, bool word) {
  double value = place.rank == 0 && word ? 1.0 : 0.0;
  solve::sum_over_ranks(&value, 1);
  return value > 0;
}

/// Rank 0: the attempt in its folder, progress on stdout. It tells the other ranks whether the run starts
/// (not when it adopts an earlier run or cannot load the scene) and lets them copy the checkpoint it resumes
/// from before its first step.
int lead_ranks(const JobProcessOptions& options, parallel::MpiPlace place) {
  const JobFiles files{options.data};
  const AttemptFiles attempt = files.attempt(options.id, options.attempt);
  SystemClock clock;
  InProcessExecutor executor(files, clock);
  bool started = false;
  executor.on_model([&](model::Model& m) {
    started = true;
    word_of_rank_zero(place, true);
    solve::synchronize_ranks();  // the others have copied the checkpoint
    run::prepare_for_ranks(m, place);
  });
  const ProgressSink report = [](const Progress& p) { write_all(STDOUT_FILENO, progress_line(p)); };
  bool recorded = false;
  Outcome outcome;
  {
    const CancelFileWatch watch(attempt.dir() / cancel_file);
    outcome = run_attempt(options, executor, attempt, report, recorded);
  }
  if (!started) word_of_rank_zero(place, false);
  const int code = record(attempt, outcome, recorded);
  // A failure of this rank alone (a full disk) leaves the others waiting in a sum: leave without MPI's
  // goodbye, and the launcher ends them.
  if (started && outcome.status == Status::failed) std::_Exit(code);
  return code;
}

/// Rank k > 0: the same steps as rank 0, in a private folder; nothing it writes is kept.
Outcome follow_in_private(const JobProcessOptions& options, parallel::MpiPlace place) {
  const JobFiles files{options.data};
  const AttemptFiles lead = files.attempt(options.id, options.attempt);
  std::string dir = lead.dir().string();
  const run::RankRun rank(place, dir, true);  // with a copy of the checkpoint rank 0 resumes from
  solve::synchronize_ranks();
  const Job job = read_job_request(lead.dir());
  model::Model model = scene::load_resolved(job.scene, files.mesh_files());
  run::prepare_for_ranks(model, place);
  const AttemptFiles own(dir);
  std::ofstream log(own.log(), std::ios::app);
  SystemClock clock;
  InProcessExecutor executor(files, clock);
  executor.without_result();
  return executor.simulate_job(job, own, model, log, child_cancel, [](const Progress&) {});
}

int follow_rank(const JobProcessOptions& options, parallel::MpiPlace place) {
  if (!word_of_rank_zero(place, false)) return 0;  // rank 0 runs nothing
  std::string reason;
  try {
    const Outcome outcome = follow_in_private(options, place);
    if (outcome.status != Status::failed) return 0;
    reason = outcome.error.value_or("failed");
  } catch (const std::bad_alloc&) {
    reason = memory_limit_reason(options.memory);
  } catch (const std::exception& e) {
    reason = e.what();
  }
  // As on rank 0: rank 0 may be waiting in a sum, and the launcher ends it.
  std::fprintf(stderr, "stoss run-job: rank %d of %d: %s\n", place.rank, place.size, reason.c_str());
  std::_Exit(1);
}

/// One rank of a launch: MPI started, its place taken from MPI, the rank count checked, then rank 0 leads and
/// the others follow.
int run_rank(const JobProcessOptions& options) {
  const AttemptFiles attempt = JobFiles{options.data}.attempt(options.id, options.attempt);
  parallel::MpiPlace place;
  try {
    std::tie(place.rank, place.size) = solve::world_place();
    solve::synchronize_ranks();
  } catch (const std::exception& e) {
    const std::string within = options.memory > 0 ? " within " + std::to_string(options.memory) +
                                                        " bytes of address space per rank (" +
                                                        "--job-memory shared by the ranks)"
                                                  : "";
    return place.rank == 0 ? record_failure(attempt, "cannot start MPI" + within + ": " + e.what()) : 0;
  }
  if (place.size != options.ranks) {
    const std::string reason = "the launcher started " + std::to_string(place.size) +
                               " ranks, the job asks for " + std::to_string(options.ranks) +
                               " (solver.ranks): see --launcher's {ranks}";
    return place.rank == 0 ? record_failure(attempt, reason) : 0;
  }
  return place.rank == 0 ? lead_ranks(options, place) : follow_rank(options, place);
}

}  // namespace

int run_job_process(const JobProcessOptions& options) {
  if (options.ranks > 1 && !options.launched) return launch_ranks(options);
  // SIGTERM cancels. It stays blocked in every thread (since the spawn: one sent while the process starts is
  // kept) and one thread waits for it. A handler missed it while a library had its own in place: METIS,
  // which UMFPACK's ordering calls, installs a SIGTERM handler around each call, and a cancel landing there
  // was lost (the job ran on and was killed 30 s later, "did not stop within 30 s of the cancel").
  server::StopSignals signals;
  signals.on_stop([](int) { child_cancel.store(true); });
  if (!enter_job_process(options)) return 3;
  if (options.launched) return run_rank(options);
  const JobFiles files{options.data};
  const AttemptFiles attempt = files.attempt(options.id, options.attempt);
  SystemClock clock;
  InProcessExecutor executor(files, clock);
  const ProgressSink report = [](const Progress& p) { write_all(progress_fd, progress_line(p)); };
  bool recorded = false;
  const Outcome outcome = run_attempt(options, executor, attempt, report, recorded);
  return record(attempt, outcome, recorded);
}

}  // namespace stoss::server::jobs
