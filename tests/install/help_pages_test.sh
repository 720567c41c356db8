#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The man page and the bash completion made from dform's --help texts (src/cli/help_pages.py):
# the page renders and has a section for every subcommand and an entry for each of a
# subcommand's options; the completion completes subcommands, options, profile names and the
# values of a setting with choices.
#   help_pages_test.sh BUILD_DIR
set -euo pipefail
build=$1
fail() { echo "help pages test: $*" >&2; exit 1; }
page=$(MANWIDTH=200 man -l "$build/dform.1.gz" 2>/dev/null) || fail "man cannot render dform.1.gz"
subcommands=$("$build/dform" --help | awk '/^Subcommands:/ {on = 1; next} on && NF {print $1}')
[ -n "$subcommands" ] || fail "dform --help lists no subcommands"
for sub in $subcommands; do
  grep -Eq "^   $sub$" <<< "$page" || fail "the man page has no section for $sub"
done
for option in $("$build/dform" forward --help | grep -Eo -- '--[a-z][a-z-]*' | sort -u); do
  grep -q -- "$option" <<< "$page" || fail "the man page does not list forward's $option"
done
complete() {  # the words the completion offers for the command line "$@" (the last word partial)
  bash -c 'source "$1"; shift; PATH="$(dirname "$0"):$PATH"; COMP_WORDS=("$@");
           COMP_CWORD=$(($# - 1)); _dform; echo "${COMPREPLY[*]}"' "$build/dform" "$build/dform.bash" "$@"
}
[ "$(complete dform fo)" = forward ] || fail "'dform fo' completes to '$(complete dform fo)'"
[ "$(complete dform forward --res)" = --resolution ] || fail "'dform forward --res' completes to '$(complete dform forward --res)'"
[ "$(complete dform validate --res)" = "" ] || fail "validate has no --resolution, yet it is offered"
grep -qw laser <<< "$(complete dform forward --profile la)" || fail "--profile does not complete to the profile names"
# A setting with choices completes to the settings table's choices, as --help lists them.
[ "$(complete dform forward --model e)" = exact ] || fail "'--model e' completes to '$(complete dform forward --model e)'"
[ "$(complete dform export out --joint "")" = "glue holes lace slots" ] ||
  fail "'--joint' completes to '$(complete dform export out --joint "")'"
echo "help pages test: $(wc -w <<< "$subcommands") subcommands in the page; completion works"
