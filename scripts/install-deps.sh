#!/usr/bin/env bash
# Installs every Debian 12 package blurcull needs to build, test and render.
# Idempotent: does nothing (and prints nothing) when all are installed.
#
#   bash scripts/install-deps.sh          install what is missing
#   bash scripts/install-deps.sh --check  exit 1 and name what is missing
#   bash scripts/install-deps.sh --list   print the package list
#
# docs/building.md says why each package is here; keep the two in sync.
set -euo pipefail

packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config
  # kernel
  libglm-dev
  # tests and benchmarks
  doctest-dev libbenchmark-dev valgrind
  # frontend: scenes, CPU and Embree backends, PNG output
  libtinygltf-dev libembree-dev libstb-dev
  # compressed glTF geometry: KHR_draco_mesh_compression, EXT_meshopt_compression
  libdraco-dev libmeshoptimizer-dev
  # EXR output (-o out.exr): OpenEXR 3 and its Imath
  libopenexr-dev
  # the blurcull command: option parsing and JSON output
  libcli11-dev nlohmann-json3-dev
  # robustness: clang with libFuzzer and its sanitizer runtimes (fuzz/);
  # gcc's ASan/UBSan runtimes come with build-essential
  clang libclang-rt-14-dev
  # GL backend (planned) and shader validation
  glslang-tools libosmesa6-dev libegl-dev libgl-dev libgles-dev libgl1-mesa-dri
  libglfw3-dev xvfb xauth
)

die() {
  echo "install-deps.sh: error: $*" >&2
  exit 1
}

missing_packages() {
  local package status
  for package in "${packages[@]}"; do
    status=$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)
    if [[ "$status" != "install ok installed" ]]; then
      echo "$package"
    fi
  done
}

case "${1:-}" in
  --list)
    printf '%s\n' "${packages[@]}"
    exit 0
    ;;
  --check|"") ;;
  *) die "unknown argument '$1' (expected --check or --list)" ;;
esac

command -v dpkg-query >/dev/null 2>&1 || die "dpkg-query not found: this script supports Debian 12 only"

mapfile -t missing < <(missing_packages)
if ((${#missing[@]} == 0)); then
  exit 0
fi
if [[ "${1:-}" == "--check" ]]; then
  echo "install-deps.sh: missing packages: ${missing[*]}" >&2
  exit 1
fi

command -v apt-get >/dev/null 2>&1 || die "apt-get not found: this script supports Debian 12 only"

as_root=()
if ((EUID != 0)); then
  command -v sudo >/dev/null 2>&1 || die "not root and sudo is not installed; run as root to install: ${missing[*]}"
  as_root=(sudo)
fi

# apt's output only matters when it fails; keep it for that case.
log=$(mktemp "${TMPDIR:-/tmp}/blurcull-install-deps.XXXXXX")
trap 'rm -f "$log"' EXIT

echo "install-deps.sh: installing ${missing[*]}"
apt_env=(env DEBIAN_FRONTEND=noninteractive)
if ! "${as_root[@]}" "${apt_env[@]}" apt-get update -q </dev/null >"$log" 2>&1; then
  cat "$log" >&2
  die "apt-get update failed (output above)"
fi
if ! "${as_root[@]}" "${apt_env[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}" \
    </dev/null >"$log" 2>&1; then
  cat "$log" >&2
  die "apt-get install failed for: ${missing[*]} (output above)"
fi

mapfile -t still_missing < <(missing_packages)
if ((${#still_missing[@]} != 0)); then
  die "still not installed after apt-get: ${still_missing[*]}"
fi
