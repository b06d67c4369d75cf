#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer on the test suite: builds the shared instrumented
# tree build-sanitize/ (.ci/sanitize-build.sh: clang 14, -DKASHA_FUZZ=ON, which .ci/fuzz.sh then
# reuses) and runs ctest there. Any report stops the test that made it (halt_on_error) and fails
# the run. Under the sanitizers the statistical integrator tests take about 20 minutes on 2 cores,
# so by default each integrator runs its closed-form tests but not the long ones (Cornell
# agreement, the furnace scene series, the point light in a sphere, uniform sensor sampling, tests
# named Slow, and the statistical agreements whose code the closed forms run too: smooth spectra,
# the mollified joins, the smooth sphere, split photons, the fluorescent caustic, merge bias, Jung18
# fig. 1, the media scenes' lt-vs-pt agreement, whose media code the media closed forms run too: 536 of the 2094 test-seconds, about 4.5 of the 17.5 minutes on 2 cores), and the closed
# forms of the estimators whose code others' closed forms run: bdpt with its pilot (it runs
# bdpt.both's, bdpt-shared's or bdpt-independent's estimator; the pilot runs in BdptFamilies.*), vcm
# with its pilot (pt's or vcm.bidirectional's; the pilot in VcmPaths.*), and vc and bpm
# (vcm.bidirectional's code with the merges or the connections switched off). In media, bdpt's and
# vcm's closed forms with four lanes run (medium vertices, lanes ended in media, merges in volumes),
# not bdpt's with one lane, bdpt-shared's, bdpt-independent's and vc's, nor vcm's with large volume
# merges, whose code they run; bdpt's, vcm's and ppm's
# scattering furnace neither (their fluorescent furnace scatters too). Nor do the checks that the
# image does not depend on the number of threads (a property of the code's logic, checked in the
# test stage; the sanitizers here do not look for races), MPI's bit-identity for bdpt and ppm and its
# time budget (MPI's reduction and budget are the same for every integrator: pt's identity, the stop
# and every disagreement run), and the volume photons in heterogeneous media (ppm's volume photons
# run in its media closed forms, the grids in AlbedoGridMedia.Grid… and HeterogeneousMedia.Delta…).
# SANITIZE_ALL=1 runs everything.
set -euo pipefail
cd "$(dirname "$0")/.."
bash .ci/sanitize-build.sh

export ASAN_OPTIONS="halt_on_error=1:abort_on_error=1:detect_leaks=1:strict_string_checks=1:check_initialization_order=1:detect_stack_use_after_return=1"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1"
exclude=()
if [ "${SANITIZE_ALL:-0}" != "1" ]; then
  exclude=(-E '^Cornell/|Scenes/Furnace\.|PointLightInsideFluorescentSphere|UniformSensorSampling|Slow|SmoothSpectraStrategies\.|SmoothSpectra\.Agrees|MollifiedConnectionsRenderWhat|SmoothSphere\.|SplitPhotonsMeetTheFurnace|FluorescentCausticAgreement\.|MergeBias\.|Jung18Fig1\.|MediaScenes(ThroughGlass)?\.|^(bdpt|vcm|vcm\.gather|vc|bpm)\.ClosedForm\.|MediaClosedForm\..*/(bdpt_lanes1|(bdpt_shared|bdpt_independent|vc)_lanes4|vcm_lanes4_large_volume_merges)|MediaClosedForm\.ScatteringFurnace/(bdpt|vcm|ppm)_|ImageDoesNotDependOnTheThreadCount|^RenderDeterminism\.OneAndTwoThreads|^MpiRender\.(IdenticalToOneProcess\.(bdpt|ppm)|time)$|^(AlbedoGridMedia|HeterogeneousMedia)\.VolumePhotons')
fi
ctest --test-dir build-sanitize --output-on-failure -j2 "${exclude[@]}"
