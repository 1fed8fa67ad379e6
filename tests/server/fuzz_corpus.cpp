#include "tests/server/fuzz_corpus.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>

namespace stoss::test {

namespace {

/// Every node of `doc` (objects, arrays and leaves), depth first.
void collect(nlohmann::json& node, std::vector<nlohmann::json*>& out) {
  out.push_back(&node);
  if (node.is_object())
    for (auto& [key, value] : node.items()) collect(value, out);
  else if (node.is_array())
    for (auto& value : node) collect(value, out);
}

}  // namespace

FuzzCorpus::FuzzCorpus(std::uint64_t seed) : rng_(seed) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::path(STOSS_SOURCE_DIR) / "api/examples"))
    if (entry.path().extension() == ".json") files.push_back(entry.path());
  std::sort(files.begin(), files.end());  // directory order is not deterministic
  for (const auto& file : files) {
    try {
      scenes_.push_back(nlohmann::json::parse(std::ifstream(file)));
    } catch (const std::exception&) {
    }
  }
  if (scenes_.empty()) scenes_.push_back({{"format", "stoss-scene/1"}});
}

nlohmann::json FuzzCorpus::hostile_value() {
  switch (below(24)) {
    case 0:
      return 4294967296.0;  // 2^32: truncated to 0 by a 32-bit cast
    case 1:
      return 2147483648.0;
    case 2:
      return -1;
    case 3:
      return 0;
    case 4:
      return 1e308;
    case 5:
      return -1e308;
    case 6:
      return 5e-324;
    case 7:
      return 9007199254740993.0;
    case 8:
      return std::numeric_limits<std::uint64_t>::max();
    case 9:
      return std::numeric_limits<std::int64_t>::min();
    case 10:
      return "";
    case 11:
      return std::string(1 + below(5000), 'x');
    case 12:
      return std::string("\xe2\x82\xac\xe2\x82", 5);  // a euro sign, then one cut after 2 bytes
    case 13:
      return nullptr;
    case 14:
      return true;
    case 15:
      return nlohmann::json::array();
    case 16:
      return nlohmann::json::object();
    case 17:
      return nlohmann::json::array({0, 0, 0});
    case 18:
      return nlohmann::json::array({1e300, -1e300, 1e-300});
    case 19:
      return nlohmann::json::array({nlohmann::json::array({0, 1}), nlohmann::json::array({2})});
    case 20:
      return 0.5;
    case 21:
      return 1000000;
    case 22:
      return "energy_momentum";
    default: {
      nlohmann::json deep = 1;
      for (std::size_t i = 0, n = 1 + below(40); i < n; ++i) deep = nlohmann::json::array({deep});
      return deep;
    }
  }
}

void FuzzCorpus::mutate_structure(nlohmann::json& doc, int mutations) {
  for (int m = 0; m < mutations; ++m) {
    std::vector<nlohmann::json*> nodes;
    collect(doc, nodes);
    nlohmann::json& node = *nodes[below(nodes.size())];
    const std::size_t op = below(10);
    if (op < 4) {
      node = hostile_value();
    } else if (op == 4 && node.is_object() && !node.empty()) {
      auto it = node.begin();
      std::advance(it, static_cast<std::ptrdiff_t>(below(node.size())));
      node.erase(it);
    } else if (op == 5 && node.is_object()) {
      node["unknown_" + std::to_string(below(3))] = hostile_value();
    } else if (op == 6 && node.is_array() && !node.empty()) {
      const std::size_t n = 1 + below(std::min<std::size_t>(node.size(), 64));
      const nlohmann::json copy = node[below(node.size())];
      for (std::size_t i = 0; i < n; ++i) node.push_back(copy);
    } else if (op == 7 && node.is_array() && !node.empty()) {
      node.erase(node.begin() + static_cast<std::ptrdiff_t>(below(node.size())));
    } else if (op == 8 && node.is_number()) {
      const double x = node.get<double>();
      static const double factors[] = {-1, 0, 2, 1e6, 1e-6, 1e300, 0.5};
      node = x * factors[below(std::size(factors))] + (below(2) ? 1 : 0);
    } else if (node.is_string()) {
      std::string s = node.get<std::string>();
      if (!s.empty()) s.resize(below(s.size()));
      node = below(2) ? s : s + "\xc3";
    } else {
      node = hostile_value();
    }
  }
}

std::string FuzzCorpus::mutate_bytes(std::string text) {
  for (std::size_t m = 0, n = 1 + below(4); m < n; ++m) {
    if (text.empty()) text = "{";
    const std::size_t at = below(text.size());
    switch (below(7)) {
      case 0:
        text[at] = static_cast<char>(below(256));
        break;
      case 1:
        text.insert(at, 1, "{}[]\",:\\0-e."[below(12)]);
        break;
      case 2:
        text.erase(at, 1 + below(16));
        break;
      case 3:
        text.resize(at);
        break;
      case 4:
        text.insert(at, std::string(1 + below(400), below(2) ? '[' : '{'));
        break;
      case 5:
        text.insert(at, below(2) ? "1e400" : "-0.0e-99999");
        break;
      default:
        text.insert(at, std::string("\xff\xfe\xc3", 1 + below(3)));
        break;
    }
  }
  return text;
}

FuzzInput FuzzCorpus::next_scene() {
  nlohmann::json scene = scenes_[below(scenes_.size())];
  if (below(4) == 0) {
    std::string text = scene.dump(below(2) ? -1 : 1);
    return {mutate_bytes(std::move(text)), false};
  }
  mutate_structure(scene, 1 + static_cast<int>(below(4)));
  return {scene.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), true};
}

FuzzInput FuzzCorpus::next_study() {
  nlohmann::json body = {{"scene", scenes_[below(scenes_.size())]}, {"steps", {0.1, 0.05}}};
  if (below(2)) body["schemes"] = {"midpoint", "hht"};
  if (below(3) == 0) body["reference_step"] = 0.01;
  if (below(4) == 0) return {mutate_bytes(body.dump()), false};
  mutate_structure(body, 1 + static_cast<int>(below(4)));
  return {body.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace), true};
}

}  // namespace stoss::test
