#!/usr/bin/env bash
# The whole test suite, after scripts/bootstrap.sh --tests has built ./build with its tests:
#   1. every test of the normal build (CPU, GL on llvmpipe, VM device tests, the one-node
#      Slurm cluster of label `cluster`), but the package test: ctest -LE package
#   2. the CPU unit tests under ASan + UBSan (build-asan/)
#   3. the threaded runtime tests under TSan (build-tsan/)
#   4. every libFuzzer target for a short fixed time on its seed corpus (build-fuzz/)
# Usage: scripts/test.sh [--quick | --package]
#   --quick: step 1 without the VM and cluster tests (ctest -LE 'vm|cluster|package'): the CPU, GL,
#   OpenXR and SDK tests; the other steps do not run.
#   --package: only the Debian package test (label `package`, in no other run: it builds
#   the package in build-pkg/, about 20 min on 2 cores the first time, and needs root,
#   mmdebstrap, lintian and Debian's mirror; docs/install.md).
# FOVEAL_FUZZ_SECONDS (default 15) sets the time per fuzz target. docs/testing.md.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
ctest_only=(-LE package)
case "${1:-}" in
  "") ;;
  --quick) ctest_only=(-LE 'vm|cluster|package') ;;
  --package) ctest_only=(-L package) ;;
  -h|--help) sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
  *) echo "scripts/test.sh: unknown argument '$1' (usage: scripts/test.sh [--quick | --package])" >&2; exit 2 ;;
esac

step() { printf '\n== %s (%s)\n' "$*" "$(date -u +%H:%M:%S)"; }
step "1: ctest ${ctest_only[*]}"

# ctest's own summary lists skipped tests among many lines; one closing line names them and
# why (the tests' GTEST_SKIP reasons, from ctest's log), so a plain clone without an OpenXR
# runtime says which tests it did not run.
ctest_log=$(mktemp)
trap 'rm -f "$ctest_log"' EXIT
set +e
ctest --test-dir build --output-on-failure -j"$jobs" ${ctest_only[@]+"${ctest_only[@]}"} 2>&1 | tee "$ctest_log"
ctest_rc=${PIPESTATUS[0]}
set -e
not_run=$(sed -n '/^The following tests did not run:/,/^$/s/^[[:space:]]*[0-9][0-9]* - \(.*\)$/\1/p' "$ctest_log" |
  paste -sd ',' - | sed 's/,/, /g')
if [[ -n "$not_run" ]]; then
  why=$(grep -h -A1 ': Skipped$' build/Testing/Temporary/LastTest.log 2>/dev/null | grep -v -e ': Skipped$' -e '^--$' |
    sort -u | paste -sd ';' - | sed 's/;/; /g')
  echo "ctest: not run: $not_run${why:+ (why: $why)}"
else
  echo "ctest: every test ran"
fi
(( ctest_rc == 0 )) || exit "$ctest_rc"
[[ "${1:-}" == "--quick" || "${1:-}" == "--package" ]] && exit 0

source scripts/compiler_cache.sh

step "ASan + UBSan: CPU unit tests"
# -O1 without debug info compiles about twice as fast; reports then name functions, not
# lines (rebuild with -DCMAKE_CXX_FLAGS_DEBUG="-O1 -g" to dig in).
fast=(-DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG=-O1 -DCMAKE_C_FLAGS_DEBUG=-O1 -DFOVEAL_BUILD_BENCHMARKS=OFF)
cmake -S . -B build-asan -G Ninja "${fast[@]}" "${launcher[@]}" -DFOVEAL_SANITIZE=address,undefined > /dev/null
ninja -C build-asan -j"$jobs" foveal_core_tests foveal_profile_tests foveal_control_tests foveal_exchange_tests \
  foveal_daemon_tests foveal_calibration_tests foveal_filter_tests foveal_hid_tests foveal_usb_tests \
  foveal_image_tests foveal_gltf_tests foveal_probe_tests foveal_quality_tests foveal_quality_cli_tests \
  foveal_study_tests foveal_bench_sweep_tests foveal_fuzz_regressions foveal_client_tests foveal_rmfr_tests foveal foveald \
  foveal_head_tests foveal_vive_tests foveal_frame_timing_tests foveal_perception_tests foveal_levels_tests \
  foveal_bench_merge_input_tests foveal_camera_path_tests foveal_gaze_video_tests foveal_openxr_quad_tests
# foveald's integration tests render through Mesa, whose allocations outlive the process
# by design: they run in the normal build; every other CPU test runs with leak checks.
ctest --test-dir build-asan -L cpu -E 'Foveald' --output-on-failure -j"$jobs"

step "TSan: threaded runtime tests"
cmake -S . -B build-tsan -G Ninja "${fast[@]}" "${launcher[@]}" -DFOVEAL_SANITIZE=thread > /dev/null
ninja -C build-tsan -j"$jobs" foveal_exchange_tests foveal_daemon_tests foveal_control_tests foveal_client_tests \
  foveal_head_tests
ctest --test-dir build-tsan -R 'SeqLock|FoveaShm|PoseTrack|GazeLoop|LatencyHistogram|ControlSocket|FovealClient|HeadTracker' --output-on-failure -j"$jobs"

step "libFuzzer: each target ${FOVEAL_FUZZ_SECONDS:-15} s"
CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DFOVEAL_FUZZ=ON "${fast[@]}" "${launcher[@]}" > /dev/null
targets=(fuzz_gaze_log fuzz_import fuzz_profile fuzz_control fuzz_hid fuzz_psvr2 fuzz_display fuzz_gltf fuzz_hmd fuzz_vive fuzz_shard)
ninja -C build-fuzz -j"$jobs" "${targets[@]}"
for t in "${targets[@]}"; do
  corpus=$(mktemp -d)
  cp -r "tests/fuzz/corpus/${t#fuzz_}/." "$corpus/"
  if ! build-fuzz/bin/"$t" "$corpus" -max_total_time="${FOVEAL_FUZZ_SECONDS:-15}" -print_final_stats=1 \
       > "$corpus.log" 2>&1; then
    tail -40 "$corpus.log"
    echo "fuzz: $t found a crash (crash-* in $PWD): keep it in tests/fuzz/regressions/${t#fuzz_}/ once fixed"
    exit 1
  fi
  echo "$t: $(grep -o 'stat::number_of_executed_units: [0-9]*' "$corpus.log" | cut -d' ' -f2) executions"
  rm -rf "$corpus" "$corpus.log"
done
step "all passed"
