#include "server/jobs/job_files.hpp"

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <system_error>

#include "core/output/durable_file.hpp"
#include "core/run/checkpoint.hpp"
#include "server/common/json_input.hpp"
#include "server/jobs/reporting/series_recorder.hpp"

namespace stoss::server::jobs {

namespace fs = std::filesystem;
using output::rename_durably;

namespace {

constexpr const char* attempt_prefix = "attempt-";

std::optional<std::string> read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// The attempt numbers that have a folder in `job_dir`, ascending.
std::vector<int> attempt_numbers(const fs::path& job_dir) {
  std::vector<int> numbers;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(job_dir, error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(attempt_prefix, 0) != 0) continue;
    const std::string digits = name.substr(std::string(attempt_prefix).size());
    if (digits.empty() || digits.size() > 9 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
      continue;
    numbers.push_back(std::stoi(digits));
  }
  std::sort(numbers.begin(), numbers.end());
  return numbers;
}

/// Copies `from` to `to` through a temporary name and a durable rename.
void copy_durably(const fs::path& from, const fs::path& to) {
  const fs::path temporary = to.string() + ".tmp";
  fs::copy_file(from, temporary, fs::copy_options::overwrite_existing);
  rename_durably(temporary, to);
}

}  // namespace

nlohmann::json outcome_json(const Outcome& outcome) {
  return {{"status", to_string(outcome.status)},
          {"summary", outcome.summary ? *outcome.summary : nlohmann::json(nullptr)},
          {"error", outcome.error ? nlohmann::json(*outcome.error) : nlohmann::json(nullptr)},
          {"result_attempt",
           outcome.result_attempt ? nlohmann::json(*outcome.result_attempt) : nlohmann::json(nullptr)}};
}

Outcome outcome_from_json(const nlohmann::json& j) {
  Outcome outcome;
  auto status = parse_status(j.at("status").get<std::string>());
  if (!status || !is_terminal(*status)) throw std::invalid_argument("outcome: bad status");
  outcome.status = *status;
  if (j.contains("summary") && !j["summary"].is_null()) outcome.summary = j["summary"];
  if (j.contains("error") && j["error"].is_string()) outcome.error = j["error"].get<std::string>();
  if (j.contains("result_attempt") && j["result_attempt"].is_number_integer())
    outcome.result_attempt = j["result_attempt"].get<int>();
  return outcome;
}

void AttemptFiles::discard_partial() const {
  std::error_code ignored;
  fs::remove(dir_ / output::partial_file_name, ignored);
  fs::remove(dir_ / output::incomplete_file_name, ignored);
  fs::remove(study_partial(), ignored);
}

void AttemptFiles::write_study(const std::string& text) const {
  output::write_durably(study(), text, study_partial());
}

void AttemptFiles::write_outcome(const Outcome& outcome) const {
  output::write_durably(outcome_file(), safe_dump(outcome_json(outcome)));
}

std::optional<Outcome> AttemptFiles::succeeded() const {
  const auto text = read_text(outcome_file());
  if (!text) return std::nullopt;
  try {
    Outcome outcome = outcome_from_json(nlohmann::json::parse(*text));
    std::error_code error;
    const bool complete = fs::is_regular_file(result(), error) || fs::is_regular_file(study(), error);
    if (outcome.status == Status::succeeded && complete) return outcome;
  } catch (const std::exception&) {  // not an outcome this program wrote: nothing to adopt
  }
  return std::nullopt;
}

std::optional<Outcome> JobFiles::completed_before(const JobId& id, int attempt_number) const {
  for (int n = attempt_number - 1; n >= 1; --n)
    if (auto outcome = attempt(id, n).succeeded()) {
      if (!outcome->result_attempt) outcome->result_attempt = n;
      return outcome;
    }
  return std::nullopt;
}

AttemptFiles JobFiles::attempt(const JobId& id, int attempt) const {
  return AttemptFiles(dir(id) / (attempt_prefix + std::to_string(attempt)));
}

AttemptFiles JobFiles::served(const Job& job) const {
  if (job.result_attempt) return attempt(job.id, *job.result_attempt);
  const AttemptFiles latest = attempt(job.id, job.attempt);
  std::error_code error;
  if (job.attempt > 0 && fs::is_directory(latest.dir(), error)) return latest;
  return AttemptFiles(dir(job.id));
}

std::string JobFiles::read_log(const JobId& id) const {
  std::string log = read_text(AttemptFiles(dir(id)).log()).value_or("");
  for (int n : attempt_numbers(dir(id))) log += read_text(attempt(id, n).log()).value_or("");
  return log;
}

std::optional<fs::path> JobFiles::stored_mesh(const std::string& id) const {
  const bool hex = id.size() == 64 && std::all_of(id.begin(), id.end(), [](char c) {
                     return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
                   });
  if (!hex) return std::nullopt;
  for (const char* extension : {".msh", ".inp"}) {
    const fs::path path = meshes_ / (id + extension);
    std::error_code error;
    if (fs::is_regular_file(path, error)) return path;
  }
  return std::nullopt;
}

scene::MeshFiles JobFiles::mesh_files() const {
  scene::MeshFiles files;
  files.stored = [jobs = *this](const std::string& id) { return jobs.stored_mesh(id); };
  return files;
}

AttemptFiles JobFiles::prepare_attempt(const JobId& id, int attempt_number) const {
  const AttemptFiles files = attempt(id, attempt_number);
  fs::create_directories(files.dir());
  files.discard_partial();
  std::error_code ignored;
  for (const fs::path& left :
       {files.result(), files.xdmf(), files.xdmf_mesh(), files.study(), files.outcome_file()})
    fs::remove(left, ignored);
  fs::remove(files.dir() / partial_series_file, ignored);
  if (!run::CheckpointStore(files.checkpoint()).exists()) seed_checkpoint(id, attempt_number, files);
  return files;
}

void JobFiles::seed_checkpoint(const JobId& id, int attempt_number, const AttemptFiles& into) const {
  std::vector<fs::path> sources;  // newest first
  const std::vector<int> numbers = attempt_numbers(dir(id));
  for (auto n = numbers.rbegin(); n != numbers.rend(); ++n)
    if (*n < attempt_number) sources.push_back(attempt(id, *n).checkpoint());
  sources.push_back(AttemptFiles(dir(id)).checkpoint());
  const fs::path seed = into.checkpoint().string() + ".seed";
  for (const fs::path& source : sources) {
    const run::CheckpointStore from(source);
    if (!from.exists()) continue;
    std::error_code ignored;
    fs::remove_all(seed, ignored);
    try {
      fs::create_directories(seed);
      copy_durably(from.state_file(), seed / from.state_file().filename());
      for (const auto& entry : fs::directory_iterator(source)) {
        const fs::path name = entry.path().filename();
        if (name.extension() == ".h5" && name != from.state_file().filename())
          copy_durably(entry.path(), seed / name);
      }
      fs::remove_all(into.checkpoint());  // frames without a state.h5 (a released attempt's): none resumable
      rename_durably(seed, into.checkpoint());
      return;
    } catch (const std::exception&) {  // the source went away meanwhile: try an older one, else start over
      fs::remove_all(seed, ignored);
    }
  }
}

namespace {

/// Whether the attempt's folder names a job process that still runs here (process.pid is written by
/// ProcessExecutor while its child lives). Such an attempt lost its lease but may still write its files.
bool attempt_process_alive(const fs::path& attempt_dir) {
  std::ifstream in(attempt_dir / "process.pid");  // ProcessExecutor's job_pid_file
  long pid = 0;
  if (!(in >> pid) || pid <= 0) return false;
  // /proc/<pid>/stat: "pid (comm) S …"; a zombie (Z) or dead (X) process writes nothing any more. A job
  // process whose serve was killed may linger as a zombie where nothing reaps it.
  std::ifstream stat("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return false;
  const auto close = line.rfind(')');
  const char state = close != std::string::npos && close + 2 < line.size() ? line[close + 2] : '?';
  return state != 'Z' && state != 'X';
}

}  // namespace

void JobFiles::prune_through(const JobId& id, int attempt_number) const {
  for (int n : attempt_numbers(dir(id))) {
    if (n > attempt_number) break;
    const AttemptFiles earlier = attempt(id, n);
    // A superseded attempt whose process still runs (stopped past its lease, say) keeps its files: it
    // writes only there, and removing them under it would only make it fail noisily.
    if (n != attempt_number && attempt_process_alive(earlier.dir())) continue;
    std::error_code ignored;
    fs::remove_all(earlier.checkpoint(), ignored);
    earlier.discard_partial();
    fs::remove(earlier.dir() / partial_series_file, ignored);
  }
}

void JobFiles::remove(const JobId& id) const {
  std::error_code ignored;
  fs::remove_all(dir(id), ignored);
}

}  // namespace stoss::server::jobs
