// Bad input and limits against the live server: the system shall answer each with its status code and
// a problem+json body that says what is wrong, and never crash.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fstream>
#include <set>

#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

/// One server for the suite: no workers (jobs stay queued) and small limits.
class BadInput : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    server_ = new LiveServer(dir_->path() / "data",
                             {"--workers", "0", "--max-body-bytes", "4096", "--max-nodes", "100",
                              "--max-steps", "1000", "--max-frames", "50", "--max-queue", "3"});
  }
  static void TearDownTestSuite() {
    delete server_;
    delete dir_;
  }
  void SetUp() override { ASSERT_TRUE(server_->alive()) << server_->output(); }
  void TearDown() override {
    EXPECT_TRUE(server_->alive()) << "the server died: " << server_->output();
    // Free the queue for the next test.
    auto c = client();
    const nlohmann::json queued = body_json(c.Get("/v1/jobs?status=queued&limit=200"));
    for (const auto& j : queued["jobs"]) c.Post("/v1/jobs/" + j["id"].get<std::string>() + "/cancel");
  }
  httplib::Client client() { return server_->client(); }

  /// The problem body of `r`, after checking its status and content type.
  static nlohmann::json problem(const httplib::Result& r, int status) {
    EXPECT_TRUE(r);
    if (!r) return nullptr;
    EXPECT_EQ(r->status, status) << r->body;
    EXPECT_EQ(r->get_header_value("Content-Type"), "application/problem+json") << r->body;
    auto j = body_json(r);
    EXPECT_EQ(j["status"], status);
    EXPECT_TRUE(j.contains("title"));
    return j;
  }

  static TempDir* dir_;
  static LiveServer* server_;
};

TempDir* BadInput::dir_ = nullptr;
LiveServer* BadInput::server_ = nullptr;

TEST_F(BadInput, MalformedJsonIs400WithThePosition) {
  auto c = client();
  for (const char* path : {"/v1/jobs", "/v1/validate"}) {
    const auto p =
        problem(c.Post(path, "{\"format\": \"stoss-scene/1\",\n \"bodies\": [", "application/json"), 400);
    EXPECT_EQ(p["type"], "urn:stoss:problem:malformed-json");
    EXPECT_NE(p["detail"].get<std::string>().find("line 2"), std::string::npos) << p.dump();
  }
  EXPECT_EQ(problem(c.Post("/v1/jobs", "", "application/json"), 400)["type"],
            "urn:stoss:problem:malformed-json");
}

TEST_F(BadInput, AnInvalidSceneIs422ListingEveryErrorWithItsPointer) {
  auto c = client();
  nlohmann::json scene = box_scene(2, 10);
  scene["bodies"][0]["material"]["poisson_ratio"] = 0.5;
  scene["bodies"][0]["material"]["density"] = -1;
  scene["time"]["scheme"] = "euler";
  const auto jobs_before = body_json(c.Get("/v1/jobs?limit=200"))["jobs"].size();
  for (const char* path : {"/v1/jobs", "/v1/validate"}) {
    const auto p = problem(c.Post(path, scene.dump(), "application/json"), 422);
    EXPECT_EQ(p["type"], "urn:stoss:problem:invalid-scene");
    std::map<std::string, std::string> errors;
    for (const auto& e : p["errors"]) errors[e["pointer"]] = e["message"];
    ASSERT_EQ(errors.count("/bodies/0/material/poisson_ratio"), 1u) << p.dump();
    EXPECT_EQ(errors["/bodies/0/material/poisson_ratio"], "must be in (-1, 0.5), got 0.5");
    EXPECT_EQ(errors.count("/bodies/0/material/density"), 1u) << p.dump();
    EXPECT_EQ(errors.count("/time/scheme"), 1u) << p.dump();
  }
  EXPECT_EQ(body_json(c.Get("/v1/jobs?limit=200"))["jobs"].size(),
            jobs_before);  // nothing invalid was queued
}

TEST_F(BadInput, ABodyAboveMaxBodyBytesIs413NamingTheLimit) {
  auto c = client();
  nlohmann::json scene = box_scene(2, 10);
  scene["name"] = std::string(5000, 'x');
  const auto p = problem(c.Post("/v1/jobs", scene.dump(), "application/json"), 413);
  EXPECT_EQ(p["limits"][0]["name"], "max_body_bytes");
  EXPECT_NE(p["detail"].get<std::string>().find("max_body_bytes"), std::string::npos);
}

TEST_F(BadInput, NodeStepAndFrameLimitsAre413NamingTheLimit) {
  auto c = client();
  struct Case {
    nlohmann::json scene;
    std::string limit;
  };
  nlohmann::json frames = box_scene(2, 500);
  frames["output"]["every"] = 1;  // 501 frames
  nlohmann::json steps = box_scene(2, 2000);
  steps["output"]["every"] = 1000;                                         // 3 frames
  for (const auto& [scene, limit] : {Case{box_scene(5, 10), "max_nodes"},  // 216 nodes
                                     Case{steps, "max_steps"}, Case{frames, "max_frames"}}) {
    for (const char* path : {"/v1/jobs", "/v1/validate"}) {
      const auto p = problem(c.Post(path, scene.dump(), "application/json"), 413);
      EXPECT_EQ(p["type"], "urn:stoss:problem:limit-exceeded");
      ASSERT_EQ(p["limits"].size(), 1u) << p.dump();
      EXPECT_EQ(p["limits"][0]["name"], limit);
      EXPECT_NE(p["detail"].get<std::string>().find(limit), std::string::npos) << p.dump();
    }
  }
}

TEST_F(BadInput, AFullQueueIs503WithRetryAfter) {
  auto c = client();
  for (int i = 0; i < 3; ++i) ASSERT_EQ(submit(c, box_scene(2, 10, {1.0 * i, 0, 0}))->status, 201);
  auto r = submit(c, box_scene(2, 10, {9, 0, 0}));
  const auto p = problem(r, 503);
  EXPECT_EQ(p["type"], "urn:stoss:problem:queue-full");
  EXPECT_EQ(r->get_header_value("Retry-After"), "5");
}

TEST_F(BadInput, UnknownAndMalformedIdsAre404) {
  auto c = client();
  for (const std::string id : {"0123456789abcdef0123456789abcdef", "not-an-id", "%2e%2e%2f%2e%2e%2fjobs.db",
                               "0123456789ABCDEF0123456789ABCDEF"}) {
    for (const std::string suffix : {"", "/result", "/result.xdmf", "/series", "/log", "/study"})
      EXPECT_EQ(problem(c.Get("/v1/jobs/" + id + suffix), 404)["status"], 404) << id << suffix;
    problem(c.Post("/v1/jobs/" + id + "/cancel"), 404);
    problem(c.Delete("/v1/jobs/" + id), 404);
  }
}

TEST_F(BadInput, AResultBeforeCompletionIs409) {
  auto c = client();
  auto r = submit(c, box_scene(2, 10));
  const std::string id = nlohmann::json::parse(r->body)["id"];
  for (const std::string suffix : {"/result", "/result.xdmf", "/series"}) {
    const auto p = problem(c.Get("/v1/jobs/" + id + suffix), 409);
    EXPECT_EQ(p["detail"], "job " + id + " is queued; the result exists once it succeeded");
  }
  EXPECT_EQ(problem(c.Delete("/v1/jobs/" + id), 409)["detail"], "job " + id + " is queued; cancel it first");
  EXPECT_EQ(c.Get("/v1/jobs/" + id + "/log")->status, 200);
}

TEST_F(BadInput, TheSameIdempotencyKeyReturnsTheSameJobAndRefusesAnotherBody) {
  auto c = client();
  auto first = submit(c, box_scene(2, 10), "order-42");
  ASSERT_EQ(first->status, 201);
  auto again = submit(c, box_scene(2, 10), "order-42");
  ASSERT_EQ(again->status, 200);
  EXPECT_EQ(nlohmann::json::parse(again->body)["id"], nlohmann::json::parse(first->body)["id"]);
  const auto p = problem(submit(c, box_scene(2, 11), "order-42"), 422);
  EXPECT_EQ(p["type"], "urn:stoss:problem:idempotency-key-reused");
  httplib::Headers bad_key = {{"Idempotency-Key", std::string(300, 'k')}};
  problem(c.Post("/v1/jobs", bad_key, box_scene(2, 10).dump(), "application/json"), 400);
}

/// A study of one hex8 element spinning about z, to t = 0.2.
nlohmann::json tiny_study() {
  return study_body(box_scene(1, 20, {0, 0, 0}, 2.0), {0.04, 0.02}, {"energy_momentum", "midpoint"});
}

/// The pointers of a 422 problem's `errors`.
std::set<std::string> error_pointers(const nlohmann::json& problem) {
  std::set<std::string> pointers;
  for (const auto& e : problem["errors"]) pointers.insert(e["pointer"].get<std::string>());
  return pointers;
}

TEST_F(BadInput, AnInvalidStudyIs422WithThePointerOfEachError) {
  auto c = client();
  struct Case {
    std::string what;
    nlohmann::json body;
    std::set<std::string> pointers;
  };
  nlohmann::json invalid_scene = tiny_study();
  invalid_scene["scene"]["bodies"][0]["material"]["poisson_ratio"] = 0.5;
  std::vector<Case> cases = {{"empty steps", tiny_study(), {"/steps"}},
                             {"negative step", tiny_study(), {"/steps/1"}},
                             {"unknown scheme", tiny_study(), {"/schemes/1"}},
                             {"invalid scene", invalid_scene, {"/scene/bodies/0/material/poisson_ratio"}},
                             {"no scene, bad reference, unknown member",
                              {{"steps", {0.1}}, {"reference_step", -1}, {"step", 1}},
                              {"/scene", "/reference_step", "/step"}},
                             {"not an object", nlohmann::json::array({1, 2}), {""}}};
  cases[0].body["steps"] = nlohmann::json::array();
  cases[1].body["steps"] = {0.04, -0.01};
  cases[2].body["schemes"] = {"midpoint", "newmark"};
  const auto jobs_before = body_json(c.Get("/v1/jobs?limit=200"))["jobs"].size();
  for (const auto& [what, body, pointers] : cases) {
    const auto p = problem(submit_study(c, body), 422);
    EXPECT_EQ(p["type"], "urn:stoss:problem:invalid-study") << what;
    EXPECT_EQ(error_pointers(p), pointers) << what << ": " << p.dump();
  }
  const auto p = problem(submit_study(c, cases[2].body), 422);
  EXPECT_EQ(p["errors"][0]["message"],
            "must be one of energy_momentum, midpoint, hht, generalized_alpha, got \"newmark\"");
  EXPECT_EQ(body_json(c.Get("/v1/jobs?limit=200"))["jobs"].size(), jobs_before);  // nothing was queued
}

TEST_F(BadInput, AStudyWhoseFinestRunExceedsMaxStepsIs413NamingTheLimit) {
  auto c = client();
  nlohmann::json body = tiny_study();  // end 0.2: the reference of h = 0.02 / 32 has 320 steps
  body["reference_step"] = 0.0001;     // 2000 steps, above --max-steps 1000
  const auto p = problem(submit_study(c, body), 413);
  EXPECT_EQ(p["type"], "urn:stoss:problem:limit-exceeded");
  ASSERT_EQ(p["limits"].size(), 1u) << p.dump();
  EXPECT_EQ(p["limits"][0]["name"], "max_steps");
  EXPECT_EQ(p["limits"][0]["value"], 2000);
  EXPECT_NE(p["detail"].get<std::string>().find("reference run"), std::string::npos) << p.dump();
  body["scene"]["time"]["step"] = 1e-5;  // the scene's own step is replaced: not counted
  body.erase("reference_step");
  EXPECT_EQ(submit_study(c, body)->status, 201);
}

// Issue 27 §5: a scene asking for more MPI ranks than --max-ranks-per-job (1 here, the default) is refused by
// every route that takes a scene, at /solver/ranks; a study's scene may ask for one rank only.
TEST_F(BadInput, MoreRanksThanMaxRanksPerJobAre422AtSolverRanks) {
  auto c = client();
  nlohmann::json scene = box_scene(2, 10);
  scene["solver"]["ranks"] = 2;
  const auto jobs_before = body_json(c.Get("/v1/jobs?limit=200"))["jobs"].size();
  for (const char* path : {"/v1/jobs", "/v1/validate"}) {
    const auto p = problem(c.Post(path, scene.dump(), "application/json"), 422);
    EXPECT_EQ(p["type"], "urn:stoss:problem:invalid-scene");
    ASSERT_EQ(p["errors"].size(), 1u) << p.dump();
    EXPECT_EQ(p["errors"][0]["pointer"], "/solver/ranks");
    EXPECT_EQ(p["errors"][0]["message"],
              "must be at most 1 on this service (stoss serve --max-ranks-per-job 1), got 2");
  }
  nlohmann::json study = tiny_study();
  study["scene"]["solver"]["ranks"] = 2;
  const auto p = problem(submit_study(c, study), 422);
  EXPECT_EQ(p["type"], "urn:stoss:problem:invalid-study");
  EXPECT_EQ(error_pointers(p), std::set<std::string>{"/scene/solver/ranks"}) << p.dump();
  EXPECT_EQ(body_json(c.Get("/v1/jobs?limit=200"))["jobs"].size(), jobs_before);  // nothing was queued
  scene["solver"]["ranks"] = 1;
  const auto accepted = submit(c, scene);
  ASSERT_EQ(accepted->status, 201) << accepted->body;
  EXPECT_EQ(body_json(accepted)["ranks"], 1);
}

TEST_F(BadInput, AQueuedStudyCancelsAndItsTableIs409UntilItSucceeds) {
  auto c = client();
  auto r = submit_study(c, tiny_study(), "study-1");
  ASSERT_EQ(r->status, 201) << r->body;
  const auto created = nlohmann::json::parse(r->body);
  const std::string id = created["id"];
  EXPECT_EQ(created["kind"], "study");
  EXPECT_EQ(created["status"], "queued");
  EXPECT_EQ(body_json(submit_study(c, tiny_study(), "study-1"))["id"], id);  // 200, the same job
  EXPECT_EQ(problem(submit(c, box_scene(1, 20, {0, 0, 0}, 2.0), "study-1"), 422)["type"],
            "urn:stoss:problem:idempotency-key-reused");  // the same key with a scene body
  EXPECT_EQ(problem(c.Get("/v1/jobs/" + id + "/study"), 409)["detail"],
            "job " + id + " is queued; the study table exists once it succeeded");

  auto canceled = c.Post("/v1/jobs/" + id + "/cancel");
  ASSERT_EQ(canceled->status, 202);
  EXPECT_EQ(nlohmann::json::parse(canceled->body)["status"], "canceled");
  EXPECT_EQ(job(c, id)["status"], "canceled");
  EXPECT_EQ(problem(c.Get("/v1/jobs/" + id + "/study"), 409)["detail"],
            "job " + id + " is canceled; it has no study table");
}

TEST_F(BadInput, TheStudyOfASimulationJobIs404) {
  auto c = client();
  const std::string id = nlohmann::json::parse(submit(c, box_scene(2, 10))->body)["id"];
  const auto p = problem(c.Get("/v1/jobs/" + id + "/study"), 404);
  EXPECT_EQ(p["type"], "urn:stoss:problem:not-a-study");
  EXPECT_EQ(job(c, id)["kind"], "simulation");
}

TEST_F(BadInput, BadListParametersAre400) {
  auto c = client();
  EXPECT_NE(problem(c.Get("/v1/jobs?status=done"), 400)["detail"].get<std::string>().find("status"),
            std::string::npos);
  problem(c.Get("/v1/jobs?limit=0"), 400);
  problem(c.Get("/v1/jobs?limit=abc"), 400);
  problem(c.Get("/v1/jobs?cursor=-1"), 400);
  problem(c.Get("/v1/jobs/0123456789abcdef0123456789abcdef/series?format=xml"), 400);
}

TEST_F(BadInput, UnknownRoutesAre404Problems) {
  auto c = client();
  EXPECT_EQ(problem(c.Get("/v2/jobs"), 404)["type"], "urn:stoss:problem:no-route");
  problem(c.Put("/v1/jobs", "{}", "application/json"), 405);
}

/// Sends raw bytes and returns whatever comes back within `timeout` (possibly nothing). With `half_close`
/// the client then closes its sending side; without, it keeps the connection open as a browser would.
std::string raw_exchange(int port, const std::string& bytes, bool half_close = true,
                         int timeout_seconds = 10) {
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_port = htons(static_cast<uint16_t>(port));
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  timeval timeout{timeout_seconds, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  std::string reply;
  if (connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0) {
    (void)!write(fd, bytes.data(), bytes.size());
    if (half_close) shutdown(fd, SHUT_WR);
    char buffer[4096];
    for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) > 0;) {
      reply.append(buffer, static_cast<std::size_t>(n));
      if (!half_close && reply.find("\r\n\r\n") != std::string::npos) break;  // the head is enough
    }
  }
  close(fd);
  return reply;
}

TEST_F(BadInput, GarbageNeverTakesTheServerDown) {
  auto c = client();
  const std::string deep = std::string(100'000, '[') + std::string(100'000, ']');
  for (const std::string& body :
       {std::string("\xff\xfe\x00garbage", 10), std::string("{\"name\": \"\xc3\x28\"}"), deep,
        std::string("[1, 2, 3]"), std::string("null"), std::string("{\"bodies\": 1e999}"),
        std::string("{\"format\": \"stoss-scene/1\", \"bodies\": [{}], \"time\": {}}")}) {
    auto r = c.Post("/v1/jobs", body, "application/json");
    ASSERT_TRUE(r) << "no answer to " << body.substr(0, 40);
    EXPECT_TRUE(r->status == 400 || r->status == 413 || r->status == 422) << r->status << " " << r->body;
  }
  raw_exchange(server_->port(), "THIS IS NOT HTTP\r\n\r\n");
  raw_exchange(server_->port(), "GET /healthz HTTP/1.1\r\nHost: x\r\nRange: bytes=zzz\r\n\r\n");
  raw_exchange(server_->port(), "POST /v1/jobs HTTP/1.1\r\nContent-Length: 99999999999999999999\r\n\r\n{");
  raw_exchange(server_->port(), "POST /v1/jobs HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\nzz\r\n");
  raw_exchange(server_->port(), "GET /v1/jobs/" + std::string(20'000, 'a') + " HTTP/1.1\r\n\r\n");
  EXPECT_EQ(c.Get("/healthz")->status, 200);
}

TEST_F(BadInput, APostWithoutContentLengthHasAnEmptyBody) {
  // What `curl -X POST http://…/cancel` sends: no Content-Length, connection kept open.
  const std::string reply = raw_exchange(
      server_->port(), "POST /v1/jobs/0123456789abcdef0123456789abcdef/cancel HTTP/1.1\r\nHost: x\r\n\r\n",
      false, 3);
  EXPECT_EQ(reply.substr(0, 22), "HTTP/1.1 404 Not Found") << reply;
}

// Issue 27 §5: a service started with --max-ranks-per-job 2 queues a two-rank scene and shows its ranks; its
// own workers (--ranks-per-job 1, the default) leave that job queued and run a younger one-rank job.
TEST(MaxRanksPerJob, ABiggerJobIsQueuedWithItsRanksAndWaitsForAWorkerWithThem) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "1", "--max-ranks-per-job", "2"});
  auto c = server.client();
  nlohmann::json scene = box_scene(2, 10);
  scene["solver"]["ranks"] = 3;
  const auto refused = body_json(submit(c, scene));
  EXPECT_EQ(refused["status"], 422);
  EXPECT_EQ(refused["errors"][0]["message"],
            "must be at most 2 on this service (stoss serve --max-ranks-per-job 2), got 3");
  scene["solver"]["ranks"] = 2;
  const auto big = submit(c, scene);
  ASSERT_EQ(big->status, 201) << big->body;
  const std::string big_id = body_json(big)["id"];
  EXPECT_EQ(body_json(big)["ranks"], 2);
  scene["solver"]["ranks"] = 1;
  const std::string small_id = body_json(submit(c, scene))["id"];
  EXPECT_EQ(wait_for_status(c, small_id, {"succeeded", "failed"})["status"], "succeeded");
  const nlohmann::json waiting = job(c, big_id);
  EXPECT_EQ(waiting["status"], "queued") << "the older job asks for more ranks than this worker has";
  EXPECT_EQ(waiting["attempt"], 0);
  EXPECT_EQ(waiting["ranks"], 2);
}

TEST(Auth, WithATokenFileEveryRouteButHealthzNeedsTheBearerToken) {
  TempDir dir;
  std::ofstream(dir.path() / "token") << "let-me-in\n";
  LiveServer server(dir.path() / "data", {"--workers", "0", "--token-file", (dir.path() / "token").string()});
  auto anonymous = server.client();
  auto wrong = server.client("let-me-out");
  auto right = server.client("let-me-in");
  EXPECT_EQ(anonymous.Get("/healthz")->status, 200);
  for (auto* c : {&anonymous, &wrong}) {
    auto r = c->Get("/v1/jobs");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 401);
    EXPECT_EQ(r->get_header_value("WWW-Authenticate"), "Bearer");
    EXPECT_EQ(nlohmann::json::parse(r->body)["type"], "urn:stoss:problem:unauthorized");
    EXPECT_EQ(c->Get("/metrics")->status, 401);
    EXPECT_EQ(c->Post("/v1/jobs", box_scene(2, 10).dump(), "application/json")->status, 401);
  }
  EXPECT_TRUE(body_json(right.Get("/v1/jobs"))["jobs"].empty());  // nothing was queued without the token
  EXPECT_EQ(right.Post("/v1/jobs", box_scene(2, 10).dump(), "application/json")->status, 201);
  EXPECT_EQ(right.Get("/metrics")->status, 200);
}

}  // namespace
}  // namespace stoss::test
