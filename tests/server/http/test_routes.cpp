// api/openapi.yaml and the server agree: the system shall serve exactly the routes the spec describes,
// each answering with a status code the spec documents for it. The test walks the spec.
#include <gtest/gtest.h>

#include <fstream>
#include <regex>
#include <set>

#include "server/common/sha256.hpp"
#include "server/http/routes.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

using namespace std::chrono_literals;

/// One operation of the spec: method, path and its documented response codes (in spec order).
struct Operation {
  std::string method;
  std::string path;
  std::vector<int> codes;
};

/// Reads the operations under `paths:` (the file keeps to 2-space indentation: path, method, responses,
/// code).
std::vector<Operation> read_spec(const std::filesystem::path& file) {
  std::ifstream in(file);
  const std::regex path_line(R"(^  (/\S*):\s*$)"), method_line(R"(^    (get|post|put|patch|delete):\s*$)"),
      code_line(R"(^        '(\d{3})':.*$)"), top_level(R"(^\S.*$)");
  std::vector<Operation> ops;
  std::string line, path;
  bool in_paths = false;
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_match(line, top_level)) in_paths = line.rfind("paths:", 0) == 0;
    if (!in_paths) continue;
    if (std::regex_match(line, m, path_line)) path = m[1];
    if (std::regex_match(line, m, method_line)) {
      std::string method = m[1];
      std::transform(method.begin(), method.end(), method.begin(), ::toupper);
      ops.push_back({method, path, {}});
    }
    if (std::regex_match(line, m, code_line) && !ops.empty()) ops.back().codes.push_back(std::stoi(m[1]));
  }
  return ops;
}

const std::filesystem::path spec_file = std::filesystem::path(STOSS_SOURCE_DIR) / "api/openapi.yaml";

TEST(OpenApi, TheSpecDescribesExactlyTheServersRoutes) {
  std::set<std::pair<std::string, std::string>> spec, served;
  for (const auto& op : read_spec(spec_file)) spec.insert({op.method, op.path});
  for (const auto& r : server::http::routes()) served.insert({r.method, r.path});
  EXPECT_EQ(spec.size(), 24u);
  EXPECT_EQ(spec, served);
}

TEST(OpenApi, EveryOperationAnswersWithItsDocumentedSuccessCodeAndNeedsTheToken) {
  TempDir dir;
  std::ofstream(dir.path() / "token") << "walk-the-spec\n";
  LiveServer server(dir.path() / "data", {"--workers", "1", "--token-file", (dir.path() / "token").string()});
  auto c = server.client("walk-the-spec");
  auto anonymous = server.client();

  // Fixtures: two succeeded jobs (one to read, one to delete), a succeeded study, and a long job to cancel.
  auto make = [&](const nlohmann::json& scene) {
    return nlohmann::json::parse(submit(c, scene)->body)["id"].get<std::string>();
  };
  const std::string done = make(box_scene(2, 10)), doomed = make(box_scene(2, 11));
  const std::string study_request = study_body(box_scene(1, 10), {0.05}, {"midpoint"}).dump();
  const std::string studied =
      nlohmann::json::parse(submit_study(c, nlohmann::json::parse(study_request))->body)["id"];
  for (const auto& id : {done, doomed, studied})
    ASSERT_EQ(wait_for_status(c, id, {"succeeded", "failed"})["status"], "succeeded");
  const std::string running = make(box_scene(4, 100'000, {1, 0, 0}, 2.0));
  const std::string scene = box_scene(2, 12).dump();
  // POST /v1/meshes stores this file (201); GET /v1/meshes/{id} reads it back by its SHA-256.
  std::ifstream mesh_in(std::filesystem::path(STOSS_SOURCE_DIR) / "tests/data/meshes/two_blocks_ascii.msh");
  const std::string mesh(std::istreambuf_iterator<char>(mesh_in), {});
  const std::string mesh_id = server::sha256_hex(mesh);

  auto call = [&](httplib::Client& client, const Operation& op) -> httplib::Result {
    const bool study = op.path.find("stud") != std::string::npos;
    std::string id = op.method == "DELETE"                          ? doomed
                     : op.path.find("/cancel") != std::string::npos ? running
                     : study                                        ? studied
                                                                    : done;
    if (op.path.rfind("/v1/meshes", 0) == 0) id = mesh_id;
    std::string path = std::regex_replace(op.path, std::regex(R"(\{id\})"), id);
    path = std::regex_replace(path, std::regex(R"(\{asset\})"), "stoss.js");
    if (op.method == "GET") return client.Get(path);
    if (op.method == "DELETE") return client.Delete(path);
    if (op.path == "/v1/meshes") return client.Post(path, mesh, "application/octet-stream");
    return client.Post(path, study ? study_request : scene, "application/json");
  };

  const auto ops = read_spec(spec_file);
  const auto served_routes = server::http::routes();
  ASSERT_FALSE(ops.empty());
  for (const auto& op : ops) {
    SCOPED_TRACE(op.method + " " + op.path);
    ASSERT_FALSE(op.codes.empty());
    const bool public_route = std::any_of(served_routes.begin(), served_routes.end(),
                                          [&](const auto& r) { return r.path == op.path && !r.needs_token; });
    if (!public_route) {
      auto refused = call(anonymous, op);
      ASSERT_TRUE(refused);
      EXPECT_EQ(refused->status, 401);
      EXPECT_NE(std::find(op.codes.begin(), op.codes.end(), 401), op.codes.end()) << "401 is not documented";
    }
    auto r = call(c, op);
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, op.codes.front()) << r->body.substr(0, 300);
  }
}

TEST(OpenApi, MethodsTheSpecDoesNotListAre405WithTheListedOnesInAllow) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "0"});
  auto c = server.client();
  const auto ops = read_spec(spec_file);
  std::set<std::pair<std::string, std::string>> listed;
  for (const auto& op : ops) listed.insert({op.method, op.path});
  for (const auto& op : ops)
    for (const std::string method : {"GET", "POST", "DELETE", "PUT", "PATCH"}) {
      if (listed.count({method, op.path})) continue;
      const std::string path = std::regex_replace(op.path, std::regex(R"(\{id\})"), std::string(32, 'a'));
      httplib::Request req;
      req.method = method;
      req.path = path;
      auto r = c.send(req);
      ASSERT_TRUE(r);
      EXPECT_EQ(r->status, 405) << method << " " << path;
      EXPECT_EQ(nlohmann::json::parse(r->body)["type"], "urn:stoss:problem:method-not-allowed")
          << method << " " << path;
      const std::string allow = r->get_header_value("Allow");
      for (const std::string listed_method : {"GET", "POST", "DELETE"})
        EXPECT_EQ(allow.find(listed_method) != std::string::npos, listed.count({listed_method, op.path}) > 0)
            << method << " " << path << ": Allow " << allow;
    }
}

}  // namespace
}  // namespace stoss::test
