#!/usr/bin/env bash
# Long missions under memory checkers, to run before a release (hours of CPU; not per-commit CI).
# docs/robustness.md says what each checker finds and what the last run reported.
#
#   bash tools/memory-check-missions.sh [OUT_DIR] [DURATION_S] [SEED]
#
# 1. Builds build-asan (AddressSanitizer + UndefinedBehaviorSanitizer, -DMSB_SANITIZE=ON) and runs
#    MonoSpheres and the grid baseline in the cave and in urban (seed 1 by default), two missions at
#    a time.
# 2. Runs the same missions with the release build under glibc's malloc checks
#    (libc_malloc_debug.so.0, MALLOC_CHECK_=3) and MALLOC_PERTURB_=165, which make a write into
#    freed memory fail close to the damage (a corrupted free list) and a read of freed memory
#    see 0xa5 bytes.
# A mission that ends with a checker report, a signal or a timeout (4x the mission's simulated
# time) is listed at the end and the script exits 1.
set -uo pipefail
cd "$(dirname "$0")/.."
out=${1:-/tmp/msbench-memory-check}
duration=${2:-1200}
seed=${3:-1}
mkdir -p "$out"
bash tools/install-deps.sh >/dev/null
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null && cmake --build build -j2 --target msbench >/dev/null || exit 2
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Release -DMSB_SANITIZE=ON >/dev/null &&
  cmake --build build-asan -j2 --target msbench >/dev/null || exit 2

missions=(cave cave_grid urban urban_grid)
timeout_s=$((4 * duration + 600))
summary="$out/summary.txt"
: > "$summary"

# run LABEL EXE SCENARIO [ENV...]: one mission; a line in the summary.
run() {
  local label=$1 exe=$2 scenario=$3
  shift 3
  local dir="$out/$label-$scenario" start
  start=$(date +%s)
  env "$@" timeout -s KILL "$timeout_s" "$exe" run "scenarios/missions/$scenario.yaml" --seed "$seed" \
    --duration "$duration" --out "$dir" --overwrite --quiet > "$dir.log" 2>&1
  local rc=$?
  local verdict=clean
  if grep -qE "ERROR: AddressSanitizer|runtime error:|malloc\(\)|free\(\)|corrupted|fatal signal" "$dir.log"; then
    verdict=REPORT
  elif [ "$rc" -eq 137 ]; then
    verdict=TIMEOUT
  elif [ "$rc" -ne 0 ]; then
    verdict="EXIT-$rc"
  fi
  echo "$label $scenario: $verdict (exit $rc, $(( $(date +%s) - start )) s wall) $(grep -o 'hash [0-9a-f]*' "$dir.log")" |
    tee -a "$summary"
}

asan_env=(ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1)
perturb_env=(LD_PRELOAD=libc_malloc_debug.so.0 MALLOC_CHECK_=3 MALLOC_PERTURB_=165)
for i in 0 2; do
  run asan build-asan/bin/msbench "${missions[$i]}" "${asan_env[@]}" &
  run asan build-asan/bin/msbench "${missions[$((i + 1))]}" "${asan_env[@]}" &
  wait
done
for i in 0 2; do
  run perturb build/bin/msbench "${missions[$i]}" "${perturb_env[@]}" &
  run perturb build/bin/msbench "${missions[$((i + 1))]}" "${perturb_env[@]}" &
  wait
done

echo "memory-check-missions: summary in $summary"
if grep -qv ": clean " "$summary"; then
  echo "memory-check-missions: not clean:"
  grep -v ": clean " "$summary"
  exit 1
fi
echo "memory-check-missions: all clean"
