#pragma once
/// @file Files that appear whole or not at all: data pushed to disk before a rename publishes it, and
/// the rename itself pushed to disk (a crash never leaves a torn result or checkpoint that looks
/// complete; docs/results.md).

#include <filesystem>

namespace stoss::output {

/// fsync of a file's (or a directory's) data; throws std::system_error naming the path.
void sync_to_disk(const std::filesystem::path& path);

/// Syncs `from`, renames it to `to` and syncs the directory that now holds `to`.
void rename_durably(const std::filesystem::path& from, const std::filesystem::path& to);

}  // namespace stoss::output
