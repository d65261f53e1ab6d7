#!/usr/bin/env bash
# Build one or more configurations of the same CMake project:
#   scripts/build.sh [native|asan|wasm|wasm-debug|all]...   (default: native wasm; "all" = native asan wasm)
# Build dirs: build/native (Release), build/asan (Debug -O1 + ASan/UBSan, clang: also the fuzz targets), build/wasm (Release, em++),
# build/wasm-debug (-sASSERTIONS=2 -g). Override the root with ADASCULPT_BUILD_ROOT (e.g. build/infra) to keep
# a private set of build dirs; the wasm builds publish public/wasm/adasculpt.{js,wasm} unless
# ADASCULPT_PUBLISH_WASM=OFF. Parallelism: ADASCULPT_JOBS (default 2 = this machine's cores).
# ccache is used for the native and ASan builds when installed (ADASCULPT_CCACHE=OFF turns it off).
set -euo pipefail
cd "$(dirname "$0")/.."

ROOT=${ADASCULPT_BUILD_ROOT:-build}
JOBS=${ADASCULPT_JOBS:-2}
PUBLISH=${ADASCULPT_PUBLISH_WASM:-ON}
# Debian's emscripten finds acorn (used by every optimised link) only through NODE_PATH.
export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
mkdir -p "$ROOT"
# ccache, when installed, makes rebuilds in several worktrees cheap (paths relative to the checkout).
LAUNCHER=()
if command -v ccache >/dev/null 2>&1 && [ "${ADASCULPT_CCACHE:-ON}" = ON ]; then
  export CCACHE_BASEDIR=${CCACHE_BASEDIR:-$PWD}
  LAUNCHER=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache)
fi

# Configure every time (well under a second when nothing changed) so cache options always match the request.
configure_native() {  # dir, extra cmake args...
  local dir=$1; shift
  cmake -S . -B "$dir" -G Ninja "${LAUNCHER[@]}" "$@" >"$dir.configure.log" 2>&1 || { cat "$dir.configure.log"; return 1; }
}

build_native() {
  configure_native "$ROOT/native" -DCMAKE_BUILD_TYPE=Release
  cmake --build "$ROOT/native" -j "$JOBS"
}

build_asan() {
  # clang when it is there: its objects also make the libFuzzer targets (scripts/fuzz.sh), so the fuzzers
  # cost no second compile of the core.
  local cxx=()
  command -v clang++ >/dev/null 2>&1 && cxx=(-DCMAKE_CXX_COMPILER="$(command -v clang++)")
  configure_native "$ROOT/asan" -DCMAKE_BUILD_TYPE=Debug -DADASCULPT_SANITIZE=ON "${cxx[@]}"
  cmake --build "$ROOT/asan" -j "$JOBS"
}

build_wasm() {  # dir, build type
  local dir=$1 type=$2
  # emcmake would add --experimental-wasm-threads, which node 20 rejects; give it our own emulator.
  emcmake cmake -S . -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE="$type" -DADASCULPT_PUBLISH_WASM="$PUBLISH" \
    -DCMAKE_CROSSCOMPILING_EMULATOR="/usr/bin/node;--no-experimental-fetch" \
    >"$dir.configure.log" 2>&1 || { cat "$dir.configure.log"; return 1; }
  cmake --build "$dir" -j "$JOBS"
}

targets=("$@")
((${#targets[@]})) || targets=(native wasm)
for t in "${targets[@]}"; do
  case "$t" in
    native)     build_native ;;
    asan)       build_asan ;;
    wasm)       build_wasm "$ROOT/wasm" Release ;;
    wasm-debug) build_wasm "$ROOT/wasm-debug" Debug ;;
    all)        build_native; build_asan; build_wasm "$ROOT/wasm" Release ;;
    *) echo "usage: $0 [native|asan|wasm|wasm-debug|all]..." >&2; exit 2 ;;
  esac
done
