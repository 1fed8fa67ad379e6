#include "server/jobs/running/process_executor.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <system_error>

#include "core/output/durable_file.hpp"
#include "server/jobs/reporting/series_recorder.hpp"
#include "server/jobs/running/job_process.hpp"
#include "server/jobs/running/launcher.hpp"

extern char** environ;

namespace stoss::server::jobs {

namespace {

using Steady = std::chrono::steady_clock;

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  return std::string(std::istreambuf_iterator<char>(in), {});
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

/// The pipe the child reports progress on: {read end, write end}, both close-on-exec (the spawn dups the
/// write end onto progress_fd), the write end never progress_fd itself.
std::pair<int, int> progress_pipe() {
  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0) throw std::system_error(errno, std::generic_category(), "pipe");
  if (fds[1] == progress_fd) {  // dup2 onto itself would keep FD_CLOEXEC
    const int moved = fcntl(fds[1], F_DUPFD_CLOEXEC, 10);
    ::close(fds[1]);
    fds[1] = moved;
  }
  return {fds[0], fds[1]};
}

/// The child's signals: it starts with only SIGTERM blocked (the server blocks SIGTERM and SIGINT in every
/// thread) and keeps it blocked, waiting for it in a thread of its own (job_process.cpp), so a cancel sent
/// while it starts is a cancel, not a kill; it has a process group of its own, so Ctrl-C reaches the server,
/// which stops its jobs itself.
void set_child_signals(posix_spawnattr_t& attributes) {
  sigset_t only_term, defaults;
  sigemptyset(&only_term);
  sigaddset(&only_term, SIGTERM);
  sigemptyset(&defaults);
  for (int s : {SIGTERM, SIGINT, SIGPIPE, SIGHUP}) sigaddset(&defaults, s);
  posix_spawnattr_setsigmask(&attributes, &only_term);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setpgroup(&attributes, 0);
  posix_spawnattr_setflags(&attributes,
                           POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETPGROUP);
}

/// Splits what arrives on the progress pipe into lines and relays each report.
class ProgressRelay {
 public:
  explicit ProgressRelay(const ProgressSink& sink) : sink_(sink) {}
  void add(const char* bytes, std::size_t size) {
    pending_.append(bytes, size);
    for (std::size_t eol; (eol = pending_.find('\n')) != std::string::npos;) {
      const auto report = progress_from_line(pending_.substr(0, eol));
      pending_.erase(0, eol + 1);
      if (sink_ && report) sink_(*report);
    }
  }

 private:
  const ProgressSink& sink_;
  std::string pending_;
};

/// The first paragraph of the launcher's messages (Open MPI frames its own in dashes), on one line.
std::string launcher_message(const std::filesystem::path& log) {
  std::ifstream in(log);
  std::string message, line;
  while (std::getline(in, line)) {
    const bool frame = line.find_first_not_of("- \t") == std::string::npos;
    if (frame && !message.empty() && line.find('-') == std::string::npos) break;  // a blank line ends it
    if (frame || line.rfind("mpiexec: Forwarding signal", 0) == 0) continue;
    if (!message.empty()) message += ' ';
    message += line.substr(line.find_first_not_of(" \t"));
  }
  constexpr std::size_t longest = 400;
  if (message.size() > longest) message = message.substr(0, longest) + " …";
  if (message.empty()) return "no message (" + log.filename().string() + " is empty)";
  return message + " (" + log.filename().string() + ")";
}

/// Cancels the job process: SIGTERM, or for a launch the file rank 0 looks for (a signal the launcher passes
/// on could reach a rank before it can take it, and kill it).
void cancel_process(pid_t pid, const std::filesystem::path& cancel_by_file) {
  if (cancel_by_file.empty()) {
    ::kill(pid, SIGTERM);
    return;
  }
  try {
    output::write_durably(cancel_by_file, "");
  } catch (const std::exception&) {  // no cancel then: the grace ends with SIGKILL
  }
}

}  // namespace

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

int ProcessExecutor::ranks(const Job& job) {
  return job.kind == Kind::simulation ? std::max(1, job.ranks) : 1;
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

Outcome ProcessExecutor::supervise(const Job& job, const std::atomic<bool>& cancel,
                                   const ProgressSink& progress) {
  const auto dir = files_.attempt(job.id, job.attempt).dir();
  std::filesystem::create_directories(dir);
  std::error_code ignored;
  std::filesystem::remove(dir / outcome_file_name, ignored);
  std::filesystem::remove(dir / cancel_file, ignored);  // of an earlier run of this attempt, released
  write_job_request(dir, job);

  const auto [read_end, write_end] = progress_pipe();
  pid_t pid = -1;
  try {
    pid = spawn(job, write_end);
  } catch (...) {
    ::close(read_end);
    throw;
  }
  try {
    output::write_durably(dir / job_pid_file, std::to_string(pid) + "\n");
  } catch (...) {
  }
  const Millis wall = wall_limit(job, limits_.wall);
  const bool launched = ranks(job) > 1;
  const Watched watched = watch(pid, read_end, wall, launched ? dir / cancel_file : "", cancel, progress);
  ::close(read_end);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::filesystem::remove(dir / job_pid_file, ignored);
  return launched ? launch_ended(job, dir, watched, status, wall) : ended(job, dir, watched, status, wall);
}

pid_t ProcessExecutor::spawn(const Job& job, int write_end) const {
  std::vector<std::string> args = {binary_.string(), "run-job", data_dir_.string(), job.id.str()};
  args.insert(args.end(), {"--attempt", std::to_string(job.attempt), "--parent", std::to_string(getpid())});
  if (limits_.memory > 0) args.insert(args.end(), {"--memory", std::to_string(limits_.memory)});
  if (const int n = ranks(job); n > 1) {
    const std::string launcher =
        limits_.launcher.empty() ? default_launcher(geteuid() == 0) : limits_.launcher;
    args.insert(args.end(), {"--ranks", std::to_string(n), "--launcher", launcher});
  }
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
  set_child_signals(attributes);
  pid_t pid = -1;
  const int spawned = posix_spawn(&pid, binary_.c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attributes);
  ::close(write_end);
  if (spawned != 0)
    throw std::system_error(spawned, std::generic_category(), "cannot start " + binary_.string());
  return pid;
}

ProcessExecutor::Watched ProcessExecutor::watch(pid_t pid, int read_end, Millis wall,
                                                const std::filesystem::path& cancel_by_file,
                                                const std::atomic<bool>& cancel,
                                                const ProgressSink& progress) const {
  const auto started = Steady::now();
  Watched watched;
  Steady::time_point terminated_at;
  ProgressRelay relay(progress);
  for (;;) {
    pollfd readable{read_end, POLLIN, 0};
    const int ready = ::poll(&readable, 1, 100);
    if (ready > 0) {
      char chunk[4096];
      const ssize_t n = ::read(read_end, chunk, sizeof chunk);
      if (n == 0) break;  // the child exited (or closed fd 3)
      if (n < 0 && errno != EINTR && errno != EAGAIN) break;
      if (n > 0) relay.add(chunk, static_cast<std::size_t>(n));
    } else if (ready < 0 && errno != EINTR) {
      break;
    }
    const auto now = Steady::now();
    if (cancel.load() && !watched.terminated) {
      cancel_process(pid, cancel_by_file);
      watched.terminated = true;
      terminated_at = now;
    }
    if (watched.terminated && !watched.killed &&
        now - terminated_at > std::chrono::milliseconds(limits_.stop_grace)) {
      ::kill(pid, SIGKILL);
      watched.killed = true;
    }
    if (wall > 0 && !watched.killed && now - started > std::chrono::milliseconds(wall)) {
      ::kill(pid, SIGKILL);
      watched.killed = watched.over_time = true;
    }
  }
  return watched;
}

Outcome ProcessExecutor::ended(const Job& job, const std::filesystem::path& dir, const Watched& watched,
                               int status, Millis wall) const {
  if (watched.over_time) return failed(job, "exceeded wall-time limit " + seconds_text(wall));
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    if (watched.terminated && signal == SIGKILL)  // canceled, and it did not stop within the grace period
      return failed(job,
                    "did not stop within " + seconds_text(limits_.stop_grace) + " of the cancel; killed");
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

Outcome ProcessExecutor::launch_ended(const Job& job, const std::filesystem::path& dir,
                                      const Watched& watched, int status, Millis wall) const {
  if (!watched.over_time) {
    try {
      return outcome_from_json(nlohmann::json::parse(read_text(dir / outcome_file_name)));
    } catch (const std::exception&) {  // none: the launch ended before rank 0 could write one
    }
  }
  if (watched.over_time || watched.killed || (WIFEXITED(status) && WEXITSTATUS(status) == 0))
    return ended(job, dir, watched, status, wall);
  const std::string how = WIFSIGNALED(status) ? signal_reason(WTERMSIG(status))
                                              : "exited with status " + std::to_string(WEXITSTATUS(status));
  return failed(job, "the launcher " + how + ": " + launcher_message(dir / launcher_log_file));
}

}  // namespace stoss::server::jobs
