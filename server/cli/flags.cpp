#include "server/cli/flags.hpp"

#include <cmath>
#include <iostream>

#include "core/scene/scene.hpp"
#include "server/jobs/running/launcher.hpp"

namespace stoss::cli {

namespace jobs = server::jobs;

long long parse_integer(const std::string& flag, const std::string& text, long long min, long long max) {
  std::size_t used = 0;
  long long value = 0;
  try {
    value = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || value < min || value > max)
    throw UsageError(flag + " needs an integer in [" + std::to_string(min) + ", " + std::to_string(max) +
                     "], got '" + text + "'");
  return value;
}

jobs::Millis parse_seconds(const std::string& flag, const std::string& text) {
  std::size_t used = 0;
  double seconds = 0;
  try {
    seconds = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || !(seconds >= 0.01 && seconds <= 86400))
    throw UsageError(flag + " needs seconds in [0.01, 86400], got '" + text + "'");
  return static_cast<jobs::Millis>(std::llround(seconds * 1000));
}

namespace {

jobs::StoreLocation parse_store(const std::string& text) {
  try {
    return jobs::parse_store_location(text);
  } catch (const jobs::StoreError& e) {
    throw UsageError(e.what());
  }
}

}  // namespace

const FlagTable<RunnerFlags>& runner_flags() {
  static const FlagTable<RunnerFlags> table = {
      {"--data", [](auto&, auto& v, auto& o) { o.data = v; }},
      {"--store", [](auto&, auto& v, auto& o) { o.store = parse_store(v); }},
      {"--workers", [](auto& f, auto& v, auto& o) { o.pool.workers = int(parse_integer(f, v, 0, 256)); }},
      {"--lease-seconds", [](auto& f, auto& v, auto& o) { o.pool.lease = parse_seconds(f, v); }},
      {"--renew-seconds", [](auto& f, auto& v, auto& o) { o.pool.renew_every = parse_seconds(f, v); }},
      {"--ranks-per-job",
       [](auto& f, auto& v, auto& o) {
         o.pool.ranks_per_job = int(parse_integer(f, v, 1, scene::max_ranks));
       }},
      {"--launcher",
       [](auto&, auto& v, auto& o) {
         if (const auto problem = jobs::launcher_problem(v)) throw UsageError(*problem);
         o.launcher = v;
       }},
      {"--max-attempts",
       [](auto& f, auto& v, auto& o) { o.max_attempts = int(parse_integer(f, v, 1, 100)); }},
      {"--job-timeout",
       [](auto& f, auto& v, auto& o) { o.job_timeout = v == "0" ? 0 : parse_seconds(f, v); }},
      {"--job-memory",
       [](auto& f, auto& v, auto& o) { o.job_memory = std::size_t(parse_integer(f, v, 0, 1ll << 50)); }},
  };
  return table;
}

void check_runner_flags(const RunnerFlags& flags) {
  if (flags.pool.renew_every >= flags.pool.lease)
    throw UsageError("--renew-seconds must be shorter than --lease-seconds");
}

jobs::StoreLocation store_location(const RunnerFlags& flags) {
  return flags.store ? *flags.store : jobs::default_store_location(flags.data);
}

jobs::JobRunnerOptions job_runner_options(const RunnerFlags& flags, const jobs::StoreLocation& location) {
  jobs::ProcessLimits limits{flags.job_timeout, flags.job_memory};
  limits.launcher = flags.launcher;
  return {flags.data, location, limits, flags.pool, flags.max_attempts};
}

const char* runner_flags_usage() {
  return R"(  --job-memory BYTES     address-space limit (RLIMIT_AS) of a job's process; 0: none (default 0)
  --lease-seconds S      a running job's lease; a job whose worker died reruns after it (default 10)
  --renew-seconds S      lease renewal interval (default 2)
  --max-attempts N       runs a job may start before an expired lease fails it (default 3)
  --ranks-per-job N      MPI ranks one job may use here: only jobs whose scene's solver.ranks is at most
                         N are claimed, bigger ones wait for a worker started with more (default 1)
  --launcher TEMPLATE    starts a job's ranks: {ranks} becomes their number, the rank's command goes last
                         (default "mpiexec -n {ranks} --use-hwthread-cpus --bind-to none", with
                         --allow-run-as-root as root; on Slurm
                         "srun --mpi=pmix -n {ranks} --kill-on-bad-exit=1 …")
)";
}

int run_subcommand(const std::string& name, const std::vector<std::string>& args, const std::string& usage,
                   const std::function<int()>& run) {
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
    std::cout << usage;
    return 0;
  }
  try {
    return run();
  } catch (const UsageError& e) {
    std::cerr << "stoss " << name << ": " << e.what() << "\n\n" << usage;
    return 2;
  } catch (const jobs::StoreOpenError& e) {
    std::cerr << "stoss " << name << ": " << e.what() << std::endl;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "stoss " << name << ": " << e.what() << std::endl;
    return 1;
  }
}

}  // namespace stoss::cli
