#!/usr/bin/env bash
# `pip install ./tools/python` into a fresh venv made from Debian's interpreter, then a 5 s urban
# mission through `import msbench` whose determinism hash must equal the command line's for the
# same scenario (docs/python.md, "Install"). Usage: pip_install_test.sh BUILD_DIR (for msbench).
set -euo pipefail
cd "$(dirname "$0")/../.."
repo=$PWD
build=${1:-build}
work=$(mktemp -d /tmp/msb_pip.XXXXXX)
trap 'rm -rf "$work"' EXIT
/usr/bin/python3 -m venv --system-site-packages "$work/venv"  # numpy and pandas from Debian
MSB_BUILD_JOBS=2 "$work/venv/bin/pip" install -q --no-build-isolation --no-cache-dir ./tools/python
rm -rf tools/python/build tools/python/msbench.egg-info
# The installed package, not the build tree's: run from an empty directory, no PYTHONPATH.
py_hash=$(cd "$work" && env -u PYTHONPATH "$work/venv/bin/python" -c '
import msbench, sys
assert "/venv/" in msbench.__file__, msbench.__file__
m = msbench.Mission(msbench.Scenario.load(sys.argv[1], set=["duration_s=5"]))
m.step(10**6)
print(m.hash)' "$repo/scenarios/missions/urban_short.yaml")
"$build/bin/msbench" run scenarios/missions/urban_short.yaml --set duration_s=5 --out "$work/cli" --quiet
cli_hash=$(/usr/bin/python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["determinism_hash"])' "$work/cli/metrics.json")
echo "pip install: venv mission hash $py_hash, command line $cli_hash"
[ "$py_hash" = "$cli_hash" ]
