#!/bin/sh
# .ci/quick-times, the CI guard against slow validation cases
# (docs/validation.md, "Quick-mode times"), on fabricated validate logs
# made from the table of docs/validation.md: all cases on time passes; a
# case 12x slower fails with a message naming it; 6x slower only warns; a
# case with no row fails; a run of some cases passes; a log without case
# times is refused.  --update on a copy of the document changes only the
# table.  And every case of `smolbridge validate --list` has a row.
set -u
src="${srcdir:-.}"
sb="${top_builddir:-.}/smolbridge"
qt="$src/.ci/quick-times"
doc="$src/docs/validation.md"
tmp=$(mktemp -d) || exit 99
trap 'rm -rf "$tmp"' EXIT
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

# the table's rows, "NAME SECONDS"
awk -F '|' '/<!-- quicktimes:begin -->/ { on = 1; next }
  /<!-- quicktimes:end -->/ { on = 0 }
  on && NF >= 3 { n = $2; t = $3; gsub(/ /, "", n); gsub(/ /, "", t)
    if (t ~ /^[0-9.]+$/) print n, t }' "$doc" > "$tmp/rows"
nrows=$(wc -l < "$tmp/rows" | tr -d ' ')
[ "$nrows" -ge 10 ] || fail "only $nrows rows in the quicktimes table of $doc"

# mklog NAME SECONDS: a validate log (as on stderr) with every case at its
# row's time, NAME at SECONDS; a case's own output lines in between
mklog() {
  awk -v slow="$1" -v ts="$2" -v n="$nrows" '
    BEGIN { print "smolbridge validate (quick, seed 12345): " n " cases -> out/" }
    { k++; t = ($1 == slow) ? ts : $2
      printf "[%d/%d] %s: a description (Author 2011, Table 1) ...\n", k, n, $1
      print "  some output of the case"
      printf "[%d/%d] %s done in %.1f s\n", k, n, $1, t }' "$tmp/rows"
}
# run the guard: its output in $tmp/out, its status in $rc
guard() { "$qt" "$@" > "$tmp/out" 2>&1; rc=$?; }

# all on time: passes, no warning
mklog none 0 > "$tmp/ontime.log"
guard --doc "$doc" "$tmp/ontime.log"
[ $rc -eq 0 ] || { fail "all cases on time: status $rc"; cat "$tmp/out"; }
grep -q "^quick-times: $nrows cases, 0 slow (warning), 0 failed$" "$tmp/out" ||
  { fail "all cases on time: no clean summary"; cat "$tmp/out"; }

# a case of 1 s or more, 12x slower (11 s or more; like the regression
# 2.6 s -> 35 s of V14/spray-reitz): fails
name=$(awk '$2 >= 1 { print $1; exit }' "$tmp/rows")
ref=$(awk '$2 >= 1 { print $2; exit }' "$tmp/rows")
[ -n "$name" ] || { fail "no row of 1 s or more"; name=none ref=1; }
slow=$(awk -v r="$ref" 'BEGIN { printf "%.1f", 12 * r }')
mklog "$name" "$slow" > "$tmp/slow.log"
guard --doc "$doc" "$tmp/slow.log"
[ $rc -eq 1 ] || { fail "$name at $slow s (row $ref s): status $rc, not 1"; cat "$tmp/out"; }
grep -q "^quick-times: FAIL: $name took $slow s" "$tmp/out" ||
  { fail "$name at $slow s: no FAIL line naming it"; cat "$tmp/out"; }
# the same with a failed case's line ("done in X s: message")
sed "s|^\(\[[0-9]*/[0-9]*\] $name done in [0-9.]* s\)\$|\1: no memory|" \
  "$tmp/slow.log" > "$tmp/slowmsg.log"
guard --doc "$doc" "$tmp/slowmsg.log"
[ $rc -eq 1 ] || { fail "'done in X s: message' line not read"; cat "$tmp/out"; }

# 6x slower and more than 2 s: a warning, status 0
warn=$(awk -v r="$ref" 'BEGIN { printf "%.1f", 6 * r + 2.1 }')
mklog "$name" "$warn" > "$tmp/warn.log"
guard --doc "$doc" "$tmp/warn.log"
[ $rc -eq 0 ] || { fail "$name at $warn s (row $ref s): status $rc, not 0"; cat "$tmp/out"; }
grep -q "^quick-times: WARNING: $name took $warn s" "$tmp/out" ||
  { fail "$name at $warn s: no WARNING line"; cat "$tmp/out"; }

# a tiny case 30x slower but only 1.5 s more: noise, nothing said
tiny=$(awk '$2 <= 0.05 { print $1; exit }' "$tmp/rows")
if [ -n "$tiny" ]; then
  mklog "$tiny" 1.5 > "$tmp/tiny.log"
  guard --doc "$doc" "$tmp/tiny.log"
  { [ $rc -eq 0 ] && ! grep -q "$tiny" "$tmp/out"; } ||
    { fail "$tiny at 1.5 s (row 0.0 s) reported"; cat "$tmp/out"; }
fi

# a case without a row: fails, naming it
{ mklog none 0; echo "[59/59] V99/new-case done in 0.3 s"; } > "$tmp/new.log"
guard --doc "$doc" "$tmp/new.log"
[ $rc -eq 1 ] || { fail "case without a row: status $rc, not 1"; cat "$tmp/out"; }
grep -q "^quick-times: FAIL: V99/new-case (0.3 s) has no row" "$tmp/out" ||
  { fail "case without a row: no FAIL line naming it"; cat "$tmp/out"; }

# a run of two cases (--case): the other rows are not needed
mklog none 0 | sed -n '1p;5,7p;14,16p' > "$tmp/some.log"
guard --doc "$doc" "$tmp/some.log"
{ [ $rc -eq 0 ] && grep -q "^quick-times: 2 cases, 0 slow" "$tmp/out"; } ||
  { fail "a run of 2 cases"; cat "$tmp/out"; }

# no case times (e.g. stdout captured instead of stderr); a --full log
echo "697 comparisons: 573 passed, 0 failed" > "$tmp/stdout.log"
guard --doc "$doc" "$tmp/stdout.log"
[ $rc -eq 2 ] || { fail "log without case times: status $rc, not 2"; cat "$tmp/out"; }
mklog none 0 | sed 's/(quick,/(full,/' > "$tmp/full.log"
guard --doc "$doc" "$tmp/full.log"
[ $rc -eq 2 ] || { fail "--full log: status $rc, not 2"; cat "$tmp/out"; }

# --update on a copy: the log's times replace the rows', a new case gets a
# row before the end marker, nothing outside the table changes
cp "$doc" "$tmp/doc.md"
guard --update --doc "$tmp/doc.md" "$tmp/new.log"
[ $rc -eq 0 ] || { fail "--update: status $rc"; cat "$tmp/out"; }
guard --doc "$tmp/doc.md" "$tmp/new.log"
[ $rc -eq 0 ] || { fail "after --update, the same log: status $rc"; cat "$tmp/out"; }
guard --update --doc "$tmp/doc.md" "$tmp/slow.log"
grep -q "^| $name | $slow |\$" "$tmp/doc.md" || fail "--update: no row '| $name | $slow |'"
grep -A1 '^| V99/new-case | 0.3 |$' "$tmp/doc.md" | grep -q 'quicktimes:end' ||
  fail "--update: no row for V99/new-case before the end marker"
notable() { awk '/<!-- quicktimes:begin -->/ { on = 1 }
  /<!-- quicktimes:end -->/ { on = 0 } !(on && /^\|/)' "$1"; }
notable "$doc" > "$tmp/text.a"
notable "$tmp/doc.md" > "$tmp/text.b"
cmp -s "$tmp/text.a" "$tmp/text.b" || fail "--update changed text outside the table"

# every case of the registry has a row (else CI's guard fails)
if [ -x "$sb" ]; then
  "$sb" validate --list | awk '{ print $1 }' | sort > "$tmp/cases"
  awk '{ print $1 }' "$tmp/rows" | sort > "$tmp/named"
  comm -23 "$tmp/cases" "$tmp/named" > "$tmp/norow"
  [ -s "$tmp/norow" ] && fail "no row in the quicktimes table of" \
    "docs/validation.md for: $(tr '\n' ' ' < "$tmp/norow")"
fi

[ $fails -eq 0 ] || exit 1
echo "quick_times.sh: all passed"
