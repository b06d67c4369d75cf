#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer: builds kasha and the tests with KASHA_SANITIZE=ON
# (RelWithDebInfo: -O2 -g) into build-asan/ and runs ctest there. Any report stops the test that
# made it (halt_on_error) and fails the run. Under the sanitizers the statistical integrator tests
# take about 20 minutes on 2 cores, so by default each integrator runs its closed-form tests but
# not the long ones (Cornell agreement, the furnace scene series, the point light in a sphere,
# uniform sensor sampling, tests named Slow): about 5 minutes. SANITIZE_ALL=1 runs everything.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/install-deps.sh
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DKASHA_SANITIZE=ON -DKASHA_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan -j2

export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_string_checks=1:check_initialization_order=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
exclude=()
if [ "${SANITIZE_ALL:-0}" != "1" ]; then
  exclude=(-E '^Cornell/|Scenes/Furnace\.|PointLightInsideFluorescentSphere|UniformSensorSampling|Slow')
fi
ctest --test-dir build-asan --output-on-failure -j2 "${exclude[@]}"
