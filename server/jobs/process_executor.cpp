#include "server/jobs/process_executor.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <string.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <fstream>
#include <new>
#include <sstream>
#include <system_error>

#include "server/common/json_input.hpp"
#include "server/jobs/inprocess_executor.hpp"
#include "server/jobs/series_recorder.hpp"

extern char** environ;

namespace stoss::server::jobs {

namespace {

using Steady = std::chrono::steady_clock;

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Writes `text` to `path` through a temporary name and a rename: readers see all of it or nothing.
void write_atomically(const std::filesystem::path& path, const std::string& text) {
  const auto temporary = path.string() + ".tmp";
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) throw std::system_error(EIO, std::generic_category(), "cannot write " + temporary);
  }
  std::filesystem::rename(temporary, path);
}

void append_log(const std::filesystem::path& log, const std::string& line) {
  std::ofstream out(log, std::ios::app);
  out << line << '\n' << std::flush;
}

/// "30 s", "1.5 s".
std::string seconds_text(Millis ms) {
  std::ostringstream s;
  s << static_cast<double>(ms) / 1000.0 << " s";
  return s.str();
}

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

/// The child's cancel flag, set by SIGTERM.
std::atomic<bool> child_cancel{false};
static_assert(std::atomic<bool>::is_always_lock_free);

extern "C" void on_terminate(int) {
  child_cancel.store(true);
}

}  // namespace

nlohmann::json job_request_json(const Job& job) {
  nlohmann::json j = {{"id", job.id.str()},
                      {"kind", to_string(job.kind)},
                      {"attempt", job.attempt},
                      {"worker", job.worker ? nlohmann::json(*job.worker) : nlohmann::json(nullptr)},
                      {"scene", job.scene},
                      {"study", job.study ? *job.study : nlohmann::json(nullptr)}};
  return j;
}

Job job_from_request(const nlohmann::json& request) {
  Job job;
  auto id = JobId::parse(request.at("id").get<std::string>());
  if (!id) throw std::invalid_argument("job request: malformed id");
  job.id = *id;
  auto kind = parse_kind(request.at("kind").get<std::string>());
  if (!kind) throw std::invalid_argument("job request: unknown kind");
  job.kind = *kind;
  job.status = Status::running;
  job.attempt = request.value("attempt", 0);
  if (request.contains("worker") && request["worker"].is_string()) job.worker = request["worker"].get<std::string>();
  job.scene = request.at("scene");
  if (request.contains("study") && !request["study"].is_null()) job.study = request["study"];
  return job;
}

std::string signal_reason(int signal) {
  const char* abbreviation = sigabbrev_np(signal);
  return "killed by signal " + (abbreviation ? "SIG" + std::string(abbreviation) : std::to_string(signal));
}

ProcessExecutor::ProcessExecutor(JobFiles files, std::filesystem::path data_dir, std::filesystem::path binary,
                                 ProcessLimits limits)
    : files_(std::move(files)), data_dir_(std::move(data_dir)), binary_(std::move(binary)), limits_(limits) {}

Millis ProcessExecutor::wall_limit(const Job& job, Millis server_limit) {
  Millis limit = server_limit > 0 ? server_limit : 0;
  if (job.scene.is_object()) {
    const auto solver = job.scene.find("solver");
    if (solver != job.scene.end() && solver->is_object()) {
      const auto seconds = solver->find("max_wall_seconds");
      if (seconds != solver->end() && seconds->is_number() && seconds->get<double>() > 0) {
        const auto scene_limit = static_cast<Millis>(std::ceil(std::min(seconds->get<double>(), 1e9) * 1000));
        limit = limit > 0 ? std::min(limit, scene_limit) : scene_limit;
      }
    }
  }
  return limit;
}

Outcome ProcessExecutor::failed(const Job& job, const std::string& reason) const {
  std::optional<nlohmann::json> summary;
  try {
    const AttemptFiles files = files_.attempt(job.id, job.attempt);  // this attempt's files only
    files.discard_partial();
    append_log(files.log(), "failed: " + reason);
    // The summary up to the last step the process recorded before it died.
    if (auto series = read_partial_series(files.dir() / partial_series_file)) summary = (*series)["summary"];
  } catch (...) {
  }
  return {Status::failed, summary, reason};
}

Outcome ProcessExecutor::run(const Job& job, const std::atomic<bool>& cancel, const ProgressSink& progress) {
  try {
    return supervise(job, cancel, progress);
  } catch (const std::exception& e) {
    return failed(job, std::string("cannot run the job process: ") + e.what());
  }
}

Outcome ProcessExecutor::supervise(const Job& job, const std::atomic<bool>& cancel, const ProgressSink& progress) {
  const auto dir = files_.attempt(job.id, job.attempt).dir();
  std::filesystem::create_directories(dir);
  std::error_code ignored;
  std::filesystem::remove(dir / outcome_file_name, ignored);
  write_atomically(dir / job_request_file, safe_dump(job_request_json(job)));

  int pipe_fds[2];
  if (pipe2(pipe_fds, O_CLOEXEC) != 0) throw std::system_error(errno, std::generic_category(), "pipe");
  int write_end = pipe_fds[1];
  if (write_end == progress_fd) {  // dup2 onto itself would keep FD_CLOEXEC
    write_end = fcntl(pipe_fds[1], F_DUPFD_CLOEXEC, 10);
    ::close(pipe_fds[1]);
  }
  const int read_end = pipe_fds[0];

  std::vector<std::string> args = {binary_.string(), "run-job", data_dir_.string(), job.id.str()};
  args.insert(args.end(), {"--attempt", std::to_string(job.attempt), "--parent", std::to_string(getpid())});
  if (limits_.memory > 0) args.insert(args.end(), {"--memory", std::to_string(limits_.memory)});
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, write_end, progress_fd);
  posix_spawn_file_actions_addclosefrom_np(&actions, progress_fd + 1);  // no listening socket, no database
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t only_term, defaults;
  sigemptyset(&only_term);
  sigaddset(&only_term, SIGTERM);
  sigemptyset(&defaults);
  for (int s : {SIGTERM, SIGINT, SIGPIPE, SIGHUP}) sigaddset(&defaults, s);
  // The server blocks SIGTERM and SIGINT in every thread; the child starts with only SIGTERM blocked and
  // unblocks it once its handler is in place, so a cancel sent while it starts is a cancel, not a kill.
  posix_spawnattr_setsigmask(&attributes, &only_term);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setpgroup(&attributes, 0);  // Ctrl-C reaches the server, which stops its jobs itself
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETPGROUP);
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, binary_.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  ::close(write_end);
  if (spawned != 0) {
    ::close(read_end);
    throw std::system_error(spawned, std::generic_category(), "cannot start " + binary_.string());
  }
  try {
    write_atomically(dir / job_pid_file, std::to_string(pid) + "\n");
  } catch (...) {
  }

  const Millis wall = wall_limit(job, limits_.wall);
  const auto started = Steady::now();
  bool terminated = false, killed = false, over_time = false;
  Steady::time_point terminated_at;
  std::string pending;
  for (;;) {
    pollfd watch{read_end, POLLIN, 0};
    const int ready = ::poll(&watch, 1, 100);
    if (ready > 0) {
      char chunk[4096];
      const ssize_t n = ::read(read_end, chunk, sizeof chunk);
      if (n == 0) break;  // the child exited (or closed fd 3)
      if (n < 0 && errno != EINTR && errno != EAGAIN) break;
      if (n > 0) pending.append(chunk, static_cast<std::size_t>(n));
      for (std::size_t eol; (eol = pending.find('\n')) != std::string::npos;) {
        const std::string line = pending.substr(0, eol);
        pending.erase(0, eol + 1);
        try {
          const auto message = nlohmann::json::parse(line);
          if (progress && message.contains("progress")) progress(progress_from_json(message["progress"]));
        } catch (const std::exception&) {  // a torn line: the next report comes soon
        }
      }
    } else if (ready < 0 && errno != EINTR) {
      break;
    }
    const auto now = Steady::now();
    if (cancel.load() && !terminated) {
      ::kill(pid, SIGTERM);
      terminated = true;
      terminated_at = now;
    }
    if (terminated && !killed && now - terminated_at > std::chrono::milliseconds(limits_.stop_grace)) {
      ::kill(pid, SIGKILL);
      killed = true;
    }
    if (wall > 0 && !killed && now - started > std::chrono::milliseconds(wall)) {
      ::kill(pid, SIGKILL);
      killed = over_time = true;
    }
  }
  ::close(read_end);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::filesystem::remove(dir / job_pid_file, ignored);

  if (over_time) return failed(job, "exceeded wall-time limit " + seconds_text(wall));
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    if (terminated && signal == SIGKILL)  // canceled, and it did not stop within the grace period
      return failed(job, "did not stop within " + seconds_text(limits_.stop_grace) + " of the cancel; killed");
    return failed(job, signal_reason(signal));
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) != 0)
    return failed(job, "the job process exited with status " + std::to_string(WEXITSTATUS(status)));
  try {
    return outcome_from_json(nlohmann::json::parse(read_text(dir / outcome_file_name)));
  } catch (const std::exception& e) {
    return failed(job, std::string("the job process left no outcome: ") + e.what());
  }
}

int run_job_command(const std::vector<std::string>& args) {
  std::string data_dir, id_text;
  std::size_t memory = 0;
  long parent = 0;
  int attempt = 0;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const bool has_value = i + 1 < args.size();
    if (args[i] == "--memory" && has_value) memory = std::stoull(args[++i]);
    else if (args[i] == "--attempt" && has_value) attempt = std::stoi(args[++i]);
    else if (args[i] == "--parent" && has_value) parent = std::stol(args[++i]);
    else if (data_dir.empty()) data_dir = args[i];
    else if (id_text.empty()) id_text = args[i];
    else return 2;
  }
  const auto id = JobId::parse(id_text);
  if (data_dir.empty() || !id || attempt < 1) {
    std::fprintf(
        stderr,
        "usage: stoss run-job DATA_DIR JOB_ID --attempt N [--memory BYTES] [--parent PID] (internal)\n");
    return 2;
  }
  // Die with the server: a job whose server is gone is rerun by another one after its lease expires.
  prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (parent > 0 && getppid() != parent) return 3;
  struct sigaction action {};
  action.sa_handler = on_terminate;
  sigemptyset(&action.sa_mask);
  sigaction(SIGTERM, &action, nullptr);
  sigset_t term;
  sigemptyset(&term);
  sigaddset(&term, SIGTERM);
  sigprocmask(SIG_UNBLOCK, &term, nullptr);  // blocked since the spawn (a SIGTERM meanwhile arrives now)
  if (memory > 0) {
    const rlimit limit{memory, memory};
    setrlimit(RLIMIT_AS, &limit);
  }
  // Batch work yields to the API: on a busy machine status polls keep their latency, and a job loses
  // nothing when the CPU is idle otherwise.
  if (nice(5) == -1 && errno != 0) errno = 0;
  signal(SIGPIPE, SIG_IGN);

  const JobFiles files{std::filesystem::path(data_dir)};
  const AttemptFiles attempt_files = files.attempt(*id, attempt);
  Outcome outcome;
  bool recorded = false;  // the executor wrote outcome.json itself
  try {
    const Job job =
        job_from_request(nlohmann::json::parse(read_text(attempt_files.dir() / job_request_file)));
    SystemClock clock;
    InProcessExecutor executor(files, clock);
    ProgressSink report = [](const Progress& p) {
      write_all(progress_fd, safe_dump({{"progress", to_json(p)}}) + "\n");
    };
    outcome = executor.run(job, child_cancel, report);
    recorded = true;
    if (outcome.status == Status::failed && memory > 0 && outcome.error &&
        outcome.error->find("bad_alloc") != std::string::npos) {
      outcome.error = "exceeded memory limit " + std::to_string(memory) + " bytes (--job-memory)";
      append_log(attempt_files.log(), "failed: " + *outcome.error);
      recorded = false;
    }
  } catch (const std::bad_alloc&) {
    outcome = {Status::failed, std::nullopt,
               "exceeded memory limit " + std::to_string(memory) + " bytes (--job-memory)"};
  } catch (const std::exception& e) {
    outcome = {Status::failed, std::nullopt, std::string("cannot run the job: ") + e.what()};
  }
  try {
    if (!recorded) attempt_files.write_outcome(outcome);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "stoss run-job: %s\n", e.what());
    return 3;
  }
  return 0;
}

}  // namespace stoss::server::jobs
