#pragma once
/// @file The wire protocol between a worker (ProcessExecutor, the parent) and the process of one job attempt
/// (`stoss run-job`, the child; job_process.hpp). The parent writes the job to job.json in the attempt's
/// folder; the child writes one JSON line {"progress": …} per progress report to descriptor progress_fd and,
/// last, how the attempt ended to outcome.json (outcome_file_name, job_files.hpp); process.pid names the
/// child while it runs.

#include <filesystem>
#include <optional>
#include <string>

#include "server/jobs/job.hpp"

namespace stoss::server::jobs {

inline constexpr const char* job_request_file = "job.json";  ///< what the child runs
inline constexpr const char* job_pid_file = "process.pid";   ///< the child's pid while it runs
/// Written by the parent to cancel a job on several ranks: rank 0 looks for it (job_process.hpp).
inline constexpr const char* cancel_file = "cancel";
/// The child writes one JSON line per progress report to this descriptor.
inline constexpr int progress_fd = 3;

/// A job as the child reads it (id, kind, attempt, worker, scene, study), and back.
nlohmann::json job_request_json(const Job& job);
Job job_from_request(const nlohmann::json& request);
/// Writes `job` to DIR/job.json durably (the parent, before the spawn), and reads it back (the child).
void write_job_request(const std::filesystem::path& attempt_dir, const Job& job);
Job read_job_request(const std::filesystem::path& attempt_dir);

/// One progress report as the child writes it: a JSON line ending in '\n'.
std::string progress_line(const Progress& progress);
/// The progress a line (without its '\n') reports; nullopt for a torn or foreign line.
std::optional<Progress> progress_from_line(const std::string& line);

}  // namespace stoss::server::jobs
