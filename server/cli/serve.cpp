#include "server/cli/serve.hpp"

#include <iostream>

#include "core/scene/scene.hpp"
#include "server/common/stop_signals.hpp"

namespace stoss::cli {

namespace {

namespace jobs = server::jobs;

void parse_listen(const std::string& text, ServeOptions& o) {
  const auto colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0)
    throw UsageError("--listen needs HOST:PORT, got '" + text + "'");
  o.host = text.substr(0, colon);
  o.port = static_cast<int>(parse_integer("--listen port", text.substr(colon + 1), 0, 65535));
}

/// The flags only `stoss serve` has.
FlagTable<ServeOptions> http_flags() {
  return {
      {"--listen", [](auto&, auto& v, auto& o) { parse_listen(v, o); }},
      {"--token-file", [](auto&, auto& v, auto& o) { o.token_file = v; }},
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
      {"--max-ranks-per-job",
       [](auto& f, auto& v, auto& o) {
         o.limits.max_ranks_per_job = int(parse_integer(f, v, 1, scene::max_ranks));
       }},
      {"--http-threads",
       [](auto& f, auto& v, auto& o) { o.http_threads = int(parse_integer(f, v, 4, 4096)); }},
      {"--max-connections-per-client",
       [](auto& f, auto& v, auto& o) {
         o.max_connections_per_client = int(parse_integer(f, v, 1, 1'000'000));
       }},
      {"--read-timeout", [](auto& f, auto& v, auto& o) { o.read_timeout = parse_seconds(f, v); }},
      {"--request-timeout",
       [](auto& f, auto& v, auto& o) {
         o.limits.request_timeout = std::chrono::milliseconds(parse_seconds(f, v));
       }},
      {"--max-queue",
       [](auto& f, auto& v, auto& o) { o.limits.max_queued = int(parse_integer(f, v, 0, 1'000'000'000)); }},
      {"--max-mesh-store-bytes",
       [](auto& f, auto& v, auto& o) {
         o.limits.max_mesh_store_bytes = std::size_t(parse_integer(f, v, 0, 1ll << 50));
       }},
  };
}

int run(const ServeOptions& options) {
  server::StopSignals signals;  // before any thread
  jobs::SystemClock clock;
  const jobs::StoreLocation location = store_location(options);
  jobs::JobRunner runner(job_runner_options(options, location), clock);
  server::http::serve_http(options, runner, signals, [&](int port) {
    runner.start();
    std::cout << "stoss serve: listening on http://" << options.host << ":" << port << " (data "
              << options.data.string() << (options.store ? ", store " + location.describe() : std::string())
              << ", " << options.pool.workers << " workers)" << std::endl;
  });
  runner.stop();
  std::cout << "stoss serve: stopped" << std::endl;
  return 0;
}

}  // namespace

ServeOptions parse_serve_options(const std::vector<std::string>& args) {
  static const FlagTable<ServeOptions> table = with_runner_flags(http_flags());
  ServeOptions options;
  parse_flags(args, table, options);
  check_runner_flags(options);
  return options;
}

std::string serve_usage() {
  return std::string(R"(usage: stoss serve [options]

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
  --max-ranks-per-job N  most MPI ranks a scene may ask for (solver.ranks); more is 422 (default 1)
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
)") + runner_flags_usage();
}

int serve_command(const std::vector<std::string>& args) {
  return run_subcommand("serve", args, serve_usage(), [&] {
    try {
      return run(parse_serve_options(args));
    } catch (const server::http::AddressInUse& e) {  // not a second listener: exit 2
      std::cerr << "stoss serve: " << e.what() << std::endl;
      return 2;
    }
  });
}

}  // namespace stoss::cli
