#!/usr/bin/env bash
# libFuzzer run of kasha's readers — the scene parser (JSON and Mitsuba XML), the spectrum/matrix reader, the strict OBJ
# reader, image (texture and render) input, material files and the checkpoint reader: installs
# clang (libFuzzer is in Debian's libclang-rt-<v>-dev), builds tests/fuzz with KASHA_FUZZ=ON
# (ASan + UBSan) into build-fuzz/, and runs each target for FUZZ_SECONDS (default 20) on a copy of its seed corpus
# tests/fuzz/corpus/<target>/. A finding stops the run, leaves the input as build-fuzz/crash-* /
# leak-* / timeout-* and fails the script. New inputs that grow coverage stay in
# build-fuzz/corpus/<target>/; copy the interesting ones (small!) to the seed corpus by hand.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET="${FUZZ_SECONDS:-20}"

bash .ci/install-deps.sh
CLANG_VERSION=14
need=()
command -v "clang++-${CLANG_VERSION}" >/dev/null || need+=("clang-${CLANG_VERSION}")
dpkg-query -W -f='${Status}' "libclang-rt-${CLANG_VERSION}-dev" 2>/dev/null | grep -q "install ok installed" ||
  need+=("libclang-rt-${CLANG_VERSION}-dev")
if [ ${#need[@]} -gt 0 ]; then
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  echo "fuzz: installing ${need[*]}"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${need[@]}"
fi

cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER="clang++-${CLANG_VERSION}" \
  -DKASHA_FUZZ=ON -DKASHA_BUILD_TESTS=OFF -DKASHA_BUILD_BENCH=OFF >/dev/null
TARGETS=(fuzz_scene fuzz_mitsuba fuzz_spectrum_csv fuzz_obj fuzz_image fuzz_material fuzz_checkpoint)
cmake --build build-fuzz -j2 --target "${TARGETS[@]}"

export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
rm -f build-fuzz/crash-* build-fuzz/leak-* build-fuzz/timeout-* build-fuzz/oom-*
for target in "${TARGETS[@]}"; do
  corpus="build-fuzz/corpus/${target}"
  mkdir -p "${corpus}"
  cp -n tests/fuzz/corpus/"${target}"/* "${corpus}/" 2>/dev/null || true
  echo "fuzz: ${target} for ${SECONDS_PER_TARGET} s"
  # -max_len keeps inputs scene-sized; -timeout flags a hang; -rss_limit_mb an allocation blow-up.
  status=0
  (cd build-fuzz && "./tests/fuzz/${target}" -max_total_time="${SECONDS_PER_TARGET}" -max_len=4096 -timeout=10 \
    -rss_limit_mb=2048 -dict="../tests/fuzz/${target}.dict" -print_final_stats=1 "corpus/${target}" \
    >"${target}.log" 2>&1) || status=$?
  if [ "${status}" -ne 0 ]; then
    tail -n 80 "build-fuzz/${target}.log"
    echo "fuzz: ${target} found a problem (exit ${status}); the input is in build-fuzz/ (crash-*, leak-*, timeout-*, oom-*)"
    exit 1
  fi
  grep -E '^(Done|stat::number_of_executed_units|stat::new_units_added|stat::peak_rss_mb)' "build-fuzz/${target}.log" || true
done
echo "fuzz: no findings"
