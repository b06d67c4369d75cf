#!/usr/bin/env bash
# libFuzzer run of kasha's readers — the scene parser (JSON and Mitsuba XML), the spectrum/matrix reader, the strict OBJ
# reader, the PLY check with assimp behind it, the Mitsuba serialized mesh reader, image (texture and render) input, material files, the
# checkpoint reader and Mitsuba's volume grids: builds the fuzz targets of tests/fuzz in the instrumented tree that .ci/sanitize.sh shares
# (.ci/sanitize-build.sh: clang 14, -DKASHA_FUZZ=ON, ASan + UBSan, into build-sanitize/; after the
# sanitizer stage there is nothing left to build), and runs each target for FUZZ_SECONDS (default
# 9) on a copy of its seed corpus tests/fuzz/corpus/<target>/. A finding stops the run, leaves the
# input as build-sanitize/crash-* / leak-* / timeout-* and fails the script. New inputs that grow
# coverage stay in build-sanitize/corpus/<target>/; copy the interesting ones (small!) to the seed
# corpus by hand.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET="${FUZZ_SECONDS:-9}"
BUILD=build-sanitize

TARGETS=(fuzz_scene fuzz_mitsuba fuzz_spectrum_csv fuzz_obj fuzz_ply fuzz_serialized fuzz_image fuzz_material fuzz_checkpoint fuzz_volume_grid)
bash .ci/sanitize-build.sh "${TARGETS[@]}"

export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
rm -f "${BUILD}"/crash-* "${BUILD}"/leak-* "${BUILD}"/timeout-* "${BUILD}"/oom-*
for target in "${TARGETS[@]}"; do
  corpus="${BUILD}/corpus/${target}"
  mkdir -p "${corpus}"
  cp -n tests/fuzz/corpus/"${target}"/* "${corpus}/" 2>/dev/null || true
  echo "fuzz: ${target} for ${SECONDS_PER_TARGET} s"
  # -max_len keeps inputs scene-sized; -timeout flags a hang; -rss_limit_mb an allocation blow-up.
  status=0
  (cd "${BUILD}" && "./tests/fuzz/${target}" -max_total_time="${SECONDS_PER_TARGET}" -max_len=4096 -timeout=10 \
    -rss_limit_mb=2048 -dict="../tests/fuzz/${target}.dict" -print_final_stats=1 "corpus/${target}" \
    >"${target}.log" 2>&1) || status=$?
  if [ "${status}" -ne 0 ]; then
    tail -n 80 "${BUILD}/${target}.log"
    echo "fuzz: ${target} found a problem (exit ${status}); the input is in ${BUILD}/ (crash-*, leak-*, timeout-*, oom-*)"
    exit 1
  fi
  grep -E '^(Done|stat::number_of_executed_units|stat::new_units_added|stat::peak_rss_mb)' "${BUILD}/${target}.log" || true
done
echo "fuzz: no findings"
