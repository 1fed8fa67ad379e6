#include "server/jobs/store/store.hpp"

#include <algorithm>
#include <limits>

namespace stoss::server::jobs {

namespace {

/// Whether some body of `scene` has "mesh": {"id": mesh_id}.
bool names_mesh(const nlohmann::json& scene, const std::string& mesh_id) {
  if (!scene.is_object() || !scene.contains("bodies") || !scene["bodies"].is_array()) return false;
  for (const auto& body : scene["bodies"]) {
    if (!body.is_object() || !body.contains("mesh") || !body["mesh"].is_object()) continue;
    const auto id = body["mesh"].find("id");
    if (id != body["mesh"].end() && id->is_string() && id->get<std::string>() == mesh_id) return true;
  }
  return false;
}

}  // namespace

int scene_ranks(const nlohmann::json& scene) {
  if (!scene.is_object() || !scene.contains("solver") || !scene["solver"].is_object()) return 1;
  const nlohmann::json& solver = scene["solver"];
  const auto ranks = solver.find("ranks");
  if (ranks == solver.end() || !ranks->is_number_integer()) return 1;
  return static_cast<int>(std::clamp<long long>(ranks->get<long long>(), 1, std::numeric_limits<int>::max()));
}

std::vector<JobId> JobStore::active_jobs_using_mesh(const std::string& mesh_id) {
  std::vector<JobId> users;
  for (const Status status : {Status::queued, Status::running}) {
    std::optional<std::int64_t> cursor;
    do {
      const Page page = list(status, 200, cursor);
      for (const Job& job : page.jobs) {
        const auto scene = this->scene(job.id);
        if (scene && names_mesh(*scene, mesh_id)) users.push_back(job.id);
      }
      cursor = page.next_cursor;
    } while (cursor);
  }
  return users;
}

}  // namespace stoss::server::jobs
