#include "server/http/options.hpp"

#include <cmath>
#include <functional>
#include <map>
#include <set>

namespace stoss::server::http {

namespace {

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

void parse_listen(const std::string& text, ServeOptions& o) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0)
    throw UsageError("--listen needs HOST:PORT, got '" + text + "'");
  o.host = text.substr(0, colon);
  o.port = static_cast<int>(parse_integer("--listen port", text.substr(colon + 1), 0, 65535));
}

jobs::StoreLocation parse_store(const std::string& text) {
  try {
    return jobs::parse_store_location(text);
  } catch (const jobs::StoreError& e) {
    throw UsageError(e.what());
  }
}

using Setter = std::function<void(const std::string& flag, const std::string& value, ServeOptions& o)>;

const std::map<std::string, Setter>& setters() {
  static const std::map<std::string, Setter> table = {
      {"--listen", [](auto&, auto& v, auto& o) { parse_listen(v, o); }},
      {"--data", [](auto&, auto& v, auto& o) { o.data = v; }},
      {"--store", [](auto&, auto& v, auto& o) { o.store = parse_store(v); }},
      {"--token-file", [](auto&, auto& v, auto& o) { o.token_file = v; }},
      {"--workers", [](auto& f, auto& v, auto& o) { o.pool.workers = int(parse_integer(f, v, 0, 256)); }},
      {"--lease-seconds", [](auto& f, auto& v, auto& o) { o.pool.lease = parse_seconds(f, v); }},
      {"--renew-seconds", [](auto& f, auto& v, auto& o) { o.pool.renew_every = parse_seconds(f, v); }},
      {"--max-attempts",
       [](auto& f, auto& v, auto& o) { o.max_attempts = int(parse_integer(f, v, 1, 100)); }},
      {"--max-body-bytes",
       [](auto& f, auto& v, auto& o) {
         o.limits.max_body_bytes = std::size_t(parse_integer(f, v, 1, 1ll << 34));
       }},
      {"--max-nodes",
       [](auto& f, auto& v, auto& o) { o.limits.max_nodes = int(parse_integer(f, v, 1, 1'000'000'000)); }},
      {"--max-steps",
       [](auto& f, auto& v, auto& o) { o.limits.max_steps = int(parse_integer(f, v, 1, 1'000'000'000)); }},
      {"--max-frames",
       [](auto& f, auto& v, auto& o) { o.limits.max_frames = int(parse_integer(f, v, 1, 1'000'000'000)); }},
      {"--http-threads",
       [](auto& f, auto& v, auto& o) { o.http_threads = int(parse_integer(f, v, 4, 4096)); }},
      {"--max-connections-per-client",
       [](auto& f, auto& v, auto& o) { o.max_connections_per_client = int(parse_integer(f, v, 1, 1'000'000)); }},
      {"--read-timeout", [](auto& f, auto& v, auto& o) { o.read_timeout = parse_seconds(f, v); }},
      {"--request-timeout",
       [](auto& f, auto& v, auto& o) {
         o.limits.request_timeout = std::chrono::milliseconds(parse_seconds(f, v));
       }},
      {"--job-timeout",
       [](auto& f, auto& v, auto& o) {
         o.job_timeout = v == "0" ? 0 : parse_seconds(f, v);
       }},
      {"--job-memory",
       [](auto& f, auto& v, auto& o) { o.job_memory = std::size_t(parse_integer(f, v, 0, 1ll << 50)); }},
      {"--max-queue",
       [](auto& f, auto& v, auto& o) { o.limits.max_queued = int(parse_integer(f, v, 0, 1'000'000'000)); }},
      {"--max-mesh-store-bytes",
       [](auto& f, auto& v, auto& o) {
         o.limits.max_mesh_store_bytes = std::size_t(parse_integer(f, v, 0, 1ll << 50));
       }},
  };
  return table;
}

/// The flags `stoss worker` takes (a subset of serve's).
bool is_worker_flag(const std::string& flag) {
  static const std::set<std::string> flags = {"--store",          "--data",         "--workers",
                                              "--lease-seconds",  "--renew-seconds", "--max-attempts",
                                              "--job-timeout",    "--job-memory"};
  return flags.count(flag) > 0;
}

ServeOptions parse_options(const std::vector<std::string>& args, bool worker) {
  ServeOptions options;
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string flag = args[i], value;
    const auto equals = flag.find('=');
    const bool inline_value = equals != std::string::npos;
    if (inline_value) value = flag.substr(equals + 1), flag = flag.substr(0, equals);
    auto setter = setters().find(flag);
    if (setter == setters().end() || (worker && !is_worker_flag(flag)))
      throw UsageError("unknown option '" + flag + "'");
    if (!inline_value) {
      if (i + 1 >= args.size()) throw UsageError(flag + " needs a value");
      value = args[++i];
    }
    setter->second(flag, value, options);
  }
  if (options.pool.renew_every >= options.pool.lease)
    throw UsageError("--renew-seconds must be shorter than --lease-seconds");
  if (worker && options.pool.workers == 0)
    throw UsageError("--workers needs an integer in [1, 256], got '0'");
  return options;
}

}  // namespace

ServeOptions parse_serve_options(const std::vector<std::string>& args) {
  return parse_options(args, false);
}

ServeOptions parse_worker_options(const std::vector<std::string>& args) {
  return parse_options(args, true);
}

jobs::StoreLocation store_location(const ServeOptions& options) {
  return options.store ? *options.store : jobs::default_store_location(options.data);
}

jobs::JobRunnerOptions job_runner_options(const ServeOptions& options, const jobs::StoreLocation& location) {
  return {options.data, location, {options.job_timeout, options.job_memory}, options.pool, options.max_attempts};
}

std::string serve_usage() {
  return R"(usage: stoss serve [options]

Runs the job service (HTTP/JSON, see api/openapi.yaml) until SIGINT or SIGTERM.

  --listen HOST:PORT     address to bind (default 127.0.0.1:8080; port 0 picks a free one)
  --data DIR             job database (DIR/jobs.db) and results (DIR/jobs/<id>/) (default ./var)
  --store STORE          the job store: sqlite:PATH (default sqlite:DIR/jobs.db) or
                         postgresql://USER[:PASSWORD]@HOST:PORT/DB, shared by many serve and worker
                         processes on many hosts (they must share DIR too; see docs/many_machines.md)
  --workers N            jobs run at once in this process (default 2; 0 only queues: an API-only front end)
  --token-file F         require "Authorization: Bearer <first line of F>" on every route but /healthz
  --max-body-bytes N     largest request body (default 16777216)
  --max-nodes N          most mesh nodes in a scene (default 200000)
  --max-steps N          most time steps in a scene (default 100000)
  --max-frames N         most output frames in a scene (default 2000)
  --max-queue N          most queued jobs; more submissions get 503 (default 1000)
  --max-mesh-store-bytes N
                         bytes of all meshes POST /v1/meshes stores; an upload beyond is 413 (default
                         1073741824; DELETE /v1/meshes/{id} frees room)
  --http-threads N       HTTP connections served at once, one thread each (default 128)
  --max-connections-per-client N
                         connections one client address may hold at once; more are answered 503 and
                         closed (default 64)
  --read-timeout S       longest wait for the next bytes of a request's head or body (default 5)
  --request-timeout S    longest time from a request's head to the last byte of its body; a slower
                         upload is answered 408 and closed (default 60)
  --job-timeout S        wall-time limit of one job attempt; 0: none (default 0); a scene may set a
                         lower one in solver.max_wall_seconds
  --job-memory BYTES     address-space limit (RLIMIT_AS) of a job's process; 0: none (default 0)
  --lease-seconds S      a running job's lease; a job whose worker died reruns after it (default 10)
  --renew-seconds S      lease renewal interval (default 2)
  --max-attempts N       runs a job may start before an expired lease fails it (default 3)
)";
}

std::string worker_usage() {
  return R"(usage: stoss worker --store STORE [options]

Runs queued jobs without HTTP until SIGINT or SIGTERM (then gives running jobs back to the queue).
API processes (`stoss serve`, possibly with --workers 0) queue the jobs; every process shares the store
and the data directory.

  --store STORE          postgresql://USER[:PASSWORD]@HOST:PORT/DB (libpq's PG* variables and PGPASSFILE
                         fill what the URL leaves out) or sqlite:PATH (default sqlite:DIR/jobs.db)
  --data DIR             results and logs (DIR/jobs/<id>/), shared with the API processes (default ./var)
  --workers N            jobs run at once in this process (default 2)
  --job-timeout S        wall-time limit of one job attempt; 0: none (default 0)
  --job-memory BYTES     address-space limit (RLIMIT_AS) of a job's process; 0: none (default 0)
  --lease-seconds S      a running job's lease; a job whose worker died reruns after it (default 10)
  --renew-seconds S      lease renewal interval (default 2)
  --max-attempts N       runs a job may start before an expired lease fails it (default 3)
)";
}

}  // namespace stoss::server::http
