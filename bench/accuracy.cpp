// What accuracy costs in time (docs/measurements.md, "Accuracy against time"): each scheme at h, h/2, h/4,
// h/8 (h = 0.04) against an energy_momentum reference at h/32, on a contact-free case and on the paper's
// example. Writes bench/results/accuracy_<case>.{csv,md,png} (the PNG needs gnuplot).
// Run: ./build/bench_accuracy [--quick] [--tolerances T1,T2,...]
//      (--quick: h and h/2 only, for a smoke check; --tolerances, or --tol, as stoss study's: also each
//      scheme with steps chosen by time.tolerance = T, first step the scene's time.step, drawn as the lines
//      "adaptive <scheme>")
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "core/scene/scene.hpp"
#include "core/study/study.hpp"

namespace {

namespace fs = std::filesystem;
const fs::path source_dir = STOSS_SOURCE_DIR;
const fs::path results_dir = source_dir / "bench" / "results";

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

/// Two panels, log-log: displacement error and energy error against wall seconds, one colour per
/// scheme, the legend inside each panel.
void plot(const std::string& name, const stoss::study::Result& r, bool tolerances) {
  const fs::path csv = results_dir / ("accuracy_" + name + ".csv"),
                 png = results_dir / ("accuracy_" + name + ".png");
  const fs::path script = results_dir / ("accuracy_" + name + ".gnuplot");
  const std::pair<const char*, const char*> schemes[] = {{"energy_momentum", "#1f77b4"},
                                                         {"midpoint", "#d62728"},
                                                         {"hht", "#2ca02c"},
                                                         {"generalized_alpha", "#9467bd"}};
  const auto panel = [&](const char* column, const char* label, const char* key) {
    std::string lines;
    // Column 11 (tolerance) is there only when a row has one: empty for the fixed steps.
    const std::string fixed = tolerances ? " && strcol(11) eq ''" : "", adaptive = " && strcol(11) ne ''";
    for (const auto& [scheme, colour] : schemes) {
      const std::string rows = "'" + csv.string() + "' using (strcol(1) eq '" + scheme + "' && $4 == 1";
      // Each point labelled with its step (h=0.02), or on the adaptive lines with its tolerance (TOL=0.001).
      const auto labels = [&](const std::string& which, const std::string& text) {
        return ", " + rows + which + " ? $8 : 1/0):" + column + ":(" + text +
               ") with labels offset char 0,0.8 font ',8' tc rgb '" + colour + "' notitle";
      };
      lines += std::string(lines.empty() ? "" : ", ") + rows + fixed + " ? $8 : 1/0):" + column +
               " with linespoints lw 2 pt 7 lc rgb '" + colour + "' title '" + scheme + "'" +
               labels(fixed, "'h='.strcol(2)");
      if (tolerances)
        lines += ", " + rows + adaptive + " ? $8 : 1/0):" + column +
                 " with linespoints lw 2 dt 2 pt 5 lc rgb '" + colour + "' title 'adaptive " + scheme + "'" +
                 labels(adaptive, "'TOL='.strcol(11)");
    }
    return std::string("set title '") + label + "'\nset ylabel '" + label + "'\nset key inside " + key +
           " box opaque\nplot " + lines + "\n";
  };
  write(
      script,
      "set datafile separator ','\nset terminal pngcairo size 1200,480 noenhanced font ',11'\nset output '" +
          png.string() + "'\nset multiplot layout 1,2 title 'accuracy against time: " + name +
          "'\nset logscale xy\nset format y '%.0e'\nset grid\n"
          "set xlabel '" +
          stoss::study::timing_note(r) + "'\n" + panel("5", "displacement error", "top right") +
          panel("6", "energy error (relative)", "right center") + "unset multiplot\n");
  if (std::system(("gnuplot '" + script.string() + "' 2>/dev/null").c_str()) != 0)
    std::cerr << "gnuplot not available: " << png << " not written\n";
}

void run_case(const std::string& name, stoss::model::Model m, bool quick,
              const std::vector<double>& tolerances) {
  stoss::study::Options o;
  o.tolerances = tolerances;
  o.steps = quick ? std::vector<double>{0.04, 0.02} : std::vector<double>{0.04, 0.02, 0.01, 0.005};
  o.reference_step = 0.04 / 32;
  o.schemes.assign(std::begin(stoss::model::all_schemes), std::end(stoss::model::all_schemes));
  const stoss::study::Result r = stoss::study::run(m, o);
  write(results_dir / ("accuracy_" + name + ".csv"), stoss::study::to_csv(r));
  write(results_dir / ("accuracy_" + name + ".md"), stoss::study::to_markdown(r));
  plot(name, r, !tolerances.empty());
  std::cout << "## " << name << " (reference energy_momentum h = " << r.reference_step << ", "
            << r.reference_wall_seconds << " s)\n\n"
            << stoss::study::to_markdown(r) << std::endl;
}

}  // namespace

/// The values of "--tolerances T1,T2,..." (or "--tol").
std::vector<double> tolerances_of(int argc, char** argv) {
  std::vector<double> out;
  for (int k = 1; k + 1 < argc; ++k)
    if (std::string(argv[k]) == "--tol" || std::string(argv[k]) == "--tolerances") {
      std::stringstream list(argv[k + 1]);
      for (std::string item; std::getline(list, item, ',');) out.push_back(std::stod(item));
    }
  return out;
}

int main(int argc, char** argv) {
  bool quick = false;
  for (int k = 1; k < argc; ++k) quick = quick || std::string(argv[k]) == "--quick";
  const std::vector<double> tolerances = tolerances_of(argc, argv);
  fs::create_directories(results_dir);
  // Contact-free: the B4 bar. (The 432-element sphere is no convergence case at these steps: its
  // through-thickness modes, ω ≈ 2000 rad/s, stay unresolved even at h/32, so every scheme's error
  // plateaus at the amplitude of those vibrations, ~3e-4.)
  run_case("tumbling_bar", stoss::scene::load_file(source_dir / "api/examples/tumbling_bar.json"), quick,
           tolerances);
  const fs::path paper = source_dir / "api/examples/hollow_ball_plate.json";
  if (!fs::exists(paper)) return 0;
  try {
    run_case("hollow_ball_plate", stoss::scene::load_file(paper), quick, tolerances);
  } catch (const std::exception& e) {
    std::cerr << "hollow_ball_plate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
