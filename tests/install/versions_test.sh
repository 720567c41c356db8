#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# One version everywhere (docs/releasing.md): CMakeLists.txt's project version is the newest entry
# of the Debian changelog and the first version section of CHANGELOG.md, `dform --version`
# prints it, and where the repository has a tag vX.Y.Z (git, when the source is a clone), that
# commit's CMakeLists.txt says X.Y.Z and CHANGELOG.md dates the section of the tagged version.
#   versions_test.sh DFORM SOURCE_DIR
set -euo pipefail
dform=$1 source=$2
fail() { echo "versions test: $*" >&2; exit 1; }
version=$(sed -n 's/^project(dform VERSION \([0-9]*\.[0-9]*\.[0-9]*\).*/\1/p' "$source/CMakeLists.txt")
[ -n "$version" ] || fail "CMakeLists.txt has no 'project(dform VERSION X.Y.Z'"
debian=$(head -1 "$source/packaging/debian/changelog")
[[ "$debian" =~ ^dform\ \(([^\)]*)\)\  ]] && [ "${BASH_REMATCH[1]}" = "$version" ] ||
  fail "packaging/debian/changelog's newest entry is '$debian', not version $version"
section=$(grep -E -m1 '^## [0-9]+\.[0-9]+\.[0-9]+ ' "$source/CHANGELOG.md" || true)
[[ "$section" =~ ^##\ ([0-9.]+)\ \((unreleased|[0-9]{4}-[0-9]{2}-[0-9]{2})\)$ ]] ||
  fail "CHANGELOG.md's first version section is '$section', not '## X.Y.Z (YYYY-MM-DD|unreleased)'"
[ "${BASH_REMATCH[1]}" = "$version" ] || fail "CHANGELOG.md's first version section is $section, not $version"
printed=$("$dform" --version)
[ "$printed" = "dform $version" ] || fail "dform --version prints '$printed', not 'dform $version'"
if git -C "$source" rev-parse --git-dir > /dev/null 2>&1; then
  for tag in $(git -C "$source" tag -l 'v[0-9]*'); do
    tagged=$(git -C "$source" show "$tag:CMakeLists.txt" |
      sed -n 's/^project(dform VERSION \([0-9.]*\).*/\1/p')
    [ "v$tagged" = "$tag" ] || fail "the tag $tag is on a commit whose CMakeLists.txt says $tagged"
    dated=$(grep -E -m1 "^## ${tag#v} " "$source/CHANGELOG.md" || true)
    [[ "$dated" =~ \([0-9]{4}-[0-9]{2}-[0-9]{2}\)$ ]] || fail "CHANGELOG.md does not date the tagged ${tag#v}: '$dated'"
  done
fi
echo "versions test: $version in CMakeLists.txt, the Debian changelog, CHANGELOG.md and dform --version"
