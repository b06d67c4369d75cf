#!/usr/bin/env bash
# Installs the dependencies and builds kasha (Release) into build/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
