#pragma once
/// @file Flags shared by the subcommands that run jobs (`stoss serve`, `stoss worker`): the parsing of
/// `--flag value` and `--flag=value`, the numbers and durations, and RunnerFlags, what a process's job
/// runner needs (--data, --store, --workers, --lease-seconds, --renew-seconds, --max-attempts,
/// --job-timeout, --job-memory, --ranks-per-job, --launcher).

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "server/jobs/running/job_runner.hpp"
#include "server/jobs/store/open_store.hpp"

namespace stoss::cli {

/// A command line a subcommand cannot work with; the message says which flag and why.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An integer in [min, max]; throws UsageError naming `flag`.
long long parse_integer(const std::string& flag, const std::string& text, long long min, long long max);
/// Seconds in [0.01, 86400] as milliseconds; throws UsageError naming `flag`.
server::jobs::Millis parse_seconds(const std::string& flag, const std::string& text);

/// What runs jobs in a process, as the flags set it.
struct RunnerFlags {
  std::filesystem::path data = "var";                ///< --data DIR: jobs.db and jobs/<id>/
  std::optional<server::jobs::StoreLocation> store;  ///< --store; unset: sqlite:DATA/jobs.db
  server::jobs::WorkerPoolOptions pool;  ///< --workers, --lease-seconds, --renew-seconds, --ranks-per-job
  int max_attempts = 3;                  ///< --max-attempts: runs before an expired lease fails a job
  server::jobs::Millis job_timeout = 0;  ///< --job-timeout: wall-time limit of one job attempt (0: none)
  std::size_t job_memory = 0;            ///< --job-memory: address-space limit of a job's process (0: none)
  std::string launcher;                  ///< --launcher: starts a job's ranks (empty: the default mpiexec)
};

/// How one flag sets its value in `Options`.
template <typename Options>
using FlagSetter = std::function<void(const std::string& flag, const std::string& value, Options& o)>;
template <typename Options>
using FlagTable = std::map<std::string, FlagSetter<Options>>;

/// The flags of RunnerFlags.
const FlagTable<RunnerFlags>& runner_flags();

/// `own` and the flags of RunnerFlags, for options that derive from it.
template <typename Options>
FlagTable<Options> with_runner_flags(FlagTable<Options> own) {
  for (const auto& [name, set] : runner_flags()) own.emplace(name, set);
  return own;
}

/// Sets `options` from `args` ("--flag value" or "--flag=value", each flag from `table`).
/// Throws UsageError for an unknown flag or one without a value.
template <typename Options>
void parse_flags(const std::vector<std::string>& args, const FlagTable<Options>& table, Options& options) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string flag = args[i], value;
    const auto equals = flag.find('=');
    const bool inline_value = equals != std::string::npos;
    if (inline_value) value = flag.substr(equals + 1), flag = flag.substr(0, equals);
    const auto setter = table.find(flag);
    if (setter == table.end()) throw UsageError("unknown option '" + flag + "'");
    if (!inline_value) {
      if (i + 1 >= args.size()) throw UsageError(flag + " needs a value");
      value = args[++i];
    }
    setter->second(flag, value, options);
  }
}

/// The checks across flags of RunnerFlags (renewal shorter than the lease). Throws UsageError.
void check_runner_flags(const RunnerFlags& flags);

/// The store the flags name: --store, or sqlite:DATA/jobs.db.
server::jobs::StoreLocation store_location(const RunnerFlags& flags);

/// What a process's job runner needs of the flags.
server::jobs::JobRunnerOptions job_runner_options(const RunnerFlags& flags,
                                                  const server::jobs::StoreLocation& location);

/// The usage lines of the lease flags, --job-memory and --ranks-per-job, the same for serve and worker.
const char* runner_flags_usage();

/// Runs `stoss <name>` (serve, worker): `--help` prints `usage` (exit 0); otherwise the exit code of `run`,
/// or 2 after a UsageError (its message, then `usage`) or a store that cannot be opened, 1 after any other
/// error, each printed as "stoss <name>: <what>".
int run_subcommand(const std::string& name, const std::vector<std::string>& args, const std::string& usage,
                   const std::function<int()>& run);

}  // namespace stoss::cli
