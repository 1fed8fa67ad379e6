#pragma once
/// @file Test support: a temporary directory, the real `stoss serve` binary on a free loopback port,
/// scenes, and polling with a deadline.

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "server/http/httplib.hpp"

namespace stoss::test {

/// A loopback port nobody listens on now.
int free_port();

/// A TCP connection to 127.0.0.1:`port` (a raw socket, for what an HTTP client will not send); -1 when
/// refused. A `receive_timeout` above zero bounds each read on it.
int connect_loopback(int port, std::chrono::seconds receive_timeout = std::chrono::seconds(0));

/// A fresh directory under the system temp dir, removed with everything in it.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// `stoss serve --listen 127.0.0.1:0 --data DATA ...` in a child process. The constructor returns once
/// the server printed its port; the destructor sends SIGTERM and waits (SIGKILL after a deadline).
class LiveServer {
 public:
  LiveServer(const std::filesystem::path& data, const std::vector<std::string>& extra_args = {});
  ~LiveServer();
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  int port() const { return port_; }
  pid_t pid() const { return pid_; }
  /// A client for this server (with `token` as bearer token when given).
  httplib::Client client(const std::string& token = "") const;
  /// SIGKILL, as a crash would; the process is reaped.
  void kill9();
  /// SIGTERM and wait for the exit code; sent to the one thread of the server with that kernel id
  /// (tgkill) when `thread` is given, as the kernel may hand a process-wide signal to any thread.
  int terminate(pid_t thread = 0);
  /// True while the process runs.
  bool alive() const;
  /// What the server wrote to stdout and stderr.
  std::string output() const;

 private:
  mutable pid_t pid_ = -1;        ///< -1 once reaped
  mutable int exit_status_ = -1;  ///< waitpid status once reaped
  int port_ = 0;
  std::filesystem::path out_;
};

/// How a `stoss` command ended: exit code (or -1) or the signal that killed it (or 0), and what it
/// printed (stdout and stderr together, or separately when asked).
struct CommandResult {
  int exit_code = -1;
  int signal = 0;
  std::string out;
  std::string err;
};

/// Starts the `stoss` binary with `args` in the background, stdout and stderr into `log` (truncated).
/// @throws std::runtime_error when it cannot be started.
pid_t spawn_stoss(const std::vector<std::string>& args, const std::filesystem::path& log);
/// Starts `command` (its program found on PATH) in the background, stdout and stderr into `log`
/// (truncated), in a process group of its own when `own_group`. @throws std::runtime_error as spawn_stoss.
pid_t spawn_program(const std::vector<std::string>& command, const std::filesystem::path& log,
                    bool own_group = false);

/// The text of file `p` (empty when it cannot be read).
std::string read_text(const std::filesystem::path& p);
/// What `command` prints on stdout, run through the shell; its exit status into `status` when given.
std::string shell_output(const std::string& command, int* status = nullptr);

/// Runs the `stoss` binary with `args`, waits at most `deadline` (then SIGKILL, signal 9 reported).
CommandResult run_stoss(const std::vector<std::string>& args,
                        std::chrono::milliseconds deadline = std::chrono::seconds(60),
                        const std::filesystem::path& cwd = {});

/// Calls `condition` until it is true or `deadline` passes; true if it became true.
bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds deadline);

/// A box [0,1]³ of `divisions`³ hex8, density 2 (mass 2), SVK, moving with velocity `v` and spinning
/// at `omega` about z; energy_momentum, `steps` steps of 0.01.
nlohmann::json box_scene(int divisions, int steps, std::array<double, 3> v = {1, 0.5, 0}, double omega = 0);

/// ½ m |v|² of box_scene's box (m = density × volume = 2).
double box_kinetic_energy(std::array<double, 3> v);

/// JSON body of a response (fails the test with the body when it is not JSON).
nlohmann::json body_json(const httplib::Result& r);

/// POST /v1/jobs with a JSON body; returns the result.
httplib::Result submit(httplib::Client& c, const nlohmann::json& scene, const std::string& key = "");

/// The body of POST /v1/studies: `scene` swept over `steps` with `schemes` (all three when empty).
nlohmann::json study_body(const nlohmann::json& scene, const std::vector<double>& steps,
                          const std::vector<std::string>& schemes = {});

/// POST /v1/studies with a JSON body; returns the result.
httplib::Result submit_study(httplib::Client& c, const nlohmann::json& body, const std::string& key = "");

/// GET /v1/jobs/{id} as JSON.
nlohmann::json job(httplib::Client& c, const std::string& id);

/// Polls the job until its status is one of `statuses`; returns the last job JSON.
nlohmann::json wait_for_status(httplib::Client& c, const std::string& id,
                               const std::vector<std::string>& statuses,
                               std::chrono::milliseconds deadline = std::chrono::seconds(120));

}  // namespace stoss::test
