#!/usr/bin/env bash
# Formats every tracked C++ file in place with clang-format-14 and .clang-format (deploy/test.sh checks it).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
cd "$ROOT"
cpp_sources | xargs -0 -n 50 clang-format-14 -i
