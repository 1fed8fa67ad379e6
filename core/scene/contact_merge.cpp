#include "core/scene/contact_merge.hpp"

#include <algorithm>
#include <set>
#include <string>

namespace stoss::scene::detail {
namespace {

/// A contact side's surfaces: one name or a list.
std::vector<std::string> surfaces_of(const json& side) {
  if (side.is_string()) return {side.get<std::string>()};
  return side.get<std::vector<std::string>>();
}

std::string body_of(const json& side) {
  const std::string first = surfaces_of(side).front();
  return first.substr(0, first.find('/'));
}

bool same_slave(const json& a, const json& b) {
  const std::vector<std::string> x = surfaces_of(a["slave"]), y = surfaces_of(b["slave"]);
  return std::set<std::string>(x.begin(), x.end()) == std::set<std::string>(y.begin(), y.end());
}

/// Every field of a pair but its surfaces.
json settings_of(json pair) {
  pair.erase("slave");
  pair.erase("master");
  return pair;
}

/// "friction 0.2 here, 0 there; master_surface absent here, "faceted" there".
std::string differences(const json& here, const json& there) {
  std::set<std::string> keys;
  for (const auto& [k, v] : here.items()) keys.insert(k);
  for (const auto& [k, v] : there.items()) keys.insert(k);
  std::string out;
  for (const std::string& k : keys) {
    const auto text = [&](const json& s) { return s.contains(k) ? shown(s[k]) : std::string("not given"); };
    if (here.value(k, json()) != there.value(k, json()))
      out += (out.empty() ? "" : "; ") + k + " " + text(here) + " here, " + text(there) + " there";
  }
  return out;
}

/// The master list of merged pairs: every surface once, in order.
json union_master(const std::vector<json>& masters) {
  std::vector<std::string> all;
  for (const json& m : masters)
    for (const std::string& s : surfaces_of(m))
      if (std::find(all.begin(), all.end(), s) == all.end()) all.push_back(s);
  return all.size() == 1 ? json(all.front()) : json(all);
}

/// The pairs as written that join pair `first`: the same slave, masters on the same body.
std::vector<size_t> partners(const json& contact, size_t first, const std::vector<char>& taken) {
  std::vector<size_t> out{first};
  for (size_t j = first + 1; j < contact.size(); ++j)
    if (!taken[j] && same_slave(contact[first], contact[j]) &&
        body_of(contact[first]["master"]) == body_of(contact[j]["master"]))
      out.push_back(j);
  return out;
}

void refuse(const json& contact, size_t first, size_t j, Checker& c) {
  const json list = union_master({contact[first]["master"], contact[j]["master"]});
  c.fail("/contact/" + std::to_string(j),
         "shares slave " + shown(contact[j]["slave"]) + " with /contact/" + std::to_string(first) +
             " and its master is on the same body, so the two are one contact surface and must be one pair, "
             "but their settings differ (" +
             differences(settings_of(contact[j]), settings_of(contact[first])) +
             "): write one pair with \"master\": " + list.dump() +
             " and one set of settings (two pairs leave a seam where their masters meet)");
}

}  // namespace

std::vector<model::Model::MergedPairs> merge_contact_pairs(json& scene, Checker& c) {
  const json contact = scene["contact"];
  std::vector<char> taken(contact.size(), 0);
  json merged = json::array();
  std::vector<model::Model::MergedPairs> merges;
  const size_t start = c.mark();
  for (size_t i = 0; i < contact.size(); ++i) {
    if (taken[i]) continue;
    const std::vector<size_t> group = partners(contact, i, taken);
    std::vector<json> masters;
    for (size_t j : group) {
      taken[j] = 1;
      masters.push_back(contact[j]["master"]);
      if (settings_of(contact[j]) != settings_of(contact[i])) refuse(contact, i, j, c);
    }
    json pair = contact[i];
    if (group.size() > 1) {
      pair["master"] = union_master(masters);
      merges.push_back({int(merged.size()), std::vector<int>(group.begin(), group.end())});
    }
    merged.push_back(pair);
  }
  if (c.mark() == start) scene["contact"] = merged;
  return merges;
}

}  // namespace stoss::scene::detail
