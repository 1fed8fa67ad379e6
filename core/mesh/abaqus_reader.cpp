// Abaqus / CalculiX input deck reader: the mesh part of a deck (*NODE, *ELEMENT, *NSET, *ELSET,
// *SURFACE, *INCLUDE). Keyword and data line syntax as in the CalculiX User's Manual, section
// "Input deck format".
#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <fstream>
#include <set>

#include "core/mesh/mesh_file.hpp"

namespace stoss::mesh {

namespace {

std::string upper(std::string s) {
  for (char& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}

std::string trimmed(const std::string& s) {
  size_t a = 0, b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) ++a;
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) --b;
  return s.substr(a, b - a);
}

/// Comma-separated fields, trimmed; a trailing comma gives no empty last field.
std::vector<std::string> fields(const std::string& text) {
  std::vector<std::string> out;
  size_t start = 0;
  while (true) {
    const size_t comma = text.find(',', start);
    out.push_back(trimmed(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (!out.empty() && out.back().empty()) out.pop_back();
  return out;
}

struct Line {
  std::string text;
  std::string file;
  long number = 0;
};

[[noreturn]] void fail(const Line& line, const std::string& message) {
  throw MeshFileError(line.file, line.number, message);
}

void load_lines(const std::filesystem::path& path, const std::string& shown, int depth, std::vector<Line>& out,
                const Line* from) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    if (from) fail(*from, "cannot read included file " + path.string());
    throw MeshFileError(shown, 0, "cannot read the file");
  }
  std::string text;
  long number = 0;
  while (std::getline(in, text)) {
    ++number;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    Line line{text, shown, number};
    const std::string t = trimmed(text);
    if (upper(t).rfind("*INCLUDE", 0) == 0) {
      if (depth >= 8) fail(line, "*INCLUDE nested too deeply");
      std::string input;
      for (const std::string& f : fields(t))
        if (upper(f).rfind("INPUT", 0) == 0 && f.find('=') != std::string::npos) input = trimmed(f.substr(f.find('=') + 1));
      if (input.size() >= 2 && input.front() == '"' && input.back() == '"') input = input.substr(1, input.size() - 2);
      if (input.empty()) fail(line, "*INCLUDE needs INPUT=<file>");
      const std::filesystem::path included = path.parent_path() / input;
      const std::filesystem::path shown_parent = std::filesystem::path(shown).parent_path();
      load_lines(included, (shown_parent / input).string(), depth + 1, out, &line);
      continue;
    }
    out.push_back(std::move(line));
  }
}

struct Keyword {
  std::string name;  ///< upper case, without '*'
  std::map<std::string, std::string> params;  ///< upper-case key → value as written ("" for flags)
  Line line;
  bool has(const std::string& key) const { return params.contains(key); }
  std::string get(const std::string& key) const {
    const auto it = params.find(key);
    return it == params.end() ? "" : it->second;
  }
};

Keyword parse_keyword(const Line& line, const std::string& text) {
  const auto parts = fields(text.substr(1));
  Keyword k;
  k.line = line;
  k.name = parts.empty() ? "" : upper(parts.front());
  for (size_t i = 1; i < parts.size(); ++i) {
    const size_t eq = parts[i].find('=');
    if (eq == std::string::npos)
      k.params[upper(parts[i])] = "";
    else
      k.params[upper(trimmed(parts[i].substr(0, eq)))] = trimmed(parts[i].substr(eq + 1));
  }
  return k;
}

long parse_id(const Line& line, const std::string& text, const std::string& what) {
  try {
    size_t used = 0;
    const long long v = std::stoll(text, &used);
    if (used == text.size() && v > 0) return static_cast<long>(v);
  } catch (const std::exception&) {
  }
  fail(line, "expected " + what + " (a positive integer), got '" + text.substr(0, 40) + "'");
}

double parse_real(const Line& line, const std::string& text, const std::string& what) {
  try {
    size_t used = 0;
    std::string t = text;
    std::replace(t.begin(), t.end(), 'D', 'E');  // Fortran exponents
    std::replace(t.begin(), t.end(), 'd', 'e');
    const double v = std::stod(t, &used);
    if (used == t.size() && std::isfinite(v)) return v;
  } catch (const std::exception&) {
  }
  fail(line, "expected " + what + " (a number), got '" + text.substr(0, 40) + "'");
}

bool is_integer_text(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

/// Abaqus C3D8 face S1..S6 → local face of hex_faces() (ζ−, ζ+, η−, η+, ξ−, ξ+):
/// S1 = 1-2-3-4 (ζ−), S2 = 5-8-7-6 (ζ+), S3 = 1-5-6-2 (η−), S4 = 2-6-7-3 (ξ+), S5 = 3-7-8-4 (η+), S6 = 4-8-5-1 (ξ−).
constexpr int abaqus_face[6] = {0, 1, 2, 5, 3, 4};

struct Deck {
  ImportedMesh mesh;
  std::map<long, int> node_index;
  std::map<long, long> node_line;
  std::map<long, int> element_index;
  std::vector<std::array<long, 8>> element_nodes;  ///< node ids until resolved
  /// Named sets, keyed by upper-case name: canonical name and members (ids) with the line naming them.
  struct Set {
    std::string name;
    std::vector<std::pair<long, const Line*>> ids;  ///< lines live as long as the Deck
  };
  std::map<std::string, Set> node_sets, element_sets;
  struct SurfaceRow {
    std::string ref;  ///< element id or ELSET name
    int face;         ///< local face of hex_faces()
    Line line;
  };
  struct Surface {
    std::string name;
    std::vector<SurfaceRow> rows;
  };
  std::map<std::string, Surface> surfaces;

  Set& set_named(std::map<std::string, Set>& sets, const std::string& name) {
    Set& s = sets[upper(name)];
    if (s.name.empty()) s.name = name;
    return s;
  }

  void add_node(const Line& line, const std::vector<std::string>& f, const std::string& nset) {
    if (f.size() < 3) fail(line, "a *NODE line needs id, x, y[, z], got " + std::to_string(f.size()) + " fields");
    const long id = parse_id(line, f[0], "node id");
    Eigen::Vector3d x(parse_real(line, f[1], "x"), parse_real(line, f[2], "y"),
                      f.size() > 3 && !f[3].empty() ? parse_real(line, f[3], "z") : 0.0);
    const auto [it, fresh] = node_index.try_emplace(id, static_cast<int>(mesh.nodes.size()));
    if (!fresh) fail(line, "duplicate node id " + std::to_string(id) + " (first defined on line " + std::to_string(node_line[id]) + ")");
    node_line[id] = line.number;
    mesh.nodes.push_back(x);
    mesh.node_ids.push_back(id);
    if (!nset.empty()) set_named(node_sets, nset).ids.push_back({id, &line});
  }

  void add_element(const Line& line, const std::vector<std::string>& f, const std::string& elset) {
    const long id = parse_id(line, f[0], "element id");
    if (f.size() != 9)
      fail(line, "element " + std::to_string(id) + " has " + std::to_string(f.size() - 1) + " nodes, C3D8 needs 8");
    const auto [it, fresh] = element_index.try_emplace(id, static_cast<int>(mesh.hex8.size()));
    if (!fresh)
      fail(line, "duplicate element id " + std::to_string(id) + " (first defined on line " +
                     std::to_string(mesh.element_lines[it->second]) + ")");
    std::array<long, 8> nodes;
    for (int k = 0; k < 8; ++k) nodes[k] = parse_id(line, f[k + 1], "node id");
    element_nodes.push_back(nodes);
    mesh.hex8.push_back({});
    mesh.element_ids.push_back(id);
    mesh.element_lines.push_back(line.number);
    if (!elset.empty()) set_named(element_sets, elset).ids.push_back({id, &line});
  }

  void add_set_line(std::map<std::string, Set>& sets, const Keyword& k, const std::string& name, const Line& line,
                    const std::vector<std::string>& f) {
    Set& s = set_named(sets, name);
    if (k.has("GENERATE")) {
      if (f.size() < 2 || f.size() > 3) fail(line, "GENERATE needs first, last[, increment]");
      const long first = parse_id(line, f[0], "first id"), last = parse_id(line, f[1], "last id");
      const long step = f.size() == 3 ? parse_id(line, f[2], "increment") : 1;
      if (last < first) fail(line, "GENERATE: last id " + std::to_string(last) + " < first id " + std::to_string(first));
      if ((last - first) / step > 10'000'000) fail(line, "GENERATE range of more than 10000000 ids");
      for (long id = first; id <= last; id += step) s.ids.push_back({id, &line});
      return;
    }
    for (const std::string& item : f) {
      if (is_integer_text(item)) {
        s.ids.push_back({parse_id(line, item, "id"), &line});
        continue;
      }
      const auto other = sets.find(upper(item));
      if (other == sets.end()) fail(line, "'" + item + "' is neither an id nor a set defined above");
      if (s.ids.size() + other->second.ids.size() > 50'000'000) fail(line, "set of more than 50000000 members");
      const std::vector<std::pair<long, const Line*>> members = other->second.ids;  // copy: may be s itself
      s.ids.insert(s.ids.end(), members.begin(), members.end());
    }
  }

  void add_surface_line(const Keyword& k, const Line& line, const std::vector<std::string>& f) {
    Surface& s = surfaces[upper(k.get("NAME"))];
    if (f.size() != 2) fail(line, "an element-based *SURFACE line needs 'element or ELSET, Sn', got '" + trimmed(line.text) + "'");
    const std::string label = upper(f[1]);
    if (label.size() != 2 || label[0] != 'S' || label[1] < '1' || label[1] > '6')
      fail(line, "face label must be S1..S6 (C3D8 faces), got '" + f[1] + "'");
    s.rows.push_back({f[0], abaqus_face[label[1] - '1'], line});
  }

  void parse(const std::vector<Line>& lines) {
    std::optional<Keyword> keyword;
    std::vector<std::string> pending;  // element fields continued over lines
    const Line* pending_line = nullptr;
    for (size_t i = 0; i < lines.size(); ++i) {
      const Line& line = lines[i];
      std::string text = trimmed(line.text);
      if (text.empty() || text.rfind("**", 0) == 0) continue;
      if (text[0] == '*') {
        if (!pending.empty()) fail(*pending_line, "element line ends with ',' but no continuation follows");
        while (text.back() == ',' && i + 1 < lines.size()) text += trimmed(lines[++i].text);
        keyword = parse_keyword(line, text);
        start_keyword(*keyword);
        continue;
      }
      if (!keyword) fail(line, "data line before any keyword");
      const Keyword& k = *keyword;
      const auto f = fields(text);
      if (k.name == "NODE") {
        add_node(line, f, k.get("NSET"));
      } else if (k.name == "ELEMENT") {
        if (pending.empty()) pending_line = &line;
        pending.insert(pending.end(), f.begin(), f.end());
        const bool continued = text.back() == ',' && pending.size() < 9;
        if (!continued) {
          add_element(*pending_line, pending, k.get("ELSET"));
          pending.clear();
        }
      } else if (k.name == "NSET") {
        add_set_line(node_sets, k, k.get("NSET"), line, f);
      } else if (k.name == "ELSET") {
        add_set_line(element_sets, k, k.get("ELSET"), line, f);
      } else if (k.name == "SURFACE") {
        add_surface_line(k, line, f);
      }
    }
    if (!pending.empty()) fail(*pending_line, "element line ends with ',' but the file ends (truncated file?)");
  }

  void start_keyword(const Keyword& k) {
    if (k.name == "ELEMENT") {
      const std::string type = upper(k.get("TYPE"));
      if (type.empty()) fail(k.line, "*ELEMENT needs TYPE=");
      if (type != "C3D8" && type != "C3D8R")
        fail(k.line, "unsupported element type " + k.get("TYPE") + "; Stoss reads 8-node hexahedra (C3D8, C3D8R)");
      if (k.has("ELSET") && k.get("ELSET").empty()) fail(k.line, "ELSET= needs a name");
      if (k.has("ELSET")) set_named(element_sets, k.get("ELSET"));
    } else if (k.name == "NSET" || k.name == "ELSET") {
      const std::string name = k.get(k.name);
      if (name.empty()) fail(k.line, "*" + k.name + " needs " + k.name + "=<name>");
      set_named(k.name == "NSET" ? node_sets : element_sets, name);
    } else if (k.name == "SURFACE") {
      const std::string name = k.get("NAME");
      if (name.empty()) fail(k.line, "*SURFACE needs NAME=<name>");
      const std::string type = upper(k.get("TYPE"));
      if (!type.empty() && type != "ELEMENT")
        fail(k.line, "*SURFACE TYPE=" + k.get("TYPE") + " is not supported; Stoss reads element-based surfaces (TYPE=ELEMENT)");
      Surface& s = surfaces[upper(name)];
      if (s.name.empty()) s.name = name;
    } else if (k.name == "NODE") {
      if (k.has("NSET")) set_named(node_sets, k.get("NSET"));
    }
  }

  int element(long id, const Line& line, const std::string& context) {
    const auto it = element_index.find(id);
    if (it == element_index.end()) fail(line, context + ": element " + std::to_string(id) + " is not defined");
    return it->second;
  }

  void resolve() {
    for (size_t e = 0; e < element_nodes.size(); ++e)
      for (int k = 0; k < 8; ++k) {
        const auto it = node_index.find(element_nodes[e][k]);
        if (it == node_index.end())
          throw MeshFileError(mesh.file, mesh.element_lines[e],
                              "element " + std::to_string(mesh.element_ids[e]) + " refers to node " +
                                  std::to_string(element_nodes[e][k]) + ", which no *NODE defines");
        mesh.hex8[e][k] = it->second;
      }
    for (const auto& [key, set] : node_sets)
      for (const auto& [id, line] : set.ids)
        if (!node_index.contains(id)) fail(*line, "NSET " + set.name + ": node " + std::to_string(id) + " is not defined");
    for (const auto& [key, set] : element_sets) {
      std::set<int> members;
      for (const auto& [id, line] : set.ids) members.insert(element(id, *line, "ELSET " + set.name));
      mesh.element_sets[set.name].assign(members.begin(), members.end());
    }
    for (const auto& [key, surface] : surfaces) {
      auto& faces = mesh.surfaces[surface.name];
      for (const SurfaceRow& row : surface.rows) {
        if (is_integer_text(row.ref)) {
          faces.push_back({element(parse_id(row.line, row.ref, "element id"), row.line, "*SURFACE " + surface.name), row.face});
          continue;
        }
        const auto set = element_sets.find(upper(row.ref));
        if (set == element_sets.end())
          fail(row.line, "*SURFACE " + surface.name + ": '" + row.ref + "' is neither an element nor an ELSET");
        for (int e : mesh.element_sets[set->second.name]) faces.push_back({e, row.face});
      }
    }
  }
};

}  // namespace

ImportedMesh read_abaqus(const std::filesystem::path& path, const std::string& shown_name) {
  const std::string shown = shown_name.empty() ? path.string() : shown_name;
  std::vector<Line> lines;
  load_lines(path, shown, 0, lines, nullptr);
  Deck deck;
  deck.mesh.file = shown;
  deck.parse(lines);
  deck.resolve();
  return std::move(deck.mesh);
}

}  // namespace stoss::mesh
