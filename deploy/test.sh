#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test with ctest.
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_dependencies
build
cd "$BUILD"
ctest --output-on-failure -j"$JOBS" --timeout 900 "$@"
