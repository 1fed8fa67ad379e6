#pragma once
/// @file Field-level checks of the scene validator: each reports an Issue naming the JSON pointer,
/// the rule and the value it got, and returns the checked value or nothing.

#include <Eigen/Core>
#include <filesystem>
#include <initializer_list>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "core/scene/scene.hpp"

namespace stoss::scene::detail {

using nlohmann::json;

/// Collects the issues found while a scene is walked.
class Checker {
 public:
  void fail(const std::string& pointer, const std::string& message) { issues_.push_back({pointer, message}); }
  const std::vector<Issue>& issues() const { return issues_; }
  /// Number of issues so far; compare two marks to see whether a part of the scene was clean.
  size_t mark() const { return issues_.size(); }

  /// Where mesh files ("mesh": {"file": ...} or {"id": ...}) are read (see MeshFiles).
  MeshFiles mesh_files;
  /// "body/surface" → why a surface the body's mesh file defines is not on the body (appended to the
  /// issue of a reference to it).
  std::map<std::string, std::string> surface_notes;
  /// body → the node sets (Abaqus *NSET) of its mesh file, which a boundary entry may name like a surface.
  std::map<std::string, std::set<std::string>> node_sets;

 private:
  std::vector<Issue> issues_;
};

/// RFC 6901 pointer of an object member (escapes '~' and '/') or of an array element.
std::string child(const std::string& pointer, std::string_view key);
std::string child(const std::string& pointer, size_t index);

/// The value as compact JSON for a message, shortened when long.
std::string shown(const json& value);

/// A number as a user would write it: 0 rather than 0.0, 1e-10 rather than 1.0000000000000001e-10.
std::string number_text(double x);
/// A computed number to 6 significant digits (no round-off noise in messages).
std::string rounded_text(double x);

/// A number interval with the text used in messages, e.g. "(-1, 0.5)" or "> 0".
struct Interval {
  double low, high;
  bool low_closed, high_closed;
  std::string text;  ///< printed after "must be "
  bool contains(double x) const;
};
Interval above(double low);     ///< (low, ∞): "> low"
Interval at_least(double low);  ///< [low, ∞): ">= low"
Interval between(double low, double high, bool low_closed, bool high_closed, std::string text = "");

/// Whether an absent member is an error, gets a default, or stays absent.
struct Presence {
  enum Kind { required, defaulted, optional } kind;
  json fallback;
  static Presence must() { return {required, nullptr}; }
  static Presence or_default(json value) { return {defaulted, std::move(value)}; }
  static Presence may() { return {optional, nullptr}; }
};

/// Checks `value` is an object whose members are all in `allowed`; reports each other one as
/// "unknown field". Returns false (after "must be an object") when it is not an object.
bool object_with(const json& value, const std::string& pointer,
                 std::initializer_list<std::string_view> allowed, Checker& checker);

/// The member `key` of `object`, after applying `presence`: nullptr when absent (reported if required).
json* member(json& object, const char* key, const std::string& pointer, const Presence& presence,
             Checker& checker);

/// Typed checks of one value at `pointer`.
std::optional<double> number(const json& value, const std::string& pointer, const Interval& range,
                             Checker& checker);
/// Accepts integral numbers (6 or 6.0) and normalises `value` to an integer.
std::optional<long long> integer(json& value, const std::string& pointer, const Interval& range,
                                 Checker& checker);
std::optional<std::string> string(const json& value, const std::string& pointer, Checker& checker);
std::optional<std::string> choice(const json& value, const std::string& pointer,
                                  const std::vector<std::string_view>& choices, Checker& checker);
std::optional<Eigen::Vector3d> vector3(const json& value, const std::string& pointer, Checker& checker);
/// A string of [A-Za-z0-9_-]+ (body and surface names).
std::optional<std::string> name(const json& value, const std::string& pointer, Checker& checker);
/// A non-empty array, or an issue "must be a non-empty array".
bool non_empty_array(const json& value, const std::string& pointer, Checker& checker);
/// An array (possibly empty), or an issue "must be an array".
bool array(const json& value, const std::string& pointer, Checker& checker);

/// Member shorthands: member() followed by the typed check at the member's pointer.
std::optional<double> number_field(json& object, const char* key, const std::string& pointer,
                                   const Presence& presence, const Interval& range, Checker& checker);
std::optional<long long> integer_field(json& object, const char* key, const std::string& pointer,
                                       const Presence& presence, const Interval& range, Checker& checker);
std::optional<std::string> choice_field(json& object, const char* key, const std::string& pointer,
                                        const Presence& presence,
                                        const std::vector<std::string_view>& choices, Checker& checker);
std::optional<Eigen::Vector3d> vector3_field(json& object, const char* key, const std::string& pointer,
                                             const Presence& presence, Checker& checker);

}  // namespace stoss::scene::detail
