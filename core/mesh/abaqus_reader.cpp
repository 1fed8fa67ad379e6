// Abaqus / CalculiX input deck reader: the mesh part of a deck (*NODE, *ELEMENT, *NSET, *ELSET,
// *SURFACE, *INCLUDE). Keyword and data line syntax as in the CalculiX User's Manual, section
// "Input deck format".
#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <optional>
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
    out.push_back(
        trimmed(text.substr(start, comma == std::string::npos ? std::string::npos : comma - start)));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (!out.empty() && out.back().empty()) out.pop_back();
  return out;
}

/// Where a line is: the index of its file in LineReader::files, and its 1-based number there.
struct Where {
  int file = 0;
  long line = 0;
};

struct Line {
  std::string text;
  Where where;
};

/// Reads the lines of a deck one at a time, following *INCLUDE as ReadLimits allow (docs/scene.md, "Meshes
/// from files"): nothing but the deck itself when includes are off, else relative paths below the top deck's
/// folder only. Only the files on the include stack are held in memory.
class LineReader {
 public:
  /// `text` must outlive the reader (included files are owned by it).
  LineReader(std::string_view text, std::string shown, std::optional<std::filesystem::path> root,
             const ReadLimits& limits)
      : limits_(limits), root_(std::move(root)) {
    push(text, nullptr, std::move(shown), root_ ? *root_ : std::filesystem::path());
  }

  std::vector<std::string> files;  ///< shown names, by Where::file

  [[noreturn]] void fail(const Where& where, const std::string& message) const {
    throw MeshFileError(files.at(where.file), where.line, message);
  }

  /// The next line (an *INCLUDE replaced by the lines of its file); false at the end of the deck.
  bool next(Line& out) {
    while (!stack_.empty()) {
      Frame& f = stack_.back();
      if (f.pos >= f.text.size()) {
        stack_.pop_back();
        continue;
      }
      const size_t end = std::min(f.text.find('\n', f.pos), f.text.size());
      out.where = {f.file, ++f.line};
      if (end - f.pos > ReadLimits::max_line_bytes)
        fail(out.where, "line longer than " + std::to_string(ReadLimits::max_line_bytes) + " bytes");
      out.text.assign(f.text, f.pos, end - f.pos);
      f.pos = end + 1;
      if (!out.text.empty() && out.text.back() == '\r') out.text.pop_back();
      if (upper(trimmed(out.text)).rfind("*INCLUDE", 0) == 0) {
        include(out);
        continue;
      }
      return true;
    }
    return false;
  }

 private:
  struct Frame {
    std::string_view text;
    std::shared_ptr<const std::string> owned;  ///< an included file's bytes (text views them)
    int file = 0;
    long line = 0;
    size_t pos = 0;
    std::filesystem::path directory;  ///< where its includes are resolved (real path)
  };

  void push(std::string_view text, std::shared_ptr<const std::string> owned, std::string shown,
            std::filesystem::path directory) {
    files.push_back(std::move(shown));
    stack_.push_back(
        {text, std::move(owned), static_cast<int>(files.size()) - 1, 0, 0, std::move(directory)});
  }

  static std::string input_of(const std::string& keyword_line) {
    std::string input;
    for (const std::string& f : fields(trimmed(keyword_line)))
      if (upper(f).rfind("INPUT", 0) == 0 && f.find('=') != std::string::npos)
        input = trimmed(f.substr(f.find('=') + 1));
    if (input.size() >= 2 && input.front() == '"' && input.back() == '"')
      input = input.substr(1, input.size() - 2);
    return input;
  }

  void include(const Line& line) {
    if (!limits_.includes || !root_)
      fail(
          line.where,
          "*INCLUDE is not accepted here: an uploaded mesh must be self-contained (its id is the hash of its "
          "bytes); put the included lines in their place");
    if (stack_.size() > static_cast<size_t>(ReadLimits::max_include_depth))
      fail(line.where,
           "*INCLUDE nested more than " + std::to_string(ReadLimits::max_include_depth) + " deep");
    if (++includes_ > ReadLimits::max_includes)
      fail(line.where, "more than " + std::to_string(ReadLimits::max_includes) + " *INCLUDE in all");
    const std::string input = input_of(line.text);
    if (input.empty()) fail(line.where, "*INCLUDE needs INPUT=<file>");
    const std::filesystem::path real = resolve(line.where, input);
    std::shared_ptr<const std::string> text;
    try {
      text = std::make_shared<const std::string>(read_regular_file(real, input));
    } catch (const MeshFileError&) {
      fail(line.where, "cannot read included file " + input);
    }
    const std::filesystem::path shown_parent = std::filesystem::path(files.at(line.where.file)).parent_path();
    push(*text, text, (shown_parent / input).string(), real.parent_path());
  }

  /// The real path of an included file: relative, no "..", and (symbolic links followed) below the root.
  std::filesystem::path resolve(const Where& where, const std::string& input) const {
    const std::filesystem::path path(input);
    if (path.has_root_name() || path.has_root_directory())
      fail(where,
           "*INCLUDE of an absolute path (" + input + ") is refused: only files below the deck's folder");
    for (const auto& part : path)
      if (part == "..")
        fail(where,
             "*INCLUDE of a path with '..' (" + input + ") is refused: only files below the deck's folder");
    std::error_code error;
    const std::filesystem::path real = std::filesystem::canonical(stack_.back().directory / path, error);
    if (error) fail(where, "cannot read included file " + input);
    const auto [root_end, ignored] = std::mismatch(root_->begin(), root_->end(), real.begin(), real.end());
    if (root_end != root_->end())
      fail(where, "*INCLUDE of " + input + " leads outside the deck's folder (a symbolic link?): refused");
    return real;
  }

  const ReadLimits& limits_;
  std::optional<std::filesystem::path> root_;  ///< real path of the top deck's folder; unset: no includes
  std::vector<Frame> stack_;
  int includes_ = 0;
};

struct Keyword {
  std::string name;                           ///< upper case, without '*'
  std::map<std::string, std::string> params;  ///< upper-case key → value as written ("" for flags)
  Where where;
  bool has(const std::string& key) const { return params.contains(key); }
  std::string get(const std::string& key) const {
    const auto it = params.find(key);
    return it == params.end() ? "" : it->second;
  }
};

Keyword parse_keyword(const Where& where, const std::string& text) {
  const auto parts = fields(text.substr(1));
  Keyword k;
  k.where = where;
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

bool is_integer_text(const std::string& s) {
  return !s.empty() &&
         std::all_of(s.begin(), s.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
}

/// Abaqus C3D8 face S1..S6 → local face of hex_faces() (ζ−, ζ+, η−, η+, ξ−, ξ+):
/// S1 = 1-2-3-4 (ζ−), S2 = 5-8-7-6 (ζ+), S3 = 1-5-6-2 (η−), S4 = 2-6-7-3 (ξ+), S5 = 3-7-8-4 (η+), S6 =
/// 4-8-5-1 (ξ−).
constexpr int abaqus_face[6] = {0, 1, 2, 5, 3, 4};

/// Abaqus 2D and 1D element families (plane stress/strain, axisymmetric, shells, membranes, surface
/// and rigid elements, trusses, beams): what a Gmsh export writes beside its volumes.
bool is_lower_dimensional(const std::string& type) {
  for (const char* family :
       {"CPS", "CPE", "CAX", "S3", "S4", "S8", "STRI", "M3D", "SFM3D", "R3D", "T2D", "T3D", "B2", "B3"})
    if (type.rfind(family, 0) == 0) return true;
  return false;
}

struct Deck {
  Deck(LineReader& reader, const ReadLimits& limits) : in(reader), limits(limits) {}
  LineReader& in;
  const ReadLimits& limits;
  ImportedMesh mesh;
  std::map<long, int> node_index;
  std::vector<long> node_lines;  ///< line of each node's definition
  std::map<long, int> element_index;
  std::vector<std::array<long, 8>> element_nodes;  ///< node ids until resolved
  /// 2D and 1D elements beside the hexahedra (a Gmsh export's CPS4, T3D2): kept apart, a quadrilateral on
  /// the hexahedra's boundary becomes that face (resolve_lower_elements).
  struct LowerElement {
    std::string type;
    std::vector<long> nodes;
    Where where;
  };
  std::map<long, LowerElement> lower_elements;
  std::string lower_type;  ///< the current *ELEMENT's TYPE when it is 2D or 1D, else empty
  /// Named sets, keyed by upper-case name: canonical name and members (ids) with where they are named.
  struct Member {
    long id;
    Where where;
  };
  struct Set {
    std::string name;
    std::vector<Member> ids;
  };
  std::map<std::string, Set> node_sets, element_sets;
  long long members = 0;  ///< set members and surface rows so far, over all sets (ReadLimits::max_members)
  struct SurfaceRow {
    std::string ref;  ///< element id or ELSET name
    int face;         ///< local face of hex_faces()
    Where where;
  };
  struct Surface {
    std::string name;
    std::vector<SurfaceRow> rows;
  };
  std::map<std::string, Surface> surfaces;

  [[noreturn]] void fail(const Where& where, const std::string& message) const { in.fail(where, message); }

  long parse_id(const Where& where, const std::string& text, const std::string& what) const {
    try {
      size_t used = 0;
      const long long v = std::stoll(text, &used);
      if (used == text.size() && v > 0) return static_cast<long>(v);
    } catch (const std::exception&) {
    }
    fail(where, "expected " + what + " (a positive integer), got '" + text.substr(0, 40) + "'");
  }

  double parse_real(const Where& where, const std::string& text, const std::string& what) const {
    try {
      size_t used = 0;
      std::string t = text;
      std::replace(t.begin(), t.end(), 'D', 'E');  // Fortran exponents
      std::replace(t.begin(), t.end(), 'd', 'e');
      const double v = std::stod(t, &used);
      if (used == t.size() && std::isfinite(v)) return v;
    } catch (const std::exception&) {
    }
    fail(where, "expected " + what + " (a number), got '" + text.substr(0, 40) + "'");
  }

  /// Counts `n` more set members (or surface rows) against the total, before they are stored.
  void count_members(const Where& where, long long n) {
    if (n > limits.max_members() - members)
      fail(where, limits.exceeded("set members in all sets and surfaces", ReadLimits::members_per_node));
    members += n;
  }

  Set& set_named(std::map<std::string, Set>& sets, const std::string& name) {
    Set& s = sets[upper(name)];
    if (s.name.empty()) s.name = name;
    return s;
  }

  void add_member(std::map<std::string, Set>& sets, const std::string& name, long id, const Where& where) {
    count_members(where, 1);
    set_named(sets, name).ids.push_back({id, where});
  }

  void add_node(const Where& where, const std::vector<std::string>& f, const std::string& nset) {
    if (f.size() < 3)
      fail(where, "a *NODE line needs id, x, y[, z], got " + std::to_string(f.size()) + " fields");
    const long id = parse_id(where, f[0], "node id");
    Eigen::Vector3d x(parse_real(where, f[1], "x"), parse_real(where, f[2], "y"),
                      f.size() > 3 && !f[3].empty() ? parse_real(where, f[3], "z") : 0.0);
    if (static_cast<long long>(mesh.nodes.size()) >= limits.max_nodes)
      fail(where, "the file has " + limits.exceeded("nodes"));
    const auto [it, fresh] = node_index.try_emplace(id, static_cast<int>(mesh.nodes.size()));
    if (!fresh)
      fail(where, "duplicate node id " + std::to_string(id) + " (first defined on line " +
                      std::to_string(node_lines[it->second]) + ")");
    node_lines.push_back(where.line);
    mesh.nodes.push_back(x);
    mesh.node_ids.push_back(id);
    if (!nset.empty()) add_member(node_sets, nset, id, where);
  }

  void add_element(const Where& where, const std::vector<std::string>& f, const std::string& elset) {
    const long id = parse_id(where, f[0], "element id");
    if (f.size() != 9)
      fail(where,
           "element " + std::to_string(id) + " has " + std::to_string(f.size() - 1) + " nodes, C3D8 needs 8");
    if (static_cast<long long>(mesh.hex8.size()) >= limits.max_nodes)
      fail(where, "the file has " + limits.exceeded("elements"));
    if (lower_elements.contains(id)) fail(where, "duplicate element id " + std::to_string(id));
    const auto [it, fresh] = element_index.try_emplace(id, static_cast<int>(mesh.hex8.size()));
    if (!fresh)
      fail(where, "duplicate element id " + std::to_string(id) + " (first defined on line " +
                      std::to_string(mesh.element_lines[it->second]) + ")");
    std::array<long, 8> nodes;
    for (int k = 0; k < 8; ++k) nodes[k] = parse_id(where, f[k + 1], "node id");
    element_nodes.push_back(nodes);
    mesh.hex8.push_back({});
    mesh.element_ids.push_back(id);
    mesh.element_lines.push_back(where.line);
    if (!elset.empty()) add_member(element_sets, elset, id, where);
  }

  void add_lower_element(const Where& where, const std::vector<std::string>& f, const std::string& elset) {
    const long id = parse_id(where, f[0], "element id");
    if (static_cast<long long>(lower_elements.size()) >= limits.max_records())
      fail(where, limits.exceeded("2D and 1D elements", ReadLimits::records_per_node));
    if (element_index.contains(id) || lower_elements.contains(id))
      fail(where, "duplicate element id " + std::to_string(id));
    LowerElement& e = lower_elements[id];
    e.type = lower_type;
    e.where = where;
    for (size_t k = 1; k < f.size(); ++k) e.nodes.push_back(parse_id(where, f[k], "node id"));
    if (!elset.empty()) add_member(element_sets, elset, id, where);
  }

  /// first, last[, increment]: last ≥ first, the ids counted against the total before one is stored.
  void add_generated(Set& s, const Where& where, const std::vector<std::string>& f) {
    if (f.size() < 2 || f.size() > 3) fail(where, "GENERATE needs first, last[, increment]");
    const long first = parse_id(where, f[0], "first id"), last = parse_id(where, f[1], "last id");
    const long step = f.size() == 3 ? parse_id(where, f[2], "increment") : 1;
    if (last < first)
      fail(where, "GENERATE: last id " + std::to_string(last) + " < first id " + std::to_string(first));
    const long count = (last - first) / step + 1;  // no overflow: 0 <= last - first, step >= 1
    count_members(where, count);
    for (long i = 0; i < count; ++i) s.ids.push_back({first + i * step, where});
  }

  void add_set_line(std::map<std::string, Set>& sets, const Keyword& k, const std::string& name,
                    const Where& where, const std::vector<std::string>& f) {
    Set& s = set_named(sets, name);
    if (k.has("GENERATE")) return add_generated(s, where, f);
    for (const std::string& item : f) {
      if (is_integer_text(item)) {
        const long id = parse_id(where, item, "id");
        count_members(where, 1);
        s.ids.push_back({id, where});
        continue;
      }
      const auto other = sets.find(upper(item));
      if (other == sets.end()) fail(where, "'" + item + "' is neither an id nor a set defined above");
      count_members(where, static_cast<long long>(other->second.ids.size()));
      const std::vector<Member> copied = other->second.ids;  // copy: may be s itself
      s.ids.insert(s.ids.end(), copied.begin(), copied.end());
    }
  }

  void add_surface_line(const Keyword& k, const Line& line, const std::vector<std::string>& f) {
    Surface& s = surfaces[upper(k.get("NAME"))];
    if (f.size() != 2)
      fail(line.where, "an element-based *SURFACE line needs 'element or ELSET, Sn', got '" +
                           trimmed(line.text).substr(0, 80) + "'");
    const std::string label = upper(f[1]);
    if (label.size() != 2 || label[0] != 'S' || label[1] < '1' || label[1] > '6')
      fail(line.where, "face label must be S1..S6 (C3D8 faces), got '" + f[1].substr(0, 40) + "'");
    count_members(line.where, 1);
    s.rows.push_back({f[0], abaqus_face[label[1] - '1'], line.where});
  }

  /// A keyword line with its continuation lines (a keyword line ending with ',' goes on on the next line).
  std::string keyword_text(const Line& line, Line& next_line) {
    std::string text = trimmed(line.text);
    while (text.back() == ',' && in.next(next_line)) {
      text += trimmed(next_line.text);
      if (text.size() > ReadLimits::max_line_bytes)
        fail(line.where, "keyword line (with its continuation lines) longer than " +
                             std::to_string(ReadLimits::max_line_bytes) + " bytes");
    }
    return text;
  }

  void parse() {
    std::optional<Keyword> keyword;
    std::vector<std::string> pending;  // element fields continued over lines
    Where pending_where;
    Line line, continued_line;
    while (in.next(line)) {
      std::string text = trimmed(line.text);
      if (text.empty() || text.rfind("**", 0) == 0) continue;
      if (text[0] == '*') {
        if (!pending.empty()) fail(pending_where, "element line ends with ',' but no continuation follows");
        keyword = parse_keyword(line.where, keyword_text(line, continued_line));
        start_keyword(*keyword);
        continue;
      }
      if (!keyword) fail(line.where, "data line before any keyword");
      const Keyword& k = *keyword;
      const auto f = fields(text);
      if (k.name == "NODE") {
        add_node(line.where, f, k.get("NSET"));
      } else if (k.name == "ELEMENT" && !lower_type.empty()) {
        add_lower_element(line.where, f, k.get("ELSET"));
      } else if (k.name == "ELEMENT") {
        if (pending.empty()) pending_where = line.where;
        pending.insert(pending.end(), f.begin(), f.end());
        const bool continued = text.back() == ',' && pending.size() < 9;
        if (!continued) {
          add_element(pending_where, pending, k.get("ELSET"));
          pending.clear();
        }
      } else if (k.name == "NSET") {
        add_set_line(node_sets, k, k.get("NSET"), line.where, f);
      } else if (k.name == "ELSET") {
        add_set_line(element_sets, k, k.get("ELSET"), line.where, f);
      } else if (k.name == "SURFACE") {
        add_surface_line(k, line, f);
      }
    }
    if (!pending.empty())
      fail(pending_where, "element line ends with ',' but the file ends (truncated file?)");
  }

  void start_keyword(const Keyword& k) {
    if (k.name == "ELEMENT") {
      const std::string type = upper(k.get("TYPE"));
      if (type.empty()) fail(k.where, "*ELEMENT needs TYPE=");
      lower_type = is_lower_dimensional(type) ? k.get("TYPE") : "";
      if (type != "C3D8" && type != "C3D8R" && lower_type.empty())
        fail(k.where, "unsupported element type " + k.get("TYPE").substr(0, 40) +
                          "; Stoss reads 8-node hexahedra (C3D8, C3D8R)");
      if (k.has("ELSET") && k.get("ELSET").empty()) fail(k.where, "ELSET= needs a name");
      if (k.has("ELSET")) set_named(element_sets, k.get("ELSET"));
    } else if (k.name == "NSET" || k.name == "ELSET") {
      const std::string name = k.get(k.name);
      if (name.empty()) fail(k.where, "*" + k.name + " needs " + k.name + "=<name>");
      set_named(k.name == "NSET" ? node_sets : element_sets, name);
    } else if (k.name == "SURFACE") {
      const std::string name = k.get("NAME");
      if (name.empty()) fail(k.where, "*SURFACE needs NAME=<name>");
      const std::string type = upper(k.get("TYPE"));
      if (!type.empty() && type != "ELEMENT")
        fail(k.where, "*SURFACE TYPE=" + k.get("TYPE").substr(0, 40) +
                          " is not supported; Stoss reads element-based surfaces (TYPE=ELEMENT)");
      Surface& s = surfaces[upper(name)];
      if (s.name.empty()) s.name = name;
    } else if (k.name == "NODE") {
      if (k.has("NSET")) set_named(node_sets, k.get("NSET"));
    }
  }

  int element(long id, const Where& where, const std::string& context) const {
    const auto it = element_index.find(id);
    if (it == element_index.end())
      fail(where, context + ": element " + std::to_string(id) + " is not defined");
    return it->second;
  }

  void resolve_elements() {
    for (size_t e = 0; e < element_nodes.size(); ++e)
      for (int k = 0; k < 8; ++k) {
        const auto it = node_index.find(element_nodes[e][k]);
        if (it == node_index.end())
          throw MeshFileError(mesh.file, mesh.element_lines[e],
                              "element " + std::to_string(mesh.element_ids[e]) + " refers to node " +
                                  std::to_string(element_nodes[e][k]) + ", which no *NODE defines");
        mesh.hex8[e][k] = it->second;
      }
  }

  /// Boundary faces of the hexahedra (faces of one element only) by their sorted nodes.
  std::map<std::array<int, 4>, ElementFace> boundary_face_index() const {
    std::map<std::array<int, 4>, std::pair<ElementFace, int>> count;
    if (lower_elements.empty()) return {};
    for (size_t e = 0; e < mesh.hex8.size(); ++e) {
      const auto quads = hex_faces(mesh.hex8[e]);
      for (int f = 0; f < 6; ++f) {
        std::array<int, 4> key = quads[f];
        std::sort(key.begin(), key.end());
        auto [it, fresh] = count.try_emplace(key, ElementFace{static_cast<int>(e), f}, 0);
        ++it->second.second;
      }
    }
    std::map<std::array<int, 4>, ElementFace> out;
    for (const auto& [key, value] : count)
      if (value.second == 1) out.emplace(key, value.first);
    return out;
  }

  /// The boundary face a 4-node 2D element covers (same nodes), if any.
  std::optional<ElementFace> face_of(const LowerElement& e,
                                     const std::map<std::array<int, 4>, ElementFace>& faces) const {
    if (e.nodes.size() != 4) return std::nullopt;
    std::array<int, 4> key;
    for (int k = 0; k < 4; ++k) {
      const auto it = node_index.find(e.nodes[k]);
      if (it == node_index.end())
        fail(e.where,
             e.type + " element refers to node " + std::to_string(e.nodes[k]) + ", which no *NODE defines");
      key[k] = it->second;
    }
    std::sort(key.begin(), key.end());
    const auto it = faces.find(key);
    return it == faces.end() ? std::nullopt : std::optional<ElementFace>(it->second);
  }

  /// An ELSET of 2D elements on the boundary as a surface of the same name.
  void add_lower_surface(const Set& set, std::vector<ElementFace> faces) {
    if (surfaces.contains(upper(set.name)))
      fail(set.ids.front().where, "ELSET " + set.name + " of 2D elements and *SURFACE " + set.name +
                                      " would both be surface '" + set.name + "'; rename one");
    mesh.surfaces[set.name] = std::move(faces);
  }

  /// One note on the 2D and 1D elements: how many became boundary faces, how many were skipped.
  void note_lower_elements(const std::map<std::array<int, 4>, ElementFace>& faces) {
    if (lower_elements.empty()) return;
    long on_boundary = 0;
    std::set<std::string> types;
    for (const auto& [id, e] : lower_elements) {
      types.insert(upper(e.type));
      on_boundary += face_of(e, faces).has_value();
    }
    std::string names;
    for (const std::string& t : types) names += (names.empty() ? "" : ", ") + t;
    const long skipped = static_cast<long>(lower_elements.size()) - on_boundary;
    mesh.skipped_elements = skipped;
    mesh.notes.push_back(std::to_string(lower_elements.size()) + " 2D/1D elements (" + names +
                         ") beside the hexahedra: " + std::to_string(on_boundary) +
                         " on the hexahedra's boundary are faces of the surfaces their ELSETs name, " +
                         std::to_string(skipped) +
                         " skipped (Stoss meshes are 8-node hexahedra; a 2D element only names a face)");
  }

  void resolve_sets() {
    for (const auto& [key, set] : node_sets)
      for (const auto& [id, where] : set.ids)
        if (!node_index.contains(id))
          fail(where, "NSET " + set.name + ": node " + std::to_string(id) + " is not defined");
    for (const auto& [key, set] : node_sets) {
      std::vector<int> members;
      for (const auto& [id, where] : set.ids) members.push_back(node_index.at(id));
      std::sort(members.begin(), members.end());
      members.erase(std::unique(members.begin(), members.end()), members.end());
      mesh.node_sets[set.name] = std::move(members);
    }
    const auto faces = boundary_face_index();
    for (auto& [key, set] : element_sets) {
      std::vector<int> members;
      std::vector<ElementFace> lower_faces;
      bool has_lower = false;
      members.reserve(set.ids.size());
      for (const auto& [id, where] : set.ids) {
        if (const auto lower = lower_elements.find(id); lower != lower_elements.end()) {
          has_lower = true;
          if (const auto face = face_of(lower->second, faces)) lower_faces.push_back(*face);
          continue;
        }
        members.push_back(element(id, where, "ELSET " + set.name));
      }
      std::sort(members.begin(), members.end());
      members.erase(std::unique(members.begin(), members.end()), members.end());
      if (!members.empty() || !has_lower) mesh.element_sets[set.name] = std::move(members);
      if (!lower_faces.empty()) add_lower_surface(set, std::move(lower_faces));
      set.ids = {};
    }
    note_lower_elements(faces);
  }

  /// The faces of every *SURFACE, an ELSET row expanded to its elements; the faces of all surfaces are
  /// counted against ReadLimits::max_members before they are stored.
  void resolve_surfaces() {
    long long faces_in_all = 0;
    for (const auto& [key, surface] : surfaces) {
      auto& faces = mesh.surfaces[surface.name];
      for (const SurfaceRow& row : surface.rows) {
        const std::vector<int>* elements = nullptr;
        int single = -1;
        if (is_integer_text(row.ref)) {
          single = element(parse_id(row.where, row.ref, "element id"), row.where, "*SURFACE " + surface.name);
        } else {
          const auto set = element_sets.find(upper(row.ref));
          if (set == element_sets.end())
            fail(row.where, "*SURFACE " + surface.name + ": '" + row.ref.substr(0, 40) +
                                "' is neither an element nor an ELSET");
          elements = &mesh.element_sets[set->second.name];
        }
        faces_in_all += elements ? static_cast<long long>(elements->size()) : 1;
        if (faces_in_all > limits.max_members())
          fail(row.where, limits.exceeded("surface faces in all surfaces", ReadLimits::members_per_node));
        if (single >= 0) faces.push_back({single, row.face});
        if (elements)
          for (int e : *elements) faces.push_back({e, row.face});
      }
    }
  }
};

/// The real path of the folder holding `path` (the top deck): includes are read below it only.
std::filesystem::path deck_folder(const std::filesystem::path& path) {
  std::error_code error;
  const auto real = std::filesystem::canonical(path, error);
  return error ? std::filesystem::path() : real.parent_path();
}

ImportedMesh parse_deck(std::string_view text, const std::string& shown,
                        std::optional<std::filesystem::path> root, const ReadLimits& limits) {
  LineReader reader(text, shown, std::move(root), limits);
  Deck deck(reader, limits);
  deck.mesh.file = shown;
  deck.parse();
  deck.resolve_elements();
  deck.resolve_sets();
  deck.resolve_surfaces();
  return std::move(deck.mesh);
}

}  // namespace

ImportedMesh read_abaqus(const std::filesystem::path& path, const std::string& shown_name,
                         const ReadLimits& limits) {
  const std::string shown = shown_name.empty() ? path.string() : shown_name;
  const std::string text = read_regular_file(path, shown);
  std::optional<std::filesystem::path> root;
  if (limits.includes) root = deck_folder(path);
  return parse_deck(text, shown, std::move(root), limits);
}

ImportedMesh parse_abaqus(std::string_view bytes, const std::string& shown_name, const ReadLimits& limits) {
  return parse_deck(bytes, shown_name, std::nullopt, limits);
}

}  // namespace stoss::mesh
