#!/usr/bin/env bash
# MPI-distributed rendering (docs/mpi.md), run by ctest:
#   mpi_render_test.sh KASHA SOURCE_DIR WORK_DIR identical INTEGRATOR
#     renders a small UV Cornell box (128×96, at most 6 bounces, 23 spp: passes of 5 samples, the last of 3) with one
#     process and with `mpirun -np 2` and `-np 3`; the EXRs (with 8 spectral bins, as in every
#     mode but error) must be the same bytes (cmp) and the
#     statistics' sample and ray counts (summed over the ranks) the same numbers; with bdpt, the
#     per-strategy images too. (That the film
#     adds the passes in pass order is tested where the order shows in the bits:
#     tests/unit/test_render_group.cpp.)
#   mpi_render_test.sh KASHA SOURCE_DIR WORK_DIR stop
#     SIGTERM to the last rank of `mpirun -np 3`: every rank stops after the same pass, exit 143,
#     the partial image and a checkpoint are written; the image equals a one-process render to
#     the same spp, and resuming the checkpoint with `-np 2` equals a one-process render to the end.
#   mpi_render_test.sh KASHA SOURCE_DIR WORK_DIR error
#     a missing scene under `mpirun -np 2`: exit code 1 with the error line (from each rank), no
#     hang, nothing written.
#   mpi_render_test.sh KASHA SOURCE_DIR WORK_DIR disagree WHAT
#     two ranks (mpirun's MPMD form, `-np 1 kasha ... : -np 1 kasha ...`) given another scene,
#     the same scene text naming a file whose content differs, seed, spp, integrator or depth (WHAT): within seconds, exit code 2 and one line from kasha,
#     `kasha: error: --mpi: rank 1 disagrees with rank 0 on FIELD (...)`, nothing written.
#   mpi_render_test.sh KASHA SOURCE_DIR WORK_DIR time
#     `--time 1` with `-np 2` ends every rank after the same pass; the image equals a one-process
#     render to the spp reached.
set -euo pipefail
kasha=$(realpath "$1") src=$(realpath "$2") work=$3 mode=$4 integrator=${5:-pt}
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }

# Open MPI in a container without a network, as root: shared memory between the ranks, the
# launcher on the loopback interface.
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_oob_tcp_if_include=lo OMPI_MCA_btl_tcp_if_include=lo
# Sanitizer builds: Open MPI's components keep allocations until exit and are unloaded by then,
# so LeakSanitizer reports them from unknown modules that no suppression can name. Leak checks
# are off here (memory errors are still caught); kasha's own leaks are checked by the
# one-process tests.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"
root=()
if [ "$(id -u)" -eq 0 ]; then root=(--allow-run-as-root); fi
mpi() { local n=$1; shift; timeout 120 mpirun "${root[@]}" --oversubscribe -np "$n" "$kasha" "$@"; }

ln -s "$src/scenes/spectra" spectra
python3 - "$src/scenes/cornell_uv.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["camera"]["resolution"] = [128, 96]
scene["render"]["max_depth"] = 6
json.dump(scene, open("scene.json", "w"), indent=1)
PY
render() { "$kasha" render scene.json --no-png -q --spectral-bins 8 "$@"; }
stat() { python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))[sys.argv[2]])' "$1" "$2"; }
same_image() { cmp "$1" "$2" || fail "$1 and $2 differ"; }

case $mode in
identical)
  # BDPT also writes its per-strategy images, which travel with the passes too.
  strategies() { if [ "$integrator" = bdpt ]; then echo --strategy-images "strategies_$1"; fi; }
  render --integrator "$integrator" --spp 23 -o one.exr $(strategies one) >/dev/null
  for n in 2 3; do
    mpi "$n" render scene.json --no-png -q --spectral-bins 8 --integrator "$integrator" --spp 23 -o "np$n.exr" $(strategies "np$n") >/dev/null
    same_image one.exr "np$n.exr"
    if [ "$integrator" = bdpt ]; then
      for f in strategies_one/*.exr; do same_image "$f" "strategies_np$n/$(basename "$f")"; done
    fi
    [ "$(stat "np$n.stats.json" ranks)" = "$n" ] || fail "np$n.stats.json: ranks is not $n"
    for key in samples rays closest_hit_rays shadow_rays spp; do
      [ "$(stat one.stats.json $key)" = "$(stat "np$n.stats.json" $key)" ] || fail "$key differs with $n ranks"
    done
  done
  ;;
stop)
  timeout 120 mpirun "${root[@]}" --oversubscribe -np 3 "$kasha" render scene.json --no-png -q --spectral-bins 8 --spp 1000000 \
    -o stopped.exr --checkpoint run.ckpt >stop.out 2>stop.err &
  launcher=$!
  # The ranks are the children of mpirun, the child of timeout: wait until the three run and the
  # render has made progress, then signal the last one.
  ranks() { local m; m=$(pgrep -P $launcher) && pgrep -P "$m"; }
  for _ in $(seq 100); do [ "$(ranks | wc -l)" -ge 3 ] && break; sleep 0.1; done
  sleep 2
  last=$(ranks | sort -n | tail -1)
  [ -n "$last" ] || { kill $launcher; fail "no ranks found under mpirun"; }
  kill -TERM "$last"
  code=0; wait $launcher || code=$?
  [ "$code" -eq 143 ] || { cat stop.err >&2; fail "mpirun exited with $code, expected 143"; }
  [ "$(stat stopped.stats.json interrupted)" = "True" ] || fail "not marked interrupted"
  [ "$(stat stopped.stats.json signal)" = "SIGTERM" ] || fail "signal not recorded"
  spp=$(stat stopped.stats.json spp)
  [ "$spp" -gt 0 ] && [ $((spp % 5)) -eq 0 ] || fail "stopped at $spp spp, not at a pass boundary"
  render --spp "$spp" -o reference_stop.exr >/dev/null
  same_image reference_stop.exr stopped.exr
  end=$((spp + 12))
  mpi 2 render scene.json --no-png -q --spectral-bins 8 --resume run.ckpt --spp "$end" -o resumed.exr >/dev/null
  render --spp "$end" -o reference_end.exr >/dev/null
  same_image reference_end.exr resumed.exr
  ;;
time)
  mpi 2 render scene.json --no-png -q --spectral-bins 8 --spp 1000000 --time 1 -o timed.exr >/dev/null
  [ "$(stat timed.stats.json interrupted)" = "False" ] || fail "a time budget is not an interruption"
  spp=$(stat timed.stats.json spp)
  [ "$spp" -gt 0 ] && [ "$spp" -lt 1000000 ] || fail "the time budget did not end the render ($spp spp)"
  render --spp "$spp" -o reference_time.exr >/dev/null
  same_image reference_time.exr timed.exr
  ;;
error)
  code=0; mpi 2 render missing.json -q >error.out 2>error.err || code=$?
  [ "$code" -eq 1 ] || fail "a missing scene under mpirun exited with $code, expected 1"
  grep -q "^kasha: error: missing.json: cannot open scene file" error.err || fail "no error line naming the file"
  [ ! -e missing.exr ] || fail "an image was written"
  ;;
disagree)
  what=$integrator
  python3 -c 'import json; s = json.load(open("scene.json")); s["camera"]["fov"] += 1; json.dump(s, open("other.json", "w"))'
  case $what in
  scene) a=(scene.json) b=(other.json) field=scene_hash ;;
  # The same scene text beside another copy of a file it names (one more comment line).
  files) mkdir -p files && cp scene.json files/ && cp -rL spectra files/spectra &&
    echo "# another copy" >>files/spectra/cornell_box_light_emission.csv
    a=(scene.json) b=(files/scene.json) field=scene_hash ;;
  seed) a=(scene.json --seed 1) b=(scene.json --seed 2) field=seed ;;
  spp) a=(scene.json --spp 4) b=(scene.json --spp 1000000) field=spp ;;
  integrator) a=(scene.json) b=(scene.json --integrator lt) field=integrator ;;
  depth) a=(scene.json --max-depth 6) b=(scene.json --max-depth 5) field=max_depth ;;
  *) fail "unknown disagreement $what" ;;
  esac
  common=(-q --no-png --spectral-bins 8 -o mixed.exr)
  start=$SECONDS code=0
  timeout 60 mpirun "${root[@]}" --oversubscribe -np 1 "$kasha" render "${a[@]}" "${common[@]}" : \
    -np 1 "$kasha" render "${b[@]}" "${common[@]}" >disagree.out 2>disagree.err || code=$?
  [ "$code" -ne 124 ] || fail "ranks given another $what hang"
  [ "$code" -eq 2 ] || { cat disagree.err >&2; fail "ranks given another $what exited with $code, expected 2"; }
  [ $((SECONDS - start)) -le 30 ] || fail "ranks given another $what took $((SECONDS - start)) s to stop"
  [ "$(grep -c '^kasha: ' disagree.err)" -eq 1 ] || { cat disagree.err >&2; fail "not one line from kasha"; }
  grep -q "^kasha: error: --mpi: rank 1 disagrees with rank 0 on $field (" disagree.err ||
    { cat disagree.err >&2; fail "no error line naming $field"; }
  [ ! -e mixed.exr ] || fail "an image was written"
  ;;
*) fail "unknown mode $mode" ;;
esac
echo "mpi_render_test $mode $integrator: ok"
