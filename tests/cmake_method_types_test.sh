#!/bin/bash
# The configure-time check (cmake/MethodTypes.cmake) stops a tree whose two method folders
# register one type, naming both files; the real tree passes.
#   cmake_method_types_test.sh SOURCE_DIR
set -u
S=$1
D=$(mktemp -d /tmp/msb_method_types.XXXXXX)
trap 'rm -rf "$D"' EXIT
cmake -DPROJECT_SOURCE_DIR="$S" -P "$S/cmake/CheckMethodTypes.cmake" || { echo "FAIL: the tree itself"; exit 1; }
mkdir -p "$D/core/baseline/a" "$D/core/baseline/b"
printf 'const MethodRegistrar k = registerMethod<A, AConfig>(\n    {"same", "a", {}});\n' >"$D/core/baseline/a/a_method.cc"
printf 'const MethodRegistrar k = registerMethod<B, BConfig>({"same", "b", {}});\n' >"$D/core/baseline/b/b_method.cc"
out=$(cmake -DPROJECT_SOURCE_DIR="$D" -P "$S/cmake/CheckMethodTypes.cmake" 2>&1) && { echo "FAIL: no error"; exit 1; }
for want in "'same' is registered twice" core/baseline/a/a_method.cc core/baseline/b/b_method.cc; do
  grep -qF "$want" <<<"$out" || { echo "FAIL: '$want' not in: $out"; exit 1; }
done
echo "ok: a type registered in two folders stops the configuration naming both"
