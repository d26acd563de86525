#!/usr/bin/env bash
# Installs the Debian 12 packages msbench needs. Idempotent: installs only what is missing and runs
# `apt-get update` at most once. Works as root on a fresh machine (uses sudo when not root).
set -euo pipefail

packages=(
  build-essential cmake git pkg-config
  libmujoco-dev libqhull-dev libosmesa6-dev  # libqhull-dev: mujoco's CMake config names its include dir
  libopencv-core-dev libopencv-imgproc-dev libopencv-video-dev libpng-dev
  libopencv-features2d-dev libopencv-calib3d-dev libopencv-imgcodecs-dev
  libcgal-dev libeigen3-dev libyaml-cpp-dev libgtest-dev liboctomap-dev nlohmann-json3-dev
  libnlopt-dev  # the MRS trajectory generator's LD_LBFGS time allocation (sim/physics)
  libssl-dev  # HMAC-SHA256 seals of run records under an evaluator's key (docs/integrity.md)
  libassimp-dev libstb-dev  # imported world meshes and their images (docs/worlds.md, "Imported meshes")
  python3-matplotlib python3-markdown  # `msbench report` figures and report.html (tools/sweep/report_*.py)
  ffmpeg  # `msbench run --video` encodes video.mp4 with the ffmpeg program (docs/video.md)
  pybind11-dev python3-dev python3-numpy python3-pandas python3-pytest  # `import msbench` (docs/python.md)
  python3-venv python3-setuptools python3-wheel  # `pip install ./tools/python` (tests/python_install)
)

# Collect the packages not yet installed.
missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -q
"${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
