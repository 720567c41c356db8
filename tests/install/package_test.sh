#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The Debian packages of this build (cpack, packaging/debian.cmake) as a user and a Debian
# administrator would find them: three packages and their -dbgsym packages, each one's control
# data (dependencies, the Python versions, py3compile and py3clean), its files (multiarch library
# paths, the DEP-5 copyright and the changelog, no file in two packages), the command and the
# module stripped with their debug symbols in -dbgsym under their build ids, the hardening
# (relro, bindnow, fortified calls), the static libraries without debug sections, and, unpacked
# into a scratch root without the source tree's help, the command running a D-Form from / with
# its own templates, its man page naming files the packages hold, and the Python module importing.
# lintian and installing them for real (as root) are scripts/check-package, which CI runs and
# which runs this script on the packages it made.
#   package_test.sh BUILD_DIR SOURCE_DIR [DEBS]   (exit 77, skipped: the build's prefix is not /usr)
# DEBS: a folder holding the packages of this build already (scripts/make-packages' output);
# without it the script makes them with cpack.
set -euo pipefail
build=$1 source=$2 made=${3:-}
fail() { echo "package test: $*" >&2; exit 1; }
prefix=$(sed -n 's/^CMAKE_INSTALL_PREFIX:PATH=//p' "$build/CMakeCache.txt")
if [ "$prefix" != /usr ]; then
  echo "package test: skipped: the build's prefix is $prefix; the packages need -DCMAKE_INSTALL_PREFIX=/usr"
  exit 77
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/dform-package-test.XXXXXX")
trap 'rm -rf "$work"' EXIT

version=$(sed -n 's/^project(dform VERSION \([0-9.]*\).*/\1/p' "$source/CMakeLists.txt")
arch=$(dpkg --print-architecture)
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH)
python=$(/usr/bin/python3 -c 'import sys; print("%d.%d %d.%d" % (sys.version_info[:2] + (sys.version_info[0], sys.version_info[1] + 1)))')
read -r python_version python_next <<< "$python"

if [ -n "$made" ]; then
  debs=$(cd "$made" && pwd)
else
  if grep -q '^docs:' "$build/Makefile"; then cmake --build "$build" --target docs > /dev/null; fi
  (cd "$build" && cpack -G DEB -B "$work/cpack") > "$work/cpack.log" 2>&1 ||
    fail "cpack failed: $(tail -3 "$work/cpack.log")"
  debs=$work/cpack
fi
for package in dform libdform-dev python3-dform; do
  [ -f "$debs/${package}_${version}_$arch.deb" ] || fail "cpack made no ${package}_${version}_$arch.deb: $(ls "$debs")"
done
for package in dform python3-dform; do
  [ -f "$debs/$package-dbgsym_${version}_$arch.ddeb" ] || fail "cpack made no $package-dbgsym package: $(ls "$debs")"
done

field() {  # field PACKAGE NAME: the control field NAME of PACKAGE's .deb
  dpkg-deb --field "$debs/$1_${version}_$arch.deb" "$2"
}
for package in dform libdform-dev python3-dform; do
  [ "$(field "$package" Version)" = "$version" ] || fail "$package's version is $(field "$package" Version)"
  [ "$(field "$package" Maintainer)" != "" ] || fail "$package has no Maintainer"
  description=$(field "$package" Description)
  [ "$(wc -l <<< "$description")" -ge 4 ] || fail "$package has no extended description: $description"
  [ "$(head -1 <<< "$description" | wc -c)" -le 81 ] || fail "$package's synopsis is over 80 characters"
done
[ "$(field dform Section)" = graphics ] && [ "$(field libdform-dev Section)" = libdevel ] &&
  [ "$(field python3-dform Section)" = python ] || fail "the sections are not graphics, libdevel, python"
depends=$(field dform Depends)
for needed in libcholmod3 libcairo2 hershey-fonts-data; do
  grep -qw "$needed" <<< "$depends" || fail "dform's Depends does not name $needed: $depends"
done
! grep -qw python3 <<< "$depends" || fail "dform depends on python3: $depends"
# The -dev packages whose CMake configs and pkg-config files dformConfig.cmake finds.
depends=$(field libdform-dev Depends)
for needed in "dform (= $version)" libeigen3-dev nlohmann-json3-dev libboost-dev libcgal-dev \
  libsuitesparse-dev libssl-dev libtinygltf-dev libcairo2-dev libpolyclipping-dev libdxflib-dev pkg-config; do
  grep -qF "$needed" <<< "$depends" || fail "libdform-dev's Depends does not name $needed: $depends"
done
for package in $(grep -Eo 'find_dependency\(([A-Za-z0-9_]+)' "$source/src/dformConfig.cmake.in" | cut -d'(' -f2); do
  case "$package" in
    Eigen3) grep -q libeigen3-dev <<< "$depends" ;; nlohmann_json) grep -q nlohmann-json3-dev <<< "$depends" ;;
    Boost) grep -q libboost-dev <<< "$depends" ;; CGAL) grep -q libcgal-dev <<< "$depends" ;;
    OpenSSL) grep -q libssl-dev <<< "$depends" ;; TinyGLTF) grep -q libtinygltf-dev <<< "$depends" ;;
    PkgConfig) grep -q pkg-config <<< "$depends" ;; Threads) true ;;
    *) fail "dformConfig.cmake finds $package, which package_test.sh does not know" ;;
  esac || fail "libdform-dev's Depends has no package for dformConfig.cmake's find_dependency($package)"
done
depends=$(field python3-dform Depends)
for needed in "dform (= $version)" "python3 (>= $python_version~)" "python3 (<< $python_next)" python3-numpy; do
  grep -qF "$needed" <<< "$depends" || fail "python3-dform's Depends does not name $needed: $depends"
done
dpkg-deb --ctrl-tarfile "$debs/python3-dform_${version}_$arch.deb" | tar -x -C "$work" ./postinst ./prerm ||
  fail "python3-dform has no postinst or prerm"
grep -q '^	py3compile -p python3-dform$' "$work/postinst" || fail "python3-dform's postinst does not run py3compile"
grep -q '^	py3clean -p python3-dform$' "$work/prerm" || fail "python3-dform's prerm does not run py3clean"

# The files: each where Debian keeps it, none in two packages.
for package in dform libdform-dev python3-dform; do
  dpkg-deb --contents "$debs/${package}_${version}_$arch.deb" | awk '!/^d/ {print substr($6, 2)}' |
    sort > "$work/$package.files"
  for file in /usr/share/doc/$package/copyright /usr/share/doc/$package/changelog.gz; do
    grep -qx "$file" "$work/$package.files" || fail "$package has no $file"
  done
done
duplicated=$(sort "$work"/*.files | uniq -d | head -3)
[ -z "$duplicated" ] || fail "files in two packages: $duplicated"
expect() {  # expect PACKAGE FILE...: each FILE is in PACKAGE
  local package=$1
  shift
  for file in "$@"; do grep -qx -- "$file" "$work/$package.files" || fail "$package has no $file"; done
}
expect dform /usr/bin/dform /usr/share/dform/templates/gates/default.json /usr/share/man/man1/dform.1.gz \
  /usr/share/bash-completion/completions/dform /usr/share/doc/dform/cli.md
expect libdform-dev /usr/include/dform/pipeline/run.h "/usr/lib/$multiarch/libdform_pipeline.a" \
  "/usr/lib/$multiarch/cmake/dform/dformConfig.cmake" /usr/share/doc/libdform-dev/api.md
extension=$(/usr/bin/python3 -c 'import sysconfig; print(sysconfig.get_config_var("EXT_SUFFIX"))')
expect python3-dform /usr/lib/python3/dist-packages/dform/__init__.py \
  "/usr/lib/python3/dist-packages/dform/_dform$extension" \
  "/usr/lib/python3/dist-packages/dform-$version.dist-info/METADATA" /usr/share/doc/python3-dform/python.md
! grep -q '^/usr/lib/[^/]*\.a$' "$work/libdform-dev.files" || fail "a static library outside /usr/lib/$multiarch"
! grep -q '__pycache__\|\.pyc$' "$work/python3-dform.files" || fail "python3-dform ships byte-compiled files"

root=$work/root
for deb in "$debs"/*.deb "$debs"/*.ddeb; do dpkg-deb -x "$deb" "$root"; done
copyright=$root/usr/share/doc/dform/copyright
head -1 "$copyright" | grep -qx 'Format: https://www.debian.org/doc/packaging-manuals/copyright-format/1.0/' ||
  fail "the copyright file is not machine-readable (DEP-5)"
grep -qx 'License: GPL-3+' "$copyright" || fail "the copyright file does not license the files GPL-3+"
newest=$(zcat "$root/usr/share/doc/dform/changelog.gz")  # whole: head would cut zcat's pipe
grep -q "^dform ($version) " <<< "${newest%%$'\n'*}" ||
  fail "changelog.gz's newest entry is not $version"
grep -qx 'License: GPL-3.0-or-later' "$root/usr/lib/python3/dist-packages/dform-$version.dist-info/METADATA" ||
  fail "the dist-info's METADATA has no licence"

# Stripped, their debug symbols (line tables) in -dbgsym under their build ids; hardened.
for binary in /usr/bin/dform "/usr/lib/python3/dist-packages/dform/_dform$extension"; do
  sections=$(readelf -S --wide "$root$binary")
  ! grep -Eq '\.symtab|\.debug_' <<< "$sections" || fail "$binary is not stripped"
  id=$(readelf -n "$root$binary" | sed -n 's/.*Build ID: //p')
  debug=$root/usr/lib/debug/.build-id/${id:0:2}/${id:2}.debug
  [ -n "$id" ] && [ -f "$debug" ] || fail "no debug symbols of $binary (build id '$id') in the -dbgsym packages"
  # (readelf finds no program interpreter in a debug file: its complaint is not the answer)
  grep -q '\.debug_line' <<< "$(readelf -S --wide "$debug" 2> /dev/null || true)" ||
    fail "the debug symbols of $binary have no line tables"
  dynamic=$(readelf -d --wide "$root$binary")
  grep -q 'BIND_NOW' <<< "$dynamic" || fail "$binary is not linked with -z now"
  grep -q GNU_RELRO <<< "$(readelf -l --wide "$root$binary")" || fail "$binary is not linked with -z relro"
  symbols=$(readelf --dyn-syms --wide "$root$binary")
  grep -q '__[a-z]*_chk@' <<< "$symbols" || fail "$binary calls no fortified function"
  grep -q '__stack_chk_fail@' <<< "$symbols" || fail "$binary has no stack protector"
done
grep -q 'DYN (Position-Independent Executable' <<< "$(readelf -h "$root/usr/bin/dform")" || fail "dform is not a PIE"
for archive in "$root/usr/lib/$multiarch"/libdform_*.a; do
  ! grep -q '\.debug_' <<< "$(readelf -S --wide "$archive")" || fail "$(basename "$archive") has debug sections"
done

# Unpacked: the command finds the templates beside it and runs from /; the man page names only
# files the packages hold.
usr=$root/usr
(cd / && env -u DFORM_TEMPLATES "$usr/bin/dform" --version) > /dev/null || fail "dform --version failed"
(cd / && env -u DFORM_TEMPLATES "$usr/bin/dform" forward -q --resolution 40 \
  "$source/samples/forward/ellipses-a.svg" "$source/samples/forward/ellipses-b.svg" \
  -o "$work/run") > "$work/run.log" 2>&1 || fail "the packaged dform did not run: $(tail -1 "$work/run.log")"
[ -s "$work/run/pattern.svg" ] && [ -s "$work/run/report.html" ] || fail "the packaged dform wrote no pattern or report"
page=$(MANWIDTH=300 man -l "$usr/share/man/man1/dform.1.gz" 2>/dev/null) || fail "the man page does not render"
for section in ENVIRONMENT EXAMPLES FILES "SEE ALSO"; do
  grep -qx "$section" <<< "$page" || fail "the man page has no $section section"
done
named=$(sed -n '/^FILES$/,/^SEE ALSO$/p' <<< "$page" | grep -Eo '/usr/share/[^ ]*' | sort -u)
[ "$(wc -l <<< "$named")" -ge 5 ] || fail "the man page's FILES names few files: $named"
for path in $named; do
  [ -e "$root$path" ] || fail "the man page names $path, which no package holds"
done
(cd / && PYTHONPATH="$usr/lib/python3/dist-packages" /usr/bin/python3 -c \
  'import dform, sys; sys.exit(0 if dform.__file__.startswith(sys.argv[1]) else 1)' "$usr") ||
  fail "the packaged Python module does not import"
echo "package test: $(cd "$debs" && ls *.deb *.ddeb | tr '\n' ' ')checked, unpacked and run"
