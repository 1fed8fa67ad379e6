// Pieces of the HTTP layer in isolation: ids, hashes, flags, problems, limits, auth, and the
// exception handler that must catch everything.
#include <gtest/gtest.h>

#include <fstream>
#include <set>
#include <thread>

#include "server/http/auth.hpp"
#include "server/http/limits.hpp"
#include "server/cli/serve.hpp"
#include "server/http/problem.hpp"
#include "server/http/request_gate.hpp"
#include "server/http/routes.hpp"
#include "server/jobs/id.hpp"
#include "server/common/sha256.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::server {
namespace {

using jobs::JobId;

TEST(JobId, IsThirtyTwoRandomLowercaseHexDigits) {
  std::set<std::string> seen;
  for (int i = 0; i < 1000; ++i) {
    const JobId id = JobId::random();
    EXPECT_TRUE(JobId::parse(id.str())) << id.str();
    seen.insert(id.str());
  }
  EXPECT_EQ(seen.size(), 1000u);
}

TEST(JobId, RejectsAnythingElseBeforeAnyLookup) {
  for (const char* bad : {"", "0123456789abcdef0123456789abcde", "0123456789abcdef0123456789abcdef0",
                          "0123456789ABCDEF0123456789ABCDEF", "../../../../etc/passwd00000000000",
                          "0123456789abcdef0123456789abcde/", "0123456789abcdef0123456789abcd\n0"})
    EXPECT_FALSE(JobId::parse(bad)) << bad;
}

TEST(Sha256, MatchesFipsTestVectors) {
  EXPECT_EQ(server::sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(server::sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(server::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(ServeOptions, HasDocumentedDefaults) {
  const cli::ServeOptions o = cli::parse_serve_options({});
  EXPECT_EQ(o.host, "127.0.0.1");
  EXPECT_EQ(o.port, 8080);
  EXPECT_EQ(o.data, "var");
  EXPECT_EQ(o.pool.workers, 2);
  EXPECT_EQ(o.pool.lease, 10'000);
  EXPECT_EQ(o.pool.renew_every, 2'000);
  EXPECT_EQ(o.limits.max_body_bytes, 16u << 20);
  EXPECT_EQ(o.limits.max_nodes, 200'000);
  EXPECT_EQ(o.limits.max_steps, 100'000);
  EXPECT_EQ(o.limits.max_frames, 2'000);
  EXPECT_EQ(o.limits.max_queued, 1'000);
  EXPECT_FALSE(o.token_file);
}

TEST(ServeOptions, ParsesEveryFlag) {
  const cli::ServeOptions o = cli::parse_serve_options({"--listen",
                                                          "0.0.0.0:9000",
                                                          "--data",
                                                          "/tmp/x",
                                                          "--workers",
                                                          "4",
                                                          "--token-file",
                                                          "t",
                                                          "--max-body-bytes=1000",
                                                          "--max-nodes",
                                                          "10",
                                                          "--max-steps",
                                                          "20",
                                                          "--max-frames",
                                                          "30",
                                                          "--max-queue",
                                                          "40",
                                                          "--lease-seconds",
                                                          "1.5",
                                                          "--renew-seconds",
                                                          "0.25",
                                                          "--max-attempts",
                                                          "5"});
  EXPECT_EQ(o.host, "0.0.0.0");
  EXPECT_EQ(o.port, 9000);
  EXPECT_EQ(o.data, "/tmp/x");
  EXPECT_EQ(o.pool.workers, 4);
  EXPECT_EQ(*o.token_file, "t");
  EXPECT_EQ(o.limits.max_body_bytes, 1000u);
  EXPECT_EQ(o.limits.max_nodes, 10);
  EXPECT_EQ(o.limits.max_steps, 20);
  EXPECT_EQ(o.limits.max_frames, 30);
  EXPECT_EQ(o.limits.max_queued, 40);
  EXPECT_EQ(o.pool.lease, 1'500);
  EXPECT_EQ(o.pool.renew_every, 250);
  EXPECT_EQ(o.max_attempts, 5);
}

TEST(ServeOptions, NamesTheFlagThatIsWrong) {
  auto message = [](std::vector<std::string> args) {
    try {
      cli::parse_serve_options(args);
    } catch (const cli::UsageError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message({"--wrokers", "2"}), "unknown option '--wrokers'");
  EXPECT_EQ(message({"--workers"}), "--workers needs a value");
  EXPECT_EQ(message({"--workers", "two"}), "--workers needs an integer in [0, 256], got 'two'");
  EXPECT_EQ(message({"--listen", "8080"}), "--listen needs HOST:PORT, got '8080'");
  EXPECT_EQ(message({"--lease-seconds", "1", "--renew-seconds", "2"}),
            "--renew-seconds must be shorter than --lease-seconds");
}

TEST(Limits, NameEveryExceededLimit) {
  scene::Summary s;
  s.nodes = 300;
  s.steps = 5000;
  s.frames = 10;
  http::Limits limits;
  limits.max_nodes = 100;
  limits.max_steps = 1000;
  auto problem = http::check_scene_limits(s, limits);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->status, 413);
  const nlohmann::json j = problem->to_json();
  ASSERT_EQ(j["limits"].size(), 2u);
  EXPECT_EQ(j["limits"][0], (nlohmann::json{{"name", "max_nodes"}, {"limit", 100}, {"value", 300}}));
  EXPECT_EQ(j["limits"][1]["name"], "max_steps");
  EXPECT_EQ(
      j["detail"],
      "the scene has 300 nodes, more than the server limit max_nodes = 100; the scene has 5000 time steps, "
      "more than the server limit max_steps = 1000");
  s.nodes = 100;
  s.steps = 1000;
  EXPECT_FALSE(http::check_scene_limits(s, limits));
}

TEST(Limits, RefuseAHugeGeneratedMeshBeforeBuildingIt) {
  nlohmann::json scene = {{"bodies", {{{"mesh", {{"box", {{"divisions", {1000, 1000, 1000}}}}}}}}},
                          {"time", {{"step", 0.01}, {"end", 1}}}};
  auto problem = http::check_scene_limits_early(scene, http::Limits{});
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->to_json()["limits"][0]["name"], "max_nodes");
  scene["bodies"][0]["mesh"]["box"]["divisions"] = {10, 10, 10};
  EXPECT_FALSE(http::check_scene_limits_early(scene, http::Limits{}));
  scene["time"]["end"] = 1e9;
  EXPECT_EQ(http::check_scene_limits_early(scene, http::Limits{})->to_json()["limits"][0]["name"],
            "max_steps");
}

TEST(Problem, IsRfc9457JsonAndSurvivesInvalidUtf8) {
  http::Problem p{422,
                  "urn:stoss:problem:invalid-scene",
                  "Invalid scene",
                  "bad \xff byte",
                  {{"errors", nlohmann::json::array()}}};
  httplib::Response res;
  p.write(res);
  EXPECT_EQ(res.status, 422);
  EXPECT_EQ(res.get_header_value("Content-Type"), "application/problem+json");
  const nlohmann::json j = nlohmann::json::parse(res.body);
  EXPECT_EQ(j["type"], "urn:stoss:problem:invalid-scene");
  EXPECT_EQ(j["status"], 422);
  EXPECT_TRUE(j["errors"].is_array());
}

TEST(BearerAuth, ReadsTheTokenFileAndComparesTheHeader) {
  test::TempDir dir;
  std::ofstream(dir.path() / "token") << "  s3cret-token \n";
  const auto auth = http::BearerAuth::from_file(dir.path() / "token");
  httplib::Request req;
  EXPECT_FALSE(auth.allows(req));
  req.set_header("Authorization", "Bearer s3cret-token");
  EXPECT_TRUE(auth.allows(req));
  httplib::Request wrong;
  wrong.set_header("Authorization", "Bearer s3cret-tokeN");
  EXPECT_FALSE(auth.allows(wrong));
  httplib::Request basic;
  basic.set_header("Authorization", "Basic s3cret-token");
  EXPECT_FALSE(auth.allows(basic));
  std::ofstream(dir.path() / "empty") << "\n";
  EXPECT_THROW(http::BearerAuth::from_file(dir.path() / "empty"), std::runtime_error);
  EXPECT_THROW(http::BearerAuth::from_file(dir.path() / "missing"), std::runtime_error);
}

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
}  // namespace stoss::server
