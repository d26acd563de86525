#!/bin/bash
# Every command that writes, on a real full file system (a small tmpfs; docs/robustness.md, "No
# unchecked write"): it fails naming the path and "No space left on device" (or, for a run's
# video, writes the run without it), keeps no half-written file or temporary, and replaces no
# existing file. Needs root to mount the tmpfs: exit 77 (ctest: skipped) where it cannot.
#   full_disk_test.sh MSBENCH SOURCE_DIR
set -u
M=$1 S=$2
if [ "$(id -u)" != 0 ]; then echo "SKIP: mounting a tmpfs needs root"; exit 77; fi
D=$(mktemp -d /tmp/msb_full_disk.XXXXXX)
mkdir "$D/fs"
if ! mount -t tmpfs -o size=160k tmpfs "$D/fs" 2>/dev/null; then
  rm -rf "$D"; echo "SKIP: cannot mount a tmpfs here"; exit 77
fi
trap 'umount "$D/fs" 2>/dev/null; rm -rf "$D"' EXIT
SCEN=$S/scenarios/missions/test_world_short.yaml
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }
# The tmpfs holds exactly the entries named (no temporary, no .partial left).
only() { local got; got=$(cd "$D/fs" && ls -A | xargs); [ "$got" = "$*" ] || fail "left on the disk: '$got', expected '$*'"; }
fill() { dd if=/dev/zero of="$D/fs/filler" bs=1k count=400 >/dev/null 2>&1; }  # until the disk is full

# A run's results (about 180 kB) on a 160 kB disk.
"$M" run "$SCEN" --duration 20 --quiet --out "$D/fs/run" >"$D/log" 2>&1; rc=$?
[ $rc -eq 1 ] && grep -q "No space left on device" "$D/log" && grep -q "$D/fs/run" "$D/log" || fail "run: rc $rc: $(cat "$D/log")"
only ""

# A golden replaced by regress --update on a full disk stays as it was.
"$M" run "$SCEN" --duration 10 --quiet --out "$D/run" >/dev/null 2>&1 || fail "run (off the tmpfs)"
printf 'scenario: %s\nset: {duration_s: 10}\nseeds: [1]\n' "$SCEN" >"$D/sweep.yaml"
"$M" sweep "$D/sweep.yaml" --out "$D/sweep" --jobs 1 >/dev/null 2>&1 || fail "sweep (off the tmpfs)"
"$M" regress "$D/sweep" --against "$D/fs/golden.json" --update >"$D/log" 2>&1 || fail "regress --update: $(cat "$D/log")"
before=$(md5sum <"$D/fs/golden.json")
fill
"$M" regress "$D/sweep" --against "$D/fs/golden.json" --update >"$D/log" 2>&1; rc=$?
[ $rc -eq 1 ] && grep -q "No space left on device" "$D/log" || fail "regress --update on a full disk: rc $rc: $(cat "$D/log")"
[ "$(md5sum <"$D/fs/golden.json")" = "$before" ] || fail "regress --update changed the golden"
only "filler golden.json"

# A report and a sweep into a full disk.
"$M" report "$D/sweep" --out "$D/fs/report" --no-figures >"$D/log" 2>&1; rc=$?
[ $rc -eq 1 ] && grep -q "No space left on device" "$D/log" || fail "report: rc $rc: $(cat "$D/log")"
only "filler golden.json"
"$M" sweep "$D/sweep.yaml" --out "$D/fs/sweep" --jobs 1 >"$D/log" 2>&1; rc=$?
[ $rc -ne 0 ] && grep -q "No space left on device" "$D/log" || fail "sweep: rc $rc: $(cat "$D/log")"
find "$D/fs/sweep" -name '*.tmp*' -o -name '*.partial' 2>/dev/null | grep -q . && fail "sweep left temporaries"
find "$D/fs/sweep" -type f -size 0 2>/dev/null | grep -q . && fail "sweep left empty files: $(find "$D/fs/sweep" -type f -size 0)"
rm -rf "$D/fs/sweep"

# A world built into a full cache: the error names the cache, no temporary directory is left.
mkdir -p "$D/fs/cache"
MSBENCH_CACHE_DIR="$D/fs/cache" "$M" world build urban >"$D/log" 2>&1; rc=$?
[ $rc -ne 0 ] && grep -q "could not write the world cache" "$D/log" && grep -q "No space left on device" "$D/log" ||
  fail "world build: rc $rc: $(cat "$D/log")"
[ -z "$(ls -A "$D/fs/cache")" ] || fail "world build left $(ls -A "$D/fs/cache")"
# A world import into a full cache: the error names the cache's file (not the checkout's), and
# neither a staging directory nor the sources folder is left.
W=$D/worlds
mkdir -p "$W/boxes" "$D/checkout/meshes"
printf 'o box\nv 7 7 0\nv 9 7 0\nv 8 9 0\nv 8 8 2\nf 1 2 3\nf 1 2 4\nf 2 3 4\nf 3 1 4\n' >"$D/checkout/meshes/box.obj"
printf '# padding\n' >>"$D/checkout/meshes/box.obj"
printf 'name: boxes\ndescription: box\nseed: 1\nground: {size_m: [40, 40]}\nstart: {position: [0, 0, 0], yaw_deg: 0}\nexploration_box: {min: [-15, -15, 0], max: [15, 15, 5]}\nsource: {repository: test/fixture, commit: 0000000}\nmeshes:\n  - {file: meshes/box.obj, name: box}\n' >"$W/boxes/spec.yaml"
# The mesh made larger than the disk's room by comment lines (assimp skips them).
for i in $(seq 4000); do printf '# %0100d\n' 0; done >>"$D/checkout/meshes/box.obj"
mkdir -p "$D/fs/cache"
MSBENCH_WORLDS_DIR=$W MSBENCH_CACHE_DIR="$D/fs/cache" "$M" world import boxes --from "$D/checkout" >"$D/log" 2>&1; rc=$?
[ $rc -ne 0 ] && grep -q "$D/fs/cache" "$D/log" && grep -q "No space left on device" "$D/log" &&
  ! grep -q "$D/checkout" "$D/log" || fail "world import: rc $rc: $(cat "$D/log")"
[ -z "$(ls -A "$D/fs/cache")" ] || fail "world import left $(ls -A "$D/fs/cache")"
rm -rf "$D/fs/filler" "$D/fs/cache" "$D/fs/golden.json"

# A run with a video on a disk with room for the run's files but not the video: the run is
# written, the video is not (metrics.json says why), nothing half-written is kept.
if command -v ffmpeg >/dev/null; then
  umount "$D/fs" && mount -t tmpfs -o size=300k tmpfs "$D/fs"
  "$M" run "$SCEN" --duration 20 --quiet --video --set video.height=1080 --out "$D/fs/v" >"$D/log" 2>&1; rc=$?
  [ $rc -eq 0 ] && grep -q "video $D/fs/v/video.mp4 not written" "$D/log" || fail "run --video: rc $rc: $(cat "$D/log")"
  [ -f "$D/fs/v/metrics.json" ] && grep -q '"error"' "$D/fs/v/metrics.json" || fail "run --video: no record of the video's error"
  ls -A "$D/fs/v" | grep -q video && fail "run --video kept $(ls -A "$D/fs/v" | grep video)"
fi

[ $failures -eq 0 ] && echo "ok: every writing command on a full file system" || exit 1
