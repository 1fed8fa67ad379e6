#pragma once
/// @file The web page at `/` (docs/web.md): its own files (server/web/*.html, *.css, *.js), Debian's
/// dygraphs (libjs-dygraphs) and the example scenes of api/examples, compiled into the binary at build time
/// by server/web/embed.cmake, so the page needs no network and no file at run time.

#include <optional>
#include <span>
#include <string_view>

namespace stoss::server::web {

/// A file as it was at build time: its name (no directory) and its bytes.
struct EmbeddedFile {
  std::string_view name;
  std::string_view bytes;
};

/// The page's assets: index.html, stoss.css, stoss.js, dygraph.min.js, dygraph.min.css (generated).
std::span<const EmbeddedFile> embedded_assets();

/// Every api/examples/*.json, by file name (generated).
std::span<const EmbeddedFile> embedded_examples();

/// An asset to serve: its bytes and its media type.
struct Asset {
  std::string_view bytes;
  std::string_view media_type;
};

/// The asset named `name` (e.g. "stoss.js"); nullopt for a name that is not one.
std::optional<Asset> find_asset(std::string_view name);

}  // namespace stoss::server::web
