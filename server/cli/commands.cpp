#include "server/cli/commands.hpp"

#include <cstdio>
#include <iostream>
#include <sstream>

#include "core/output/result_writer.hpp"
#include "core/scene/scene.hpp"
#include "core/simulate.hpp"
#include "core/study/study.hpp"
#include "server/cli/progress.hpp"

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
  std::printf("energy drift %.3e (relative, max over steps)\n", s.energy_drift);
  std::printf("momentum drift: linear %.3e, angular %.3e\n", s.linear_momentum_drift, s.angular_momentum_drift);
  if (!m.contact.empty())
    std::printf("max penetration %.3e (closest master face), %.3e (own face)\n", s.max_penetration,
                s.max_own_face_penetration);
  std::printf("newton iterations %d (%.2f per step)\n", s.newton_iterations, s.newton_iterations_per_step);
  std::printf("wall %.3f s (linear solver %.3f s)\n", s.wall_seconds, s.linear_solver_seconds);
}

int usage(const char* text) {
  std::cerr << "usage: " << text << "\n";
  return invalid_scene;
}

}  // namespace

int run_command(const std::vector<std::string>& args) {
  std::string scene_path, out_dir = "out";
  for (size_t i = 0; i < args.size(); ++i) {
    if ((args[i] == "-o" || args[i] == "--output") && i + 1 < args.size()) out_dir = args[++i];
    else if (scene_path.empty() && args[i].rfind("-", 0) != 0) scene_path = args[i];
    else return usage("stoss run SCENE.json [-o DIR]");
  }
  if (scene_path.empty()) return usage("stoss run SCENE.json [-o DIR]");
  try {
    const model::Model model = scene::load_file(scene_path);
    output::ResultWriter writer(out_dir);
    ProgressObserver progress;
    model::ObserverList observers({&writer, &progress});
    const model::Summary summary = simulate(model, observers);
    print_summary(model, summary);
    std::printf("result: %s/result.h5\n", out_dir.c_str());
    return success;
  } catch (const scene::SceneError& e) {
    print_scene_error(e);
    return invalid_scene;
  } catch (const std::invalid_argument& e) {
    std::cerr << "invalid scene: " << e.what() << "\n";
    return invalid_scene;
  } catch (const std::exception& e) {
    std::cerr << "solver failure: " << e.what() << "\n";
    return solver_failure;
  }
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
  throw std::invalid_argument("--schemes: unknown scheme \"" + name + "\" (energy_momentum, midpoint, hht)");
}

study::Options study_options(const std::vector<std::string>& args, std::string& scene_path, std::string& format) {
  study::Options o;
  for (size_t i = 0; i < args.size(); ++i) {
    const bool has_value = i + 1 < args.size();
    if (args[i] == "--steps" && has_value) {
      for (const auto& h : split_commas(args[++i])) o.steps.push_back(std::stod(h));
    } else if (args[i] == "--schemes" && has_value) {
      o.schemes.clear();
      for (const auto& name : split_commas(args[++i])) o.schemes.push_back(parse_scheme(name));
    } else if (args[i] == "--reference" && has_value) {
      o.reference_step = std::stod(args[++i]);
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
  return o;
}

}  // namespace

int study_command(const std::vector<std::string>& args) {
  constexpr const char* text =
      "stoss study SCENE.json --steps h1,h2,... [--schemes energy_momentum,midpoint,hht] [--reference H] "
      "[--csv|--json]";
  std::string scene_path, format = "markdown";
  study::Options options;
  try {
    options = study_options(args, scene_path, format);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return usage(text);
  }
  try {
    const study::Result result = study::run(scene::load_file(scene_path), options);
    if (format == "csv") std::cout << study::to_csv(result);
    else if (format == "json") std::cout << study::to_json(result).dump(2) << "\n";
    else std::cout << "reference: energy_momentum, h = " << result.reference_step << "\n\n" << study::to_markdown(result);
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
  if (args.empty() || args.size() > 2) return usage("stoss validate SCENE.json [--json]");
  const bool json = args.size() == 2 && args[1] == "--json";
  try {
    const scene::Summary s = scene::summarize(scene::load_file(args[0]));
    if (json) {
      std::cout << nlohmann::json{{"valid", true}, {"effects", s.effects}, {"nodes", s.nodes},
                                  {"elements", s.elements}, {"dofs", s.dofs}, {"steps", s.steps},
                                  {"frames", s.frames}}.dump(2)
                << "\n";
    } else {
      std::printf("valid scene\neffects: %s\nnodes %d, elements %d, dofs %d\nsteps %d, frames %d\n",
                  join(s.effects).c_str(), s.nodes, s.elements, s.dofs, s.steps, s.frames);
    }
    return success;
  } catch (const scene::SceneError& e) {
    if (json) {
      nlohmann::json errors = nlohmann::json::array();
      for (const auto& i : e.issues) errors.push_back({{"pointer", i.pointer}, {"message", i.message}});
      std::cout << nlohmann::json{{"valid", false}, {"errors", errors}}.dump(2) << "\n";
    } else {
      print_scene_error(e);
    }
    return invalid_scene;
  }
}

}  // namespace stoss::cli
