#include "server/jobs/store/store.hpp"

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
