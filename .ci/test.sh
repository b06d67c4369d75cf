#!/usr/bin/env bash
# Installs, builds and runs the whole test suite through ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/build.sh
ctest --test-dir build --output-on-failure -j2
