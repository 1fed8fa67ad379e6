#pragma once
/// @file JSON from untrusted text (request bodies, scene files): nesting is capped before the recursive
/// parser runs, and every parser error (syntax, a number out of the range of double) becomes one
/// JsonInputError with the byte offset where it is known. Never a crash, never an uncaught exception.

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>

namespace stoss::server {

/// Deepest nesting of arrays and objects accepted (the scene format needs 6).
inline constexpr int max_json_depth = 256;

/// Why a text is not usable JSON.
class JsonInputError : public std::runtime_error {
 public:
  enum class Kind { syntax, too_deep };
  JsonInputError(Kind kind, const std::string& message, std::optional<std::size_t> byte)
      : std::runtime_error(message), kind(kind), byte(byte) {}
  Kind kind;
  std::optional<std::size_t> byte;  ///< 1-based offset of the error, when known
};

/// The byte offset (0-based) of the first bracket that opens level `max_depth + 1`, or nullopt when the
/// text nests no deeper than `max_depth`. Brackets inside strings do not count; the text need not be
/// valid JSON (a single linear pass, no recursion).
std::optional<std::size_t> nesting_beyond(std::string_view text, int max_depth = max_json_depth);

/// Parses `text`. Throws JsonInputError (too_deep before any parsing; syntax for anything the parser
/// refuses, with nlohmann's message stripped of its "[json.exception…] " tag).
nlohmann::json parse_json_input(std::string_view text, int max_depth = max_json_depth);

/// True when the first non-blank byte of `text` can start a JSON document that holds a scene or a
/// study ('{' or '[').
bool looks_like_json(std::string_view text);

/// `j` as text; invalid UTF-8 (e.g. a string cut inside a multi-byte character) is replaced by U+FFFD,
/// never thrown on.
std::string safe_dump(const nlohmann::json& j, int indent = -1);

}  // namespace stoss::server
