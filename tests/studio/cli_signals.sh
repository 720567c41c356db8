#!/bin/sh
# SPDX-License-Identifier: GPL-3.0-or-later
# dform studio from the command line: it prints its address with the token, starts without a
# browser to open (no xdg-open on the PATH) and stops with 130 on SIGINT and 143 on SIGTERM; with
# one, xdg-open is given a page only this user can read, never the token on its command line.
#     cli_signals.sh DFORM
set -u
dform=$1
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir "$work/bin"
ln -s "$(command -v sh)" "$work/bin/sh"
fail=0
for signal in INT TERM; do
  rm -f "$work/out"
  # Only sh on the PATH: no xdg-open (the browser is optional); dform is given by its path.
  PATH="$work/bin" "$dform" studio --port 0 >"$work/out" 2>"$work/err" &
  pid=$!
  for _ in $(seq 100); do grep -q token= "$work/out" 2>/dev/null && break; sleep 0.1; done
  if ! grep -Eq '^dform studio: open http://127\.0\.0\.1:[0-9]+/\?token=[0-9a-f]{32}$' "$work/out"; then
    echo "FAIL: no address printed: $(cat "$work/out" "$work/err")"; fail=1
  fi
  kill -s "$signal" "$pid"
  wait "$pid"
  code=$?
  want=$([ "$signal" = INT ] && echo 130 || echo 143)
  if [ "$code" -ne "$want" ]; then echo "FAIL: SIG$signal gave exit $code, not $want"; fail=1; else echo "ok   SIG$signal -> $code"; fi
done
# A stand-in xdg-open records what it was given: its arguments, the file's and folder's modes and
# the page.
cat >"$work/bin/xdg-open" <<EOF
#!/bin/sh
printf '%s\n' "\$@" >"$work/args"
/usr/bin/stat -c %a "\$1" >"$work/mode"
/usr/bin/stat -c %a "\$(/usr/bin/dirname "\$1")" >"$work/folder-mode"
/bin/cat "\$1" >"$work/page"
EOF
chmod +x "$work/bin/xdg-open"
PATH="$work/bin" "$dform" studio --port 0 >"$work/out" 2>"$work/err" &
pid=$!
for _ in $(seq 100); do [ -s "$work/page" ] && break; sleep 0.1; done
token=$(sed -n 's/.*token=\([0-9a-f]*\)$/\1/p' "$work/out")
page=$(cat "$work/args" 2>/dev/null)
if [ -z "$token" ] || [ ! -s "$work/page" ]; then
  echo "FAIL: xdg-open was not started: $(cat "$work/out" "$work/err")"; fail=1
elif grep -q "$token" "$work/args"; then
  echo "FAIL: the token is on xdg-open's command line: $(cat "$work/args")"; fail=1
elif [ "$(cat "$work/mode")" != 600 ] || [ "$(cat "$work/folder-mode")" != 700 ]; then
  echo "FAIL: the page is mode $(cat "$work/mode") in a folder of mode $(cat "$work/folder-mode")"; fail=1
elif ! grep -q "url=http://127.0.0.1:[0-9]*/?token=$token\"" "$work/page"; then
  echo "FAIL: the page does not lead to the address: $(cat "$work/page")"; fail=1
else
  echo "ok   xdg-open $page: a private page leads to the address"
fi
kill -s INT "$pid"
wait "$pid"
if [ -n "$page" ] && [ -e "$page" ]; then echo "FAIL: $page left behind"; fail=1; fi
"$dform" studio a.svg b.svg c.svg --no-browser >/dev/null 2>"$work/err"
code=$?
if [ "$code" -ne 2 ]; then echo "FAIL: three inputs gave exit $code, not 2"; fail=1; else echo "ok   three inputs -> 2: $(cat "$work/err")"; fi
"$dform" studio "$work/missing.svg" "$work/missing-b.svg" --no-browser >/dev/null 2>"$work/err"
code=$?
if [ "$code" -ne 3 ]; then echo "FAIL: a missing outline gave exit $code, not 3"; fail=1; else echo "ok   missing outline -> 3: $(cat "$work/err")"; fi
exit $fail
