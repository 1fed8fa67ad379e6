#include "server/http/connection_limit.hpp"

#include <netdb.h>
#include <sys/socket.h>

#include <cstdlib>
#include <filesystem>
#include <optional>

#include "server/http/problem.hpp"

namespace stoss::server::http {

namespace {

/// The client whose connection this pool thread serves, once its first request counted it.
thread_local std::optional<std::string> counted_client;
/// Whether this thread's connection is to be shut down once the current answer is written.
thread_local bool close_marked = false;

class CountingThreadPool : public httplib::ThreadPool {
 public:
  CountingThreadPool(std::size_t threads, ConnectionLimit& limit) : ThreadPool(threads), limit_(limit) {}
  void enqueue(std::function<void()> fn) override {
    ThreadPool::enqueue([this, fn = std::move(fn)] {
      fn();                  // serves one connection until it closes
      close_marked = false;  // a mark left by a connection that ended unanswered is not the next one's
      limit_.release_this_thread();
    });
  }

 private:
  ConnectionLimit& limit_;
};

/// Numeric host and port of a socket address, as cpp-httplib writes them into a Request.
std::optional<std::pair<std::string, int>> numeric(const sockaddr_storage& address, socklen_t length) {
  char host[NI_MAXHOST], port[NI_MAXSERV];
  if (getnameinfo(reinterpret_cast<const sockaddr*>(&address), length, host, sizeof host, port, sizeof port,
                  NI_NUMERICHOST | NI_NUMERICSERV) != 0)
    return std::nullopt;
  return std::pair<std::string, int>{host, std::atoi(port)};
}

bool socket_matches(int fd, const httplib::Request& req) {
  sockaddr_storage local{}, peer{};
  socklen_t local_length = sizeof local, peer_length = sizeof peer;
  if (getsockname(fd, reinterpret_cast<sockaddr*>(&local), &local_length) != 0) return false;
  if (getpeername(fd, reinterpret_cast<sockaddr*>(&peer), &peer_length) != 0) return false;
  const auto here = numeric(local, local_length), there = numeric(peer, peer_length);
  return here && there && here->second == req.local_port && there->second == req.remote_port &&
         here->first == req.local_addr && there->first == req.remote_addr;
}

/// Ends an answered connection: FIN after the answer, then the bytes the client already sent are
/// dropped (at most drain_bytes, without waiting), so that closing does not reset the connection
/// before the client read the answer; then no more is read (cpp-httplib's next read sees the end).
bool end_connection(int fd) {
  constexpr std::size_t drain_bytes = 1 << 20;
  const bool ended = ::shutdown(fd, SHUT_WR) == 0;
  char buffer[16384];
  for (std::size_t drained = 0; drained < drain_bytes;) {
    const ssize_t n = ::recv(fd, buffer, sizeof buffer, MSG_DONTWAIT);
    if (n <= 0) break;
    drained += static_cast<std::size_t>(n);
  }
  ::shutdown(fd, SHUT_RD);
  return ended;
}

}  // namespace

bool ConnectionLimit::admit(const std::string& client) {
  if (counted_client) return true;  // a later request of a counted connection
  std::lock_guard lock(mutex_);
  int& open = open_[client];
  if (open >= per_client_) return false;
  ++open;
  counted_client = client;
  return true;
}

void ConnectionLimit::release_this_thread() {
  if (!counted_client) return;
  {
    std::lock_guard lock(mutex_);
    const auto it = open_.find(*counted_client);
    if (it != open_.end() && --it->second <= 0) open_.erase(it);
  }
  counted_client.reset();
}

int ConnectionLimit::open(const std::string& client) const {
  std::lock_guard lock(mutex_);
  const auto it = open_.find(client);
  return it == open_.end() ? 0 : it->second;
}

httplib::TaskQueue* counting_thread_pool(std::size_t threads, ConnectionLimit& limit) {
  return new CountingThreadPool(threads, limit);
}

void refuse_connection(const ConnectionLimit& limit, const httplib::Request& req, httplib::Response& res) {
  const std::string cap = std::to_string(limit.per_client());
  Problem{503,
          "urn:stoss:problem:too-many-connections",
          "Too many connections",
          "client " + req.remote_addr + " already holds " + cap +
              " connections, the most max_connections_per_client (--max-connections-per-client) allows; "
              "this one is closed: reuse an open connection or retry after one closes",
          {{"limits", nlohmann::json::array(
                          {{{"name", "max_connections_per_client"}, {"limit", limit.per_client()}}})}}}
      .write(res);
  close_after_answer(req);
}

void close_after_answer(const httplib::Request& req) {
  // cpp-httplib writes "Connection: close" when the request asked for it (req is the server's own).
  auto& request = const_cast<httplib::Request&>(req);
  request.headers.erase("Connection");
  request.headers.emplace("Connection", "close");
  close_marked = true;
}

bool end_marked_connection(const httplib::Request& req) {
  if (!close_marked) return false;
  close_marked = false;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", error)) {
    const std::string name = entry.path().filename().string();
    char* end = nullptr;
    const long fd = std::strtol(name.c_str(), &end, 10);
    if (end == name.c_str() || *end != '\0') continue;
    // Only this thread closes this connection's socket, so the descriptor that matches stays it.
    if (socket_matches(int(fd), req)) return end_connection(int(fd));
  }
  return false;
}

}  // namespace stoss::server::http
