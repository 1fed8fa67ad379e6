#include "server/http/study_check.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/model/model.hpp"
#include "server/http/scene_check.hpp"
#include "server/jobs/running/study_job.hpp"

namespace stoss::server::http {

namespace {

const char* const study_members[] = {"scene", "steps", "tolerances", "schemes", "reference_step", "repeat"};

/// Most runs of each scheme × step (`repeat`).
constexpr int max_study_repeat = 9;

void add(nlohmann::json& errors, const std::string& pointer, const std::string& message) {
  errors.push_back({{"pointer", pointer}, {"message", message}});
}

/// The JSON pointer of member `name` of the root (RFC 6901 escapes).
std::string member_pointer(const std::string& name) {
  std::string out = "/";
  for (char c : name) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}

/// A value for a message: scalars as JSON, arrays and objects by their type (they may be large).
std::string describe(const nlohmann::json& v) {
  return v.is_structured() ? std::string("an ") + v.type_name() : dump(v);
}

bool positive_number(const nlohmann::json& v) {
  return v.is_number() && std::isfinite(v.get<double>()) && v.get<double>() > 0;
}

std::string format_step(double h) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", h);
  return text;
}

void check_members(const nlohmann::json& body, nlohmann::json& errors) {
  for (const auto& [name, value] : body.items())
    if (std::find(std::begin(study_members), std::end(study_members), name) == std::end(study_members))
      add(errors, member_pointer(name),
          "is not a member of a study (scene, steps, tolerances, schemes, reference_step, repeat)");
}

std::vector<double> check_steps(const nlohmann::json& body, nlohmann::json& errors) {
  auto it = body.find("steps");
  if (it == body.end()) {
    add(errors, "/steps", "is required: a non-empty array of step sizes");
    return {};
  }
  if (!it->is_array() || it->empty() || it->size() > max_study_steps) {
    add(errors, "/steps",
        "must be an array of 1 to " + std::to_string(max_study_steps) + " step sizes, got " +
            (it->is_array() ? std::to_string(it->size()) + " items" : describe(*it)));
    return {};
  }
  std::vector<double> steps;
  for (std::size_t i = 0; i < it->size(); ++i) {
    const auto& h = (*it)[i];
    if (positive_number(h))
      steps.push_back(h.get<double>());
    else
      add(errors, "/steps/" + std::to_string(i), "must be a positive number, got " + describe(h));
  }
  return steps;
}

/// time.tolerance values to sweep beside the steps (docs/scene.md "Time"): optional, each finite and > 0.
std::vector<double> check_tolerances(const nlohmann::json& body, nlohmann::json& errors) {
  auto it = body.find("tolerances");
  if (it == body.end()) return {};
  if (!it->is_array() || it->empty() || it->size() > max_study_steps) {
    add(errors, "/tolerances",
        "must be an array of 1 to " + std::to_string(max_study_steps) + " tolerances, got " +
            (it->is_array() ? std::to_string(it->size()) + " items" : describe(*it)));
    return {};
  }
  std::vector<double> tolerances;
  for (std::size_t i = 0; i < it->size(); ++i) {
    const auto& tol = (*it)[i];
    if (positive_number(tol))
      tolerances.push_back(tol.get<double>());
    else
      add(errors, "/tolerances/" + std::to_string(i), "must be a finite number > 0, got " + describe(tol));
  }
  return tolerances;
}

/// "energy_momentum, midpoint, hht, generalized_alpha": every scheme, in model::all_schemes order.
std::string scheme_names() {
  std::string names;
  for (model::Scheme s : model::all_schemes) names += (names.empty() ? "" : ", ") + model::to_string(s);
  return names;
}

std::vector<model::Scheme> check_schemes(const nlohmann::json& body, nlohmann::json& errors) {
  auto it = body.find("schemes");
  if (it == body.end()) return study::Options{}.schemes;
  if (!it->is_array() || it->empty()) {
    add(errors, "/schemes", "must be a non-empty array of scheme names, got " + describe(*it));
    return {};
  }
  std::vector<model::Scheme> schemes;
  for (std::size_t i = 0; i < it->size(); ++i) {
    const auto& name = (*it)[i];
    auto scheme = name.is_string() ? jobs::parse_scheme(name.get<std::string>()) : std::nullopt;
    if (scheme)
      schemes.push_back(*scheme);
    else
      add(errors, "/schemes/" + std::to_string(i),
          "must be one of " + scheme_names() + ", got " + describe(name));
  }
  return schemes;
}

/// The reference step asked for; 0 when absent.
double check_reference(const nlohmann::json& body, nlohmann::json& errors) {
  auto it = body.find("reference_step");
  if (it == body.end()) return 0;
  if (positive_number(*it)) return it->get<double>();
  add(errors, "/reference_step", "must be a positive number, got " + describe(*it));
  return 0;
}

/// Runs per scheme × step whose median wall time a row shows; study::Options' default when absent.
int check_repeat(const nlohmann::json& body, nlohmann::json& errors) {
  auto it = body.find("repeat");
  if (it == body.end()) return study::Options{}.repeat;
  if (it->is_number_integer() && it->get<long long>() >= 1 && it->get<long long>() <= max_study_repeat)
    return it->get<int>();
  add(errors, "/repeat",
      "must be an integer in [1, " + std::to_string(max_study_repeat) + "], got " + describe(*it));
  return 1;
}

/// Checks the scene (its own step and frames aside, on one rank); its 422 errors are added under /scene, a
/// 413 is thrown.
scene::Summary check_study_scene(const nlohmann::json& body, const Limits& limits,
                                 const scene::MeshFiles& mesh_files, nlohmann::json& resolved,
                                 nlohmann::json& errors) {
  if (!body.contains("scene")) {
    add(errors, "/scene", "is required: the scene to study");
    return {};
  }
  Limits relaxed = limits;
  relaxed.max_steps = INT_MAX;
  relaxed.max_frames = INT_MAX;
  relaxed.max_ranks_per_job = scene::max_ranks;  // the rule below is stricter: one rank
  try {
    scene::Summary summary = check_scene(body["scene"], relaxed, mesh_files, &resolved);
    // Every run of a study is a call in the study's one process (study::run), not a process of its own.
    if (summary.ranks > 1)
      add(errors, "/scene/solver/ranks",
          "must be 1: a study runs its runs on one rank, got " + std::to_string(summary.ranks));
    return summary;
  } catch (const ProblemError& e) {
    if (e.problem().status != 422) throw;
    for (const auto& error : e.problem().extra.value("errors", nlohmann::json::array()))
      add(errors, "/scene" + error.value("pointer", ""), error.value("message", ""));
  }
  return {};
}

Problem invalid_study(nlohmann::json errors) {
  const std::size_t n = errors.size();
  std::string detail = n == 1 ? "the study has 1 error" : "the study has " + std::to_string(n) + " errors";
  const std::string pointer = errors[0].value("pointer", "");
  detail +=
      ", the first: " + (pointer.empty() ? "the study " : pointer + ": ") + errors[0].value("message", "");
  return {422, "urn:stoss:problem:invalid-study", "Invalid study", detail, {{"errors", std::move(errors)}}};
}

/// The smallest step a tolerance run of the study may take: the scene's time.min_step when the scene has a
/// tolerance of its own, else its default time.step / 1024 (study::run keeps the one, sets the other).
double tolerance_min_step(const nlohmann::json& time) {
  if (time.contains("tolerance") && time.value("min_step", 0.0) > 0) return time["min_step"].get<double>();
  return time.value("step", 0.0) / 1024;
}

/// The study's run with the most time steps: its name for a message and its step (a bound for a tolerance
/// run).
struct FinestRun {
  std::string name;
  double step = 0;
};

FinestRun finest_run(const study::Options& options, const nlohmann::json& time) {
  const double finest_swept = *std::min_element(options.steps.begin(), options.steps.end());
  FinestRun finest = options.reference_step <= finest_swept
                         ? FinestRun{"the reference run", options.reference_step}
                         : FinestRun{"the run", finest_swept};
  const double min_step = tolerance_min_step(time);
  if (!options.tolerances.empty() && min_step > 0 && min_step < finest.step)
    finest = {"a tolerance run at its min_step", min_step};
  return finest;
}

/// 413 when the finest run of the study needs more than max_steps time steps (a tolerance run: end/min_step,
/// as for a scene with time.tolerance).
void check_run_limit(const study::Options& options, const nlohmann::json& time, const Limits& limits) {
  const FinestRun finest = finest_run(options, time);
  const long long value = model::step_count(time.value("end", 0.0), finest.step);
  if (value <= limits.max_steps) return;
  throw ProblemError(
      Problem{413,
              "urn:stoss:problem:limit-exceeded",
              "Study exceeds a server limit",
              "the study's finest run (" + finest.name + ", h = " + format_step(finest.step) + ") has " +
                  std::to_string(value) +
                  " time steps, more than the server limit max_steps = " + std::to_string(limits.max_steps),
              {{"limits", {{{"name", "max_steps"}, {"limit", limits.max_steps}, {"value", value}}}}}});
}

}  // namespace

StudyRequest check_study(const nlohmann::json& body, const Limits& limits,
                         const scene::MeshFiles& mesh_files) {
  if (!body.is_object()) {
    nlohmann::json errors = nlohmann::json::array();
    add(errors, "", "must be an object {\"scene\": {...}, \"steps\": [...]}, got " + describe(body));
    throw ProblemError(invalid_study(std::move(errors)));
  }
  nlohmann::json errors = nlohmann::json::array();
  check_members(body, errors);
  StudyRequest request;
  request.options.steps = check_steps(body, errors);
  request.options.tolerances = check_tolerances(body, errors);
  request.options.schemes = check_schemes(body, errors);
  request.options.reference_step = check_reference(body, errors);
  request.options.repeat = check_repeat(body, errors);
  request.summary = check_study_scene(body, limits, mesh_files, request.scene, errors);
  if (!errors.empty()) throw ProblemError(invalid_study(std::move(errors)));
  if (request.options.reference_step == 0)
    request.options.reference_step =
        *std::min_element(request.options.steps.begin(), request.options.steps.end()) / 32;
  check_run_limit(request.options, request.scene.value("time", nlohmann::json::object()), limits);
  request.runs = study::run_count(request.options);
  return request;
}

}  // namespace stoss::server::http
