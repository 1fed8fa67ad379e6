#include "core/scene/warnings.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>

#include "core/scene/master_surface.hpp"

namespace stoss::scene {
namespace {

/// A scale to 3 significant digits, as a user writes it: 1.6e5, 0.00025, 2e11.
std::string rounded_text(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", x);
  if (const double shown = std::atof(text); shown == std::floor(shown) && std::abs(shown) < 1e4)
    return std::to_string(static_cast<long long>(shown));
  std::string out = text;
  const size_t e = out.find('e');
  if (e == std::string::npos) return out;
  std::string exponent = out.substr(e + 1);
  const bool negative = exponent[0] == '-';
  exponent.erase(0, exponent.find_first_not_of("+-0"));
  return out.substr(0, e) + "e" + (negative ? "-" : "") + exponent;
}

std::string pair_pointer(size_t i, const std::string& field) {
  return "/contact/" + std::to_string(i) + "/" + field;
}

/// At most ~200 of a surface's nodes, evenly spread over its numbering.
std::vector<int> sampled_nodes(const mesh::Mesh& mesh, const std::string& surface) {
  const std::vector<int> all = mesh.surface_nodes(surface);
  const size_t stride = std::max<size_t>(1, all.size() / 200);
  std::vector<int> out;
  for (size_t i = 0; i < all.size(); i += stride) out.push_back(all[i]);
  return out;
}

/// Where `nodes` lie against the faces of `surface`: how many lie behind their nearest face (by centre),
/// (x − c_f)·n_f < −ℓ_f / 20 with n_f the outward normal (b−a)×(d−a) and ℓ_f the face's size (a body
/// resting on the face, or pressed slightly into it, is not behind), and their mean distance to that
/// face's centre.
struct Side {
  size_t behind = 0;
  double mean_distance = 0;
};

Side side_of(const mesh::Mesh& mesh, const std::vector<int>& nodes, const std::string& surface) {
  struct Face {
    Eigen::Vector3d centre, normal;
    double size;
  };
  std::vector<Face> faces;
  for (const mesh::Quad& q : mesh.surface(surface)) {
    const auto& x = mesh.nodes;
    const Eigen::Vector3d centre = (x[q[0]] + x[q[1]] + x[q[2]] + x[q[3]]) / 4;
    const Eigen::Vector3d normal = (x[q[1]] - x[q[0]]).cross(x[q[3]] - x[q[0]]);
    faces.push_back({centre, normal.normalized(), std::sqrt(normal.norm())});
  }
  Side side;
  if (faces.empty()) return side;
  for (int n : nodes) {
    const Eigen::Vector3d& x = mesh.nodes[n];
    const auto nearest = std::min_element(faces.begin(), faces.end(), [&](const Face& a, const Face& b) {
      return (x - a.centre).squaredNorm() < (x - b.centre).squaredNorm();
    });
    side.behind += (x - nearest->centre).dot(nearest->normal) < -nearest->size / 20;
    side.mean_distance += (x - nearest->centre).norm() / static_cast<double>(nodes.size());
  }
  return side;
}

/// The master body's named surface that every slave node lies in front of, the nearest such one.
std::optional<std::string> facing_surface(const model::Model& m, const model::ContactPair& p,
                                          const std::vector<int>& slave) {
  const std::string body = p.master.substr(0, p.master.find('/'));
  std::optional<std::string> best;
  double best_distance = std::numeric_limits<double>::infinity();
  for (const auto& [name, faces] : m.mesh.bodies[m.mesh.find_body(body)].surfaces) {
    const std::string ref = body + "/" + name;
    if (name == "boundary" || name.find('+') != std::string::npos || ref == p.master || faces.empty())
      continue;
    const Side side = side_of(m.mesh, slave, ref);
    if (side.behind == 0 && side.mean_distance < best_distance)
      best = ref, best_distance = side.mean_distance;
  }
  return best;
}

/// Pair i of the model (after merges), reported at its index as written (`written`).
void check_orientation(const model::Model& m, size_t i, int written, std::vector<Warning>& out) {
  const model::ContactPair& p = m.contact[i];
  const std::vector<int> slave = sampled_nodes(m.mesh, p.slave);
  if (slave.empty() || side_of(m.mesh, slave, p.master).behind < slave.size()) return;
  const auto better = facing_surface(m, p, slave);
  const std::string fix = better ? "did you mean " + *better + "?"
                                 : "name a surface of the master body whose outward normals face " + p.slave;
  out.push_back(
      {warning::contact_behind_master, pair_pointer(static_cast<size_t>(written), "master"),
       "every node of " + p.slave + " is behind " + p.master + " (its normals point away); " + fix});
}

/// ρ and E of no solid in SI units: c₀ = √(E/ρ) above 2e4 (beryllium's ~1.3e4 m/s is the fastest) with an
/// SI-sized E (≥ 1e8 Pa).
void check_units(const model::Model& m, const Estimates& e, std::vector<Warning>& out) {
  for (size_t b = 0; b < e.bodies.size(); ++b) {
    const model::Material& mat = m.bodies[b].material;
    if (mat.youngs_modulus < 1e8 || e.bodies[b].bar_speed <= 2e4) continue;
    const std::string guess =
        mat.density < 100 ? "density in g/cm³? In kg/m³ it is " + rounded_text(mat.density * 1000) + ". "
                          : "E and ρ in one unit system? ";
    out.push_back({warning::unit_scale, "/bodies/" + std::to_string(b) + "/material/density",
                   "ρ = " + rounded_text(mat.density) + " with E = " + rounded_text(mat.youngs_modulus) +
                       ": " + guess + "The wave speed √(E/ρ) is " + rounded_text(e.bodies[b].bar_speed) +
                       ", faster than any solid (about 2e4 m/s at most)"});
  }
}

void check_contact_step(const model::Model& m, const Estimates& e, std::vector<Warning>& out) {
  for (const PairScale& s : e.pairs) {
    if (m.time.step <= s.duration) continue;
    const model::ContactPair& p = m.contact[s.pair];
    out.push_back({warning::step_longer_than_contact, "/time/step",
                   "the contact of " + p.slave + " on " + p.master + " lasts about " +
                       rounded_text(s.duration) + " (approach speed " + rounded_text(s.approach_speed) +
                       "), less than one step h = " + rounded_text(m.time.step) + ": take h <= " +
                       rounded_text(s.duration / 10) + " to resolve it, or check the units"});
  }
}

/// The step against the body scales: more than 10 periods of the slowest body's lowest mode in one step,
/// or (over at least 1,000 steps) a Courant number below 1e-3 in every body.
void check_mode_step(const model::Model& m, const Estimates& e, std::vector<Warning>& out) {
  if (e.bodies.empty()) return;
  const auto slowest = std::max_element(
      e.bodies.begin(), e.bodies.end(),
      [](const BodyScale& a, const BodyScale& b) { return a.lowest_period < b.lowest_period; });
  if (m.time.step > 10 * slowest->lowest_period)
    out.push_back({warning::step_longer_than_modes, "/time/step",
                   "the step h = " + rounded_text(m.time.step) + " spans " +
                       rounded_text(m.time.step / slowest->lowest_period) +
                       " periods of the slowest mode of " + slowest->name + " (about " +
                       rounded_text(slowest->lowest_period) + "): no vibration is resolved; take h <= " +
                       rounded_text(slowest->lowest_period / 10) + ", or check the units"});
  const double courant =
      std::max_element(e.bodies.begin(), e.bodies.end(), [](const BodyScale& a, const BodyScale& b) {
        return a.courant < b.courant;
      })->courant;
  if (courant < 1e-3 && m.time.steps() >= 1000)
    out.push_back({warning::step_far_below_waves, "/time/step",
                   "the step h = " + rounded_text(m.time.step) + " is " + rounded_text(courant) +
                       " of the time a wave takes through the smallest element (Courant number): an implicit "
                       "scheme needs no such step; a step 100 times larger would still resolve the waves"});
}

/// A mesh file's 2D/1D elements that are no face of the hexahedra were dropped: a mesh meant as a shell or
/// plane model does not run as one.
void check_skipped_elements(const model::Model& m, std::vector<Warning>& out) {
  for (size_t i = 0; i < m.mesh.bodies.size(); ++i)
    if (const std::string& note = m.mesh.bodies[i].skipped_note; !note.empty())
      out.push_back({warning::mesh_elements_skipped, "/bodies/" + std::to_string(i) + "/mesh", note});
}

}  // namespace

std::vector<Warning> warnings(const model::Model& m, const Estimates& e) {
  std::vector<Warning> out;
  check_skipped_elements(m, out);
  const std::vector<int> written = detail::written_contact_indices(m);
  for (size_t i = 0; i < m.contact.size(); ++i) check_orientation(m, i, written[i], out);
  check_units(m, e, out);
  if (m.time.scheme !=
      model::Scheme::equilibrium) {  // a static step is a load increment: no modes to resolve
    check_contact_step(m, e, out);
    check_mode_step(m, e, out);
  }
  return out;
}

/// "/contact/0, /contact/1 and /contact/3".
std::string pair_list(const std::vector<int>& written) {
  std::string out;
  for (size_t k = 0; k < written.size(); ++k) {
    const char* separator = k == 0 ? "" : k + 1 == written.size() ? " and " : ", ";
    out += separator + std::string("/contact/") + std::to_string(written[k]);
  }
  return out;
}

/// The merge of pairs that share a slave (docs/scene.md, "Pairs that share a slave").
ResolvedChoice merge_choice(const model::Model& m, const model::Model::MergedPairs& merge) {
  const nlohmann::json& pair = m.scene["contact"][merge.pair];
  const std::string master = pair["master"].dump();
  return {pair_pointer(merge.pair, "master"), master,
          "pairs " + pair_list(merge.written) + " as written share slave " + pair["slave"].dump() +
              " and their masters are surfaces of one body: merged into one pair with the union master " +
              master + ", so a slave node crosses from one surface to the next with no seam"};
}

std::vector<ResolvedChoice> resolved_choices(const model::Model& m) {
  std::vector<ResolvedChoice> out;
  for (const model::Model::MergedPairs& merge : m.merged_contact) out.push_back(merge_choice(m, merge));
  for (size_t i = 0; i < m.contact.size(); ++i) {
    const model::ContactPair& p = m.contact[i];
    const bool smooth = p.master_surface == model::MasterSurface::smooth;
    const bool mortar = p.discretization == model::Discretization::mortar;
    const auto why_not = smooth || mortar ? std::nullopt : detail::smooth_unavailable(m, p);
    const std::string surface_reason =
        smooth    ? p.master + " qualifies for the smooth surface, the default wherever it can be had"
        : mortar  ? "discretization \"mortar\" integrates on the faceted surface, the mesh's bilinear faces "
                    "(docs/theory.md "
                    "§4.7; asking for smooth would be an error)"
        : why_not ? *why_not + "; faceted is the fallback (asking for smooth would be an error)"
                  : "the scene asks for it (smooth could be had)";
    out.push_back({pair_pointer(i, "master_surface"), smooth ? "smooth" : "faceted", surface_reason});
    const bool keep = p.switch_gap == model::SwitchGap::keep;
    const bool as_default = keep == smooth;
    const std::string gap_reason =
        mortar       ? "unused: a node-to-segment setting, and a mortar pair has no face switches"
        : as_default ? std::string("the default on a ") + (smooth ? "smooth" : "faceted") + " surface"
                     : "the scene asks for it";
    out.push_back({pair_pointer(i, "switch_gap"), keep ? "keep" : "clamp", gap_reason});
  }
  return out;
}

nlohmann::json before_run_json(const Summary& s) {
  nlohmann::json warnings = nlohmann::json::array(), choices = nlohmann::json::array();
  for (const Warning& w : s.warnings)
    warnings.push_back({{"code", w.code}, {"pointer", w.pointer}, {"message", w.message}});
  for (const ResolvedChoice& c : s.choices)
    choices.push_back({{"pointer", c.pointer}, {"value", c.value}, {"reason", c.reason}});
  return {{"warnings", warnings}, {"choices", choices}, {"estimates", to_json(s.estimates)}};
}

}  // namespace stoss::scene
