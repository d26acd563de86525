#!/bin/bash
# The configure-time checks stop a tree whose two method folders register one type, naming both
# files (cmake/MethodTypes.cmake), and a method folder whose sources register no method, naming
# its CMakeLists.txt (msb_add_method, cmake/MsbHelpers.cmake); the real tree passes.
#   cmake_method_types_test.sh SOURCE_DIR
set -u
S=$1
D=$(mktemp -d /tmp/msb_method_types.XXXXXX)
trap 'rm -rf "$D"' EXIT
cmake -DPROJECT_SOURCE_DIR="$S" -P "$S/cmake/CheckMethodTypes.cmake" || { echo "FAIL: the tree itself"; exit 1; }
mkdir -p "$D/core/methods/a" "$D/core/methods/b"
printf 'const MethodRegistrar k = registerMethod<A, AConfig>(\n    {"same", "a", {}});\n' >"$D/core/methods/a/a_method.cc"
printf 'const MethodRegistrar k = registerMethod<B, BConfig>({"same", "b", {}});\n' >"$D/core/methods/b/b_method.cc"
out=$(cmake -DPROJECT_SOURCE_DIR="$D" -P "$S/cmake/CheckMethodTypes.cmake" 2>&1) && { echo "FAIL: no error"; exit 1; }
for want in "'same' is registered twice" core/methods/a/a_method.cc core/methods/b/b_method.cc; do
  grep -qF "$want" <<<"$out" || { echo "FAIL: '$want' not in: $out"; exit 1; }
done
echo "ok: a type registered in two folders stops the configuration naming both"

# A method folder without its registration: msb_add_method refuses it before any target exists.
mkdir -p "$D/core/methods/c"
printf 'int helper() { return 1; }\n' >"$D/core/methods/c/c_explorer.cc"
cat >"$D/core/methods/c/CMakeLists.txt" <<EOF
include("$S/cmake/MsbHelpers.cmake")
set(CMAKE_CURRENT_SOURCE_DIR "$D/core/methods/c")
set(PROJECT_SOURCE_DIR "$D")
msb_add_method(msb_method_c SOURCES c_explorer.cc DEPS msb::explorer)
EOF
out=$(cmake -P "$D/core/methods/c/CMakeLists.txt" 2>&1) && { echo "FAIL: no error for a folder without registration"; exit 1; }
for want in "core/methods/c/CMakeLists.txt" "msb_add_method(msb_method_c) has no source"; do
  grep -qF "$want" <<<"$out" || { echo "FAIL: '$want' not in: $out"; exit 1; }
done
echo "ok: a method folder without its registration stops the configuration naming it"
