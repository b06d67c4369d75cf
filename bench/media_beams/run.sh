#!/bin/bash
# The beam experiment of docs/media-beams.md: photon points, photon points against the camera's
# query beam, and photon beams at equal time (2 s each), seeds 1–3, five pairs of first radii
# (points; points along the query and beams), on the four media scenes of the media
# convergence report, against its references (120 s of bdpt) and at its resolutions: run
# `python3 bench/convergence/run.py bench/convergence/media_scenes.json` first. Tables to stdout.
#   bash bench/media_beams/run.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
report=build/convergence_media
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for name in uv_dye_caustic tonic_water fluorescein_cuvette lsc_slab; do
  scene="$report/$name/scene/$name.json"
  [ -f "$scene" ] || scene="scenes/$name.json"  # rendered at its own resolution
  for radii in "0.05 0.02" "0.1 0.05" "0.2 0.1" "0.4 0.2" "0.8 0.4"; do
    set -- $radii
    dirs=()
    for seed in 1 2 3; do
      d="$work/${name}_$1_$2_$seed"
      mkdir -p "$d"
      "$build/bench/beam_experiment" "$scene" 2 "$seed" "$1" "$2" "$d" > /dev/null
      dirs+=("$d")
    done
    echo "$name, first radii: points $1, beams $2"
    python3 bench/media_beams/region_errors.py "$name" "$report/references/$name.exr" "${dirs[@]}"
    echo
  done
done
