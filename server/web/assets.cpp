#include "server/web/assets.hpp"

namespace stoss::server::web {

namespace {

std::string_view media_type_of(std::string_view name) {
  auto ends_with = [&](std::string_view suffix) {
    return name.size() >= suffix.size() && name.substr(name.size() - suffix.size()) == suffix;
  };
  if (ends_with(".html")) return "text/html; charset=utf-8";
  if (ends_with(".css")) return "text/css; charset=utf-8";
  if (ends_with(".js")) return "text/javascript; charset=utf-8";
  return "application/octet-stream";
}

}  // namespace

std::optional<Asset> find_asset(std::string_view name) {
  for (const EmbeddedFile& file : embedded_assets())
    if (file.name == name) return Asset{file.bytes, media_type_of(name)};
  return std::nullopt;
}

}  // namespace stoss::server::web
