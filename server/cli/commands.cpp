#include "server/cli/commands.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "core/output/durable_file.hpp"
#include "core/output/result_writer.hpp"
#include "core/parallel/mpi_place.hpp"
#include "core/parallel/worker_threads.hpp"
#include "core/run/ranks.hpp"
#include "core/scene/scene.hpp"
#include "core/scene/warnings.hpp"
#include "core/simulate.hpp"
#include "core/study/study.hpp"
#include "server/cli/progress.hpp"
#include "server/cli/ranks.hpp"
#include "server/common/json_input.hpp"
#include "server/jobs/store/store.hpp"

namespace stoss::cli {
namespace {

void print_scene_error(const scene::SceneError& e) {
  std::cerr << "invalid scene:\n";
  for (const scene::Issue& i : e.issues)
    std::cerr << "  " << (i.pointer.empty() ? "" : i.pointer + ": ") << i.message << "\n";
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : " ") + s;
  return out;
}

void print_summary(const model::Model& m, const model::Summary& s) {
  std::printf("steps %d, t = %.6g\n", s.steps, s.end_time);
  // Loads or prescribed motion, the scenes with series/external_work (core/run/series_table.cpp): H − W_ext
  const bool external = m.has_external_work();
  if (external) std::printf("external work %.6e (W_ext, series/external_work at the end)\n", s.external_work);
  if (m.time.scheme == model::Scheme::equilibrium)  // equilibria at load levels keep no energy between them
    std::printf("energy drift: not reported (static load steps)\n");
  else if (external)
    std::printf("energy drift %.3e (H − W_ext, relative, max over steps)\n", s.energy_drift);
  else
    std::printf("energy drift %.3e (relative, max over steps)\n", s.energy_drift);
  if (model::has_check(s, "linear_momentum_drift"))  // the system is free
    std::printf("momentum drift: linear %.3e, angular %.3e\n", s.linear_momentum_drift,
                s.angular_momentum_drift);
  else
    std::printf("momentum drift: not reported (supports or gravity act: the system is not free)\n");
  if (!m.contact.empty())
    std::printf("max penetration %.3e (closest master face), %.3e (own face)\n", s.max_penetration,
                s.max_own_face_penetration);
  std::printf("newton iterations %d (%.2f per step)\n", s.newton_iterations, s.newton_iterations_per_step);
  std::printf("wall %.3f s (linear solver %.3f s)\n", s.wall_seconds, s.linear_solver_seconds);
  const double other = std::max(0.0, s.wall_seconds - s.assembly_seconds - s.contact_seconds -
                                         s.linear_solver_seconds - s.output_seconds);
  std::printf(
      "time: assembly %.3f s, contact %.3f s, linear solver %.3f s (factorisation %.3f s, solves %.3f s), "
      "output "
      "%.3f s, other %.3f s\n",
      s.assembly_seconds, s.contact_seconds, s.linear_solver_seconds, s.linear_factorization_seconds,
      s.linear_solve_seconds, s.output_seconds, other);
  if (const int ranks = parallel::mpi_place().size; ranks > 1)
    std::printf("peak memory %.1f MB (resident, the sum over %d MPI ranks)\n", s.peak_memory_bytes / 1e6,
                ranks);
  else
    std::printf("peak memory %.1f MB (resident)\n", s.peak_memory_bytes / 1e6);
  if (s.krylov_iterations_per_solve > 0)
    std::printf("krylov iterations %.1f per solve (%d fell back to LU)\n", s.krylov_iterations_per_solve,
                s.krylov_fallbacks);
}

/// The verdict and, when a check failed, the warning block (docs/command_line.md, "stoss run").
void print_verdict(const model::Summary& s) {
  for (const model::Check& c : s.checks)
    std::printf("check %s: %.3e (bound %.3e) %s\n", c.name.c_str(), c.value, c.bound,
                c.passed ? "passed" : "FAILED");
  std::printf("verdict: %s\n", s.verdict.c_str());
  if (s.verdict != "suspect") return;
  std::printf("warning: the result is suspect; failed checks:\n");
  for (const model::Check& c : s.checks)
    if (!c.passed)
      std::printf("  %s = %.3e exceeds %.3e (docs/results.md, \"Verdict\")\n", c.name.c_str(), c.value,
                  c.bound);
}

/// The scales, the choices loading made and the warnings of `stoss validate` (docs/command_line.md).
void print_before_run(const scene::Summary& s) {
  // A static step is a load increment: it resolves no wave and no mode, so neither scale applies to it.
  const bool statics = std::find(s.effects.begin(), s.effects.end(), "static") != s.effects.end();
  for (const scene::BodyScale& b : s.estimates.bodies)
    if (statics)
      std::printf("body %s: wave speed %.3g, smallest element %.3g (static load steps: no Courant number)\n",
                  b.name.c_str(), b.dilatational_speed, b.smallest_element);
    else
      std::printf(
          "body %s: wave speed %.3g, smallest element %.3g, Courant number %.3g, lowest period ~%.3g\n",
          b.name.c_str(), b.dilatational_speed, b.smallest_element, b.courant, b.lowest_period);
  for (const scene::PairScale& p : s.estimates.pairs)
    std::printf("contact %s on %s: approach speed %.3g, contact lasts ~%.3g (Hertz %.3g, wave %.3g)\n",
                p.slave.c_str(), p.master.c_str(), p.approach_speed, p.duration, p.hertz_duration,
                p.wave_duration);
  for (const scene::ResolvedChoice& c : s.choices)
    std::printf("%s: %s (%s)\n", c.pointer.c_str(), c.value.c_str(), c.reason.c_str());
  std::printf("estimated run time %.3g s\n", s.estimates.wall_seconds);
  if (!s.warnings.empty())
    std::printf("%zu warning%s:\n", s.warnings.size(), s.warnings.size() == 1 ? "" : "s");
  for (const scene::Warning& w : s.warnings)
    std::printf("  warning %s: %s: %s\n", w.code.c_str(), w.pointer.c_str(), w.message.c_str());
}

int usage(const char* text) {
  std::cerr << "usage: " << text << "\n";
  return invalid_scene;
}

bool wants_help(const std::vector<std::string>& args) {
  for (const auto& a : args)
    if (a == "--help" || a == "-h") return true;
  return false;
}

/// Checks that `path` holds usable JSON before the core reads it: nesting within server::max_json_depth,
/// numbers within the range of double, valid syntax. Throws scene::SceneError (pointer "") when not.
void precheck_scene_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return;  // load_file reports an unreadable file
  const std::string text{std::istreambuf_iterator<char>(in), {}};
  try {
    server::parse_json_input(text);
  } catch (const server::JsonInputError& e) {
    throw scene::SceneError(std::vector<scene::Issue>{{"", e.what()}});
  }
}

}  // namespace

namespace {

namespace fs = std::filesystem;

/// DIR/checkpoint/run.json: what `stoss run --resume DIR` needs besides the checkpoint, the resolved scene
/// and the directory its mesh files are read from.
fs::path run_file(const fs::path& out_dir) {
  return out_dir / output::checkpoint_directory_name / "run.json";
}

void write_run_file(const fs::path& out_dir, const model::Model& model, const std::string& scene_path) {
  const fs::path path = run_file(out_dir);
  fs::create_directories(path.parent_path());
  const nlohmann::json run = {{"scene", model.scene},
                              {"mesh_directory", fs::absolute(fs::path(scene_path)).parent_path().string()}};
  output::write_durably(path, run.dump());  // a crash right after the first checkpoint can still resume
}

/// The model of the run that wrote DIR's checkpoint. @throws std::invalid_argument when DIR has none.
model::Model resumed_model(const fs::path& out_dir) {
  std::ifstream in(run_file(out_dir), std::ios::binary);
  if (!in)
    throw std::invalid_argument(out_dir.string() + " holds no checkpoint of stoss run (" +
                                run_file(out_dir).string() + " is missing)");
  const nlohmann::json run = nlohmann::json::parse(in);
  scene::MeshFiles files;
  files.directory = fs::path(run.at("mesh_directory").get<std::string>());
  return scene::load_resolved(run.at("scene"), files);
}

/// The ranks the scene of a run asks for (solver.ranks; 1 when absent), read from the scene file or, with
/// --resume, from DIR's run file; 1 when either cannot be read (the run reports why itself).
int scene_ranks(const std::string& scene_path, const std::optional<fs::path>& resumed_dir) {
  try {
    std::ifstream in(resumed_dir ? run_file(*resumed_dir) : fs::path(scene_path), std::ios::binary);
    const nlohmann::json file = nlohmann::json::parse(in);
    return server::jobs::scene_ranks(resumed_dir ? file.at("scene") : file);
  } catch (const std::exception&) {
    return 1;
  }
}

/// The command line of `stoss run`.
struct RunOptions {
  std::string scene_path;
  std::string out_dir = "out";
  bool resume = false, out_given = false, strict = false;
  std::optional<int> ranks;  ///< --ranks N (server/cli/ranks.hpp)
};

/// nullopt when `args` is not a command line of `stoss run`.
std::optional<RunOptions> parse_run_options(const std::vector<std::string>& args) {
  RunOptions o;
  std::string resume_dir;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i] == "--strict")
      o.strict = true;
    else if ((args[i] == "-o" || args[i] == "--output") && i + 1 < args.size())
      o.out_dir = args[++i], o.out_given = true;
    else if (args[i] == "--resume" && i + 1 < args.size())
      resume_dir = args[++i];
    else if (args[i] == "--ranks" && i + 1 < args.size()) {
      const std::string& value = args[++i];
      size_t end = 0;
      try {
        o.ranks = std::stoi(value, &end);
      } catch (const std::exception&) {
        return std::nullopt;
      }
      if (end != value.size()) return std::nullopt;
    } else if (o.scene_path.empty() && args[i].rfind("-", 0) != 0)
      o.scene_path = args[i];
    else
      return std::nullopt;
  }
  o.resume = !resume_dir.empty();
  if (o.resume == !o.scene_path.empty() || (o.resume && o.out_given)) return std::nullopt;
  if (o.resume) o.out_dir = resume_dir;
  return o;
}

/// Without -o, out/ is written only when it is absent or empty: nothing is overwritten unasked.
bool refuses_default_output(const RunOptions& o) {
  std::error_code error;
  // A rank k > 0 of a launch writes elsewhere, and rank 0 may have begun writing out/ already.
  if (parallel::mpi_place().rank > 0) return false;
  if (o.resume || o.out_given || !fs::exists(o.out_dir, error)) return false;
  if (fs::is_directory(o.out_dir, error) && fs::is_empty(o.out_dir, error)) return false;
  std::cerr << "stoss run: " << o.out_dir << "/ exists and is not empty; nothing was overwritten. Pass -o "
            << o.out_dir << " to overwrite it, or -o DIR for another directory.\n";
  return true;
}

/// Simulates (or resumes) into o.out_dir and prints the summary and the verdict; the exit code. On rank k > 0
/// of an MPI launch, into a private directory (core/run/ranks.hpp).
int simulate_into(RunOptions o) {
  const std::string given_dir = o.out_dir;  // every rank's: rank k > 0 writes elsewhere
  std::optional<stoss::run::RankRun> rank;
  try {
    rank.emplace(parallel::mpi_place(), o.out_dir, o.resume);
  } catch (const std::exception& e) {
    std::cerr << "stoss run: " << e.what() << "\n";
    return solver_failure;
  }
  const fs::path checkpoint_dir = fs::path(o.out_dir) / output::checkpoint_directory_name;
  std::error_code error;
  try {
    model::Model model;
    if (o.resume && !fs::exists(run_file(given_dir)) &&
        fs::exists(fs::path(given_dir) / output::result_file_name)) {
      std::printf("result: %s/result.h5 (the run had completed: nothing to resume)\n", given_dir.c_str());
      return success;
    }
    if (o.resume) {
      model = resumed_model(o.out_dir);
    } else {
      precheck_scene_file(o.scene_path);
      model = scene::load_file(o.scene_path);
      fs::remove_all(checkpoint_dir, error);  // a checkpoint of an earlier run in DIR
      write_run_file(o.out_dir, model, o.scene_path);
    }
    rank->prepare(model);
    // Rank 0 alone writes the result and the progress; the others keep checkpoints only (core/run/ranks.hpp).
    std::optional<output::ResultWriter> writer;
    ProgressObserver progress;
    std::vector<model::Observer*> listeners;
    if (rank->reports()) listeners = {&writer.emplace(o.out_dir), &progress};
    model::ObserverList observers(listeners);
    const model::Summary summary = simulate(model, observers, nullptr, {checkpoint_dir, true});
    fs::remove_all(checkpoint_dir, error);  // result.h5 has it all
    print_summary(model, summary);
    std::printf("result: %s/result.h5\n", o.out_dir.c_str());
    print_verdict(summary);
    return o.strict && summary.verdict == "suspect" ? suspect_result : success;
  } catch (const scene::SceneError& e) {
    print_scene_error(e);
    return invalid_scene;
  } catch (const std::invalid_argument& e) {
    std::cerr << (o.resume ? "stoss run --resume: " : "invalid scene: ") << e.what() << "\n";
    return invalid_scene;
  } catch (const nlohmann::json::exception& e) {  // a scene value the core could not take
    std::cerr << "invalid scene: " << e.what() << "\n";
    return invalid_scene;
  } catch (const SolverError& e) {
    fs::remove_all(checkpoint_dir, error);  // the same step would fail again
    std::cerr << "solver failure: " << e.what() << "\n";
    return solver_failure;
  } catch (const std::exception& e) {
    std::cerr << "solver failure: " << e.what() << "\n";
    return solver_failure;
  }
}

}  // namespace

int run_command(const std::vector<std::string>& args) {
  constexpr const char* text =
      "stoss run SCENE.json [-o DIR] [--strict] [--ranks N] | stoss run --resume DIR [--strict] [--ranks N]\n"
      "  simulates the scene; writes DIR/result.h5 and DIR/result.xdmf (DIR defaults to out/, which must\n"
      "  then be absent or empty: pass -o DIR to write into, or over, an existing directory). While it runs\n"
      "  it keeps a checkpoint in DIR/checkpoint/ (every output.checkpoint_seconds, or checkpoint_every "
      "steps);\n"
      "  --resume DIR goes on from it after a crash and writes the result the run would have written.\n"
      "  It ends with the checks and the verdict (ok or suspect); --strict exits 3 on a suspect result.\n"
      "  --ranks N runs it on N MPI ranks of this machine (mpiexec; solver.linear petsc_gamg), as does\n"
      "  `mpiexec -n N stoss run ...` (docs/many_machines.md); without it, the scene's solver.ranks (1).\n"
      "  exit 0 success, 1 solver failure, 2 invalid scene or command line, 3 suspect result with --strict";
  if (wants_help(args)) {
    std::cout << "usage: " << text << "\n";
    return success;
  }
  const std::optional<RunOptions> options = parse_run_options(args);
  if (!options) return usage(text);
  // Under a launch started by hand the launcher's count rules, not the scene's.
  const bool launched = parallel::mpi_place().several();
  const int asked =
      options->ranks ? *options->ranks
      : launched     ? 1
                     : scene_ranks(options->scene_path,
                               options->resume ? std::optional<fs::path>(options->out_dir) : std::nullopt);
  if (asked != 1 || options->ranks) {
    if (const auto problem =
            ranks_problem(asked, parallel::machine_cores(), options->ranks ? "--ranks" : "solver.ranks")) {
      std::cerr << "stoss run: " << *problem << "\n";
      return invalid_scene;
    }
    if (asked > 1 && !launched) {
      const std::string why_not = launch_ranks(args, asked);  // returns only when mpiexec did not start
      std::cerr << "stoss run: " << why_not << "\n";
      return solver_failure;
    }
  }
  if (refuses_default_output(*options)) return invalid_scene;
  return simulate_into(*options);
}

namespace {

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ',')) out.push_back(item);
  return out;
}

model::Scheme parse_scheme(const std::string& name) {
  if (auto scheme = model::scheme_from_string(name)) return *scheme;
  throw std::invalid_argument("--schemes: unknown scheme \"" + name +
                              "\" (energy_momentum, midpoint, hht, generalized_alpha)");
}

study::Options study_options(const std::vector<std::string>& args, std::string& scene_path,
                             std::string& format) {
  study::Options o;
  for (size_t i = 0; i < args.size(); ++i) {
    const bool has_value = i + 1 < args.size();
    if (args[i] == "--steps" && has_value) {
      for (const auto& h : split_commas(args[++i])) o.steps.push_back(std::stod(h));
    } else if (args[i] == "--tolerances" && has_value) {
      for (const auto& tol : split_commas(args[++i])) o.tolerances.push_back(std::stod(tol));
    } else if (args[i] == "--schemes" && has_value) {
      o.schemes.clear();
      for (const auto& name : split_commas(args[++i])) o.schemes.push_back(parse_scheme(name));
    } else if (args[i] == "--reference" && has_value) {
      o.reference_step = std::stod(args[++i]);
    } else if (args[i] == "--repeat" && has_value) {
      o.repeat = std::stoi(args[++i]);
      if (o.repeat < 1) throw std::invalid_argument("--repeat: must be >= 1");
    } else if (args[i] == "--csv" || args[i] == "--json") {
      format = args[i].substr(2);
    } else if (scene_path.empty() && args[i].rfind("-", 0) != 0) {
      scene_path = args[i];
    } else {
      throw std::invalid_argument("unexpected argument \"" + args[i] + "\"");
    }
  }
  if (scene_path.empty() || o.steps.empty()) throw std::invalid_argument("a scene and --steps are required");
  for (double h : o.steps)
    if (!(h > 0)) throw std::invalid_argument("--steps: every step must be > 0");
  for (double tol : o.tolerances)
    if (!(tol > 0) || !std::isfinite(tol))
      throw std::invalid_argument("--tolerances: every tolerance must be a finite number > 0");
  return o;
}

}  // namespace

int study_command(const std::vector<std::string>& args) {
  constexpr const char* text =
      "stoss study SCENE.json --steps h1,h2,... [--tolerances TOL1,TOL2,...] "
      "[--schemes energy_momentum,midpoint,hht,generalized_alpha] [--reference H] [--repeat N] "
      "[--csv|--json]\n"
      "  each scheme at each step, and with --tolerances also with steps chosen by time.tolerance = TOL\n"
      "  (first step the scene's time.step); wall seconds are the median of N runs of each row (default 3)";
  if (wants_help(args)) {
    std::cout << "usage: " << text << "\n";
    return success;
  }
  std::string scene_path, format = "markdown";
  study::Options options;
  try {
    options = study_options(args, scene_path, format);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return usage(text);
  }
  try {
    precheck_scene_file(scene_path);
    const study::Result result = study::run(scene::load_file(scene_path), options);
    if (format == "csv")
      std::cout << study::to_csv(result);
    else if (format == "json")
      std::cout << server::safe_dump(study::to_json(result), 2) << "\n";
    else
      std::cout << "reference: energy_momentum, h = " << result.reference_step << "\n\n"
                << study::to_markdown(result);
    return success;
  } catch (const scene::SceneError& e) {
    print_scene_error(e);
    return invalid_scene;
  } catch (const std::exception& e) {
    std::cerr << "study failed: " << e.what() << "\n";
    return solver_failure;
  }
}

int validate_command(const std::vector<std::string>& args) {
  constexpr const char* text =
      "stoss validate SCENE.json [--json]\n"
      "  checks a scene: prints its effects, node/element/DOF counts, steps and frames, or every error\n"
      "  with its JSON pointer (--json: the same as JSON). exit 0 valid, 2 invalid";
  if (wants_help(args)) {
    std::cout << "usage: " << text << "\n";
    return success;
  }
  std::string path;
  bool json = false;
  for (const auto& a : args) {
    if (a == "--json")
      json = true;
    else if (path.empty() && a.rfind("-", 0) != 0)
      path = a;
    else
      return usage(text);
  }
  if (path.empty()) return usage(text);
  auto print_errors = [json](const std::vector<scene::Issue>& issues) {
    if (json) {
      nlohmann::json errors = nlohmann::json::array();
      for (const auto& i : issues) errors.push_back({{"pointer", i.pointer}, {"message", i.message}});
      std::cout << server::safe_dump(nlohmann::json{{"valid", false}, {"errors", errors}}, 2) << "\n";
    } else {
      print_scene_error(scene::SceneError(issues));
    }
    return invalid_scene;
  };
  try {
    precheck_scene_file(path);
    const scene::Summary s = scene::summarize(scene::load_file(path));
    if (json) {
      nlohmann::json out{{"valid", true},          {"effects", s.effects}, {"nodes", s.nodes},
                         {"elements", s.elements}, {"dofs", s.dofs},       {"steps", s.steps},
                         {"frames", s.frames}};
      out.update(scene::before_run_json(s));
      std::cout << server::safe_dump(out, 2) << "\n";
    } else {
      std::printf("valid scene\neffects: %s\nnodes %d, elements %d, dofs %d\nsteps %d, frames %d\n",
                  join(s.effects).c_str(), s.nodes, s.elements, s.dofs, s.steps, s.frames);
      print_before_run(s);
    }
    return success;
  } catch (const scene::SceneError& e) {
    return print_errors(e.issues);
  } catch (const std::exception& e) {  // a scene that validates but cannot be built
    return print_errors(std::vector<scene::Issue>{{"", e.what()}});
  }
}

}  // namespace stoss::cli
