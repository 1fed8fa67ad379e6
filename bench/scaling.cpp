// How a step's cost and memory grow with the mesh (issue 12, item 2): the tumbling hollow sphere of
// api/examples/tumbling_sphere.json with `divisions` and `layers` raised, energy_momentum, h = 0.01,
// 5 steps. Each size runs as its own process, `stoss run` on a generated scene, so the peak resident
// memory it prints is that size's alone. Records s/step, Newton iterations/step, peak memory and the
// shares of the wall time (linear solver, assembly, output) from the run's summary.
// Writes bench/results/scaling.csv and bench/results/scaling.png (gnuplot).
// Run: ./build/bench_scaling [--linear direct|iterative|petsc_gamg] [--large | --only-large] [--steps N]
//                            [--ranks N [--oversubscribe]] [--stoss PATH]
//   default sizes about 1k, 8k and 27k elements; --large adds 64k and 100k, --only-large runs just those
//   (appending to the CSV). --linear sets the scene's solver.linear (default direct); other than direct
//   the results go to scaling_<linear>.csv, with the Krylov iterations per solve and the most one took.
//   scaling.png draws every scaling*.csv there is, one line per linear solver.
//   --ranks N runs each size with `stoss run --ranks N` (solver.linear petsc_gamg; results to
//   scaling_petsc_gamg_ranks<N>.csv); peak memory is then the sum over the ranks, each of which holds the
//   whole model (docs/many_machines.md, "One run on several MPI ranks"). --oversubscribe starts the ranks
//   with `mpiexec --oversubscribe` itself, so that N may exceed the cores (stoss run --ranks refuses that).
//   stoss defaults to the stoss next to this executable (build it first: --target stoss).
#include <unistd.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;
const fs::path source_dir = STOSS_SOURCE_DIR;
const fs::path results_dir = source_dir / "bench" / "results";

struct Size {
  int divisions, layers;  ///< hollow_sphere: 6 · divisions² · layers hex8
};

struct Row {
  int divisions = 0, layers = 0, elements = 0, dofs = 0, steps = 0;
  double wall = 0, linear = 0, assembly = 0, contact = 0, output = 0, newton_per_step = 0, peak_mb = 0;
  double krylov_per_solve = 0, krylov_max = 0, krylov_fallbacks = 0;
};

struct Options {
  std::string linear = "direct";
  int steps = 5;
  int ranks = 1;
  bool oversubscribe = false;  ///< mpiexec --oversubscribe: more ranks than cores
};

/// The command that runs `stoss run ARGS` on o.ranks ranks.
std::string run_command(const fs::path& stoss, const std::string& args, const Options& o) {
  if (o.ranks > 1 && o.oversubscribe)
    return "mpiexec -n " + std::to_string(o.ranks) + " --oversubscribe --bind-to none" +
           (geteuid() == 0 ? " --allow-run-as-root " : " ") + stoss.string() + " run " + args;
  return stoss.string() + " run " + args + (o.ranks > 1 ? " --ranks " + std::to_string(o.ranks) : "");
}

std::string run_capture(const std::string& command, int& status) {
  std::string out;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) {
    status = -1;
    return out;
  }
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) out += buffer.data();
  status = pclose(pipe);
  return out;
}

double match(const std::string& text, const std::string& pattern, int group = 1) {
  std::smatch m;
  if (!std::regex_search(text, m, std::regex(pattern))) {
    std::cerr << "bench_scaling: no match for /" << pattern << "/ in:\n" << text << "\n";
    std::exit(1);
  }
  return std::stod(m[group].str());
}

/// The example scene with a finer sphere, `steps` steps, frames only at the ends.
fs::path write_scene(const Size& size, const fs::path& dir, const Options& o) {
  std::ifstream in(source_dir / "api" / "examples" / "tumbling_sphere.json");
  nlohmann::json scene = nlohmann::json::parse(in);
  auto& sphere = scene["bodies"][0]["mesh"]["hollow_sphere"];
  sphere["divisions"] = size.divisions;
  sphere["layers"] = size.layers;
  scene["name"] =
      "scaling: tumbling hollow sphere " + std::to_string(size.divisions) + "x" + std::to_string(size.layers);
  scene["time"]["step"] = 0.01;
  scene["time"]["end"] = 0.01 * o.steps;
  scene["output"]["every"] = o.steps;
  scene["solver"]["linear"] = o.linear;
  const fs::path path =
      dir / ("sphere_" + std::to_string(size.divisions) + "_" + std::to_string(size.layers) + ".json");
  std::ofstream(path) << scene.dump(2);
  return path;
}

Row measure(const fs::path& stoss, const Size& size, const fs::path& work, const Options& o) {
  Row r;
  r.divisions = size.divisions;
  r.layers = size.layers;
  const fs::path scene = write_scene(size, work, o);
  int status = 0;
  const std::string validated = run_capture(stoss.string() + " validate " + scene.string() + " 2>&1", status);
  if (status != 0) {
    std::cerr << validated;
    std::exit(1);
  }
  r.elements = int(match(validated, R"(elements (\d+))"));
  r.dofs = int(match(validated, R"(dofs (\d+))"));
  const fs::path out = work / ("out_" + std::to_string(size.divisions));
  // The log (stderr) carries the Krylov line; the progress line's carriage returns do no harm.
  const std::string ran =
      run_capture(run_command(stoss, scene.string() + " -o " + out.string(), o) + " 2>&1", status);
  if (status != 0) {
    std::cerr << "bench_scaling: stoss run failed (status " << status << "):\n" << ran;
    std::exit(1);
  }
  r.steps = int(match(ran, R"(steps (\d+), t =)"));
  r.newton_per_step = match(ran, R"(newton iterations \d+ \(([0-9.]+) per step\))");
  r.wall = match(ran, R"(wall ([0-9.]+) s)");
  r.assembly = match(ran, R"(time: assembly ([0-9.]+) s)");
  r.contact = match(ran, R"(contact ([0-9.]+) s,)");
  r.linear = match(ran, R"(, linear solver ([0-9.]+) s \(factorisation)");
  r.output = match(ran, R"(output ([0-9.]+) s)");
  r.peak_mb = match(ran, R"(peak memory ([0-9.]+) MB)");
  if (o.linear != "direct") {
    r.krylov_per_solve = match(ran, R"(Krylov solves, ([0-9.]+) iterations per solve)");
    r.krylov_max = match(ran, R"(per solve, at most (\d+))");
    r.krylov_fallbacks = match(ran, R"(at most \d+, (\d+) fell back to LU)");
  }
  fs::remove_all(out);
  return r;
}

/// One line per linear solver whose CSV exists (scaling.csv is UMFPACK's).
void write_plot(const fs::path& png) {
  const std::vector<std::pair<std::string, std::string>> series = {
      {"scaling.csv", "UMFPACK (direct)"},
      {"scaling_petsc_gamg.csv", "PETSc GMRES + GAMG (petsc_gamg)"},
      {"scaling_iterative.csv", "BiCGSTAB + Jacobi (iterative)"}};
  const std::vector<std::string> colours = {"#d62728", "#1f77b4", "#7f7f7f"};
  std::string time_plot, memory_plot;
  for (size_t k = 0; k < series.size(); ++k) {
    const fs::path csv = results_dir / series[k].first;
    if (!fs::exists(csv)) continue;
    const std::string c = "'" + csv.string() + "'",
                      style = " with linespoints lw 2 lc rgb '" + colours[k] + "'";
    time_plot += std::string(time_plot.empty() ? "plot " : ", ") + c + " using 3:8" + style +
                 " pt 7 title '" + series[k].second + "', " + c + " using 3:($8*$10)" + style +
                 " dt 2 pt 6 title '  its linear solver'";
    memory_plot += std::string(memory_plot.empty() ? "plot " : ", ") + c + " using 3:14" + style +
                   " pt 7 title '" + series[k].second + "'";
  }
  fs::path script = png;
  script.replace_extension(".gnuplot");
  std::ofstream(script)
      << "set datafile separator ','\n"
      << "set terminal pngcairo size 1200,480 noenhanced font ',11'\n"
      << "set output '" << png.string() << "'\n"
      << "set multiplot layout 1,2 title 'tumbling hollow sphere, energy_momentum, h = 0.01 (2 shared "
         "cores)'\n"
      << "set logscale xy\nset grid\nset xlabel 'elements (hex8)'\nset key inside bottom right box opaque\n"
      << "set title 'seconds per step'\nset ylabel 's/step'\n"
      << time_plot << "\n"
      << "set title 'peak resident memory'\nset ylabel 'MB'\n"
      << memory_plot << "\n"
      << "unset multiplot\n";
  const std::string command = "gnuplot " + script.string();
  if (std::system(command.c_str()) != 0)
    std::cerr << "bench_scaling: gnuplot failed; the CSV files are written\n";
}

}  // namespace

int main(int argc, char** argv) {
  bool large = false, only_large = false;
  Options o;
  fs::path stoss = fs::read_symlink("/proc/self/exe").parent_path() / "stoss";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--large")
      large = true;
    else if (a == "--only-large")
      large = only_large = true;
    else if (a == "--linear" && i + 1 < argc)
      o.linear = argv[++i];
    else if (a == "--steps" && i + 1 < argc)
      o.steps = std::atoi(argv[++i]);
    else if (a == "--stoss" && i + 1 < argc)
      stoss = argv[++i];
    else if (a == "--ranks" && i + 1 < argc)
      o.ranks = std::atoi(argv[++i]);
    else if (a == "--oversubscribe")
      o.oversubscribe = true;
    else {
      std::cerr << "usage: bench_scaling [--linear direct|iterative|petsc_gamg] [--large | --only-large] "
                   "[--steps N] [--ranks N [--oversubscribe]] "
                   "[--stoss PATH]\n";
      return 2;
    }
  }
  if (!fs::exists(stoss)) {
    std::cerr << "bench_scaling: " << stoss << " not found (build the stoss target, or pass --stoss PATH)\n";
    return 2;
  }
  // layers ≈ divisions / 3, as in the issue's table (6·12²·4 = 3456, 6·24²·8 = 27648).
  std::vector<Size> sizes;
  if (!only_large) sizes = {{8, 3}, {16, 5}, {24, 8}};  // 1152, 7680, 27648 elements
  if (large) {
    sizes.push_back({32, 10});  // 61440
    sizes.push_back({38, 12});  // 103968
  }
  const fs::path work = fs::temp_directory_path() / ("stoss_scaling_" + std::to_string(::getpid()));
  fs::create_directories(work);
  fs::create_directories(results_dir);
  if (o.ranks > 1) o.linear = "petsc_gamg";  // the solver that spans ranks
  const std::string base = (o.linear == "direct" ? "scaling" : "scaling_" + o.linear) +
                           (o.ranks > 1 ? "_ranks" + std::to_string(o.ranks) : "");
  const fs::path csv = results_dir / (base + ".csv"), png = results_dir / "scaling.png";
  const bool append = only_large && fs::exists(csv);
  std::ofstream out(csv, append ? std::ios::app : std::ios::trunc);
  if (!append)
    out << "divisions,layers,elements,dofs,steps,wall_seconds,newton_per_step,s_per_step,linear_solver_"
           "seconds,"
           "linear_solver_share,assembly_share,contact_share,output_share,peak_memory_mb,krylov_per_solve,"
           "krylov_max_per_solve,krylov_fallbacks\n";
  std::printf(
      "| elements | dofs | s/step | Newton its/step | peak memory MB | linear solver | assembly | output | "
      "Krylov its/solve (max) |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
  for (const Size& size : sizes) {
    const Row r = measure(stoss, size, work, o);
    const double per_step = r.wall / r.steps;
    char line[512];
    std::snprintf(line, sizeof line,
                  "%d,%d,%d,%d,%d,%.4f,%.3f,%.5f,%.4f,%.4f,%.4f,%.4f,%.4f,%.1f,%.1f,%.0f,%.0f\n", r.divisions,
                  r.layers, r.elements, r.dofs, r.steps, r.wall, r.newton_per_step, per_step, r.linear,
                  r.linear / r.wall, r.assembly / r.wall, r.contact / r.wall, r.output / r.wall, r.peak_mb,
                  r.krylov_per_solve, r.krylov_max, r.krylov_fallbacks);
    out << line << std::flush;
    char krylov[64] = "–";
    if (o.linear != "direct")
      std::snprintf(krylov, sizeof krylov, "%.1f (%.0f)%s", r.krylov_per_solve, r.krylov_max,
                    r.krylov_fallbacks > 0 ? ", some fell back to LU" : "");
    std::printf("| %d | %d | %.3f | %.1f | %.0f | %.0f %% | %.0f %% | %.1f %% | %s |\n", r.elements, r.dofs,
                per_step, r.newton_per_step, r.peak_mb, 100 * r.linear / r.wall, 100 * r.assembly / r.wall,
                100 * r.output / r.wall, krylov);
    std::fflush(stdout);
  }
  out.close();
  fs::remove_all(work);
  write_plot(png);
  std::printf("wrote %s and %s\n", csv.c_str(), png.c_str());
  return 0;
}
