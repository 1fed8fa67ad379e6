#pragma once
/// @file "Did you mean": the closest allowed name to a misspelt one (unknown fields).

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

namespace stoss::scene::detail {

/// Levenshtein distance (insertions, deletions and substitutions of one character each cost 1).
size_t edit_distance(std::string_view a, std::string_view b);

/// The allowed name closest to `name` when it is a plausible slip: at most 2 edits, and fewer than a
/// third of the longer name's characters (so "mu" suggests nothing, "intial_velocity" suggests
/// "initial_velocity"). Ties go to the first in `allowed`.
std::optional<std::string> closest_name(std::string_view name,
                                        std::initializer_list<std::string_view> allowed);

/// "unknown field", followed by "; did you mean \"initial_velocity\"?" when closest_name finds one.
std::string unknown_field_message(std::string_view key, std::initializer_list<std::string_view> allowed);

}  // namespace stoss::scene::detail
