# Shared by run.sh and test.sh: install what is missing, configure and build (Release).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD="${STOSS_BUILD_DIR:-$ROOT/build}"
JOBS="${STOSS_JOBS:-$(nproc)}"

install_dependencies() {
  local missing=()
  while read -r pkg; do
    [[ -z "$pkg" || "$pkg" == \#* ]] && continue
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
  done <"$ROOT/deploy/packages.txt"
  if ((${#missing[@]})); then
    echo "deploy: installing ${missing[*]}"
    local sudo=""
    [[ $(id -u) -ne 0 ]] && sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
  fi
}

build() {
  if [[ ! -f "$BUILD/CMakeCache.txt" ]]; then
    cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
  fi
  cmake --build "$BUILD" -j"$JOBS"
}

# Every tracked C++ file is formatted by .clang-format with clang-format-14 (deploy/packages.txt), the one
# binary every machine has alike. Fails naming the files that deviate; `deploy/format.sh` rewrites them.
cpp_sources() {
  if git -C "$ROOT" rev-parse --git-dir >/dev/null 2>&1; then
    git -C "$ROOT" ls-files -z -- '*.cpp' '*.hpp'
  else
    (cd "$ROOT" && find core server tests bench \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' \) -print0)
  fi
}

check_format() {
  local deviating
  deviating=$(cd "$ROOT" && cpp_sources | xargs -0 -n 50 clang-format-14 --dry-run -Werror 2>&1 |
    sed -n 's/^\([^:]*\):[0-9]*:[0-9]*: error:.*/\1/p' | sort -u || true)
  if [[ -n "$deviating" ]]; then
    echo "deploy: these files deviate from .clang-format (run ./deploy/format.sh):" >&2
    echo "$deviating" >&2
    return 1
  fi
}
