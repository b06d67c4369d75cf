#!/bin/bash
# The beam experiment of docs/media-beams.md: photon points and photon beams on uv_dye_caustic at
# equal time (2 s each), three seeds, five pairs of first radii (points, beams), against the media
# convergence report's reference (120 s of bdpt; run bench/convergence/run.py
# bench/convergence/media_scenes.json first). Writes the table to stdout.
#   bash bench/media_beams/run.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
reference=build/convergence_media/references/uv_dye_caustic.exr
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for radii in "0.05 0.02" "0.1 0.05" "0.2 0.1" "0.4 0.2" "0.8 0.4"; do
  set -- $radii
  dirs=()
  for seed in 1 2 3; do
    d="$work/$1_$2_$seed"
    mkdir -p "$d"
    "$build/bench/beam_experiment" scenes/uv_dye_caustic.json 2 "$seed" "$1" "$2" "$d" > /dev/null
    dirs+=("$d")
  done
  echo "first radii: points $1, beams $2"
  python3 bench/media_beams/region_errors.py "$reference" "${dirs[@]}"
  echo
done
