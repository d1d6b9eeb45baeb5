#!/bin/sh
# End-to-end checks of the `smolbridge` command: help texts, eval against
# independently computed values, error handling and exit codes, and the
# validate report format.
set -u
sb="${top_builddir:-.}/smolbridge"
out="${top_builddir:-.}/tests/cli-out"
fails=0
pass() { :; }
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
expect_rc() {  # expect_rc RC CMD...
  want=$1; shift
  "$@" >/dev/null 2>&1
  got=$?
  [ "$got" -eq "$want" ] || fail "'$*' exited $got, want $want"
}
# relclose GOT WANT TOL: |got-want| <= tol*|want| (awk, double precision)
relclose() {
  awk -v g="$1" -v w="$2" -v t="$3" 'BEGIN { d = g - w; if (d < 0) d = -d;
    m = w < 0 ? -w : w; exit !(d <= t * m) }'
}

# --- help for every subcommand
expect_rc 0 "$sb" --help
expect_rc 0 "$sb" --version
expect_rc 0 "$sb" eval --help
expect_rc 0 "$sb" validate --help
expect_rc 0 "$sb" eval --list
expect_rc 2 "$sb"
expect_rc 2 "$sb" no-such-command

# --- eval: the README example against awk's independent evaluation of the
# closed form expm1(2a(x+y-a)/v)/expm1(2xy/v) (moderate arguments: no
# cancellation in the naive form)
got=$("$sb" eval bes3b_cross_prob x=1.5 y=1.3 a=1 v=1)
want=$(awk 'BEGIN { printf "%.17g", (exp(3.6) - 1) / (exp(3.9) - 1) }')
relclose "$got" "$want" 1e-13 || fail "bes3b_cross_prob: $got vs $want"
case "$got" in *.*[0-9]) ;; *) fail "not a decimal number: $got" ;; esac
# arguments in any order, with and without the sb_ prefix
got2=$("$sb" eval sb_bes3b_cross_prob v=1 a=1 y=1.3 x=1.5)
[ "$got" = "$got2" ] || fail "argument order changed the value: $got2"
# Brownian bridge exp(-2(x-a)(y-a)/v)
got=$("$sb" eval bb_cross_prob x=2 y=3 a=1 v=4)
want=$(awk 'BEGIN { printf "%.17g", exp(-1) }')
relclose "$got" "$want" 1e-15 || fail "bb_cross_prob: $got vs $want"
# samplers are reproducible given the seed
s1=$("$sb" eval bb_hit_sample seed=7 x=2 y=1.5 a=1 sigma2=1 t=1)
s2=$("$sb" eval bb_hit_sample seed=7 x=2 y=1.5 a=1 sigma2=1 t=1)
[ "$s1" = "$s2" ] || fail "sampler not reproducible: $s1 vs $s2"

# --- eval errors: usage (2) and domain errors (1, message on stderr)
expect_rc 2 "$sb" eval no_such_function x=1
expect_rc 2 "$sb" eval bb_cross_prob x=1 y=1 a=0
expect_rc 2 "$sb" eval bb_cross_prob x=1 y=1 a=0 v=1 w=2
expect_rc 2 "$sb" eval bb_cross_prob x=1 y=1 a=zero v=1
expect_rc 2 "$sb" eval bb_cross_prob x=1 x=1 y=1 a=0 v=1
expect_rc 1 "$sb" eval bb_cross_prob x=1 y=1 a=0 v=-1
msg=$("$sb" eval bes3b_cross_prob x=1 y=1 a=-1 v=1 2>&1 >/dev/null)
[ -n "$msg" ] || fail "no message for a < 0"

# --- validate: listing, filtering, report files and CSV header
expect_rc 0 "$sb" validate --list
expect_rc 2 "$sb" validate --case NoSuchCase
expect_rc 2 "$sb" validate --seed -3
rm -rf "$out"
first=$("$sb" validate --list | awk 'NR == 1 {print $1}')
if "$sb" validate --quick --case "$first" --out "$out" >"$out.txt" 2>&1; then
  head -n 1 "$out/validate.csv" | grep -qx 'case,estimate,reference,ci_low,ci_high,p_value,rule,level,verdict' \
    || fail "validate.csv header"
  [ -s "$out/report.md" ] || fail "no report.md"
  awk -F, 'NR > 1 && $9 != "pass" && $9 != "fail" && $9 != "info" { bad = 1 } END { exit bad }' \
    "$out/validate.csv" || fail "verdict column not pass/fail"
  awk -F, 'NR > 1 && $1 !~ /^V[0-9]+\// { bad = 1 } END { exit bad }' \
    "$out/validate.csv" || fail "case names must start with a V-number"
else
  fail "validate --case $first failed:"; cat "$out.txt"
fi
rm -f "$out.txt"

# --- pbe: constant kernel, monodisperse start: M0 = N0 / (1 + tau/2),
# tau = K N0 t (analytic), file headers as documented
expect_rc 0 "$sb" pbe --help
expect_rc 2 "$sb" pbe --kernel no-such-kernel --n0 1 --init mono --method discrete --sizes 10 --times 1 --out "$out-p.csv"
if "$sb" pbe --kernel constant --param K=2 --n0 3 --init mono --method discrete \
     --sizes 30 --times 0.5,1 --out "$out-p.csv" 2>/dev/null; then
  head -n 1 "$out-p.csv" | grep -qx 't,k,v,n' || fail "pbe csv header"
  head -n 1 "$out-p-moments.csv" | grep -qx 't,M0,M1,M2' || fail "pbe moments header"
  m0=$(awk -F, '$1 == 1 {print $2}' "$out-p-moments.csv")
  want=$(awk 'BEGIN { tau = 2 * 3 * 1; printf "%.17g", 3 / (1 + tau / 2) }')
  relclose "$m0" "$want" 1e-8 || fail "pbe M0(t=1) = $m0, want $want"
else
  fail "smolbridge pbe failed"
fi
rm -f "$out-p.csv" "$out-p-moments.csv"

# --- collide: an example configuration runs and writes its outputs; an
# unknown key is rejected with a message naming the file, line and key
expect_rc 0 "$sb" collide --help
ini="${srcdir:-.}/examples/v9_two_spheres_45.ini"
mkdir -p "$out"
sed "s|^output = .*|output = $out/collide|" "$ini" > "$out/two.ini"
if "$sb" collide "$out/two.ini" 2>/dev/null; then
  [ -s "$out/collide/summary.json" ] || fail "collide: no summary.json"
  grep -q '"collisions": 1,' "$out/collide/summary.json" || fail "collide: expected 1 collision"
  head -n 1 "$out/collide/series.csv" | grep -q '^t,' || fail "collide: series.csv header"
else
  fail "smolbridge collide $ini failed"
fi
# the Langevin-bridge detector from the INI file (detect = langevin)
ini="${srcdir:-.}/examples/v12_nano_langevin.ini"
sed -e "s|^output = .*|output = $out/nano|" -e "s|^steps = .*|steps = 40|" \
  "$ini" > "$out/nano.ini"
if "$sb" collide "$out/nano.ini" 2>/dev/null; then
  grep -q '"detect": "langevin"' "$out/nano/summary.json" ||
    fail "collide: detect = langevin not in summary.json"
  grep -q '^  "collisions": 0,' "$out/nano/summary.json" &&
    fail "collide: no collision with detect = langevin"
else
  fail "smolbridge collide $ini failed"
fi
printf '[run]\nL = 1e-4\nbogus = 3\n' > "$out/bad.ini"
msg=$("$sb" collide "$out/bad.ini" 2>&1 >/dev/null)
rc=$?
[ $rc -eq 1 ] || fail "collide bad.ini exited $rc, want 1"
case "$msg" in *bad.ini:3*bogus*) ;; *) fail "collide bad key message: $msg" ;; esac
rm -rf "$out"

[ "$fails" -eq 0 ] && echo "cli: all checks passed"
exit $((fails > 0))
