// POST /v1/meshes and "mesh": {"id": ...} (issue 13, item 1): a mesh file travels to the service once, is
// stored by content, and a job naming its id runs as the same scene with "file" does on the command line.

#include <gtest/gtest.h>

#include <fstream>

#include "core/output/result_reader.hpp"
#include "server/http/limits.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

const std::filesystem::path meshes = std::filesystem::path(STOSS_SOURCE_DIR) / "tests" / "data" / "meshes";

std::string bytes_of(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

httplib::Result post_mesh(httplib::Client& c, const std::string& bytes, const std::string& query = "") {
  return c.Post(("/v1/meshes" + query).c_str(), bytes, "application/octet-stream");
}

/// One block of two_blocks.geo ("left", [0,1]³ in 8 hexahedra) named by `mesh`, spinning; 20 steps.
nlohmann::json block_scene(const nlohmann::json& mesh) {
  nlohmann::json scene = box_scene(1, 20, {0.5, 0, 0.2}, 2.0);
  scene["bodies"][0]["mesh"] = mesh;
  return scene;
}

class MeshUpload : public ::testing::Test {
 protected:
  TempDir data;
  LiveServer server{data.path()};
  httplib::Client c = server.client();
};

TEST_F(MeshUpload, GmshFilesAsciiAndBinaryAnswerTheirCountsAndAreStoredByContent) {
  for (const char* name : {"two_blocks_ascii.msh", "two_blocks_binary.msh"}) {
    SCOPED_TRACE(name);
    const std::string bytes = bytes_of(meshes / name);
    const auto r = post_mesh(c, bytes);  // format sniffed from $MeshFormat
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 201) << r->body;
    const auto answer = body_json(r);
    EXPECT_EQ(answer["format"], "msh");
    EXPECT_EQ(answer["nodes"], 45);
    EXPECT_EQ(answer["elements"], 16);
    EXPECT_EQ(answer["element_sets"], nlohmann::json({{"left", 8}, {"right", 8}}));
    EXPECT_EQ(answer["surfaces"], nlohmann::json({{"bottom", 8}, {"top", 8}, {"xmax", 4}}));
    const std::string id = answer["id"];
    EXPECT_EQ(id.size(), 64u);
    EXPECT_EQ(r->get_header_value("Location"), "/v1/meshes/" + id);
    EXPECT_TRUE(std::filesystem::is_regular_file(data.path() / "meshes" / (id + ".msh")));

    const auto again = post_mesh(c, bytes, "?format=msh");
    ASSERT_TRUE(again);
    EXPECT_EQ(again->status, 200);
    EXPECT_EQ(body_json(again)["id"], id);

    const auto stored = c.Get(("/v1/meshes/" + id).c_str());
    ASSERT_TRUE(stored);
    EXPECT_EQ(stored->status, 200);
    EXPECT_TRUE(stored->body == bytes) << "the stored file differs from the posted bytes";
  }
}

TEST_F(MeshUpload, AbaqusDeckAnswersItsCounts) {
  const auto r = post_mesh(c, bytes_of(meshes / "cgx_block.inp"), "?format=inp");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 201) << r->body;
  const auto answer = body_json(r);
  EXPECT_EQ(answer["format"], "inp");
  EXPECT_GT(answer["nodes"].get<int>(), 8);
  EXPECT_GT(answer["elements"].get<int>(), 0);
  EXPECT_TRUE(answer["element_sets"].contains("Eall")) << answer.dump();
}

TEST_F(MeshUpload, ATruncatedFileIs422NamingTheLineAndIsNotStored) {
  const std::string bytes = bytes_of(meshes / "two_blocks_ascii.msh");
  const std::string truncated = bytes.substr(0, bytes.find("$EndNodes"));
  const auto r = post_mesh(c, truncated);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 422) << r->body;
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/problem+json");
  const auto problem = body_json(r);
  EXPECT_EQ(problem["type"], "urn:stoss:problem:invalid-mesh");
  const std::string detail = problem["detail"];
  EXPECT_EQ(detail.rfind("request body:", 0), 0u) << detail;
  ASSERT_TRUE(problem.contains("line")) << problem.dump();
  EXPECT_GT(problem["line"].get<int>(), 1);
  EXPECT_NE(detail.find(":" + std::to_string(problem["line"].get<int>()) + ":"), std::string::npos) << detail;
  std::size_t files = 0;
  if (std::filesystem::exists(data.path() / "meshes"))  // parsed before anything is written
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(data.path() / "meshes"))
      ++files;
  EXPECT_EQ(files, 0u) << "a bad upload left a file behind";
}

TEST_F(MeshUpload, ABodyOfUnknownFormatIs400AndAnUnknownMeshIs404) {
  const auto r = post_mesh(c, "hello");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 400);
  EXPECT_NE(body_json(r)["detail"].get<std::string>().find("format=msh or format=inp"), std::string::npos);
  const auto missing = c.Get(("/v1/meshes/" + std::string(64, 'a')).c_str());
  ASSERT_TRUE(missing);
  EXPECT_EQ(missing->status, 404);
  EXPECT_EQ(body_json(missing)["type"], "urn:stoss:problem:unknown-mesh");
}

TEST(MeshUploadLimits, AFileAboveMaxBodyBytesIs413NamingTheLimit) {
  TempDir data;
  LiveServer server(data.path(), {"--max-body-bytes", "1000"});
  auto c = server.client();
  const auto r = post_mesh(c, bytes_of(meshes / "two_blocks_ascii.msh"));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
  EXPECT_EQ(body_json(r)["limits"][0]["name"], "max_body_bytes");
  EXPECT_FALSE(std::filesystem::exists(data.path() / "meshes"));
}

TEST_F(MeshUpload, AnUnknownIdIs422AtItsPointer) {
  const auto r = submit(c, block_scene({{"id", std::string(64, '0')}, {"elements", "left"}}));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 422) << r->body;
  const auto errors = body_json(r)["errors"];
  ASSERT_EQ(errors.size(), 1u) << errors.dump();
  EXPECT_EQ(errors[0]["pointer"], "/bodies/0/mesh/id");
  EXPECT_EQ(errors[0]["message"], "no mesh with this id; POST it to /v1/meshes first");
}

TEST_F(MeshUpload, AJobNamingTheIdRunsAsTheSameSceneWithFileOnTheCommandLine) {
  const auto posted = post_mesh(c, bytes_of(meshes / "two_blocks_ascii.msh"));
  ASSERT_TRUE(posted);
  const std::string id = body_json(posted)["id"];
  const nlohmann::json transform = {{"rotate", {{"axis", {0, 0, 1}}, {"degrees", 30}}}};
  const auto r = submit(c, block_scene({{"id", id}, {"elements", "left"}, {"transform", transform}}));
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  const std::string job_id = body_json(r)["id"];
  const auto done = wait_for_status(c, job_id, {"succeeded", "failed", "canceled"});
  ASSERT_EQ(done["status"], "succeeded") << done.dump();
  EXPECT_EQ(body_json(c.Get(("/v1/jobs/" + job_id + "/scene").c_str()))["bodies"][0]["mesh"]["id"], id);
  const auto xdmf_mesh = c.Get(("/v1/jobs/" + job_id + "/result_mesh.xdmf").c_str());
  ASSERT_TRUE(xdmf_mesh);
  EXPECT_EQ(xdmf_mesh->status, 200);
  EXPECT_NE(xdmf_mesh->body.find("<Xdmf"), std::string::npos);
  const auto series = body_json(c.Get(("/v1/jobs/" + job_id + "/series").c_str()));

  TempDir cli;
  const auto scene_path = cli.path() / "scene.json";
  std::ofstream(scene_path) << block_scene({{"file", (meshes / "two_blocks_ascii.msh").string()},
                                            {"elements", "left"},
                                            {"transform", transform}})
                                   .dump();
  const CommandResult run = run_stoss({"run", scene_path.string(), "-o", (cli.path() / "out").string()});
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const auto expected = output::series_json(cli.path() / "out" / "result.h5");
  for (const char* name : {"time", "total_energy", "kinetic_energy", "newton_iterations"}) {
    SCOPED_TRACE(name);
    ASSERT_EQ(series[name].size(), expected[name].size());
    ASSERT_EQ(series[name].size(), 21u);
    for (std::size_t i = 0; i < expected[name].size(); ++i)
      EXPECT_NEAR(series[name][i].get<double>(), expected[name][i].get<double>(),
                  1e-12 * std::max(1.0, std::abs(expected[name][i].get<double>())));
  }
  EXPECT_EQ(done["summary"]["steps"], 20);
}

// Issue 20: an upload reads no server file, a stored mesh is parsed once, the store has a quota and DELETE.

TEST_F(MeshUpload, AnIncludeOfAServerFileIs422AndTheAnswerEchoesNothingOfIt) {
  const std::string cube = bytes_of(meshes / "cgx_block.inp");
  for (const std::string target : {"/etc/passwd", "../jobs.db", "/proc/self/cmdline", "/dev/zero"}) {
    SCOPED_TRACE(target);
    const auto r = post_mesh(c, cube + "*SURFACE, NAME=S\n*INCLUDE, INPUT=" + target + "\n");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 422) << r->body;
    const std::string detail = body_json(r)["detail"];
    EXPECT_NE(detail.find("*INCLUDE is not accepted here: an uploaded mesh must be self-contained"),
              std::string::npos)
        << detail;
    EXPECT_EQ(detail.find("root:"), std::string::npos) << detail;
  }
  EXPECT_FALSE(std::filesystem::exists(data.path() / "meshes") &&
               !std::filesystem::is_empty(data.path() / "meshes"));
}

TEST(MeshUploadLimits, TheCapsFollowMaxNodesAndNameTheLimit) {
  TempDir data;
  LiveServer server(data.path(), {"--max-nodes", "20"});
  auto c = server.client();
  const auto r = post_mesh(c, bytes_of(meshes / "two_blocks_ascii.msh"));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 422) << r->body;
  EXPECT_NE(body_json(r)["detail"].get<std::string>().find(
                "the file has more than 20 nodes (the server limit max_nodes = 20)"),
            std::string::npos)
      << r->body;
}

TEST_F(MeshUpload, LaterRequestsUseTheParsedFormNotTheFile) {
  const auto posted = post_mesh(c, bytes_of(meshes / "two_blocks_ascii.msh"));
  ASSERT_TRUE(posted);
  const std::string id = body_json(posted)["id"];
  // Were the stored file parsed again, this validation would fail: the parse of the upload is what is used.
  std::ofstream(data.path() / "meshes" / (id + ".msh"), std::ios::trunc) << "$MeshFormat\nnot a mesh\n";
  const auto r =
      c.Post("/v1/validate", block_scene({{"id", id}, {"elements", "left"}}).dump(), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
  EXPECT_EQ(body_json(r)["nodes"], 27);
}

TEST(MeshDelete, IsRefusedWhileAQueuedJobNamesTheMeshAndThenRemovesIt) {
  TempDir data;
  LiveServer server(data.path(), {"--workers", "0"});
  auto c = server.client();
  const std::string id = body_json(post_mesh(c, bytes_of(meshes / "two_blocks_ascii.msh")))["id"];
  const auto queued = submit(c, block_scene({{"id", id}, {"elements", "left"}}));
  ASSERT_TRUE(queued);
  ASSERT_EQ(queued->status, 201) << queued->body;
  const std::string job_id = body_json(queued)["id"];
  const std::string path = "/v1/meshes/" + id;

  const auto refused = c.Delete(path.c_str());
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 409) << refused->body;
  const auto problem = body_json(refused);
  EXPECT_EQ(problem["type"], "urn:stoss:problem:mesh-in-use");
  EXPECT_EQ(problem["jobs"], nlohmann::json::array({job_id}));
  EXPECT_EQ(c.Get(path.c_str())->status, 200);

  ASSERT_EQ(c.Post(("/v1/jobs/" + job_id + "/cancel").c_str())->status, 202);
  const auto removed = c.Delete(path.c_str());
  ASSERT_TRUE(removed);
  EXPECT_EQ(removed->status, 204) << removed->body;
  EXPECT_EQ(c.Get(path.c_str())->status, 404);
  EXPECT_EQ(c.Delete(path.c_str())->status, 404);
  EXPECT_FALSE(std::filesystem::exists(data.path() / "meshes" / (id + ".msh")));
  const auto stale =
      c.Post("/v1/validate", block_scene({{"id", id}, {"elements", "left"}}).dump(), "application/json");
  EXPECT_EQ(stale->status, 422) << stale->body;
}

TEST(MeshStoreQuota, AnUploadBeyondMaxMeshStoreBytesIs413NamingTheLimitUntilRoomIsMade) {
  TempDir data;
  const std::string ascii = bytes_of(meshes / "two_blocks_ascii.msh"),
                    binary = bytes_of(meshes / "two_blocks_binary.msh");
  const std::size_t limit = ascii.size() + binary.size() - 1;
  LiveServer server(data.path(), {"--max-mesh-store-bytes", std::to_string(limit)});
  auto c = server.client();
  const auto first = post_mesh(c, ascii);
  ASSERT_EQ(first->status, 201) << first->body;
  const auto full = post_mesh(c, binary);
  ASSERT_TRUE(full);
  EXPECT_EQ(full->status, 413) << full->body;
  const auto problem = body_json(full);
  EXPECT_EQ(problem["type"], "urn:stoss:problem:mesh-store-full");
  EXPECT_EQ(
      problem["limits"],
      nlohmann::json::parse("[{\"name\": \"max_mesh_store_bytes\", \"limit\": " + std::to_string(limit) +
                            ", \"value\": " + std::to_string(ascii.size() + binary.size()) + "}]"));
  EXPECT_NE(problem["detail"].get<std::string>().find("DELETE /v1/meshes/{id}"), std::string::npos);
  EXPECT_EQ(post_mesh(c, ascii)->status, 200);  // stored before: no room needed
  ASSERT_EQ(c.Delete(("/v1/meshes/" + body_json(first)["id"].get<std::string>()).c_str())->status, 204);
  EXPECT_EQ(post_mesh(c, binary)->status, 201);
}

TEST(MeshUploadLimits, AGeneratedSphereIsCountedExactlyBeforeItIsBuilt) {
  // (6 d² + 2)(layers + 1) = (6 · 1600 + 2) · 3 = 28806 nodes: between 1 and 4 × max_nodes, which used to be
  // generated in the request thread before the 413.
  nlohmann::json scene = box_scene(1, 1);
  scene["bodies"][0]["mesh"] = {
      {"hollow_sphere", {{"outer_radius", 1}, {"inner_radius", 0.5}, {"divisions", 40}, {"layers", 2}}}};
  server::http::Limits limits;
  limits.max_nodes = 10'000;
  const auto problem = server::http::check_scene_limits_early(scene, limits);
  ASSERT_TRUE(problem);
  EXPECT_EQ(problem->to_json()["limits"][0],
            nlohmann::json({{"name", "max_nodes"}, {"limit", 10'000}, {"value", 28'806}}));
}

}  // namespace
}  // namespace stoss::test
