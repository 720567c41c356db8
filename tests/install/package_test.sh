#!/bin/bash
# Builds the Debian package from the build folder (cpack -G DEB) and checks it as a user would
# find it: its control data, the files it holds, and, unpacked into a scratch root without the
# source tree's help, the command running a D-Form from / with its own templates, its man page
# and the Python module importing. Installing it for real (`apt install ./dform_*.deb`, as root)
# is scripts/check-package, which CI runs.
#   package_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build=$1 source=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/dform-package-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "package test: $*" >&2; exit 1; }

(cd "$build" && cpack -G DEB -B "$work/cpack") > "$work/cpack.log" 2>&1 ||
  fail "cpack failed: $(tail -3 "$work/cpack.log")"
deb=$(ls "$work"/cpack/dform_*.deb 2>/dev/null | head -1)
[ -n "$deb" ] || fail "cpack made no dform_*.deb: $(ls "$work/cpack")"
info=$(dpkg-deb --info "$deb")
for field in "Package: dform" "Architecture: amd64" "Section: graphics"; do
  grep -q "^ $field$" <<< "$info" || fail "the control data has no '$field': $info"
done
depends=$(grep '^ Depends:' <<< "$info")
for needed in libcholmod3 libcairo2 python3-numpy; do
  grep -q "$needed" <<< "$depends" || fail "Depends does not name $needed: $depends"
done
contents=$(dpkg-deb --contents "$deb" | awk '{print $6}')
for file in ./usr/bin/dform ./usr/share/dform/templates/gates/default.json \
  ./usr/include/dform/pipeline/run.h ./usr/lib/cmake/dform/dformConfig.cmake \
  ./usr/share/man/man1/dform.1.gz ./usr/share/bash-completion/completions/dform; do
  grep -qx -- "$file" <<< "$contents" || fail "the package has no $file"
done
grep -q '^./usr/lib/python3/dist-packages/dform' <<< "$contents" ||
  fail "the package has no Python module in /usr/lib/python3/dist-packages"

# Unpacked into a scratch root: the command finds the templates beside it and runs from /.
dpkg-deb -x "$deb" "$work/root"
usr=$work/root/usr
(cd / && env -u DFORM_TEMPLATES "$usr/bin/dform" --version) > /dev/null || fail "dform --version failed"
(cd / && env -u DFORM_TEMPLATES "$usr/bin/dform" forward -q --resolution 40 \
  "$source/samples/forward/ellipses-a.svg" "$source/samples/forward/ellipses-b.svg" \
  -o "$work/run") > "$work/run.log" 2>&1 || fail "the packaged dform did not run: $(tail -1 "$work/run.log")"
[ -s "$work/run/pattern.svg" ] && [ -s "$work/run/report.html" ] || fail "the packaged dform wrote no pattern or report"
man -l "$usr/share/man/man1/dform.1.gz" 2>/dev/null | grep -q forward || fail "the man page does not render"
(cd / && PYTHONPATH="$usr/lib/python3/dist-packages" /usr/bin/python3 -c \
  'import dform, sys; sys.exit(0 if dform.__file__.startswith(sys.argv[1]) else 1)' "$usr") ||
  fail "the packaged Python module does not import"
echo "package test: $(basename "$deb"), $(wc -l <<< "$contents") entries, runs from an unpacked root"
