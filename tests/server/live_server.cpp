#include "tests/server/live_server.hpp"

#include <arpa/inet.h>
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdio>
#include <fstream>
#include <regex>
#include <stdexcept>
#include <thread>

extern char** environ;

namespace stoss::test {

int free_port() {
  const int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof a;
  bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a);
  getsockname(s, reinterpret_cast<sockaddr*>(&a), &length);
  close(s);
  return ntohs(a.sin_port);
}

int connect_loopback(int port, std::chrono::seconds receive_timeout) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (receive_timeout.count() > 0) {
    const timeval timeout{static_cast<time_t>(receive_timeout.count()), 0};
    setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  }
  if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
    close(fd);
    return -1;
  }
  return fd;
}

namespace {

/// The stoss binary followed by `arguments`.
std::vector<std::string> stoss_command(const std::vector<std::string>& arguments) {
  std::vector<std::string> args = {STOSS_BINARY};
  args.insert(args.end(), arguments.begin(), arguments.end());
  return args;
}

/// argv for posix_spawn, pointing into `args` (which must outlive it), null-terminated.
std::vector<char*> argv_of(std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  return argv;
}

/// Waits up to `deadline` for the child to exit; its status, or -1 if it still runs.
int wait_exit(pid_t pid, std::chrono::milliseconds deadline) {
  int status = -1;
  const bool exited = eventually([&] { return waitpid(pid, &status, WNOHANG) == pid; }, deadline);
  return exited ? status : -1;
}

}  // namespace

TempDir::TempDir() {
  std::string pattern = (std::filesystem::temp_directory_path() / "stoss-test-XXXXXX").string();
  if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
  path_ = pattern;
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

LiveServer::LiveServer(const std::filesystem::path& data, const std::vector<std::string>& extra_args) {
  static std::atomic<int> counter{0};
  std::filesystem::create_directories(data);
  out_ = data / ("server-" + std::to_string(counter++) + ".log");
  std::vector<std::string> args = {"serve", "--listen", "127.0.0.1:0", "--data", data.string()};
  args.insert(args.end(), extra_args.begin(), extra_args.end());
  pid_ = spawn_stoss(args, out_);

  const std::regex listening(R"(listening on http://127\.0\.0\.1:(\d+))");
  const bool up = eventually(
      [&] {
        std::smatch m;
        const std::string text = read_text(out_);
        if (std::regex_search(text, m, listening)) port_ = std::stoi(m[1]);
        return port_ != 0 || !alive();
      },
      std::chrono::seconds(30));
  if (!up || port_ == 0) {
    const std::string text = output();
    kill9();
    throw std::runtime_error("stoss serve did not start: " + text);
  }
}

LiveServer::~LiveServer() {
  if (pid_ > 0) terminate();
}

httplib::Client LiveServer::client(const std::string& token) const {
  httplib::Client c("127.0.0.1", port_);
  c.set_read_timeout(std::chrono::seconds(60));
  c.set_connection_timeout(std::chrono::seconds(10));
  if (!token.empty()) c.set_bearer_token_auth(token);
  return c;
}

void LiveServer::kill9() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGKILL);
  waitpid(pid_, nullptr, 0);
  pid_ = -1;
}

int LiveServer::terminate(pid_t thread) {
  if (pid_ <= 0) return exit_status_ == -1 ? -1 : WIFEXITED(exit_status_) ? WEXITSTATUS(exit_status_) : 128;
  if (thread > 0)
    ::syscall(SYS_tgkill, pid_, thread, SIGTERM);
  else
    ::kill(pid_, SIGTERM);
  const int status = wait_exit(pid_, std::chrono::seconds(60));
  if (status == -1) {
    ADD_FAILURE() << "stoss serve did not stop on SIGTERM within 60 s";
    kill9();
    return -1;
  }
  pid_ = -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

bool LiveServer::alive() const {
  if (pid_ <= 0) return false;
  int status = 0;
  if (waitpid(pid_, &status, WNOHANG) != pid_) return true;
  exit_status_ = status;
  pid_ = -1;
  return false;
}

std::string LiveServer::output() const {
  return read_text(out_);
}

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string shell_output(const std::string& command, int* status) {
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) {
    if (status) *status = -1;
    return {};
  }
  std::string out;
  std::array<char, 256> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) out += buffer.data();
  const int ended = pclose(pipe);
  if (status) *status = ended;
  return out;
}

pid_t spawn_program(const std::vector<std::string>& command, const std::filesystem::path& log,
                    bool own_group) {
  std::vector<std::string> args = command;
  const std::vector<char*> argv = argv_of(args);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  if (own_group) {
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attributes, 0);
  }
  pid_t pid = -1;
  const int rc = posix_spawnp(&pid, args.front().c_str(), &actions, &attributes, argv.data(), environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0)
    throw std::runtime_error("cannot start " + command.front() +
                             (command.size() > 1 ? " " + command[1] : ""));
  return pid;
}

pid_t spawn_stoss(const std::vector<std::string>& arguments, const std::filesystem::path& log) {
  return spawn_program(stoss_command(arguments), log);
}

CommandResult run_stoss(const std::vector<std::string>& arguments, std::chrono::milliseconds deadline,
                        const std::filesystem::path& cwd) {
  static std::atomic<int> counter{0};
  const auto base = std::filesystem::temp_directory_path() /
                    ("stoss-cmd-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
  const std::string out_file = base.string() + ".out", err_file = base.string() + ".err";
  std::vector<std::string> args = stoss_command(arguments);
  const std::vector<char*> argv = argv_of(args);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (!cwd.empty()) posix_spawn_file_actions_addchdir_np(&actions, cwd.c_str());
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, STOSS_BINARY, &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  CommandResult result;
  if (rc != 0) return result;
  int status = -1;
  const auto end = std::chrono::steady_clock::now() + deadline;
  while (waitpid(pid, &status, WNOHANG) != pid) {  // finer than eventually(): commands take milliseconds
    if (std::chrono::steady_clock::now() > end) {
      status = -1;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  if (status == -1) {
    ::kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
  }
  if (WIFEXITED(status)) result.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  result.out = read_text(out_file);
  result.err = read_text(err_file);
  std::error_code ignored;
  std::filesystem::remove(out_file, ignored);
  std::filesystem::remove(err_file, ignored);
  return result;
}

bool eventually(const std::function<bool()>& condition, std::chrono::milliseconds deadline) {
  const auto end = std::chrono::steady_clock::now() + deadline;
  while (!condition()) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

nlohmann::json box_scene(int divisions, int steps, std::array<double, 3> v, double omega) {
  return {{"format", "stoss-scene/1"},
          {"name", "box " + std::to_string(divisions) + "^3, " + std::to_string(steps) + " steps"},
          {"bodies",
           {{{"name", "box"},
             {"mesh",
              {{"box",
                {{"min", {0, 0, 0}}, {"max", {1, 1, 1}}, {"divisions", {divisions, divisions, divisions}}}}}},
             {"material",
              {{"model", "saint_venant_kirchhoff"},
               {"youngs_modulus", 1000},
               {"poisson_ratio", 0.3},
               {"density", 2}}},
             {"initial_velocity", v},
             {"initial_angular_velocity", {0, 0, omega}}}}},
          {"time", {{"scheme", "energy_momentum"}, {"step", 0.01}, {"end", 0.01 * steps}}},
          {"output", {{"every", std::max(1, steps / 100)}}}};
}

double box_kinetic_energy(std::array<double, 3> v) {
  return 0.5 * 2.0 * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

nlohmann::json body_json(const httplib::Result& r) {
  if (!r) {
    ADD_FAILURE() << "no response: " << httplib::to_string(r.error());
    return nullptr;
  }
  try {
    return nlohmann::json::parse(r->body);
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not JSON (" << e.what() << "): " << r->body;
    return nullptr;
  }
}

httplib::Result submit(httplib::Client& c, const nlohmann::json& scene, const std::string& key) {
  httplib::Headers headers;
  if (!key.empty()) headers.emplace("Idempotency-Key", key);
  return c.Post("/v1/jobs", headers, scene.dump(), "application/json");
}

nlohmann::json study_body(const nlohmann::json& scene, const std::vector<double>& steps,
                          const std::vector<std::string>& schemes) {
  nlohmann::json body = {{"scene", scene}, {"steps", steps}};
  if (!schemes.empty()) body["schemes"] = schemes;
  return body;
}

httplib::Result submit_study(httplib::Client& c, const nlohmann::json& body, const std::string& key) {
  httplib::Headers headers;
  if (!key.empty()) headers.emplace("Idempotency-Key", key);
  return c.Post("/v1/studies", headers, body.dump(), "application/json");
}

nlohmann::json job(httplib::Client& c, const std::string& id) {
  return body_json(c.Get("/v1/jobs/" + id));
}

nlohmann::json wait_for_status(httplib::Client& c, const std::string& id,
                               const std::vector<std::string>& statuses, std::chrono::milliseconds deadline) {
  nlohmann::json last;
  const bool reached = eventually(
      [&] {
        auto r = c.Get("/v1/jobs/" + id);
        if (!r || r->status != 200) return false;
        last = nlohmann::json::parse(r->body);
        return std::find(statuses.begin(), statuses.end(), last["status"].get<std::string>()) !=
               statuses.end();
      },
      deadline);
  if (!reached) ADD_FAILURE() << "job " << id << " did not reach the expected status; last: " << last.dump();
  return last;
}

}  // namespace stoss::test
