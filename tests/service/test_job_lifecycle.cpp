// The live service: the real `stoss serve` binary on a free loopback port with a temporary data
// directory, driven over HTTP. Each test states the requirement it checks.
#include <gtest/gtest.h>
#include <signal.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <thread>

#include "core/output/result_reader.hpp"
#include "tests/server/live_server.hpp"

namespace stoss::test {
namespace {

using namespace std::chrono_literals;

/// Relative tolerance of energies against ½ m v² (the scheme conserves energy to round-off).
constexpr double energy_tolerance = 1e-9;

std::filesystem::path download(httplib::Client& c, const std::string& path, const std::filesystem::path& to) {
  auto r = c.Get(path);
  EXPECT_TRUE(r);
  if (!r) return to;
  EXPECT_EQ(r->status, 200) << r->body;
  std::ofstream(to, std::ios::binary) << r->body;
  return to;
}

std::string id_of(const httplib::Result& r) {
  EXPECT_TRUE(r);
  if (!r) return "";
  EXPECT_EQ(r->status, 201) << r->body;
  return nlohmann::json::parse(r->body).value("id", "");
}

/// The system shall run a submitted scene and serve an HDF5 result whose energies match the scene.
TEST(Service, SubmitPollDownloadAndCheckTheEnergies) {
  TempDir dir;
  LiveServer server(dir.path() / "data");
  auto c = server.client();
  const std::array<double, 3> v = {1, 0.5, 0};
  auto r = submit(c, box_scene(2, 30, v));
  ASSERT_TRUE(r);
  ASSERT_EQ(r->status, 201) << r->body;
  const auto created = nlohmann::json::parse(r->body);
  const std::string id = created["id"];
  EXPECT_EQ(r->get_header_value("Location"), "/v1/jobs/" + id);
  EXPECT_EQ(created["status"], "queued");
  EXPECT_EQ(created["effects"], (nlohmann::json{"inertia", "elasticity"}));
  EXPECT_EQ(created["progress"]["steps"], 30);

  const auto done = wait_for_status(c, id, {"succeeded", "failed"});
  ASSERT_EQ(done["status"], "succeeded") << done.dump();
  EXPECT_EQ(done["progress"]["step"], 30);
  EXPECT_DOUBLE_EQ(done["progress"]["time"].get<double>(), 0.3);
  const auto& summary = done["summary"];
  EXPECT_EQ(summary["steps"], 30);
  EXPECT_LT(summary["energy_drift"].get<double>(), energy_tolerance);
  EXPECT_LT(summary["linear_momentum_drift"].get<double>(), energy_tolerance);
  EXPECT_LT(summary["angular_momentum_drift"].get<double>(), energy_tolerance);
  EXPECT_TRUE(summary.contains("newton_iterations"));
  EXPECT_TRUE(summary["newton_iterations_per_step"].is_number());  // 0 here: rigid translation is exact
  EXPECT_GT(summary["wall_seconds"].get<double>(), 0.0);
  EXPECT_EQ(done["kind"], "simulation");
  EXPECT_FALSE(summary.contains("max_penetration"));  // no contact in the scene
  EXPECT_EQ(done["links"]["result"], "/v1/jobs/" + id + "/result");

  const auto h5 = download(c, "/v1/jobs/" + id + "/result", dir.path() / "result.h5");
  download(c, "/v1/jobs/" + id + "/result.xdmf", dir.path() / "result.xdmf");
  const auto file = output::ResultFile::open(h5);
  EXPECT_EQ(file.attribute_double("complete"), 1.0);
  EXPECT_EQ(file.mesh_nodes().rows(), 27);
  const Eigen::MatrixXd kinetic = file.series("kinetic_energy");
  const Eigen::MatrixXd total = file.series("total_energy");
  ASSERT_EQ(total.rows(), 31);
  const double expected = box_kinetic_energy(v);  // ½ (ρ V) |v|² = 1.25
  EXPECT_NEAR(kinetic(0, 0), expected, energy_tolerance * expected);
  for (int i = 0; i < total.rows(); ++i) EXPECT_NEAR(total(i, 0), expected, energy_tolerance * expected) << i;
}

/// The system shall serve the XDMF sidecar pointing ParaView at result.h5, and only after success.
TEST(Service, ServesTheXdmfSidecar) {
  TempDir dir;
  LiveServer server(dir.path() / "data");
  auto c = server.client();
  const std::string id = id_of(submit(c, box_scene(2, 10)));
  ASSERT_EQ(wait_for_status(c, id, {"succeeded", "failed"})["status"], "succeeded");
  auto r = c.Get("/v1/jobs/" + id + "/result.xdmf");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_EQ(r->get_header_value("Content-Type"), "application/xml");
  EXPECT_NE(r->body.find("<Xdmf"), std::string::npos);
  EXPECT_NE(r->body.find("result.h5:/mesh/hex8"), std::string::npos);
  EXPECT_NE(r->body.find("CollectionType=\"Temporal\""), std::string::npos);
}

/// The system shall serve the series as JSON and CSV, and byte ranges and ETags of the result.
TEST(Service, ServesSeriesAsJsonAndCsvAndTheResultByRange) {
  TempDir dir;
  LiveServer server(dir.path() / "data");
  auto c = server.client();
  const std::string id = id_of(submit(c, box_scene(2, 20, {0, 0, 2})));
  ASSERT_EQ(wait_for_status(c, id, {"succeeded", "failed"})["status"], "succeeded");
  const auto series = body_json(c.Get("/v1/jobs/" + id + "/series"));
  ASSERT_EQ(series["time"].size(), 21u);
  EXPECT_NEAR(series["kinetic_energy"][0].get<double>(), 4.0, 4.0 * energy_tolerance);
  EXPECT_EQ(series["linear_momentum"][0].size(), 3u);
  EXPECT_NEAR(series["linear_momentum"][20][2].get<double>(), 4.0, 1e-9);  // p = m v = 2 · 2
  auto csv = c.Get("/v1/jobs/" + id + "/series?format=csv");
  ASSERT_EQ(csv->status, 200);
  EXPECT_EQ(csv->get_header_value("Content-Type"), "text/csv");
  EXPECT_EQ(csv->body.substr(0, csv->body.find('\n')).substr(0, 20), "time,kinetic_energy,");
  EXPECT_EQ(std::count(csv->body.begin(), csv->body.end(), '\n'), 22);

  auto whole = c.Get("/v1/jobs/" + id + "/result");
  const std::string etag = whole->get_header_value("ETag");
  EXPECT_FALSE(etag.empty());
  EXPECT_EQ(whole->body.substr(0, 8), "\x89HDF\r\n\x1a\n");
  auto part = c.Get("/v1/jobs/" + id + "/result", {{"Range", "bytes=1-3"}});
  EXPECT_EQ(part->status, 206);
  EXPECT_EQ(part->body, "HDF");
  EXPECT_EQ(part->get_header_value("Content-Range"), "bytes 1-3/" + std::to_string(whole->body.size()));
  EXPECT_EQ(c.Get("/v1/jobs/" + id + "/result", {{"If-None-Match", etag}})->status, 304);
}

/// The system shall cancel a queued job at once and a running one within a step, keeping the log.
TEST(Service, CancelsQueuedAndRunningJobs) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "1"});
  auto c = server.client();
  const std::string running = id_of(submit(c, box_scene(4, 100'000, {1, 0, 0}, 2.0)));
  ASSERT_TRUE(eventually([&] { return job(c, running)["progress"]["step"].get<int>() >= 1; }, 120s));
  const std::string queued = id_of(submit(c, box_scene(2, 10)));

  auto canceled_queued = c.Post("/v1/jobs/" + queued + "/cancel");
  ASSERT_EQ(canceled_queued->status, 202);
  EXPECT_EQ(nlohmann::json::parse(canceled_queued->body)["status"], "canceled");  // at once

  auto cancel_running = c.Post("/v1/jobs/" + running + "/cancel");
  ASSERT_EQ(cancel_running->status, 202);
  const auto requested = nlohmann::json::parse(cancel_running->body);
  EXPECT_TRUE(requested["cancel_requested"].get<bool>());
  const auto stopped = wait_for_status(c, running, {"canceled", "succeeded", "failed"}, 30s);
  ASSERT_EQ(stopped["status"], "canceled");
  EXPECT_LT(stopped["summary"]["steps"].get<int>(), 100'000);
  EXPECT_FALSE(stopped["summary"]["completed"].get<bool>());

  auto log = c.Get("/v1/jobs/" + running + "/log");
  EXPECT_EQ(log->status, 200);
  EXPECT_NE(log->body.find("attempt 1 started"), std::string::npos) << log->body;
  EXPECT_NE(log->body.find("canceled at step"), std::string::npos) << log->body;
  auto result = c.Get("/v1/jobs/" + running + "/result");
  EXPECT_EQ(result->status, 409);
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "data/jobs" / running / "attempt-1/log.txt"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "data/jobs" / running / "attempt-1/result.h5"));
  EXPECT_EQ(c.Post("/v1/jobs/" + running + "/cancel")->status, 409);  // a canceled job is finished

  EXPECT_EQ(c.Delete("/v1/jobs/" + running)->status, 204);
  EXPECT_EQ(c.Get("/v1/jobs/" + running)->status, 404);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "data/jobs" / running));
}

/// The system shall mark a job whose run fails as failed with the solver's reason and keep its log.
TEST(Service, AFailedRunKeepsItsLogAndReason) {
  TempDir dir;
  LiveServer server(dir.path() / "data");
  auto c = server.client();
  nlohmann::json scene = box_scene(2, 20, {0, 0, 0}, 5.0);
  scene["solver"] = {{"max_iterations", 1}, {"tolerance", 1e-12}};  // a spinning box needs more than one
  const std::string id = id_of(submit(c, scene));
  const auto failed = wait_for_status(c, id, {"failed", "succeeded"});
  ASSERT_EQ(failed["status"], "failed");
  ASSERT_TRUE(failed.contains("error"));
  const std::string reason = failed["error"];
  EXPECT_FALSE(reason.empty());
  EXPECT_NE(c.Get("/v1/jobs/" + id + "/log")->body.find("failed: " + reason), std::string::npos);
  EXPECT_EQ(c.Get("/v1/jobs/" + id + "/result")->status, 409);
  // The series and summary up to the failing step stay readable, marked incomplete (issue 10).
  auto series = c.Get("/v1/jobs/" + id + "/series");
  EXPECT_EQ(series->status, 200);
  EXPECT_EQ(nlohmann::json::parse(series->body)["completed"], false);
  EXPECT_EQ(failed["summary"]["completed"], false) << failed.dump();
}

/// The system shall keep every accepted job across a kill -9, run the interrupted one again to
/// success, and never serve a partial result.
TEST(Service, RecoversFromKill9) {
  TempDir dir;
  const auto data = dir.path() / "data";
  const std::vector<std::string> flags = {"--workers", "1", "--lease-seconds", "1", "--renew-seconds", "0.2"};
  const std::array<double, 3> v = {1, 0.5, 0};
  std::string interrupted, waiting;
  {
    LiveServer first(data, flags);
    auto c = first.client();
    interrupted = id_of(submit(c, box_scene(6, 800, v, 2.0)));
    waiting = id_of(submit(c, box_scene(2, 30, v)));
    ASSERT_TRUE(eventually([&] { return job(c, interrupted)["progress"]["step"].get<int>() >= 1; }, 120s));
    first.kill9();
  }
  EXPECT_TRUE(std::filesystem::exists(data / "jobs" / interrupted / "attempt-1/log.txt"));
  EXPECT_FALSE(std::filesystem::exists(data / "jobs" / interrupted / "attempt-1/result.h5"));

  LiveServer second(data, flags);
  auto c = second.client();
  const auto before = job(c, interrupted);
  ASSERT_NE(before["status"], "succeeded") << before.dump();
  EXPECT_EQ(c.Get("/v1/jobs/" + interrupted + "/result")->status, 409);
  EXPECT_EQ(c.Get("/v1/jobs/" + waiting)->status, 200);  // accepted before the crash: still there

  const auto after = wait_for_status(c, interrupted, {"succeeded", "failed"}, 300s);
  ASSERT_EQ(after["status"], "succeeded") << after.dump();
  EXPECT_EQ(after["attempt"], 2);
  EXPECT_LT(after["summary"]["energy_drift"].get<double>(), 1e-6);
  const auto file =
      output::ResultFile::open(download(c, "/v1/jobs/" + interrupted + "/result", dir.path() / "r.h5"));
  EXPECT_EQ(file.attribute_double("complete"), 1.0);
  EXPECT_EQ(file.series("time").rows(), 801);
  // Translation ½ m |v|² plus rotation ½ ω² I_zz, I_zz = m (1² + 1²) / 12 for the unit cube.
  const double expected = box_kinetic_energy(v) + 0.5 * 4.0 * (2.0 * 2.0 / 12.0);
  EXPECT_NEAR(file.series("kinetic_energy")(0, 0), expected, 1e-9 * expected);
  EXPECT_EQ(wait_for_status(c, waiting, {"succeeded", "failed"})["status"], "succeeded");
  EXPECT_NE(c.Get("/v1/jobs/" + interrupted + "/log")->body.find("attempt 2 started"), std::string::npos);
}

/// The system shall accept 50 concurrent submissions from several clients and finish each correctly.
TEST(Service, FiftyConcurrentSubmissionsAllFinishCorrectly) {
  TempDir dir;
  LiveServer server(dir.path() / "data", {"--workers", "2"});
  constexpr int clients = 5, per_client = 10;
  std::vector<std::string> ids(clients * per_client);
  auto velocity = [](int k) { return std::array<double, 3>{0.1 * (k + 1), 0.5, -0.25}; };
  std::vector<std::thread> threads;
  for (int t = 0; t < clients; ++t)
    threads.emplace_back([&, t] {
      auto c = server.client();
      for (int i = 0; i < per_client; ++i) {
        const int k = t * per_client + i;
        auto r = submit(c, box_scene(2, 20, velocity(k)));
        if (r && r->status == 201) ids[k] = nlohmann::json::parse(r->body)["id"];
      }
    });
  for (auto& t : threads) t.join();
  auto c = server.client();
  for (int k = 0; k < clients * per_client; ++k) {
    ASSERT_FALSE(ids[k].empty()) << "submission " << k << " was not accepted";
    const auto done = wait_for_status(c, ids[k], {"succeeded", "failed", "canceled"}, 300s);
    ASSERT_EQ(done["status"], "succeeded") << done.dump();
    const auto series = body_json(c.Get("/v1/jobs/" + ids[k] + "/series"));
    const double expected = box_kinetic_energy(velocity(k));
    EXPECT_NEAR(series["total_energy"][0].get<double>(), expected, energy_tolerance * expected) << k;
    EXPECT_NEAR(series["total_energy"][20].get<double>(), expected, energy_tolerance * expected) << k;
  }
  const auto list = body_json(c.Get("/v1/jobs?status=succeeded&limit=200"));
  EXPECT_EQ(list["jobs"].size(), 50u);
}

/// Kernel ids of the threads of process `pid` that do not block SIGTERM (/proc/PID/task/*/status, SigBlk).
std::vector<pid_t> threads_not_blocking_sigterm(pid_t pid) {
  std::vector<pid_t> found;
  for (const auto& task : std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/task")) {
    std::ifstream status(task.path() / "status");
    for (std::string line; std::getline(status, line);)
      if (line.rfind("SigBlk:", 0) == 0 &&
          !(std::stoull(line.substr(7), nullptr, 16) & (1ull << (SIGTERM - 1))))
        found.push_back(pid_t(std::stol(task.path().filename().string())));
  }
  return found;
}

/// Starts a server with one worker and a long job, sends SIGTERM once the job runs (to the thread
/// `pick_thread` names, 0: to the process), and checks that the server stopped with exit 0 and that a
/// server started again on the same data finds the job queued with no attempt spent.
void expect_sigterm_stops_cleanly(const std::function<pid_t(const LiveServer&)>& pick_thread) {
  TempDir dir;
  const auto data = dir.path() / "data";
  std::string id, output;
  {
    LiveServer server(data, {"--workers", "1"});
    auto c = server.client();
    id = id_of(submit(c, box_scene(4, 100'000, {1, 0, 0}, 2.0)));
    ASSERT_TRUE(eventually([&] { return job(c, id)["status"] == "running"; }, 60s));
    EXPECT_EQ(server.terminate(pick_thread(server)), 0) << server.output();
    output = server.output();
    EXPECT_NE(output.find("SIGTERM, stopping"), std::string::npos) << output;
  }
  LiveServer again(data, {"--workers", "0"});
  auto c = again.client();
  const auto j = job(c, id);
  const auto log = c.Get("/v1/jobs/" + id + "/log");
  EXPECT_EQ(j["status"], "queued") << j.dump() << "\n" << (log ? log->body : "no log") << "\n" << output;
  EXPECT_EQ(j["attempt"], 0);
}

/// The system shall stop cleanly on SIGTERM and give a running job back to the queue.
TEST(Service, StopsCleanlyOnSigterm) {
  expect_sigterm_stops_cleanly([](const LiveServer&) { return pid_t(0); });
}

/// The system shall stop cleanly on SIGTERM whichever of its threads the kernel hands it to. The server
/// blocks SIGTERM in every thread it starts and waits for it in one; a thread a library started before
/// main (OpenBLAS's pthread build starts its pool while loading) does not block it, and the signal
/// landing there killed the server (exit 143, the job left "running": a CI failure).
TEST(Service, StopsCleanlyWhenSigtermLandsOnALibrarysThread) {
  if (threads_not_blocking_sigterm(LiveServer(TempDir().path() / "probe").pid()).empty())
    GTEST_SKIP() << "every thread of stoss serve blocks SIGTERM here (no BLAS pool threads)";
  expect_sigterm_stops_cleanly(
      [](const LiveServer& server) { return threads_not_blocking_sigterm(server.pid()).front(); });
}

}  // namespace
}  // namespace stoss::test
