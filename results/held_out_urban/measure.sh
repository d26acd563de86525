#!/bin/bash
# MonoSpheres on held-out urbans (docs/worlds.md, "Held-out worlds"): table1_reference's urban
# configuration (the published code, `fast`), 300 s, seeds 1-8, each seed on the world its own salt
# draws. The fixed-world runs beside them (runs/fixed-s*) are table1_reference.yaml's urban
# MonoSpheres runs (1200 s, binary 9a90737; their curves to 299 s are what is compared).
#   bash results/held_out_urban/measure.sh OUT && python3 results/held_out_urban/compare.py OUT
set -euo pipefail
out=${1:?usage: measure.sh OUT}
here=$(cd "$(dirname "$0")" && pwd)
B=${MSBENCH_BIN:-$here/../../build/bin/msbench}
C=$here/runs/fixed-s1/config.yaml
one() {
  MSBENCH_WORLD_SALT="msbench-held-out-urban-$1-0f1e2d3c4b5a" "$B" run "$C" --seed "$1" --set duration_s=300 \
    --set held_out=true --out "$out/held-s$1" --quiet
}
for pair in "1 2" "3 4" "5 6" "7 8"; do
  set -- $pair
  one "$1" & one "$2" & wait
done
