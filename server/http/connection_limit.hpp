#pragma once
/// @file The per-client cap on concurrent connections (`stoss serve --max-connections-per-client`).
///
/// cpp-httplib serves each connection on one thread of its pool and hands handlers no socket. The cap is
/// therefore kept per pool thread: the first request of a connection counts it for its client address
/// (thread-local), and the pool's task ends the count when the connection closes. A connection over the
/// cap gets 503 (`urn:stoss:problem:too-many-connections`) and is shut down once that answer is written,
/// so it frees its thread at once. A connection that has not yet sent a request head is not counted; the
/// read timeout bounds how long it can hold its thread.

#include <cstddef>
#include <map>
#include <mutex>
#include <string>

#include "server/http/httplib.hpp"

namespace stoss::server::http {

class ConnectionLimit {
 public:
  /// `per_client` ≥ 1: the most connections one client address may hold at once.
  explicit ConnectionLimit(int per_client) : per_client_(per_client) {}

  /// Called on the thread serving `client`'s connection, for each request. True when the connection is
  /// already counted or fits under the cap (it is counted from now on); false when it is one too many.
  bool admit(const std::string& client);
  /// The connection served on this thread has closed: its client holds one connection fewer.
  void release_this_thread();

  int per_client() const { return per_client_; }
  /// Connections `client` holds now (counted ones).
  int open(const std::string& client) const;

 private:
  int per_client_;
  mutable std::mutex mutex_;
  std::map<std::string, int> open_;
};

/// A thread pool of `threads` threads for httplib::Server::new_task_queue whose tasks (one connection
/// each) call limit.release_this_thread() when they end.
httplib::TaskQueue* counting_thread_pool(std::size_t threads, ConnectionLimit& limit);

/// The 503 for a connection over the cap, naming the client, the cap and the flag; marks the connection
/// (this thread's) to be shut down by end_refused_connection once the answer is written.
void refuse_connection(const ConnectionLimit& limit, const httplib::Request& req, httplib::Response& res);

/// After an answer is written (the server's logger): when refuse_connection marked this thread's
/// connection, shuts its socket down (found among this process's sockets by the request's two addresses),
/// so the client sees the connection end and the thread is free at once. True when it did.
bool end_refused_connection(const httplib::Request& req);

}  // namespace stoss::server::http
