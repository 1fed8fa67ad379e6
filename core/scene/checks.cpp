#include "core/scene/checks.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "core/scene/spelling.hpp"

namespace stoss::scene::detail {

std::string child(const std::string& pointer, std::string_view key) {
  std::string escaped;
  for (char c : key) escaped += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return pointer + "/" + escaped;
}

std::string child(const std::string& pointer, size_t index) {
  return pointer + "/" + std::to_string(index);
}

std::string shown(const json& value) {
  const std::string text = value.dump();
  return text.size() <= 60 ? text : text.substr(0, 57) + "...";
}

std::string number_text(double x) {
  if (std::floor(x) == x && std::abs(x) < 1e18) return std::to_string(static_cast<long long>(x));
  return json(x).dump();
}

std::string rounded_text(double x) {
  std::ostringstream out;
  out << std::setprecision(6) << x;
  return out.str();
}

bool Interval::contains(double x) const {
  const bool above_low = low_closed ? x >= low : x > low;
  const bool below_high = high_closed ? x <= high : x < high;
  return above_low && below_high;
}

Interval above(double low) {
  return {low, INFINITY, false, false, "> " + number_text(low)};
}

Interval at_least(double low) {
  return {low, INFINITY, true, false, ">= " + number_text(low)};
}

Interval between(double low, double high, bool low_closed, bool high_closed, std::string text) {
  if (text.empty()) text = number_text(low) + ", " + number_text(high);
  return {low, high, low_closed, high_closed,
          std::string("in ") + (low_closed ? "[" : "(") + text + (high_closed ? "]" : ")")};
}

bool object_with(const json& value, const std::string& pointer,
                 std::initializer_list<std::string_view> allowed, Checker& checker) {
  if (!value.is_object()) {
    checker.fail(pointer, "must be an object, got " + shown(value));
    return false;
  }
  for (const auto& [key, ignored] : value.items())
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end())
      checker.fail(child(pointer, key), unknown_field_message(key, allowed));
  return true;
}

json* member(json& object, const char* key, const std::string& pointer, const Presence& presence,
             Checker& checker) {
  if (object.contains(key)) return &object[key];
  if (presence.kind == Presence::required) checker.fail(child(pointer, key), "required");
  if (presence.kind != Presence::defaulted) return nullptr;
  return &(object[key] = presence.fallback);
}

std::optional<double> number(const json& value, const std::string& pointer, const Interval& range,
                             Checker& checker) {
  if (!value.is_number() || !std::isfinite(value.get<double>())) {
    checker.fail(pointer, "must be a number, got " + shown(value));
    return std::nullopt;
  }
  const double x = value.get<double>();
  if (!range.contains(x)) {
    checker.fail(pointer, "must be " + range.text + ", got " + shown(value));
    return std::nullopt;
  }
  return x;
}

std::optional<long long> integer(json& value, const std::string& pointer, const Interval& range,
                                 Checker& checker) {
  const bool integral = value.is_number() && std::isfinite(value.get<double>()) &&
                        std::floor(value.get<double>()) == value.get<double>() &&
                        std::abs(value.get<double>()) <= 9007199254740992.0;
  if (!integral) {
    checker.fail(pointer, "must be an integer, got " + shown(value));
    return std::nullopt;
  }
  if (!number(value, pointer, range, checker)) return std::nullopt;
  if (std::abs(value.get<double>()) > 2147483647.0) {  // every integer of the model is an int
    checker.fail(pointer, "must fit a 32-bit integer (at most 2147483647), got " + shown(value));
    return std::nullopt;
  }
  const auto x = static_cast<long long>(value.get<double>());
  value = x;
  return x;
}

std::optional<std::string> string(const json& value, const std::string& pointer, Checker& checker) {
  if (value.is_string()) return value.get<std::string>();
  checker.fail(pointer, "must be a string, got " + shown(value));
  return std::nullopt;
}

std::optional<std::string> choice(const json& value, const std::string& pointer,
                                  const std::vector<std::string_view>& choices, Checker& checker) {
  if (value.is_string() &&
      std::find(choices.begin(), choices.end(), value.get<std::string>()) != choices.end())
    return value.get<std::string>();
  std::string list;
  for (std::string_view c : choices) list += (list.empty() ? "" : ", ") + std::string(c);
  checker.fail(pointer, "must be one of " + list + ", got " + shown(value));
  return std::nullopt;
}

std::optional<Eigen::Vector3d> vector3(const json& value, const std::string& pointer, Checker& checker) {
  const bool ok = value.is_array() && value.size() == 3 &&
                  std::all_of(value.begin(), value.end(),
                              [](const json& x) { return x.is_number() && std::isfinite(x.get<double>()); });
  if (!ok) {
    checker.fail(pointer, "must be an array of 3 numbers, got " + shown(value));
    return std::nullopt;
  }
  return Eigen::Vector3d(value[0].get<double>(), value[1].get<double>(), value[2].get<double>());
}

std::optional<std::string> name(const json& value, const std::string& pointer, Checker& checker) {
  const auto is_name_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
  };
  if (value.is_string()) {
    const auto& s = value.get_ref<const std::string&>();
    if (!s.empty() && std::all_of(s.begin(), s.end(), is_name_char)) return s;
  }
  checker.fail(pointer, "must match [A-Za-z0-9_-]+, got " + shown(value));
  return std::nullopt;
}

bool non_empty_array(const json& value, const std::string& pointer, Checker& checker) {
  if (value.is_array() && !value.empty()) return true;
  checker.fail(pointer, "must be a non-empty array, got " + shown(value));
  return false;
}

bool array(const json& value, const std::string& pointer, Checker& checker) {
  if (value.is_array()) return true;
  checker.fail(pointer, "must be an array, got " + shown(value));
  return false;
}

std::optional<double> number_field(json& object, const char* key, const std::string& pointer,
                                   const Presence& presence, const Interval& range, Checker& checker) {
  json* value = member(object, key, pointer, presence, checker);
  return value ? number(*value, child(pointer, key), range, checker) : std::nullopt;
}

std::optional<long long> integer_field(json& object, const char* key, const std::string& pointer,
                                       const Presence& presence, const Interval& range, Checker& checker) {
  json* value = member(object, key, pointer, presence, checker);
  return value ? integer(*value, child(pointer, key), range, checker) : std::nullopt;
}

std::optional<std::string> choice_field(json& object, const char* key, const std::string& pointer,
                                        const Presence& presence,
                                        const std::vector<std::string_view>& choices, Checker& checker) {
  json* value = member(object, key, pointer, presence, checker);
  return value ? choice(*value, child(pointer, key), choices, checker) : std::nullopt;
}

std::optional<Eigen::Vector3d> vector3_field(json& object, const char* key, const std::string& pointer,
                                             const Presence& presence, Checker& checker) {
  json* value = member(object, key, pointer, presence, checker);
  return value ? vector3(*value, child(pointer, key), checker) : std::nullopt;
}

}  // namespace stoss::scene::detail
