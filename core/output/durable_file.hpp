#pragma once
/// @file Files that appear whole or not at all: data pushed to disk before a rename publishes it, and
/// the rename itself pushed to disk (a crash never leaves a torn result or checkpoint that looks
/// complete; docs/results.md).

#include <filesystem>
#include <string_view>

namespace stoss::output {

/// fsync of a file's (or a directory's) data; throws std::system_error naming the path.
void sync_to_disk(const std::filesystem::path& path);

/// Syncs `from`, renames it to `to` and syncs the directory that now holds `to`.
void rename_durably(const std::filesystem::path& from, const std::filesystem::path& to);

/// The one way a whole file is written (core and server alike): `bytes` go to `temporary` (default: the
/// path with ".tmp" appended), are synced to disk, renamed to `path` and the folder is synced, so readers
/// and a crash see the old file or all of the new one. On failure the temporary is removed.
/// @throws std::system_error naming the path.
void write_durably(const std::filesystem::path& path, std::string_view bytes,
                   const std::filesystem::path& temporary = {});

}  // namespace stoss::output
