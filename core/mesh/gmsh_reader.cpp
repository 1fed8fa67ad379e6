// Gmsh MSH 4.1 reader (ASCII and binary). Format reference: the Gmsh reference manual, section
// "MSH file format" (version 4.1): $MeshFormat, $PhysicalNames, $Entities, $Nodes, $Elements; other
// sections are skipped.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <set>
#include <sstream>
#include <string_view>

#include "core/mesh/mesh_file.hpp"

namespace stoss::mesh {

namespace {

/// Nodes per element of the MSH element types Stoss can meet (and skip); 0 = unknown.
int nodes_of_type(int type) {
  switch (type) {
    case 1:
      return 2;  // 2-node line
    case 2:
      return 3;  // 3-node triangle
    case 3:
      return 4;  // 4-node quadrangle
    case 4:
      return 4;  // 4-node tetrahedron
    case 5:
      return 8;  // 8-node hexahedron
    case 6:
      return 6;  // 6-node prism
    case 7:
      return 5;  // 5-node pyramid
    case 8:
      return 3;  // 3-node line
    case 9:
      return 6;  // 6-node triangle
    case 10:
      return 9;  // 9-node quadrangle
    case 11:
      return 10;  // 10-node tetrahedron
    case 12:
      return 27;  // 27-node hexahedron
    case 13:
      return 18;  // 18-node prism
    case 14:
      return 14;  // 14-node pyramid
    case 15:
      return 1;  // point
    case 16:
      return 8;  // 8-node quadrangle
    case 17:
      return 20;  // 20-node hexahedron
    case 18:
      return 15;  // 15-node prism
    case 19:
      return 13;  // 13-node pyramid
    default:
      return 0;
  }
}

std::string type_name(int type) {
  static const std::map<int, std::string> names{
      {1, "2-node line"},        {2, "3-node triangle"},      {3, "4-node quadrangle"},
      {4, "4-node tetrahedron"}, {5, "8-node hexahedron"},    {6, "6-node prism"},
      {7, "5-node pyramid"},     {8, "3-node line"},          {9, "6-node triangle"},
      {10, "9-node quadrangle"}, {11, "10-node tetrahedron"}, {12, "27-node hexahedron"},
      {13, "18-node prism"},     {14, "14-node pyramid"},     {15, "point"},
      {16, "8-node quadrangle"}, {17, "20-node hexahedron"},  {18, "15-node prism"},
      {19, "13-node pyramid"}};
  const auto it = names.find(type);
  return "type " + std::to_string(type) + (it == names.end() ? "" : " (" + it->second + ")");
}

/// Walks the file text: whitespace-separated words in ASCII parts, raw little-endian values in binary
/// parts. Knows the current line for messages.
class Cursor {
 public:
  /// `text` must outlive the cursor.
  Cursor(std::string_view text, std::string file) : text_(text), file_(std::move(file)) {}

  bool binary = false;

  [[noreturn]] void fail(const std::string& message) const {
    if (binary && in_binary_section_)
      throw MeshFileError(file_, 0, "byte " + std::to_string(pos_) + " (in " + section_ + "): " + message);
    throw MeshFileError(file_, line_, message);
  }

  void skip_space() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_]))) {
      if (text_[pos_] == '\n') ++line_;
      ++pos_;
    }
  }
  bool at_end() {
    skip_space();
    return pos_ >= text_.size();
  }
  long line() const { return line_; }

  std::string word() {
    skip_space();
    const size_t start = pos_;
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(text_[pos_]))) ++pos_;
    return std::string(text_.substr(start, pos_ - start));
  }

  /// The rest of the current line (without the newline), the newline consumed.
  std::string rest_of_line() {
    const size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    std::string out(text_.substr(start, pos_ - start));
    if (pos_ < text_.size()) {
      ++pos_;
      ++line_;
    }
    if (!out.empty() && out.back() == '\r') out.pop_back();
    return out;
  }

  /// The words of the next non-empty line.
  std::vector<std::string> line_words() {
    skip_space();
    if (pos_ >= text_.size()) fail("unexpected end of file in " + section_ + " (truncated file?)");
    std::istringstream in(rest_of_line());
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    return words;
  }

  long long integer(const std::string& what) {
    if (binary && in_binary_section_) fail("integer expected");
    const std::string w = word();
    return parse_integer(w, what);
  }

  long long parse_integer(const std::string& w, const std::string& what) const {
    if (w.empty())
      fail("unexpected end of file in " + section_ + ", expected " + what + " (truncated file?)");
    try {
      size_t used = 0;
      const long long v = std::stoll(w, &used);
      if (used == w.size()) return v;
    } catch (const std::exception&) {
    }
    fail("expected " + what + ", got '" + w.substr(0, 40) + "'");
  }

  double real(const std::string& what) {
    const std::string w = word();
    if (w.empty())
      fail("unexpected end of file in " + section_ + ", expected " + what + " (truncated file?)");
    try {
      size_t used = 0;
      const double v = std::stod(w, &used);
      if (used == w.size()) return v;
    } catch (const std::exception&) {
    }
    fail("expected " + what + ", got '" + w.substr(0, 40) + "'");
  }

  template <typename T>
  T raw(const std::string& what) {
    if (pos_ + sizeof(T) > text_.size())
      fail("unexpected end of file in " + section_ + ", expected " + what + " (truncated file?)");
    T v;
    std::memcpy(&v, text_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return v;
  }

  /// A count or tag as stored: size_t in binary parts, a word in ASCII ones.
  long long size_value(const std::string& what) {
    if (binary) {
      const auto v = raw<std::uint64_t>(what);
      if (v > (1ull << 40)) fail(what + " " + std::to_string(v) + " is out of range (corrupt file?)");
      return static_cast<long long>(v);
    }
    return integer(what);
  }
  long long int_value(const std::string& what) {
    if (binary) return raw<std::int32_t>(what);
    return integer(what);
  }
  double double_value(const std::string& what) { return binary ? raw<double>(what) : real(what); }

  /// Enters a section whose header was just read: in binary files its data starts after the newline.
  void enter(const std::string& section) {
    section_ = section;
    if (binary) {
      rest_of_line();
      in_binary_section_ = true;
    }
  }
  /// Expects "$End<section>".
  void leave() {
    in_binary_section_ = false;
    const std::string end = "$End" + section_.substr(1);
    const std::string w = word();
    if (w != end)
      fail(w.empty()
               ? "unexpected end of file, expected " + end + " (truncated file?)"
               : "expected " + end + ", got '" + w.substr(0, 40) + "' (wrong counts in " + section_ + "?)");
  }
  /// Skips an unknown section up to and including its $End line.
  void skip_section(const std::string& section) {
    const std::string end = "$End" + section.substr(1);
    const size_t at = text_.find(end, pos_);
    if (at == std::string::npos) fail("section " + section + " has no " + end + " (truncated file?)");
    line_ += std::count(text_.begin() + static_cast<long>(pos_), text_.begin() + static_cast<long>(at), '\n');
    pos_ = at + end.size();
  }
  const std::string& section() const { return section_; }

 private:
  std::string_view text_;
  std::string file_;
  size_t pos_ = 0;
  long line_ = 1;
  std::string section_ = "$MeshFormat";
  bool in_binary_section_ = false;
};

struct PhysicalKey {
  int dim;
  int tag;
  auto operator<=>(const PhysicalKey&) const = default;
};

struct Reader {
  Reader(Cursor cursor, const ReadLimits& limits) : c(std::move(cursor)), limits(limits) {}
  Cursor c;
  const ReadLimits& limits;
  long long records = 0;  ///< entities, physical names and tags, element records (ReadLimits::max_records)
  long long members = 0;  ///< element set members and surface faces (ReadLimits::max_members)
  ImportedMesh mesh;
  std::map<PhysicalKey, std::string> physical_names;
  std::map<PhysicalKey, std::vector<int>> entity_physicals;  ///< (dim, entity tag) → physical tags
  std::map<long, int> node_index;                            ///< node tag → index
  struct PendingQuad {
    Quad nodes;
    long tag;
    long line;
    std::vector<std::string> surfaces;
  };
  std::vector<PendingQuad> quads;
  bool have_nodes = false, have_elements = false;

  std::string physical_name(int dim, int tag) const {
    const auto it = physical_names.find({dim, tag});
    return it != physical_names.end() ? it->second : std::to_string(tag);
  }

  void read_format() {
    if (c.word() != "$MeshFormat") c.fail("not a Gmsh mesh file: it must start with $MeshFormat");
    const std::string version = c.word();
    if (version != "4.1")
      c.fail("MSH format version " + version +
             " is not supported; Stoss reads version 4.1 (gmsh -format msh41)");
    const long long file_type = c.integer("file type");
    const long long data_size = c.integer("data size");
    if (file_type != 0 && file_type != 1)
      c.fail("file type must be 0 (ASCII) or 1 (binary), got " + std::to_string(file_type));
    if (data_size != 8) c.fail("data size must be 8, got " + std::to_string(data_size));
    if (file_type == 1) {
      c.rest_of_line();
      c.binary = true;
      const auto one = c.raw<std::int32_t>("endianness marker");
      if (one != 1) c.fail("binary file of another endianness is not supported");
    }
    c.leave();
  }

  /// Counts `n` more records against ReadLimits::max_records before they are read.
  void count_records(long long n, const std::string& what) {
    if (n < 0) c.fail("negative number of " + what);
    if (n > limits.max_records() - records)
      c.fail("the file has " + limits.exceeded("records (entities, physical groups, elements of every type)",
                                               ReadLimits::records_per_node));
    records += n;
  }
  /// Counts `n` more element set members or surface faces against ReadLimits::max_members.
  void count_members(long long n, long line) {
    if (n > limits.max_members() - members)
      throw MeshFileError(
          mesh.file, line,
          limits.exceeded("element set members and surface faces in all", ReadLimits::members_per_node));
    members += n;
  }

  void read_physical_names() {
    const long long n = c.integer("number of physical names");
    count_records(n, "physical names");
    for (long long i = 0; i < n; ++i) {
      const int dim = static_cast<int>(c.integer("physical dimension"));
      const int tag = static_cast<int>(c.integer("physical tag"));
      c.skip_space();
      std::string name = c.rest_of_line();
      while (!name.empty() && std::isspace(static_cast<unsigned char>(name.back()))) name.pop_back();
      if (name.size() >= 2 && name.front() == '"' && name.back() == '"')
        name = name.substr(1, name.size() - 2);
      if (name.empty()) c.fail("physical group " + std::to_string(tag) + " has an empty name");
      physical_names[{dim, tag}] = name;
    }
  }

  void read_entities() {
    c.enter("$Entities");
    long long count[4];
    for (long long& n : count) {
      n = c.size_value("number of entities");
      count_records(n, "entities");
    }
    for (int dim = 0; dim < 4; ++dim)
      for (long long i = 0; i < count[dim]; ++i) {
        const int tag = static_cast<int>(c.int_value("entity tag"));
        for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) c.double_value("bounding box");
        const long long nphys = c.size_value("number of physical tags");
        count_records(nphys, "physical tags");
        std::vector<int>& phys = entity_physicals[{dim, tag}];
        for (long long k = 0; k < nphys; ++k) {
          const long long physical = c.int_value("physical tag");  // the sign is the orientation
          const long long magnitude = physical < 0 ? -std::max<long long>(physical, -INT32_MAX) : physical;
          phys.push_back(static_cast<int>(std::min<long long>(magnitude, INT32_MAX)));
        }
        if (dim > 0) {
          const long long nbound = c.size_value("number of bounding entities");
          for (long long k = 0; k < nbound; ++k) c.int_value("bounding entity tag");
        }
      }
    c.leave();
  }

  void read_nodes() {
    c.enter("$Nodes");
    const long long blocks = c.size_value("number of node blocks");
    const long long total = c.size_value("number of nodes");
    if (total > limits.max_nodes) c.fail("the file has " + limits.exceeded("nodes"));
    c.size_value("min node tag");
    c.size_value("max node tag");
    long long seen = 0;
    for (long long b = 0; b < blocks; ++b) {
      const long long dim = c.int_value("entity dimension");
      c.int_value("entity tag");
      const long long parametric = c.int_value("parametric flag");
      const long long n = c.size_value("number of nodes in block");
      if (n < 0 || n > limits.max_nodes - seen) c.fail("the file has " + limits.exceeded("nodes"));
      std::vector<std::pair<long, long>> tags;  // tag, line
      for (long long i = 0; i < n; ++i) {
        const long tag = static_cast<long>(c.size_value("node tag"));
        tags.emplace_back(tag, c.line());
      }
      for (const auto& [tag, line] : tags) {
        Eigen::Vector3d x;
        for (int k = 0; k < 3; ++k) x[k] = c.double_value("node coordinate");
        for (long long k = 0; k < (parametric ? dim : 0); ++k) c.double_value("parametric coordinate");
        if (!x.allFinite()) c.fail("node " + std::to_string(tag) + " has a coordinate that is not finite");
        const auto [it, fresh] = node_index.try_emplace(tag, static_cast<int>(mesh.nodes.size()));
        if (!fresh) c.fail("duplicate node tag " + std::to_string(tag));
        mesh.nodes.push_back(x);
        mesh.node_ids.push_back(tag);
      }
      seen += n;
    }
    if (seen != total)
      c.fail("$Nodes header says " + std::to_string(total) + " nodes, its blocks hold " +
             std::to_string(seen));
    c.leave();
    have_nodes = true;
  }

  int node(long tag, long element, long line) {
    const auto it = node_index.find(tag);
    if (it == node_index.end())
      throw MeshFileError(mesh.file, line,
                          "element " + std::to_string(element) + " refers to node " + std::to_string(tag) +
                              ", which $Nodes does not define");
    return it->second;
  }

  void read_elements() {
    if (!have_nodes) c.fail("$Elements before $Nodes");
    c.enter("$Elements");
    const long long blocks = c.size_value("number of element blocks");
    const long long total = c.size_value("number of elements");
    count_records(total, "elements");
    records -= total;  // counted again block by block
    c.size_value("min element tag");
    c.size_value("max element tag");
    long long seen = 0;
    std::set<long> tags_seen;
    for (long long b = 0; b < blocks; ++b) {
      const int dim = static_cast<int>(c.int_value("entity dimension"));
      const int entity = static_cast<int>(c.int_value("entity tag"));
      const int type = static_cast<int>(c.int_value("element type"));
      const long long n = c.size_value("number of elements in block");
      count_records(n, "elements");
      const int per = nodes_of_type(type);
      if (per == 0)
        c.fail("element block of entity " + std::to_string(entity) + ": unsupported element " +
               type_name(type));
      static const std::vector<int> none;
      const auto known = entity_physicals.find({dim, entity});
      const std::vector<int>& phys = known == entity_physicals.end() ? none : known->second;
      if (dim == 3 && type != 5)
        c.fail("unsupported volume element " + type_name(type) + " in volume " + std::to_string(entity) +
               "; Stoss needs 8-node hexahedra (type 5): use Recombine and a "
               "transfinite or extruded mesh");
      if (dim == 2 && type != 3 && !phys.empty())
        c.fail("unsupported surface element " + type_name(type) + " in physical surface '" +
               physical_name(2, phys.front()) +
               "'; surfaces must be 4-node quadrangles (type 3): use Recombine");
      for (long long i = 0; i < n; ++i) {
        long tag = 0;
        std::vector<long> node_tags;
        long line = 0;
        if (c.binary) {
          tag = static_cast<long>(c.size_value("element tag"));
          for (int k = 0; k < per; ++k) node_tags.push_back(static_cast<long>(c.size_value("node tag")));
        } else {
          const auto words = c.line_words();
          line = c.line() - 1;
          tag = static_cast<long>(c.parse_integer(words.front(), "element tag"));
          if (static_cast<int>(words.size()) != per + 1)
            throw MeshFileError(mesh.file, line,
                                "element " + std::to_string(tag) + " has " +
                                    std::to_string(words.size() - 1) + " node tags, " + type_name(type) +
                                    " needs " + std::to_string(per));
          for (int k = 0; k < per; ++k)
            node_tags.push_back(static_cast<long>(c.parse_integer(words[k + 1], "node tag")));
        }
        if (!tags_seen.insert(tag).second)
          throw MeshFileError(mesh.file, line, "duplicate element tag " + std::to_string(tag));
        if (dim == 3) {
          if (static_cast<long long>(mesh.hex8.size()) >= limits.max_nodes)
            throw MeshFileError(mesh.file, line, "the file has " + limits.exceeded("hexahedra"));
          count_members(static_cast<long long>(phys.size()), line);
          Hex h;
          for (int k = 0; k < 8; ++k) h[k] = node(node_tags[k], tag, line);
          const int index = static_cast<int>(mesh.hex8.size());
          mesh.hex8.push_back(h);
          mesh.element_ids.push_back(tag);
          mesh.element_lines.push_back(line);
          for (int p : phys) mesh.element_sets[physical_name(3, p)].push_back(index);
        } else if (dim == 2 && type == 3 && !phys.empty()) {
          count_members(static_cast<long long>(phys.size()), line);
          PendingQuad q{{}, tag, line, {}};
          for (int k = 0; k < 4; ++k) q.nodes[k] = node(node_tags[k], tag, line);
          for (int p : phys) q.surfaces.push_back(physical_name(2, p));
          quads.push_back(std::move(q));
        }
      }
      seen += n;
    }
    if (seen != total)
      c.fail("$Elements header says " + std::to_string(total) + " elements, its blocks hold " +
             std::to_string(seen));
    c.leave();
    have_elements = true;
  }

  /// Each physical-surface quadrangle becomes the faces of the hexahedra that have the same four nodes
  /// (only the quadrangles' keys are kept, so memory follows the surfaces, not the volume).
  void attach_quads() {
    std::map<std::array<int, 4>, std::vector<ElementFace>> faces;
    for (const PendingQuad& q : quads) {
      std::array<int, 4> key = q.nodes;
      std::sort(key.begin(), key.end());
      faces.try_emplace(key);
    }
    for (size_t e = 0; e < mesh.hex8.size() && !faces.empty(); ++e) {
      const auto local = hex_faces(mesh.hex8[e]);
      for (int f = 0; f < 6; ++f) {
        std::array<int, 4> key = local[f];
        std::sort(key.begin(), key.end());
        const auto it = faces.find(key);
        if (it == faces.end()) continue;
        count_members(1, mesh.element_lines[e]);
        it->second.push_back({static_cast<int>(e), f});
      }
    }
    for (const PendingQuad& q : quads) {
      std::array<int, 4> key = q.nodes;
      std::sort(key.begin(), key.end());
      const auto& found = faces.at(key);
      if (found.empty())
        throw MeshFileError(mesh.file, q.line,
                            "quadrangle " + std::to_string(q.tag) + " of physical surface '" +
                                q.surfaces.front() + "' is not a face of any hexahedron");
      count_members(static_cast<long long>(found.size() * q.surfaces.size()), q.line);
      for (const std::string& s : q.surfaces)
        for (const ElementFace& f : found) mesh.surfaces[s].push_back(f);
    }
    // Physical groups that ended up without elements are still named (so that a scene naming one gets
    // "empty", not "missing").
    for (const auto& [key, name] : physical_names) {
      if (key.dim == 3) mesh.element_sets.try_emplace(name);
      if (key.dim == 2) mesh.surfaces.try_emplace(name);
    }
  }

  void read() {
    read_format();
    while (!c.at_end()) {
      const std::string section = c.word();
      if (section.empty() || section[0] != '$')
        c.fail("expected a section such as $Nodes, got '" + section.substr(0, 40) + "'");
      if (section == "$PhysicalNames") {
        c.enter(section);
        // $PhysicalNames is ASCII in binary files too.
        const bool binary = c.binary;
        c.binary = false;
        read_physical_names();
        c.binary = binary;
        c.leave();
      } else if (section == "$Entities") {
        read_entities();
      } else if (section == "$Nodes") {
        read_nodes();
      } else if (section == "$Elements") {
        read_elements();
      } else if (section.rfind("$End", 0) == 0) {
        c.fail("unexpected " + section);
      } else {
        c.skip_section(section);
      }
    }
    if (!have_nodes) c.fail("no $Nodes section (truncated file?)");
    if (!have_elements) c.fail("no $Elements section (truncated file?)");
    attach_quads();
  }
};

}  // namespace

ImportedMesh parse_gmsh(std::string_view bytes, const std::string& shown_name, const ReadLimits& limits) {
  Reader r(Cursor(bytes, shown_name), limits);
  r.mesh.file = shown_name;
  r.read();
  return std::move(r.mesh);
}

ImportedMesh read_gmsh(const std::filesystem::path& path, const std::string& shown_name,
                       const ReadLimits& limits) {
  const std::string shown = shown_name.empty() ? path.string() : shown_name;
  return parse_gmsh(read_regular_file(path, shown), shown, limits);
}

}  // namespace stoss::mesh
