#!/usr/bin/env bash
# Installs what is missing, builds, and starts the service on 127.0.0.1:8080 with SQLite in ./var/.
# Extra arguments go to `stoss serve` (e.g. --listen 127.0.0.1:9000 --workers 2).
source "$(dirname "${BASH_SOURCE[0]}")/common.sh"
install_dependencies
build
mkdir -p "$ROOT/var"
exec "$BUILD/stoss" serve --listen 127.0.0.1:8080 --data "$ROOT/var" "$@"
