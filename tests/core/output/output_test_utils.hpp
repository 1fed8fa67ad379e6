#pragma once
/// @file A tiny hand-built run (two one-element bodies, 130 steps, 3 frames) and helpers for the output
/// tests.

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "core/fem/assembly.hpp"
#include "core/model/model.hpp"
#include "core/model/observer.hpp"

namespace stoss::output::testing {

/// A unit cube as one hex8 element, shifted by `x0` along x, with its six faces as surface "all".
inline mesh::BodyMesh unit_cube(double x0) {
  mesh::BodyMesh body;
  for (double z : {0.0, 1.0})
    for (auto [x, y] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {1.0, 1.0}, {0.0, 1.0}})
      body.nodes.emplace_back(x0 + x, y, z);
  body.hex8.push_back({0, 1, 2, 3, 4, 5, 6, 7});
  const auto faces = mesh::hex_faces(body.hex8.front());
  body.surfaces["all"] = std::vector<mesh::Quad>(faces.begin(), faces.end());
  return body;
}

/// Two bodies, "ball" and "wall", one element each: 16 nodes, 2 elements.
inline model::Model tiny_model() {
  model::Model m;
  m.name = "tiny";
  m.scene = {{"name", "tiny"}, {"time", {{"scheme", "energy_momentum"}, {"step", 0.01}, {"end", 1.29}}}};
  m.mesh.add_body("ball", unit_cube(0.0));
  m.mesh.add_body("wall", unit_cube(2.0));
  for (const char* name : {"ball", "wall"}) {
    model::BodySpec body;
    body.name = name;
    body.material = {"saint_venant_kirchhoff", 1e4, 0.25, 1};  // λ = μ = 4000
    m.bodies.push_back(body);
  }
  m.time.scheme = model::Scheme::energy_momentum;
  m.time.step = 0.01;
  m.time.end = 1.29;
  m.effects = {"inertia", "elasticity", "contact_frictionless"};
  return m;
}

/// kinetic_energy, total_energy, linear_momentum (3), newton_iterations (int): 6 values a row.
inline model::SeriesLayout tiny_layout() {
  return model::SeriesLayout{
      {{"kinetic_energy"}, {"total_energy"}, {"linear_momentum", 3}, {"newton_iterations", 1, true}}};
}

/// Step s of the tiny run, with values that are easy to state exactly.
inline model::StepRow tiny_row(int s) {
  return model::StepRow{
      s, s / 100.0, {1.0 + 0.5 * s, 1.0 / (s + 1), double(s), -2.0 * s, 0.25 * s, double(s % 5 + 1)}};
}

inline constexpr int tiny_steps = 130;
inline const std::vector<double> tiny_frame_times{0.0, 0.64, 1.29};

/// The element stresses of `frame`'s positions, from fem's kernel as a run computes them.
inline void add_stresses(const model::Model& m, model::Frame& frame) {
  std::vector<std::shared_ptr<const fem::Material>> material;
  for (int body : m.mesh.element_body) material.push_back(fem::make_material(m.bodies[body].material));
  const fem::ElasticityTerm term(m.mesh, fem::precompute_mesh(m.mesh), std::move(material));
  term.element_stresses(frame.position, frame.cauchy_stress, frame.von_mises);
}

/// Frame k of the tiny run: positions drift by 0.001·node·k, velocity (k, node, −k), pressure 0.5·node·k,
/// and the element stresses of those positions.
inline model::Frame tiny_frame(const model::Model& m, int k, bool with_pressure) {
  const int n = m.mesh.node_count();
  model::Frame f;
  f.time = tiny_frame_times.at(k);
  f.position = m.mesh.reference_positions();
  f.velocity.resize(3 * n);
  if (with_pressure) f.contact_pressure.resize(n);
  for (int i = 0; i < n; ++i) {
    f.position.segment<3>(3 * i).array() += 0.001 * i * k;
    f.velocity.segment<3>(3 * i) << k, i, -k;
    if (with_pressure) f.contact_pressure[i] = 0.5 * i * k;
  }
  add_stresses(m, f);
  return f;
}

/// Plays the tiny run into `observer`: begin, 130 steps, frames at steps 0, 64 and 129.
inline void play_tiny_run(model::Observer& observer, const model::Model& m, bool with_pressure = true) {
  observer.begin(m, tiny_layout());
  for (int s = 0; s < tiny_steps; ++s) {
    observer.step(tiny_row(s));
    if (s == 0) observer.frame(tiny_frame(m, 0, with_pressure));
    if (s == 64) observer.frame(tiny_frame(m, 1, with_pressure));
    if (s == tiny_steps - 1) observer.frame(tiny_frame(m, 2, with_pressure));
  }
}

inline model::Summary summary(bool completed) {
  model::Summary s;
  s.completed = completed;
  s.steps = tiny_steps - 1;
  s.wall_seconds = 1.5;
  return s;
}

/// A fresh directory per test, removed afterwards.
class OutputDirectory : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir = std::filesystem::temp_directory_path() / ("stoss_output_" + std::string(info->test_suite_name()) +
                                                    "_" + info->name() + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(dir);
  }
  void TearDown() override { std::filesystem::remove_all(dir); }

  std::filesystem::path dir;
};

/// Number of non-overlapping occurrences of `needle` in `text`.
inline int count_of(const std::string& text, const std::string& needle) {
  int n = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + needle.size()))
    ++n;
  return n;
}

/// Whether `xml` is well formed as far as elements go: every start tag is closed in order,
/// one root element, no text outside it. Declarations (<?...?>, <!...>) are skipped.
/// Returns an empty string when well formed, else what is wrong.
inline std::string xml_structure_error(const std::string& xml) {
  std::vector<std::string> open;
  int roots = 0;
  size_t at = 0;
  while ((at = xml.find('<', at)) != std::string::npos) {
    const size_t close = xml.find('>', at);
    if (close == std::string::npos) return "unterminated tag at " + std::to_string(at);
    const std::string tag = xml.substr(at + 1, close - at - 1);
    at = close + 1;
    if (tag.empty()) return "empty tag";
    if (tag[0] == '?' || tag[0] == '!') continue;
    if (tag[0] == '/') {
      const std::string name = tag.substr(1);
      if (open.empty() || open.back() != name) return "unexpected </" + name + ">";
      open.pop_back();
      continue;
    }
    const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
    if (open.empty()) ++roots;
    if (tag.back() != '/') open.push_back(name);
    if (count_of(tag, "\"") % 2 != 0) return "unbalanced quotes in <" + name + ">";
  }
  if (!open.empty()) return "unclosed <" + open.back() + ">";
  if (roots != 1) return std::to_string(roots) + " root elements";
  return "";
}

}  // namespace stoss::output::testing
