// The service under hostile input and hostile clients (issue 10): any body gets an answer and never a
// crash, one listener per port, stalled uploads do not starve other clients, Range follows RFC 9110, and
// the smaller holes (405 with Allow, the OpenAPI document, cancel of a finished job, the scene of a job).
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fstream>
#include <thread>

#include "server/common/json_input.hpp"
#include "server/http/byte_range.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

using namespace std::chrono_literals;
using server::http::ByteRange;
using server::http::resolve_range;

std::string read_text(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// A connected loopback socket (-1 on failure).
nlohmann::json nested_arrays(int depth) {
  return nlohmann::json::parse(std::string(depth, '[') + std::string(depth, ']'));
}

// --- unit level -------------------------------------------------------------------------------------

TEST(JsonInput, NestingIsMeasuredWithoutRecursionAndIgnoresBracketsInStrings) {
  EXPECT_FALSE(server::nesting_beyond("{\"a\": [[1]]}", 3));
  EXPECT_EQ(server::nesting_beyond("{\"a\": [[1]]}", 2), 7u);
  EXPECT_FALSE(server::nesting_beyond("{\"a\": \"[[[[[[\\\"[[[\"}", 1));
  const std::string deep = std::string(60'000, '[') + std::string(60'000, ']');
  EXPECT_EQ(server::nesting_beyond(deep, 256), 256u);
  EXPECT_NO_THROW(server::parse_json_input(std::string(256, '[') + std::string(256, ']')));
  try {
    server::parse_json_input(deep);
    FAIL() << "60000 levels were parsed";
  } catch (const server::JsonInputError& e) {
    EXPECT_EQ(e.kind, server::JsonInputError::Kind::too_deep);
    EXPECT_NE(std::string(e.what()).find("256"), std::string::npos) << e.what();
  }
}

TEST(JsonInput, NumbersOutOfRangeAndCutUtf8AreErrorsNotCrashes) {
  EXPECT_THROW(server::parse_json_input("{\"every\": 1e400}"), server::JsonInputError);
  EXPECT_THROW(server::parse_json_input("{\"name\": \"\xc3\"}"), server::JsonInputError);
  nlohmann::json j = {{"name", std::string("\xe2\x82", 2)}};  // a 3-byte character cut after 2
  EXPECT_EQ(server::safe_dump(j), "{\"name\":\"\xef\xbf\xbd\"}");
}

TEST(ByteRanges, FollowRfc9110) {
  const std::uint64_t size = 1000;
  auto partial = [&](const std::string& h, std::uint64_t first, std::uint64_t length) {
    const ByteRange r = resolve_range(h, size);
    EXPECT_EQ(r.kind, ByteRange::Kind::partial) << h;
    EXPECT_EQ(r.first, first) << h;
    EXPECT_EQ(r.length, length) << h;
  };
  auto unsatisfiable = [&](const std::string& h, std::uint64_t s = 1000) {
    EXPECT_EQ(resolve_range(h, s).kind, ByteRange::Kind::unsatisfiable) << h;
  };
  partial("bytes=0-99", 0, 100);
  partial("bytes=0-99999999999", 0, 1000);  // clamped to the file
  partial("bytes=990-", 990, 10);
  partial("bytes=999-", 999, 1);
  partial("bytes=-10", 990, 10);
  partial("bytes=-5000", 0, 1000);
  partial("bytes=0-18446744073709551616000", 0, 1000);  // saturates, no overflow
  unsatisfiable("bytes=1000-");                         // SIZE-
  unsatisfiable("bytes=999999999-");
  unsatisfiable("bytes=-0");
  unsatisfiable("bytes=0-", 0);  // an empty file has no byte to send
  EXPECT_EQ(resolve_range("", size).kind, ByteRange::Kind::whole);
  EXPECT_EQ(resolve_range("bytes=5-2", size).kind, ByteRange::Kind::whole);  // invalid: ignored
  EXPECT_EQ(resolve_range("bytes=0-1,5-6", size).kind, ByteRange::Kind::whole);
  EXPECT_EQ(resolve_range("items=0-1", size).kind, ByteRange::Kind::whole);
}

// --- against the live server ------------------------------------------------------------------------

/// One server, no workers: jobs stay queued.
class Hostile : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir();
    server_ = new LiveServer(dir_->path() / "data", {"--workers", "0", "--read-timeout", "3"});
  }
  static void TearDownTestSuite() {
    delete server_;
    delete dir_;
  }
  void SetUp() override { ASSERT_TRUE(server_->alive()) << server_->output(); }
  void TearDown() override { EXPECT_TRUE(server_->alive()) << "the server died: " << server_->output(); }
  httplib::Client client() { return server_->client(); }
  static TempDir* dir_;
  static LiveServer* server_;
};

TempDir* Hostile::dir_ = nullptr;
LiveServer* Hostile::server_ = nullptr;

TEST_F(Hostile, DeepNestingIs400NamingTheLimitBeforeAnyParsing) {
  auto c = client();
  const std::string deep = std::string(60'000, '[') + std::string(60'000, ']');  // 120 KB
  for (const char* path : {"/v1/validate", "/v1/jobs", "/v1/studies"}) {
    auto r = c.Post(path, deep, "application/json");
    ASSERT_TRUE(r) << path;
    EXPECT_EQ(r->status, 400) << r->body;
    const auto p = body_json(r);
    EXPECT_EQ(p["type"], "urn:stoss:problem:too-deep");
    EXPECT_EQ(p["limits"][0]["name"], "max_json_depth");
    EXPECT_EQ(p["limits"][0]["limit"], 256);
    EXPECT_NE(p["detail"].get<std::string>().find("256"), std::string::npos) << p.dump();
  }
  // 256 levels are parsed (and refused as a scene), 257 are not.
  EXPECT_EQ(c.Post("/v1/validate", nested_arrays(256).dump(), "application/json")->status, 422);
  EXPECT_EQ(c.Post("/v1/validate", std::string(257, '[') + std::string(257, ']'), "application/json")->status,
            400);
  EXPECT_EQ(c.Get("/healthz")->status, 200);
}

TEST_F(Hostile, JsonIsAcceptedWhateverTheContentTypeAndAbove8KiB) {
  auto c = client();
  nlohmann::json scene = box_scene(2, 10);
  scene["name"] = std::string(20'000, 'x');  // a body well above cpp-httplib's 8 KiB form cap
  const std::string body = scene.dump();
  for (const char* type :
       {"application/x-www-form-urlencoded", "text/plain", "application/json; charset=utf-8",
        "application/octet-stream", "application/vnd.stoss+json"}) {
    auto r = c.Post("/v1/validate", body, type);
    ASSERT_TRUE(r) << type;
    EXPECT_EQ(r->status, 200) << type << ": " << r->body.substr(0, 300);
  }
  // No Content-Type at all.
  httplib::Request req;
  req.method = "POST";
  req.path = "/v1/validate";
  req.body = body;
  auto r = c.send(req);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body.substr(0, 300);
}

TEST_F(Hostile, ABodyThatIsNotJsonIs415NamingTheExpectedType) {
  auto c = client();
  const std::string multipart =
      "--XyZ\r\nContent-Disposition: form-data; name=\"scene\"\r\n\r\nhello\r\n--XyZ--\r\n";
  for (const auto& [body, type] : std::vector<std::pair<std::string, std::string>>{
           {"scene=tumbling", "application/x-www-form-urlencoded"},
           {"hello", "text/plain"},
           {multipart, "multipart/form-data; boundary=XyZ"},
           {"<scene/>", "application/xml"}}) {
    for (const char* path : {"/v1/jobs", "/v1/validate", "/v1/studies"}) {
      auto r = c.Post(path, body, type.c_str());
      ASSERT_TRUE(r);
      EXPECT_EQ(r->status, 415) << path << " " << type << ": " << r->body;
      EXPECT_EQ(r->get_header_value("Accept-Post"), "application/json");
      const auto p = body_json(r);
      EXPECT_EQ(p["expected"], nlohmann::json::array({"application/json"})) << p.dump();
    }
  }
  // Declared JSON that is not JSON stays a 400 with the position.
  EXPECT_EQ(c.Post("/v1/jobs", "hello", "application/json")->status, 400);
}

TEST_F(Hostile, ABodyAboveTheLimitIs413WithLimitAndValue) {
  TempDir dir;
  LiveServer small(dir.path() / "data", {"--workers", "0", "--max-body-bytes", "4096"});
  auto c = small.client();
  const std::string body = "{\"name\": \"" + std::string(5000, 'x') + "\"}";
  for (const char* type : {"application/json", "application/x-www-form-urlencoded"}) {
    auto r = c.Post("/v1/jobs", body, type);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 413) << r->body;
    const auto p = body_json(r);
    EXPECT_EQ(p["limits"][0]["name"], "max_body_bytes") << p.dump();
    EXPECT_EQ(p["limits"][0]["limit"], 4096) << p.dump();
    EXPECT_EQ(p["limits"][0]["value"], body.size()) << p.dump();
  }
}

TEST_F(Hostile, AWrongMethodIs405WithAllow) {
  auto c = client();
  auto r = c.Put("/v1/jobs", "{}", "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 405);
  EXPECT_EQ(r->get_header_value("Allow"), "POST, GET");
  EXPECT_EQ(body_json(r)["type"], "urn:stoss:problem:method-not-allowed");
  r = c.Post("/healthz", "", "application/json");
  EXPECT_EQ(r->status, 405);
  EXPECT_EQ(r->get_header_value("Allow"), "GET");
  r = c.Delete("/v1/jobs/" + std::string(32, 'a') + "/result");
  EXPECT_EQ(r->status, 405);
  EXPECT_EQ(r->get_header_value("Allow"), "GET");
  EXPECT_EQ(c.Get("/v2/nothing")->status, 404);
}

TEST_F(Hostile, TheOpenApiDocumentIsServed) {
  auto c = client();
  auto r = c.Get("/v1/openapi.yaml");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->body, read_text(std::filesystem::path(STOSS_SOURCE_DIR) / "api/openapi.yaml"));
}

TEST_F(Hostile, ARootLevelErrorReadsAsASentence) {
  auto c = client();
  const auto p = body_json(c.Post("/v1/jobs", "[1, 2]", "application/json"));
  EXPECT_EQ(p["status"], 422);
  const std::string detail = p["detail"];
  EXPECT_EQ(detail.find(": :"), std::string::npos) << detail;
  EXPECT_NE(detail.find("the first: the scene must be an object"), std::string::npos) << detail;
}

TEST_F(Hostile, AJobCarriesItsSceneNameAndItsSceneResolvedOnce) {
  auto c = client();
  nlohmann::json scene = box_scene(2, 10);
  scene["name"] = "named box";
  const auto job = body_json(submit(c, scene));
  const std::string id = job["id"];
  EXPECT_EQ(job["name"], "named box");
  EXPECT_EQ(job["links"]["scene"], "/v1/jobs/" + id + "/scene");
  // The job stores the scene as validated and resolved at POST: the posted members, every default added.
  const auto stored = body_json(c.Get("/v1/jobs/" + id + "/scene"));
  EXPECT_EQ(stored["name"], "named box");
  EXPECT_EQ(stored["time"]["step"], scene["time"]["step"]);
  EXPECT_TRUE(stored["solver"].contains("tolerance")) << "no default was filled in";
  EXPECT_EQ(stored["time"]["scheme"], "energy_momentum");
  EXPECT_NE(stored, scene);
  EXPECT_EQ(body_json(c.Get("/v1/jobs/" + id + "/scene?resolved=true")), stored) << "resolving is idempotent";
  EXPECT_EQ(c.Get("/v1/jobs/" + id + "/scene?resolved=maybe")->status, 400);
  // Cancel: 202 once, then 409 for the canceled job.
  EXPECT_EQ(c.Post("/v1/jobs/" + id + "/cancel")->status, 202);
  auto again = c.Post("/v1/jobs/" + id + "/cancel");
  EXPECT_EQ(again->status, 409) << again->body;
  EXPECT_EQ(body_json(again)["type"], "urn:stoss:problem:already-finished");
}

TEST_F(Hostile, FiftyStalledUploadsDoNotStarveHealthz) {
  std::vector<int> stalled;
  for (int i = 0; i < 50; ++i) {
    const int fd = connect_loopback(server_->port());
    ASSERT_GE(fd, 0);
    const std::string head =
        "POST /v1/jobs HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nContent-Length: "
        "100000\r\n\r\n"
        "{\"format\": \"stoss-scene/1\", ";
    ASSERT_EQ(write(fd, head.data(), head.size()), static_cast<ssize_t>(head.size()));
    stalled.push_back(fd);
  }
  std::this_thread::sleep_for(200ms);  // every stalled request is being read
  httplib::Client c("127.0.0.1", server_->port());
  c.set_connection_timeout(5s);
  c.set_read_timeout(5s);
  for (int i = 0; i < 3; ++i) {
    auto r = c.Get("/healthz");
    ASSERT_TRUE(r) << "no answer within 5 s while 50 uploads stall: " << httplib::to_string(r.error());
    EXPECT_EQ(r->status, 200);
  }
  for (int fd : stalled) close(fd);
}

TEST_F(Hostile, AStalledUploadIsDroppedAfterTheReadTimeout) {
  const int fd = connect_loopback(server_->port());
  ASSERT_GE(fd, 0);
  const std::string head = "POST /v1/validate HTTP/1.1\r\nHost: x\r\nContent-Length: 1000\r\n\r\n{";
  ASSERT_EQ(write(fd, head.data(), head.size()), static_cast<ssize_t>(head.size()));
  timeval timeout{20, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  char buffer[512];
  std::string reply;
  for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) > 0;)
    reply.append(buffer, static_cast<std::size_t>(n));
  close(fd);
  // The server (read timeout 3 s) gives up on the body and closes the connection: read() saw EOF (or a
  // 400), not the 20 s receive timeout of this socket (errno EAGAIN).
  EXPECT_TRUE(reply.empty() || reply.rfind("HTTP/1.1 400", 0) == 0) << reply;
}

TEST(OneListener, ASecondServerOnAPortInUseExits2AndOnAnotherPortSharesTheData) {
  TempDir dir;
  LiveServer first(dir.path() / "a", {"--workers", "0"});
  const auto second = run_stoss({"serve", "--listen", "127.0.0.1:" + std::to_string(first.port()), "--data",
                                 (dir.path() / "b").string(), "--workers", "0"},
                                30s);
  EXPECT_EQ(second.signal, 0);
  EXPECT_EQ(second.exit_code, 2) << second.out << second.err;
  EXPECT_NE((second.out + second.err).find("address in use"), std::string::npos) << second.out << second.err;
  EXPECT_TRUE(first.alive());
  EXPECT_EQ(first.client().Get("/healthz")->status, 200);
  // On another port, a second server may share the first one's data directory: one queue, both see it.
  LiveServer sharing(dir.path() / "a", {"--workers", "0"});
  ASSERT_NE(sharing.port(), first.port());
  auto a = first.client(), b = sharing.client();
  const auto posted = submit(a, box_scene(1, 5));
  ASSERT_TRUE(posted);
  ASSERT_EQ(posted->status, 201) << posted->body;
  const std::string id = body_json(posted)["id"];
  const auto seen = b.Get("/v1/jobs/" + id);
  ASSERT_TRUE(seen);
  EXPECT_EQ(seen->status, 200) << seen->body;
}

/// A succeeded job's result with Range headers, as curl and browsers send them.
TEST(Ranges, TheResultHonoursRfc9110) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "1"});
  auto c = server.client();
  const std::string id = body_json(submit(c, box_scene(2, 5)))["id"];
  ASSERT_EQ(wait_for_status(c, id, {"succeeded", "failed"})["status"], "succeeded");
  const std::string path = "/v1/jobs/" + id + "/result";
  auto whole = c.Get(path);
  ASSERT_EQ(whole->status, 200);
  const std::string file = whole->body;
  const std::string size = std::to_string(file.size());
  auto get = [&](const std::string& range) { return c.Get(path, {{"Range", range}}); };

  for (const std::string range :
       {"bytes=" + size + "-", std::string("bytes=999999999-"), std::string("bytes=-0")}) {
    auto r = get(range);
    ASSERT_TRUE(r) << range;
    EXPECT_EQ(r->status, 416) << range;
    EXPECT_EQ(r->get_header_value("Content-Range"), "bytes */" + size) << range;
  }
  auto r = get("bytes=0-99999999999");
  EXPECT_EQ(r->status, 206);
  EXPECT_EQ(r->get_header_value("Content-Range"), "bytes 0-" + std::to_string(file.size() - 1) + "/" + size);
  EXPECT_EQ(r->get_header_value("Content-Length"), size);
  EXPECT_EQ(r->body, file);
  r = get("bytes=-10");
  EXPECT_EQ(r->status, 206);
  EXPECT_EQ(r->body, file.substr(file.size() - 10));
  r = get("bytes=100-199");
  EXPECT_EQ(r->status, 206);
  EXPECT_EQ(r->get_header_value("Content-Length"), "100");
  EXPECT_EQ(r->body, file.substr(100, 100));
  r = get("bytes=" + std::to_string(file.size() - 1) + "-");
  EXPECT_EQ(r->status, 206);
  EXPECT_EQ(r->body, file.substr(file.size() - 1));
  // A finished job cannot be canceled.
  EXPECT_EQ(c.Post("/v1/jobs/" + id + "/cancel")->status, 409);
}

}  // namespace
}  // namespace stoss::test
