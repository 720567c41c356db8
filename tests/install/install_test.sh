#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
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
for internal in pipeline/run_steps.h pipeline/json_values.h forward/seam_layout.h io/json_util.h export/internal.h studio/studio.h; do
  [ ! -e "$include/$internal" ] || fail "the internal header $internal is installed"
done
"$work/prefix/bin/dform" --version > /dev/null || fail "the installed dform does not run"
# Moved to another prefix, the command reads the templates beside it (a profile only the moved
# copy has is listed) and runs from / with no DFORM_TEMPLATES.
cp -r "$work/prefix" "$work/moved"
cp "$work/moved/share/dform/templates/profiles/laser.json" \
  "$work/moved/share/dform/templates/profiles/moved-here.json"
profiles=$(cd / && env -u DFORM_TEMPLATES "$work/moved/bin/dform" export --list-profiles) ||
  fail "the moved dform cannot list its profiles"
grep -qx moved-here <<< "$profiles" || fail "the moved dform reads another templates folder than its own"
(cd / && env -u DFORM_TEMPLATES "$work/moved/bin/dform" forward -q --resolution 40 \
  "$source/samples/forward/ellipses-a.svg" "$source/samples/forward/ellipses-b.svg" \
  -o "$work/moved-run") > "$work/moved-run.log" 2>&1 ||
  fail "the moved dform did not run: $(tail -1 "$work/moved-run.log")"
[ -s "$work/moved-run/report.html" ] || fail "the moved dform wrote no report.html"
# Each installed header compiles alone, included as a user includes it, and reaches nothing but
# the other installed headers, Eigen and the standard library.
eigen=$(pkg-config --cflags-only-I eigen3)
for header in $(cd "$work/prefix/include" && find dform -name '*.h' | sort); do
  echo "#include <$header>" > "$work/header.cpp"
  g++ -std=c++17 -fsyntax-only -MD -MF "$work/header.d" -I"$work/prefix/include" $eigen \
    "$work/header.cpp" 2> "$work/header.log" ||
    fail "$header does not compile alone: $(grep -m1 error "$work/header.log")"
  outside=$(tr ' \\' '\n\n' < "$work/header.d" | grep '^/' | grep -v -e "^$work/" \
    -e '^/usr/include/eigen3/' -e '^/usr/include/c++/' -e '^/usr/include/x86_64-linux-gnu/' \
    -e '^/usr/lib/gcc/' -e '^/usr/include/[a-z0-9_-]*\.h$' -e '^/usr/include/\(bits\|sys\|linux\|asm-generic\)/' | head -1 || true)
  [ -z "$outside" ] || fail "$header reaches $outside"
done

# The package config names its dependencies by imported target (found again where it is used),
# never by a library path of this machine, and exports no build-only target.
# Under lib/ or, configured for /usr, the multiarch lib/<triplet>/.
targets=$(find "$work/prefix" -path "*/cmake/dform/dformTargets*.cmake" -exec cat {} +)
[ -n "$targets" ] || fail "no dformTargets.cmake under $work/prefix"
libpath=$(grep -Eo '/usr/lib[^";]*\.(so|a)' <<< "$targets" | head -1 || true)
[ -z "$libpath" ] || fail "dformTargets.cmake names a library path: $libpath"
if grep -q 'dform_warnings' <<< "$targets"; then fail "dformTargets.cmake exports the build-only dform_warnings"; fi

# The consumer: consumer/CMakeLists.txt, docs/api.md's first C++ block as main.cpp (a run that
# writes its folder), its second as memory.cpp (a D-Form made in memory), its third as files.cpp
# (outline files read, one OBJ written), and collide.cpp, which
# has a core/types.h of its own ahead of dform's headers on the include path.
mkdir "$work/example"
cp -r "$source/tests/install/consumer/CMakeLists.txt" "$source/tests/install/consumer/collide.cpp" \
  "$source/tests/install/consumer/where.cpp" "$source/tests/install/consumer/include" "$work/example/"
cppBlock() {  # the Nth ```cpp block of docs/api.md
  awk -v want="$1" '/^```cpp$/ {n++; inside = (n == want); next} /^```$/ {inside = 0} inside' \
    "$source/docs/api.md"
}
cppBlock 1 > "$work/example/main.cpp"
cppBlock 2 > "$work/example/memory.cpp"
cppBlock 3 > "$work/example/files.cpp"
for example in main memory files; do
  grep -q "int main" "$work/example/$example.cpp" || fail "docs/api.md has no C++ example for $example.cpp"
done

flags=()
if [ "$sanitized" = ON ]; then  # the installed libraries need the sanitizers' runtimes
  flags=(-DCMAKE_CXX_FLAGS="-fsanitize=address,undefined" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined")
fi
cmake -S "$work/example" -B "$work/consumer" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" "${flags[@]}" > "$work/configure.log" 2>&1 ||
  fail "find_package(dform) failed: $(grep -m3 -i error "$work/configure.log")"
# A project that finds dform sees no warning of dform's or of its dependencies' configs (CGAL's
# about the build type among them): the configure below has no build type.
cmake -S "$work/example" -B "$work/consumer-debug" -DCMAKE_PREFIX_PATH="$work/prefix" \
  > "$work/configure-debug.log" 2>&1 || fail "find_package(dform) failed without a build type"
if grep -qi warning "$work/configure-debug.log"; then
  fail "configuring a consumer warns: $(grep -i -m1 -A2 warning "$work/configure-debug.log")"
fi
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
"$work/consumer/files" "$source/samples/forward/ellipses-a.svg" "$source/samples/forward/ellipses-b.svg" \
  "$work/piece-a.obj" || fail "the file example failed"
# One OBJ: vertices, triangles, then the seam as a grouped polyline.
[ "$(grep -c '^v ' "$work/piece-a.obj")" -gt 3 ] && grep -q '^f ' "$work/piece-a.obj" &&
  grep -qx 'g seam' "$work/piece-a.obj" || fail "the file example wrote no OBJ piece: $(head -c 200 "$work/piece-a.obj")"
"$work/consumer/collide" || fail "the consumer with its own core/types.h failed"
where=$(DFORM_TEMPLATES="$work/moved/share/dform/templates" "$work/consumer/where") ||
  fail "the consumer finds no templates folder"
[ "$where" = "$work/moved/share/dform/templates" ] || fail "DFORM_TEMPLATES is not the folder read: $where"
echo "install test: installed, found, built and ran a separate project ($made)"
