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
/// Whether this thread answered its connection's request with the too-many-connections 503.
thread_local bool refused_here = false;

class CountingThreadPool : public httplib::ThreadPool {
 public:
  CountingThreadPool(std::size_t threads, ConnectionLimit& limit) : ThreadPool(threads), limit_(limit) {}
  void enqueue(std::function<void()> fn) override {
    ThreadPool::enqueue([this, fn = std::move(fn)] {
      fn();  // serves one connection until it closes
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
          {{"limits", nlohmann::json::array({{{"name", "max_connections_per_client"}, {"limit", limit.per_client()}}})}}}
      .write(res);
  // cpp-httplib writes "Connection: close" when the request asked for it (req is the server's own).
  auto& request = const_cast<httplib::Request&>(req);
  request.headers.erase("Connection");
  request.headers.emplace("Connection", "close");
  refused_here = true;
}

bool end_refused_connection(const httplib::Request& req) {
  if (!refused_here) return false;
  refused_here = false;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/fd", error)) {
    const std::string name = entry.path().filename().string();
    char* end = nullptr;
    const long fd = std::strtol(name.c_str(), &end, 10);
    if (end == name.c_str() || *end != '\0') continue;
    // Only this thread closes this connection's socket, so the descriptor that matches stays it.
    if (socket_matches(int(fd), req)) return ::shutdown(int(fd), SHUT_RDWR) == 0;
  }
  return false;
}

}  // namespace stoss::server::http
