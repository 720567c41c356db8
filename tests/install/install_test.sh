#!/bin/bash
# Installs the built dform into a temporary prefix and builds and runs a separate project that
# finds it with find_package(dform): the package's targets, public headers (and none of the
# internal ones), dependencies and templates work without the source tree's include path. The
# project's source is the C++ example of docs/api.md, so the documented example is what is built.
#   install_test.sh BUILD_DIR SOURCE_DIR SANITIZED(ON|OFF)
set -euo pipefail
build=$1 source=$2 sanitized=$3
work=$(mktemp -d "${TMPDIR:-/tmp}/dform-install-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "install test: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$work/prefix" > "$work/install.log" ||
  fail "cmake --install failed: $(tail -3 "$work/install.log")"
include=$work/prefix/include/dform
[ -f "$include/pipeline/run.h" ] || fail "pipeline/run.h is not installed"
for internal in pipeline/run_steps.h model/exact_model.h forward/seam_layout.h model/term_table.h model/run_control.h io/json_util.h export/internal.h; do
  [ ! -e "$include/$internal" ] || fail "the internal header $internal is installed"
done
"$work/prefix/bin/dform" --version > /dev/null || fail "the installed dform does not run"

# The consumer: consumer/CMakeLists.txt, docs/api.md's first C++ block as main.cpp (a run that
# writes its folder) and its second as memory.cpp (a D-Form made in memory).
mkdir "$work/example"
cp "$source/tests/install/consumer/CMakeLists.txt" "$work/example/"
cppBlock() {  # the Nth ```cpp block of docs/api.md
  awk -v want="$1" '/^```cpp$/ {n++; inside = (n == want); next} /^```$/ {inside = 0} inside' \
    "$source/docs/api.md"
}
cppBlock 1 > "$work/example/main.cpp"
cppBlock 2 > "$work/example/memory.cpp"
for example in main memory; do
  grep -q "int main" "$work/example/$example.cpp" || fail "docs/api.md has no C++ example for $example.cpp"
done

flags=()
if [ "$sanitized" = ON ]; then  # the installed libraries need the sanitizers' runtimes
  flags=(-DCMAKE_CXX_FLAGS="-fsanitize=address,undefined" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined")
fi
cmake -S "$work/example" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" "${flags[@]}" > "$work/configure.log" 2>&1 ||
  fail "find_package(dform) failed: $(grep -m3 -i error "$work/configure.log")"
cmake --build "$work/consumer" > "$work/build.log" 2>&1 ||
  fail "the consumer does not build: $(grep -m3 -i error "$work/build.log")"
# Only the installed headers: the source tree's src/ is on no compile line.
if grep -rq -- "-I$source/src" "$work/consumer/CMakeFiles"; then fail "the source tree's src/ is on the include path"; fi

DFORM_TEMPLATES="$work/prefix/share/dform/templates" "$work/consumer/consumer" \
  "$source/samples/forward/ellipses-a.svg" "$source/samples/forward/ellipses-b.svg" "$work/out" ||
  fail "the consumer's run failed"
for file in report.json report.html pattern.svg piece-a-3d.obj; do
  [ -s "$work/out/$file" ] || fail "the consumer's result has no $file"
done
# The disc and the square are both convex: the exact model makes them, its seam closed.
made=$("$work/consumer/memory") || fail "the in-memory example failed"
[[ "$made" =~ ^model\ exact,\ [0-9]+\ vertices,\ L_max\ [0-9.]+\ %,\ seam\ gap\ 0\ mm$ ]] ||
  fail "the in-memory example printed: $made"
echo "install test: installed, found, built and ran a separate project ($made)"
