// Limits before reading (issue 20, "What must hold" 3 and two small items of 5): a chunked body is
// counted as it arrives and cut off at --max-body-bytes, a route that needs a token refuses before it
// reads, a slow upload ends --request-timeout after its head, one address cannot make /healthz answer
// 503, a 413 reports 64-bit counts exactly, the server and the model count steps with one formula, and
// the exception handler turns anything a route throws into a 500 problem.
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <thread>

#include "core/model/model.hpp"
#include "server/cli/serve.hpp"
#include "server/http/limits.hpp"
#include "server/http/request_gate.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

using namespace std::chrono_literals;
using server::http::Limits;
using server::http::ProblemError;
namespace http = server::http;

// --- one step-count formula -------------------------------------------------------------------------

/// The steps of `end` / `step` as the model (TimeSpec), the server's early limit check
/// (estimate_scene_counts) and the core function each count them; all three must agree.
struct ThreeCounts {
  long long core, model, server;
};

ThreeCounts count_steps(double end, double step) {
  model::TimeSpec t;
  t.end = end;
  t.step = step;
  const nlohmann::json scene = {{"time", {{"end", end}, {"step", step}}}};
  return {model::step_count(end, step), t.steps(), server::http::estimate_scene_counts(scene).steps};
}

void expect_steps(double end, double step, long long expected) {
  const ThreeCounts n = count_steps(end, step);
  EXPECT_EQ(n.core, expected) << end << " / " << step;
  EXPECT_EQ(n.server, expected) << "the server counts " << end << " / " << step << " otherwise";
  EXPECT_EQ(n.model, expected) << "the model counts " << end << " / " << step << " otherwise";
}

TEST(StepCount, AQuotientWithinOneUlpOfAnIntegerIsThatIntegerEverywhere) {
  for (const double n : {100.0, 1e6, 1e9}) {
    expect_steps(std::nextafter(n, 0.0), 1, static_cast<long long>(n));  // n − 1 ulp: floor gave n − 1
    expect_steps(n, 1, static_cast<long long>(n));
    expect_steps(std::nextafter(n, 2 * n), 1, static_cast<long long>(n));  // n + 1 ulp: ceil gave n + 1
  }
  expect_steps(1, 0.01, 100);   // 1 / 0.01 = 100 exactly in doubles
  expect_steps(0.7, 0.1, 7);    // 6.999999999999999
  expect_steps(0.9, 0.03, 30);  // 30.000000000000004
}

TEST(StepCount, APartialLastStepCountsAndNothingIsCountedForNoTime) {
  expect_steps(100.5, 1, 101);
  expect_steps(0.105, 0.01, 11);
  expect_steps(0.01, 1, 1);
  expect_steps(0, 1, 0);
  expect_steps(1, 0, 0);
  expect_steps(-1, 0.1, 0);
  expect_steps(std::nan(""), 1, 0);
  expect_steps(1, INFINITY, 0);
  EXPECT_EQ(model::step_count(1e300, 1e-300), model::max_step_count) << "saturates instead of overflowing";
}

// --- exact 413 values ---------------------------------------------------------------------------------

TEST(ExactLimits, A413ReportsCountsBeyond32BitsExactly) {
  const nlohmann::json scene = {
      {"bodies", {{{"mesh", {{"box", {{"divisions", {1'000'000, 1'000'000, 1'000'000}}}}}}}}},
      {"time", {{"step", 1}, {"end", 1e12}}},
      {"output", {{"every", 10}}}};
  const auto problem = server::http::check_scene_limits_early(scene, Limits{});
  ASSERT_TRUE(problem);
  const nlohmann::json limits = problem->to_json()["limits"];
  ASSERT_EQ(limits.size(), 3u) << limits.dump();
  EXPECT_EQ(limits[0]["name"], "max_nodes");
  EXPECT_EQ(limits[0]["value"].get<long long>(), 1'000'003'000'003'000'001LL) << "(10^6 + 1)^3";
  EXPECT_EQ(limits[1]["name"], "max_steps");
  EXPECT_EQ(limits[1]["value"].get<long long>(), 1'000'000'000'000LL);
  EXPECT_EQ(limits[2]["name"], "max_frames");
  EXPECT_EQ(limits[2]["value"].get<long long>(), 100'000'000'001LL) << "every 10th step and step 0";
  EXPECT_NE(problem->detail.find("1000000000000 time steps"), std::string::npos) << problem->detail;
}

// --- reading a body within the limits (a fake cpp-httplib content reader) ----------------------------

/// A content reader that offers `chunks` chunks of `chunk` bytes; `offered` counts the bytes it handed
/// over, `refused` whether the receiver asked it to stop.
struct FakeReader {
  std::size_t chunk = 1000, chunks = 0;
  std::size_t offered = 0;
  bool refused = false;
  bool cut_off = false;  ///< ends as a connection that dropped would, after the last chunk
  httplib::ContentReader reader() {
    return httplib::ContentReader(
        [this](httplib::ContentReceiver receiver) {
          const std::string bytes(chunk, 'x');
          for (std::size_t i = 0; i < chunks; ++i) {
            offered += chunk;
            if (!receiver(bytes.data(), bytes.size())) return !(refused = true);
          }
          return !cut_off;
        },
        nullptr);
  }
};

/// What read_body_within_limits made of `fake`: the body, or the problem it threw.
struct Read {
  std::optional<std::string> body;
  std::optional<server::http::Problem> problem;
};

Read read_with(FakeReader& fake, const Limits& limits,
               std::chrono::steady_clock::time_point deadline = std::chrono::steady_clock::now() + 1h) {
  httplib::Response res;
  res.status = 400;  // what cpp-httplib leaves after a failed read
  try {
    return {server::http::read_body_within_limits(fake.reader(), limits, deadline, res), std::nullopt};
  } catch (const ProblemError& e) {
    return {std::nullopt, e.problem()};
  }
}

TEST(ReadBody, StopsAtTheFirstChunkBeyondTheLimitAndNeverHoldsMore) {
  Limits limits;
  limits.max_body_bytes = 10'500;
  FakeReader fake{1000, 1'000'000};  // 1 GB offered
  const Read r = read_with(fake, limits);
  ASSERT_TRUE(r.problem);
  EXPECT_EQ(r.problem->status, 413);
  EXPECT_TRUE(fake.refused);
  EXPECT_EQ(fake.offered, 11'000u) << "reading must stop at the chunk that passes the limit";
  const nlohmann::json j = r.problem->to_json();
  EXPECT_EQ(j["limits"][0]["name"], "max_body_bytes");
  EXPECT_EQ(j["limits"][0]["limit"], 10'500);
  EXPECT_FALSE(j["limits"][0].contains("value")) << "a body cut off unread has no known size";

  FakeReader within{1000, 10};
  const Read ok = read_with(within, limits);
  ASSERT_TRUE(ok.body);
  EXPECT_EQ(*ok.body, std::string(10'000, 'x'));
}

TEST(ReadBody, BytesArrivingAfterTheDeadlineAre408NamingTheFlag) {
  Limits limits;
  limits.request_timeout = 2500ms;
  FakeReader fake{10, 100};
  const Read r = read_with(fake, limits, std::chrono::steady_clock::now() - 1ms);
  ASSERT_TRUE(r.problem);
  EXPECT_EQ(r.problem->status, 408);
  EXPECT_EQ(fake.offered, 10u);
  const nlohmann::json j = r.problem->to_json();
  EXPECT_EQ(j["type"], "urn:stoss:problem:request-timeout");
  EXPECT_EQ(j["limits"][0]["name"], "request_timeout");
  EXPECT_EQ(j["limits"][0]["limit"], 2.5);
  EXPECT_NE(r.problem->detail.find("2.5 s after the request's head (10 bytes by then)"), std::string::npos)
      << r.problem->detail;
  EXPECT_NE(r.problem->detail.find("--request-timeout"), std::string::npos) << r.problem->detail;
}

TEST(ReadBody, ABodyCutOffIs400WithTheBytesRead) {
  FakeReader fake{100, 3};
  fake.cut_off = true;
  const Read r = read_with(fake, Limits{});
  ASSERT_TRUE(r.problem);
  EXPECT_EQ(r.problem->status, 400);
  EXPECT_NE(r.problem->detail.find("300 bytes read"), std::string::npos) << r.problem->detail;
}

// --- against the live server ------------------------------------------------------------------------

/// VmHWM (peak resident set) or VmRSS of a process, in bytes, from /proc/PID/status.
std::uint64_t status_bytes(pid_t pid, const std::string& field) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind(field + ":", 0) == 0) return std::stoull(line.substr(field.size() + 1)) * 1024;
  ADD_FAILURE() << "no " << field << " for process " << pid;
  return 0;
}

bool send_all(int fd, const std::string& bytes) {
  for (std::size_t sent = 0; sent < bytes.size();) {
    const ssize_t n = send(fd, bytes.data() + sent, bytes.size() - sent, MSG_NOSIGNAL);
    if (n <= 0) return false;
    sent += static_cast<std::size_t>(n);
  }
  return true;
}

/// Whatever the server sends until it closes the connection (or 10 s pass without a byte).
std::string read_until_closed(int fd) {
  std::string reply;
  char buffer[4096];
  for (ssize_t n; (n = recv(fd, buffer, sizeof buffer, 0)) > 0;)
    reply.append(buffer, static_cast<std::size_t>(n));
  return reply;
}

/// The answer to a request whose body is streamed: `head`, then `body_bytes` generated on the fly in
/// chunks of `piece` (chunked framing when `chunked`), stopping as soon as the server answers or stops
/// taking bytes; `sent` counts the body bytes that went out.
struct Streamed {
  std::string reply;
  std::uint64_t sent = 0;
};

Streamed stream_body(int port, const std::string& head, std::uint64_t body_bytes, bool chunked,
                     std::size_t piece = 1 << 16, std::chrono::milliseconds pause = 0ms) {
  Streamed out;
  const int fd = connect_loopback(port, 10s);
  if (fd < 0 || !send_all(fd, head)) return out;
  const std::string data(piece, ' ');  // JSON whitespace: a body that is valid as far as it goes
  char size_line[32];
  std::snprintf(size_line, sizeof size_line, "%zx\r\n", piece);
  const std::string framed = chunked ? size_line + data + "\r\n" : data;
  while (out.sent < body_bytes) {
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, 0) > 0) break;  // the server answered (or closed): stop sending
    if (!send_all(fd, framed)) break;
    out.sent += piece;
    if (pause > 0ms) std::this_thread::sleep_for(pause);
  }
  if (chunked && out.sent >= body_bytes) send_all(fd, "0\r\n\r\n");
  out.reply = read_until_closed(fd);
  close(fd);
  return out;
}

nlohmann::json problem_of(const std::string& reply) {
  const auto at = reply.find("\r\n\r\n");
  return at == std::string::npos ? nlohmann::json()
                                 : nlohmann::json::parse(reply.substr(at + 4), nullptr, false);
}

bool is_status(const std::string& reply, int status) {
  return reply.rfind("HTTP/1.1 " + std::to_string(status) + " ", 0) == 0;
}

constexpr std::uint64_t one_gigabyte = 1ull << 30;
constexpr std::uint64_t max_body = 32ull << 20;

std::string chunked_post(const std::string& path, const std::string& extra_headers = "") {
  return "POST " + path + " HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n" + extra_headers +
         "Transfer-Encoding: chunked\r\n\r\n";
}

/// A server with --max-body-bytes 32 MiB: a 1 GB chunked body to each route that reads one is answered
/// 413 and the server's peak resident memory grows by less than 2 × 32 MiB.
TEST(ChunkedFlood, OneGigabyteChunkedIsCutOffAtTheLimitWithMemoryUnderTwiceIt) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "0", "--max-body-bytes", std::to_string(max_body)});
  for (const char* path : {"/v1/validate", "/v1/jobs", "/v1/studies", "/v1/meshes"}) {
    const std::uint64_t before = status_bytes(server.pid(), "VmRSS");
    const Streamed r = stream_body(server.port(), chunked_post(path), one_gigabyte, true);
    const std::uint64_t peak = status_bytes(server.pid(), "VmHWM");
    ASSERT_TRUE(is_status(r.reply, 413)) << path << ": " << r.reply.substr(0, 300);
    EXPECT_NE(r.reply.find("Connection: close"), std::string::npos) << r.reply.substr(0, 300);
    const nlohmann::json p = problem_of(r.reply);
    EXPECT_EQ(p["limits"][0]["name"], "max_body_bytes") << p.dump();
    EXPECT_EQ(p["limits"][0]["limit"], max_body) << p.dump();
    EXPECT_LT(r.sent, one_gigabyte) << path << ": the server read the whole gigabyte";
    EXPECT_LT(peak, before + 2 * max_body)
        << path << ": the peak resident set grew by " << (peak - before) / (1 << 20) << " MiB for "
        << r.sent / (1 << 20) << " MiB sent";
    std::printf("[ measure  ] %s: %llu MiB sent, peak RSS %llu MiB above the RSS before (limit 32 MiB)\n",
                path, static_cast<unsigned long long>(r.sent >> 20),
                static_cast<unsigned long long>(peak > before ? (peak - before) >> 20 : 0));
  }
  EXPECT_EQ(server.client().Get("/healthz")->status, 200);
}

TEST(ChunkedFlood, WithATokenFileAnUnauthorizedChunkedUploadIs401UnreadAndOtherBodiesAreRefusedFromTheHead) {
  TempDir dir;
  std::ofstream(dir.path() / "token") << "let-me-in\n";
  LiveServer server(dir.path() / "data", {"--workers", "0", "--max-body-bytes", std::to_string(max_body),
                                          "--token-file", (dir.path() / "token").string()});
  const std::uint64_t before = status_bytes(server.pid(), "VmRSS");
  const Streamed r = stream_body(server.port(), chunked_post("/v1/meshes"), one_gigabyte, true);
  const std::uint64_t peak = status_bytes(server.pid(), "VmHWM");
  ASSERT_TRUE(is_status(r.reply, 401)) << r.reply.substr(0, 300);
  EXPECT_EQ(problem_of(r.reply)["type"], "urn:stoss:problem:unauthorized");
  EXPECT_LT(r.sent, one_gigabyte);
  EXPECT_LT(peak, before + 2 * max_body) << "grew by " << (peak - before) / (1 << 20) << " MiB";
  std::printf("[ measure  ] 401: %llu MiB sent, peak RSS %llu MiB above the RSS before\n",
              static_cast<unsigned long long>(r.sent >> 20),
              static_cast<unsigned long long>(peak > before ? (peak - before) >> 20 : 0));

  // With the token: a chunked body to an unknown route (404), to a route that takes none (411), in
  // another transfer coding (501), or a Content-Length above the limit (413 with the exact length,
  // beyond 32 bits), all answered from the head before a byte of the body.
  const std::string token = "Authorization: Bearer let-me-in\r\n";
  EXPECT_TRUE(is_status(
      stream_body(server.port(), chunked_post("/v2/nothing", token), one_gigabyte, true).reply, 404));
  const std::string cancel = "/v1/jobs/" + std::string(32, 'a') + "/cancel";
  EXPECT_TRUE(
      is_status(stream_body(server.port(), chunked_post(cancel, token), one_gigabyte, true).reply, 413))
      << "a POST route that ignores its body still counts it";
  const Streamed get = stream_body(
      server.port(), "GET /v1/jobs HTTP/1.1\r\nHost: x\r\n" + token + "Transfer-Encoding: chunked\r\n\r\n",
      one_gigabyte, true);
  EXPECT_TRUE(is_status(get.reply, 411)) << get.reply.substr(0, 300);
  const Streamed gzip = stream_body(
      server.port(), "POST /v1/validate HTTP/1.1\r\nHost: x\r\n" + token + "Transfer-Encoding: gzip\r\n\r\n",
      one_gigabyte, false);
  EXPECT_TRUE(is_status(gzip.reply, 501)) << gzip.reply.substr(0, 300);
  for (const std::string length : {"1073741824", "18446744073709551615"}) {
    const int fd = connect_loopback(server.port(), 10s);
    ASSERT_TRUE(send_all(
        fd, "POST /v1/validate HTTP/1.1\r\nHost: x\r\n" + token + "Content-Length: " + length + "\r\n\r\n{"));
    const std::string reply = read_until_closed(fd);
    close(fd);
    ASSERT_TRUE(is_status(reply, 413)) << reply.substr(0, 300);
    const nlohmann::json p = problem_of(reply);
    EXPECT_EQ(p["limits"][0]["value"].get<std::uint64_t>(), std::stoull(length)) << p.dump();
    EXPECT_NE(p["detail"].get<std::string>().find(length), std::string::npos) << p.dump();
  }
  // A client that waits for 100 Continue is refused instead, and sends no body.
  const int fd = connect_loopback(server.port(), 10s);
  ASSERT_TRUE(send_all(fd,
                       "POST /v1/meshes HTTP/1.1\r\nHost: x\r\nContent-Length: 1073741824\r\n"
                       "Expect: 100-continue\r\n\r\n"));
  const std::string expecting = read_until_closed(fd);
  close(fd);
  EXPECT_TRUE(is_status(expecting, 401)) << "no token: " << expecting.substr(0, 300);
  EXPECT_TRUE(server.alive()) << server.output();
}

// --- slow uploads and /healthz ------------------------------------------------------------------------

TEST(RequestTimeout, TheFlagHasADefaultARangeAndItsHelp) {
  EXPECT_EQ(cli::parse_serve_options({}).limits.request_timeout, 60s);
  EXPECT_EQ(cli::parse_serve_options({"--request-timeout", "2.5"}).limits.request_timeout, 2500ms);
  try {
    cli::parse_serve_options({"--request-timeout", "0"});
    ADD_FAILURE() << "0 must be refused";
  } catch (const cli::UsageError& e) {
    EXPECT_EQ(std::string(e.what()), "--request-timeout needs seconds in [0.01, 86400], got '0'");
  }
  EXPECT_NE(cli::serve_usage().find("--request-timeout S"), std::string::npos);
}

/// With --request-timeout 1 (and a read timeout of 5 s, far above the 0.1 s between bytes), an upload
/// that drips a byte every 0.1 s is answered 408 and closed before its 100 bytes are in, framed by
/// Content-Length or chunked.
TEST(RequestTimeout, ADrippingUploadEndsAfterTheTotalTimeNotOnlyTheGapBetweenBytes) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "0", "--request-timeout", "1", "--read-timeout", "5"});
  const std::string framed = "POST /v1/validate HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n";
  for (const bool chunked : {false, true}) {
    const std::string head =
        framed + (chunked ? "Transfer-Encoding: chunked\r\n\r\n" : "Content-Length: 100\r\n\r\n");
    const Streamed r = stream_body(server.port(), head, 100, chunked, 1, 100ms);
    ASSERT_TRUE(is_status(r.reply, 408)) << (chunked ? "chunked: " : "") << r.reply.substr(0, 300);
    EXPECT_LT(r.sent, 100u) << "the answer came only after the whole body";
    const nlohmann::json p = problem_of(r.reply);
    EXPECT_EQ(p["type"], "urn:stoss:problem:request-timeout");
    EXPECT_EQ(p["limits"][0]["name"], "request_timeout");
    EXPECT_EQ(p["limits"][0]["limit"], 1.0);
    EXPECT_NE(r.reply.find("Connection: close"), std::string::npos);
  }
  EXPECT_EQ(server.client().Get("/healthz")->status, 200);
}

/// The report's reproducer: 64 uploads from one address (the default cap) stalled mid-body; /healthz
/// from that address is still answered 200 (and that connection is closed after it), while any other
/// route from it gets the cap's 503.
TEST(HealthzUnderTheCap, SixtyFourStalledUploadsFromOneAddressDoNotMakeHealthz503) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "0", "--read-timeout", "60"});
  std::vector<int> uploads;
  for (int i = 0; i < 64; ++i) {
    uploads.push_back(connect_loopback(server.port(), 10s));
    ASSERT_GE(uploads.back(), 0);
    ASSERT_TRUE(
        send_all(uploads.back(), "POST /v1/jobs HTTP/1.1\r\nHost: x\r\nContent-Length: 1000\r\n\r\n{"));
  }
  auto ask = [&](const std::string& path) {
    const int fd = connect_loopback(server.port(), 10s);
    send_all(fd, "GET " + path + " HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n");
    std::string reply = read_until_closed(fd);
    close(fd);
    return reply;
  };
  // Once the server counts all 64 (it does when it has read their heads), another route is refused.
  ASSERT_TRUE(eventually([&] { return is_status(ask("/v1/schema/scene"), 503); }, 20s))
      << "the 64 uploads were never counted against the cap";
  for (int i = 0; i < 3; ++i) {
    const std::string reply = ask("/healthz");
    EXPECT_TRUE(is_status(reply, 200)) << reply.substr(0, 300);
    EXPECT_NE(reply.find("{\"status\":\"ok\"}"), std::string::npos) << reply;
  }
  for (int fd : uploads) close(fd);
  EXPECT_TRUE(server.alive()) << server.output();
}

// --- the exception handler --------------------------------------------------------------------------

TEST(ExceptionHandler, TurnsAnyThrownValueIntoA500ProblemAndKeepsServing) {
  httplib::Server server;
  http::Metrics metrics;
  http::install_error_handling(server, metrics);
  server.Get("/std", [](const httplib::Request&, httplib::Response&) { throw std::runtime_error("boom"); });
  server.Get("/int", [](const httplib::Request&, httplib::Response&) { throw 42; });
  server.Get("/json", [](const httplib::Request&, httplib::Response& res) {
    res.body = nlohmann::json::parse("{").dump();
  });
  server.Get("/ok",
             [](const httplib::Request&, httplib::Response& res) { res.set_content("ok", "text/plain"); });
  const int port = server.bind_to_any_port("127.0.0.1");
  std::thread thread([&] { server.listen_after_bind(); });
  httplib::Client client("127.0.0.1", port);
  for (const char* path : {"/std", "/int", "/json"}) {
    auto r = client.Get(path);
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 500) << path;
    EXPECT_EQ(r->get_header_value("Content-Type"), "application/problem+json");
    const auto j = nlohmann::json::parse(r->body);
    EXPECT_EQ(j["type"], "urn:stoss:problem:internal");
  }
  EXPECT_EQ(nlohmann::json::parse(client.Get("/std")->body)["detail"], "boom");
  auto unknown = client.Get("/nowhere");
  EXPECT_EQ(unknown->status, 404);
  EXPECT_EQ(nlohmann::json::parse(unknown->body)["type"], "urn:stoss:problem:no-route");
  EXPECT_EQ(client.Get("/ok")->body, "ok");
  server.stop();
  thread.join();
  EXPECT_NE(metrics.render({}, 0).find("stoss_http_requests_total{code=\"500\"} 4"), std::string::npos);
}

}  // namespace
}  // namespace stoss::test
