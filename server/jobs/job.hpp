#pragma once
/// @file Job: one submitted scene and everything the queue knows about it.

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "server/jobs/clock.hpp"
#include "server/jobs/id.hpp"

namespace stoss::server::jobs {

/// Life cycle: queued → running → succeeded | failed | canceled (running → queued again when a lease
/// expires).
enum class Status { queued, running, succeeded, failed, canceled };

inline constexpr Status all_statuses[] = {Status::queued, Status::running, Status::succeeded, Status::failed,
                                          Status::canceled};

std::string to_string(Status s);
/// The status named `text`, or nullopt.
std::optional<Status> parse_status(std::string_view text);
/// succeeded, failed and canceled: nothing will happen to the job any more.
bool is_terminal(Status s);

/// What a job runs: one simulation of its scene, or a study (a sweep of schemes × step sizes against a
/// fine reference run, core/study).
enum class Kind { simulation, study };

std::string to_string(Kind k);
/// The kind named `text`, or nullopt.
std::optional<Kind> parse_kind(std::string_view text);

/// How far a run has come (docs/api.md `progress`). For a study, `step`/`steps` count runs.
struct Progress {
  int step = 0;                       ///< converged steps so far
  int steps = 0;                      ///< steps to reach `end`
  double time = 0;                    ///< simulated time reached
  double end = 0;                     ///< simulated end time
  std::optional<double> eta_seconds;  ///< wall seconds still to go, once it can be estimated
};

nlohmann::json to_json(const Progress& p);
Progress progress_from_json(const nlohmann::json& j);

/// A job as the store holds it.
struct Job {
  std::int64_t seq = 0;  ///< insertion order (the list cursor); not shown as an id
  JobId id = JobId::random();
  Kind kind = Kind::simulation;
  Status status = Status::queued;
  Millis created = 0;
  std::optional<Millis> started;  ///< start of the latest attempt
  std::optional<Millis> finished;
  int attempt = 0;                    ///< number of claims so far
  std::optional<std::string> worker;  ///< the worker holding the lease while running
  std::optional<Millis> lease_expires;
  bool cancel_requested = false;
  std::optional<std::string> idempotency_key;
  std::string body_hash;             ///< SHA-256 (hex) of the canonical scene JSON
  nlohmann::json scene;              ///< the scene as submitted (only set for a claimed job)
  std::optional<std::string> name;   ///< the scene's `name`, when it has one
  std::vector<std::string> effects;  ///< resolved at submission
  Progress progress;
  std::optional<nlohmann::json> summary;  ///< set when the run ended (also for canceled runs)
  std::optional<std::string> error;       ///< set when failed
  /// Set when the run ended: the attempt whose folder (DIR/jobs/<id>/attempt-<n>/) holds the job's files,
  /// the result GET /v1/jobs/{id}/result serves. Unset for jobs that ended before attempts had folders.
  std::optional<int> result_attempt;
  /// A study's parameters as accepted (steps, schemes, reference_step, defaults filled in); unset for a
  /// simulation.
  std::optional<nlohmann::json> study;
  /// The MPI ranks the run asks for: its scene's solver.ranks, 1 when the scene does not say. Only a worker
  /// started with --ranks-per-job at least this claims the job.
  int ranks = 1;
};

}  // namespace stoss::server::jobs
