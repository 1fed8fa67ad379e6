// The system shall cap the connections one client address holds at once (issue 10, "What must hold" 3,
// `stoss serve --max-connections-per-client`): a connection over the cap is answered 503 naming the limit
// and closed at once, while other clients (and /healthz for them) stay served and the client gets its
// connections back as it closes some. /healthz is answered even over the cap (issue 20), then closed.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <thread>

#include "server/cli/serve.hpp"
#include "server/http/connection_limit.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

using namespace std::chrono_literals;
using server::http::ConnectionLimit;

// --- unit level -------------------------------------------------------------------------------------

TEST(ConnectionLimit, CountsEachConnectionOnceAndFreesItsPlaceWhenItCloses) {
  ConnectionLimit limit(2);
  // Each connection is served on a thread of its own; its later requests do not count it again.
  auto serve_one = [&](bool& admitted, bool& admitted_again) {
    admitted = limit.admit("10.0.0.1");
    admitted_again = limit.admit("10.0.0.1");
  };
  bool a = false, a2 = false, b = false, b2 = false, c = true, d = false;
  std::thread first([&] { serve_one(a, a2); });  // both stay open: their threads never release them
  first.join();
  std::thread second([&] { serve_one(b, b2); });
  second.join();
  EXPECT_TRUE(a && a2 && b && b2);
  EXPECT_EQ(limit.open("10.0.0.1"), 2);
  std::thread third([&] {
    c = limit.admit("10.0.0.1");
    limit.release_this_thread();  // a refused connection was never counted: closing it frees nothing
  });
  third.join();
  EXPECT_FALSE(c) << "the third connection of one client is over the cap of 2";
  EXPECT_EQ(limit.open("10.0.0.1"), 2);
  std::thread other_client([&] {
    d = limit.admit("10.0.0.2");
    EXPECT_EQ(limit.open("10.0.0.2"), 1);
    limit.release_this_thread();
  });
  other_client.join();
  EXPECT_TRUE(d) << "another client has a cap of its own";
  EXPECT_EQ(limit.open("10.0.0.2"), 0) << "a closed connection frees its place";
}

TEST(ConnectionLimit, TheFlagHasADefaultAndARange) {
  EXPECT_EQ(cli::parse_serve_options({}).max_connections_per_client, 64);
  EXPECT_EQ(cli::parse_serve_options({"--max-connections-per-client", "3"}).max_connections_per_client, 3);
  try {
    cli::parse_serve_options({"--max-connections-per-client", "0"});
    ADD_FAILURE() << "0 must be refused";
  } catch (const cli::UsageError& e) {
    EXPECT_EQ(std::string(e.what()),
              "--max-connections-per-client needs an integer in [1, 1000000], got '0'");
  }
}

// --- against the live server ------------------------------------------------------------------------

/// A socket connected to the server's loopback port from `source` (127.0.0.1, or another address of the
/// loopback net for a second client); -1 on failure. Reads on it time out after 5 s.
int connect_from(const char* source, int port) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in local{}, server{};
  local.sin_family = AF_INET;
  inet_pton(AF_INET, source, &local.sin_addr);
  server.sin_family = AF_INET;
  server.sin_port = htons(static_cast<uint16_t>(port));
  server.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  const timeval timeout{5, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  if (bind(fd, reinterpret_cast<sockaddr*>(&local), sizeof local) != 0 ||
      connect(fd, reinterpret_cast<sockaddr*>(&server), sizeof server) != 0) {
    close(fd);
    return -1;
  }
  return fd;
}

/// One response read from `fd`: its head and body (Content-Length framed), and whether the server then
/// closed the connection (EOF seen within the socket's 5 s read timeout).
struct Reply {
  std::string head, body;
  bool closed = false;
};

Reply exchange(int fd, const std::string& request, bool expect_close) {
  Reply reply;
  if (write(fd, request.data(), request.size()) != static_cast<ssize_t>(request.size())) return reply;
  std::string data;
  char buffer[4096];
  std::size_t head_end = std::string::npos, length = 0;
  for (;;) {
    if (head_end == std::string::npos && (head_end = data.find("\r\n\r\n")) != std::string::npos) {
      reply.head = data.substr(0, head_end);
      const auto at = reply.head.find("Content-Length: ");
      if (at != std::string::npos) length = std::stoul(reply.head.substr(at + 16));
    }
    if (head_end != std::string::npos && data.size() >= head_end + 4 + length && !expect_close) break;
    const ssize_t n = read(fd, buffer, sizeof buffer);
    if (n == 0) reply.closed = true;
    if (n <= 0) break;
    data.append(buffer, static_cast<std::size_t>(n));
  }
  if (head_end != std::string::npos) reply.body = data.substr(head_end + 4, length);
  return reply;
}

const std::string healthz = "GET /healthz HTTP/1.1\r\nHost: x\r\n\r\n";
const std::string schema = "GET /v1/schema/scene HTTP/1.1\r\nHost: x\r\n\r\n";

bool is_status(const Reply& r, int status) {
  return r.head.rfind("HTTP/1.1 " + std::to_string(status), 0) == 0;
}

TEST(ConnectionLimitLive, AConnectionOverTheCapIs503AndClosedWhileOtherClientsAreServed) {
  TempDir dir;
  LiveServer server(dir.path() / "data",
                    {"--workers", "0", "--max-connections-per-client", "4", "--read-timeout", "30"});
  // 127.0.0.1 holds four kept-alive connections; each has been answered, so each is counted.
  std::vector<int> held;
  for (int i = 0; i < 4; ++i) {
    held.push_back(connect_from("127.0.0.1", server.port()));
    ASSERT_GE(held.back(), 0);
    ASSERT_TRUE(is_status(exchange(held.back(), healthz, false), 200)) << i;
  }
  // A fifth is answered 503 naming the limit, and the server closes it (EOF, not the 5 s read timeout).
  const int fifth = connect_from("127.0.0.1", server.port());
  ASSERT_GE(fifth, 0);
  const Reply refused = exchange(fifth, schema, true);
  close(fifth);
  ASSERT_TRUE(is_status(refused, 503)) << refused.head;
  EXPECT_TRUE(refused.closed) << "the refused connection must be closed by the server";
  const auto problem = nlohmann::json::parse(refused.body);
  EXPECT_EQ(problem["type"], "urn:stoss:problem:too-many-connections");
  EXPECT_EQ(problem["limits"][0]["name"], "max_connections_per_client");
  EXPECT_EQ(problem["limits"][0]["limit"], 4);
  EXPECT_NE(problem["detail"].get<std::string>().find("client 127.0.0.1 already holds 4 connections"),
            std::string::npos)
      << problem["detail"];

  // /healthz over the cap is answered (issue 20: one address cannot make it 503), and that connection
  // is then closed too, so it cannot hold a thread past its answer.
  const int health = connect_from("127.0.0.1", server.port());
  ASSERT_GE(health, 0);
  const Reply alive = exchange(health, healthz, true);
  close(health);
  EXPECT_TRUE(is_status(alive, 200)) << alive.head;
  EXPECT_TRUE(alive.closed) << "/healthz over the cap must end its connection";
  EXPECT_EQ(alive.body, "{\"status\":\"ok\"}");

  // Another client (127.0.0.2 on the loopback net) is served, and so are the held connections.
  const int other = connect_from("127.0.0.2", server.port());
  ASSERT_GE(other, 0);
  EXPECT_TRUE(is_status(exchange(other, healthz, false), 200));
  close(other);
  EXPECT_TRUE(is_status(exchange(held[0], healthz, false), 200));

  // Once one held connection closes, 127.0.0.1 may open another (the server notices the close at once;
  // the loop's bound is generous).
  close(held.back());
  held.pop_back();
  const bool admitted = eventually(
      [&] {
        const int fd = connect_from("127.0.0.1", server.port());
        const bool ok = fd >= 0 && is_status(exchange(fd, schema, false), 200);
        if (fd >= 0) close(fd);
        return ok;
      },
      5s);
  EXPECT_TRUE(admitted) << "a closed connection must give its place back";
  for (int fd : held) close(fd);
  EXPECT_TRUE(server.alive()) << server.output();
}

}  // namespace
}  // namespace stoss::test
