#include "server/jobs/running/job_process.hpp"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <fstream>
#include <new>

#include "server/common/stop_signals.hpp"
#include "server/jobs/job_files.hpp"
#include "server/jobs/running/inprocess_executor.hpp"
#include "server/jobs/running/job_protocol.hpp"

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

/// Runs the attempt; `recorded` says whether the executor wrote outcome.json itself.
Outcome run_attempt(const JobProcessOptions& options, const JobFiles& files, const AttemptFiles& attempt,
                    bool& recorded) {
  recorded = false;
  try {
    const Job job = read_job_request(attempt.dir());
    SystemClock clock;
    InProcessExecutor executor(files, clock);
    ProgressSink report = [](const Progress& p) { write_all(progress_fd, progress_line(p)); };
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

}  // namespace

int run_job_process(const JobProcessOptions& options) {
  // SIGTERM cancels. It stays blocked in every thread (since the spawn: one sent while the process starts is
  // kept) and one thread waits for it. A handler missed it while a library had its own in place: METIS,
  // which UMFPACK's ordering calls, installs a SIGTERM handler around each call, and a cancel landing there
  // was lost (the job ran on and was killed 30 s later, "did not stop within 30 s of the cancel").
  server::StopSignals signals;
  signals.on_stop([](int) { child_cancel.store(true); });
  if (!enter_job_process(options)) return 3;
  const JobFiles files{options.data};
  const AttemptFiles attempt = files.attempt(options.id, options.attempt);
  bool recorded = false;
  const Outcome outcome = run_attempt(options, files, attempt, recorded);
  try {
    if (!recorded) attempt.write_outcome(outcome);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stoss run-job: %s\n", e.what());
    return 3;
  }
  return 0;
}

}  // namespace stoss::server::jobs
