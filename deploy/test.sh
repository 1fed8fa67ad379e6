#!/usr/bin/env bash
# Installs what is missing, checks the C++ formatting (deploy/format.sh fixes it), builds, and runs every
# test with ctest.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_dependencies
check_format
build
cd "$BUILD"
ctest --output-on-failure -j"$JOBS" --timeout 900 "$@"
