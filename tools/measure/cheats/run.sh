#!/bin/bash
# The earned score of each cheat (cheats.py) against MonoSpheres in urban (seed 1), at the given
# durations (default 60 and 300 s): docs/metrics.md, "The earned score".
#   tools/measure/cheats/run.sh [MSBENCH] [OUT] [DURATIONS...]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../../.." && pwd)
msbench=${1:-$root/build/bin/msbench}
out=${2:-/tmp/cheats}
shift $(( $# > 2 ? 2 : $# ))
durations=("${@:-60 300}")
mkdir -p "$out"
for d in ${durations[@]}; do
  "$msbench" run "$root/scenarios/missions/urban.yaml" --out "$out/monospheres-$d" --overwrite --quiet \
    --set duration_s="$d"
  for k in blanket ceiling high_spin outside kamikaze; do
    extra=()
    # The flight outside the box also retunes the camera and the speed, as the issue's cheat did.
    [ "$k" = outside ] && extra=(--set camera.clip_far_m=150 --set "trajectory.limits={max_speed_mps: 12, max_accel_mps2: 4, max_jerk_mps3: 10, max_yaw_rate_radps: 1}")
    "$msbench" run "$here/cheat.yaml" --out "$out/$k-$d" --overwrite --quiet --set duration_s="$d" \
      --set method.params.kind="$k" "${extra[@]}"
  done
done
python3 - "$out" <<'P'
import json, os, sys
out = sys.argv[1]
print(f"{'run':22s} {'status':9s} {'A m2':>8s} {'verified m2':>11s} {'earned m3':>10s} {'credited':>9s} "
      f"{'falsely free':>12s} {'unseen':>8s} {'outside s':>9s}")
for name in sorted(os.listdir(out), key=lambda n: (int(n.rsplit('-', 1)[1]), n != f"monospheres-{n.rsplit('-', 1)[1]}", n)):
    m = json.load(open(os.path.join(out, name, "metrics.json")))
    s, c = m["score"], m["coverage"]
    print(f"{name:22s} {m['status']:9s} {c['area_m2']:8.0f} {c['verified_area_m2']:11.0f} {s['earned']:10.0f} "
          f"{s['credited_m3']:9.0f} {s['falsely_free_m3']:12.0f} {s['unseen_m3']:8.0f} {s['time_outside_box_s']:9.0f}")
P
