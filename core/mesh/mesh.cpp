#include "core/mesh/mesh.hpp"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace stoss::mesh {

int Mesh::add_body(const std::string& name, const BodyMesh& body) {
  Body b;
  b.name = name;
  const int offset = node_count();
  b.node_begin = offset;
  b.node_end = offset + static_cast<int>(body.nodes.size());
  b.element_begin = element_count();
  b.element_end = b.element_begin + static_cast<int>(body.hex8.size());
  nodes.insert(nodes.end(), body.nodes.begin(), body.nodes.end());
  const int index = static_cast<int>(bodies.size());
  for (Hex h : body.hex8) {
    for (int& n : h) n += offset;
    hex8.push_back(h);
    element_body.push_back(index);
  }
  for (const auto& [surface_name, quads] : body.surfaces) {
    auto& out = b.surfaces[surface_name];
    for (Quad q : quads) {
      for (int& n : q) n += offset;
      out.push_back(q);
    }
  }
  for (const auto& [set_name, members] : body.node_sets) {
    auto& out = b.node_sets[set_name];
    for (int n : members) out.push_back(n + offset);
  }
  b.skipped_note = body.skipped_note;
  bodies.push_back(std::move(b));
  return index;
}

int Mesh::find_body(const std::string& name) const {
  for (size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].name == name) return static_cast<int>(i);
  return -1;
}

const std::vector<Quad>& Mesh::surface(const std::string& body_slash_surface) const {
  const auto slash = body_slash_surface.find('/');
  if (slash == std::string::npos)
    throw std::out_of_range("surface reference '" + body_slash_surface + "' is not of the form body/surface");
  const int b = find_body(body_slash_surface.substr(0, slash));
  if (b < 0) throw std::out_of_range("no body named '" + body_slash_surface.substr(0, slash) + "'");
  const auto& surfaces = bodies[b].surfaces;
  const auto it = surfaces.find(body_slash_surface.substr(slash + 1));
  if (it == surfaces.end())
    throw std::out_of_range("body '" + bodies[b].name + "' has no surface '" +
                            body_slash_surface.substr(slash + 1) + "'");
  return it->second;
}

std::string Mesh::add_surface_union(const std::vector<std::string>& body_slash_surfaces) {
  if (body_slash_surfaces.empty()) throw std::invalid_argument("a surface union needs at least one surface");
  if (body_slash_surfaces.size() == 1) return body_slash_surfaces.front();
  const std::string body_name = body_slash_surfaces.front().substr(0, body_slash_surfaces.front().find('/'));
  std::string name;
  std::vector<Quad> faces;
  std::set<std::array<int, 4>> seen;
  for (const std::string& ref : body_slash_surfaces) {
    if (ref.substr(0, ref.find('/')) != body_name)
      throw std::invalid_argument("surfaces of one union must belong to one body: " + ref +
                                  " is not on body '" + body_name + "'");
    name += (name.empty() ? "" : "+") + ref.substr(ref.find('/') + 1);
    for (const Quad& q : surface(ref)) {
      std::array<int, 4> key = q;
      std::sort(key.begin(), key.end());
      if (seen.insert(key).second) faces.push_back(q);
    }
  }
  bodies[find_body(body_name)].surfaces[name] = std::move(faces);
  return body_name + "/" + name;
}

std::vector<int> Mesh::surface_nodes(const std::string& body_slash_surface) const {
  std::vector<int> out;
  for (const Quad& q : surface(body_slash_surface)) out.insert(out.end(), q.begin(), q.end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

const std::vector<int>& Mesh::node_set(const std::string& body_slash_set) const {
  const auto slash = body_slash_set.find('/');
  if (slash == std::string::npos)
    throw std::out_of_range("node set reference '" + body_slash_set + "' is not of the form body/set");
  const int b = find_body(body_slash_set.substr(0, slash));
  if (b < 0) throw std::out_of_range("no body named '" + body_slash_set.substr(0, slash) + "'");
  const auto it = bodies[b].node_sets.find(body_slash_set.substr(slash + 1));
  if (it == bodies[b].node_sets.end())
    throw std::out_of_range("body '" + bodies[b].name + "' has no node set '" +
                            body_slash_set.substr(slash + 1) + "'");
  return it->second;
}

std::vector<int> Mesh::named_nodes(const std::string& body_slash_name) const {
  const auto slash = body_slash_name.find('/');
  const int b = slash == std::string::npos ? -1 : find_body(body_slash_name.substr(0, slash));
  if (b < 0) return surface_nodes(body_slash_name);  // its message names what is wrong
  const std::string name = body_slash_name.substr(slash + 1);
  if (bodies[b].surfaces.contains(name)) return surface_nodes(body_slash_name);
  if (bodies[b].node_sets.contains(name)) return node_set(body_slash_name);
  throw std::out_of_range("body '" + bodies[b].name + "' has no surface or node set '" + name + "'");
}

Eigen::VectorXd Mesh::reference_positions() const {
  Eigen::VectorXd x(3 * nodes.size());
  for (size_t i = 0; i < nodes.size(); ++i) x.segment<3>(3 * i) = nodes[i];
  return x;
}

std::array<Quad, 6> hex_faces(const Hex& h) {
  // docs/theory.md §1.1, face table: outward local order.
  return {Quad{h[0], h[3], h[2], h[1]}, Quad{h[4], h[5], h[6], h[7]}, Quad{h[0], h[1], h[5], h[4]},
          Quad{h[2], h[3], h[7], h[6]}, Quad{h[0], h[4], h[7], h[3]}, Quad{h[1], h[2], h[6], h[5]}};
}

std::vector<Quad> boundary_faces(const std::vector<Hex>& hex8) {
  std::map<std::array<int, 4>, std::pair<Quad, int>> count;
  for (const Hex& h : hex8)
    for (const Quad& q : hex_faces(h)) {
      std::array<int, 4> key = q;
      std::sort(key.begin(), key.end());
      auto [it, inserted] = count.try_emplace(key, q, 0);
      ++it->second.second;
    }
  std::vector<Quad> out;
  for (const auto& [key, value] : count)
    if (value.second == 1) out.push_back(value.first);
  return out;
}

}  // namespace stoss::mesh
