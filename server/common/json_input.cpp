#include "server/common/json_input.hpp"

namespace stoss::server {

namespace {

/// nlohmann's message without its "[json.exception.parse_error.101] " prefix.
std::string plain_message(const std::exception& e) {
  std::string text = e.what();
  if (text.rfind("[json.exception.", 0) == 0) {
    const auto end = text.find("] ");
    if (end != std::string::npos) text.erase(0, end + 2);
  }
  return text;
}

}  // namespace

std::optional<std::size_t> nesting_beyond(std::string_view text, int max_depth) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
      continue;
    }
    switch (c) {
      case '"':
        in_string = true;
        break;
      case '[':
      case '{':
        if (++depth > max_depth) return i;
        break;
      case ']':
      case '}':
        if (depth > 0) --depth;
        break;
      default:
        break;
    }
  }
  return std::nullopt;
}

nlohmann::json parse_json_input(std::string_view text, int max_depth) {
  if (auto at = nesting_beyond(text, max_depth))
    throw JsonInputError(JsonInputError::Kind::too_deep,
                         "JSON nested deeper than " + std::to_string(max_depth) +
                             " levels (limit max_json_depth = " + std::to_string(max_depth) + ") at byte " +
                             std::to_string(*at + 1),
                         *at + 1);
  try {
    return nlohmann::json::parse(text.begin(), text.end());
  } catch (const nlohmann::json::parse_error& e) {
    throw JsonInputError(JsonInputError::Kind::syntax, plain_message(e), e.byte);
  } catch (const nlohmann::json::exception& e) {  // e.g. 1e400: out of the range of double
    throw JsonInputError(JsonInputError::Kind::syntax, plain_message(e), std::nullopt);
  }
}

bool looks_like_json(std::string_view text) {
  for (char c : text) {
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') continue;
    return c == '{' || c == '[';
  }
  return false;
}

std::string safe_dump(const nlohmann::json& j, int indent) {
  return j.dump(indent, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace stoss::server
