#!/usr/bin/env bash
# Configures the core-only AddressSanitizer + UBSan build (clang 16) in the
# directory $1, with the libFuzzer targets under fuzz/: one build serves the
# unit tests under sanitizers (scripts/sanitize.sh) and the fuzzers
# (scripts/fuzz.sh), so make test pays for one sanitized build, not two.
# Sourced or run; exits non-zero when the compiler is missing or CMake fails.
set -uo pipefail
build_dir=$1
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# clang 16: clang 14 rejects the core's lambdas that capture structured
# bindings (a C++20 feature GCC and clang >= 16 accept in C++17 mode).
cxx=${SANITIZE_CXX:-clang++-16}
cc=${SANITIZE_CC:-clang-16}
command -v "$cxx" >/dev/null || { echo "sanitizer build: $cxx missing (scripts/install_deps.sh installs it)" >&2; exit 1; }
# CMake cannot switch compilers in place: start over when configured with another.
if [[ -f "$build_dir/CMakeCache.txt" ]] && ! grep -q "CMAKE_CXX_COMPILER:.*=$(command -v "$cxx")\$" "$build_dir/CMakeCache.txt"; then
  rm -rf "$build_dir"
fi
# Eigen switches to its own aligned malloc (offset stored before each block)
# under AddressSanitizer, while the prebuilt PCL frees and allocates with
# plain malloc: clouds crossing the boundary then look like heap overflows in
# handmade_aligned_free. Keep the ABI of the system libraries.
eigen_flags="-DEIGEN_MALLOC_ALREADY_ALIGNED=1"
# Line tables are all a sanitizer report needs (file:line in each frame); full
# debug info of the PCL-heavy code only makes the build slower.
CC=$cc CXX=$cxx cmake -S "$root" -B "$build_dir" -DBRICK_POSE_CORE_ONLY=ON -DBRICK_POSE_SANITIZE=ON \
  -DBRICK_POSE_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS="$eigen_flags" \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" >/dev/null || { echo "sanitizer build: configure failed" >&2; exit 1; }
