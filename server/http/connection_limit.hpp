#pragma once
/// @file The per-client cap on concurrent connections (`stoss serve --max-connections-per-client`).
///
/// cpp-httplib serves each connection on one thread of its pool and hands handlers no socket. The cap is
/// therefore kept per pool thread: the first request of a connection counts it for its client address
/// (thread-local), and the pool's task ends the count when the connection closes. A connection over the
/// cap gets 503 (`urn:stoss:problem:too-many-connections`) and is shut down once that answer is written,
/// so it frees its thread at once. `GET /healthz` is the exception: over the cap it is still answered (a
/// client's own uploads must not make the server look dead to it), and that connection is then closed
/// the same way, so it cannot hold a thread past its one answer. A connection that has not yet sent a
/// request head is not counted; the read timeout bounds how long it can hold its thread.

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

/// The 503 for a connection over the cap, naming the client, the cap and the flag; the connection is
/// closed once the answer is written (close_after_answer).
void refuse_connection(const ConnectionLimit& limit, const httplib::Request& req, httplib::Response& res);

/// Marks the connection serving `req` (this thread's) to be shut down by end_marked_connection once its
/// answer is written, and says so to the client (Connection: close). For connections over the cap, and
/// for answers given before a body was read: what is left of that body must not be taken for the next
/// request.
void close_after_answer(const httplib::Request& req);

/// After an answer is written (the server's logger): when close_after_answer marked this thread's
/// connection, shuts its socket down (found among this process's sockets by the request's two addresses),
/// so the client sees the connection end and the thread is free at once. True when it did.
bool end_marked_connection(const httplib::Request& req);

}  // namespace stoss::server::http
