#!/usr/bin/env bash
# The one instrumented build that .ci/sanitize.sh and .ci/fuzz.sh share (README "Reliability
# checks"): clang 14 with AddressSanitizer + UndefinedBehaviorSanitizer and libFuzzer's coverage
# instrumentation (-DKASHA_FUZZ=ON, RelWithDebInfo with line tables only: -O2 -gline-tables-only,
# enough for the sanitizers' file:line stack traces, and about half the object size of -g, which
# the CI time feels in compiling and linking ~100 test programs), the tests and the fuzz targets,
# into build-sanitize/. The tests link the sanitizers only; the fuzz targets also libFuzzer's main.
#   bash .ci/sanitize-build.sh                 # everything (the sanitizer stage)
#   bash .ci/sanitize-build.sh TARGET...       # only these targets (fuzzing on its own)
# Both stages configure with exactly these options, so the second one rebuilds nothing.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/install-deps.sh
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only -DNDEBUG" \
  -DKASHA_FUZZ=ON -DKASHA_BUILD_TESTS=ON -DKASHA_BUILD_BENCH=OFF >/dev/null
targets=()
if [ $# -gt 0 ]; then targets=(--target "$@"); fi
cmake --build build-sanitize -j2 "${targets[@]}"
