#!/bin/sh
# End-to-end checks of `smolbridge spray`: help and exit codes, input
# errors naming file, line and key, the example configurations (BKW check,
# breakup with volume conservation), and a failing check exiting 1.
set -u
sb="${top_builddir:-.}/smolbridge"
ex="${srcdir:-.}/examples"
out="${top_builddir:-.}/tests/spray-cli-out"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
expect_rc() {  # expect_rc RC CMD...
  want=$1; shift
  "$@" >/dev/null 2>&1
  got=$?
  [ "$got" -eq "$want" ] || fail "'$*' exited $got, want $want"
}
rm -rf "$out"
mkdir -p "$out"

expect_rc 0 "$sb" spray --help
expect_rc 2 "$sb" spray
expect_rc 2 "$sb" spray "$out/no-such.ini"
printf '[run]\nvolume = 1\nbogus = 3\n' > "$out/bad.ini"
msg=$("$sb" spray "$out/bad.ini" 2>&1 >/dev/null)
rc=$?
[ $rc -eq 2 ] || fail "bad key: exit $rc, want 2"
case "$msg" in *bad.ini:3*bogus*) ;; *) fail "bad key message: $msg" ;; esac
printf '[run]\nmethod = dsmc\n' > "$out/bad2.ini"
msg=$("$sb" spray "$out/bad2.ini" 2>&1 >/dev/null)
case "$msg" in *bad2.ini:2*bird*nanbu*) ;; *) fail "bad value message: $msg" ;; esac
printf '[run]\nvolume = 1\ndt = 1\nsteps = 1\n' > "$out/nopop.ini"
expect_rc 2 "$sb" spray "$out/nopop.ini"
printf '[run]\ncoalescence = brazier\n' > "$out/badcoal.ini"
msg=$("$sb" spray "$out/badcoal.ini" 2>&1 >/dev/null)
case "$msg" in *badcoal.ini:2*theta*orourke*) ;; *) fail "bad coalescence message: $msg" ;; esac
# keys that contradict each other: exit 2 with a message naming them
pop='[droplets a]\ncount = 10\nradius = 1e-5\n'
for c in "steps|[run]\nvolume = 1\ndt = 1\nsteps = 2\nt_end = 3\n$pop|t_end and steps" \
         "T theta|[run]\nvolume = 1\ndt = 1\nsteps = 2\n${pop}T = 300\ntheta = 1\n|T and theta" \
         "bird weight|[run]\nvolume = 1\ndt = 1\nsteps = 2\n${pop}weight = 5\n|method = bird gives every parcel"; do
  name=${c%%|*}; rest=${c#*|}; ini=${rest%|*}; want=${rest##*|}
  printf "$ini" > "$out/conflict.ini"
  msg=$("$sb" spray "$out/conflict.ini" 2>&1 >/dev/null)
  rc=$?
  [ $rc -eq 2 ] || fail "$name: exit $rc, want 2"
  case "$msg" in *"$want"*) ;; *) fail "$name message: $msg" ;; esac
done
# nothing replaced or merged silently: a key given twice, a section
# repeated (as collide)
for c in "key twice|[run]\nvolume = 1\ndt = 1\nsteps = 2\ndt = 2\n$pop|twice.ini:5: [run] dt given twice (first at $out/twice.ini:3); give each key once" \
         "droplets key twice|[run]\nvolume = 1\ndt = 1\nsteps = 2\n${pop}radius = 2e-5\n|twice.ini:8: [droplets a] radius given twice (first at $out/twice.ini:7)" \
         "section twice|[run]\nvolume = 1\ndt = 1\nsteps = 2\n${pop}[gas]\nrho_g = 1\n[droplets a]\nT = 300\n|twice.ini:10: section [droplets a] repeated (first at $out/twice.ini:5); put its keys in one section"; do
  name=${c%%|*}; rest=${c#*|}; ini=${rest%|*}; want=${rest##*|}
  printf "$ini" > "$out/twice.ini"
  msg=$("$sb" spray "$out/twice.ini" 2>&1 >/dev/null)
  rc=$?
  [ $rc -eq 2 ] || fail "$name: exit $rc, want 2"
  case "$msg" in *"$want"*) ;; *) fail "$name message: $msg" ;; esac
done
printf '[reitz]\nblob = 2\n' > "$out/badblob.ini"
msg=$("$sb" spray "$out/badblob.ini" 2>&1 >/dev/null)
case "$msg" in *badblob.ini:2*blob*) ;; *) fail "bad blob message: $msg" ;; esac

# BKW example: the run checks itself (exit 0), writes its files
sed "s|^output = .*|output = $out/bkw|" "$ex/spray_bkw.ini" > "$out/bkw.ini"
if "$sb" spray "$out/bkw.ini" 2>/dev/null; then
  head -n 1 "$out/bkw/series.csv" | grep -q '^t,parcels,number,.*,M4_bkw$' \
    || fail "series.csv header"
  grep -q '"bkw"' "$out/bkw/summary.json" || fail "summary.json: no bkw"
  # Bird conserves energy exactly: the energy column is constant
  awk -F, 'NR == 2 { e = $5 } NR > 2 { d = ($5 - e) / e; if (d < 0) d = -d;
    if (d > 1e-12) bad = 1 } END { exit bad }' "$out/bkw/series.csv" \
    || fail "Bird energy not conserved"
else
  fail "spray $ex/spray_bkw.ini failed"
fi
# the same with an impossible tolerance: the check fails, exit 1
sed "s|^bkw = 1|bkw = 1\nnse = 1e-6|" "$out/bkw.ini" > "$out/bkw-strict.ini"
expect_rc 1 "$sb" spray "$out/bkw-strict.ini"

# breakup example: volume conserved, every drop below 7 um at the end
sed "s|^output = .*|output = $out/brk|" "$ex/spray_breakup.ini" > "$out/brk.ini"
if "$sb" spray "$out/brk.ini" 2>/dev/null; then
  awk -F, 'NR == 2 { v = $9 } END { d = ($9 - v) / v; if (d < 0) d = -d;
    exit !(d < 1e-13) }' "$out/brk/series.csv" || fail "volume not conserved"
  awk -F, 'NR > 1 && $2 >= 7e-6 { bad = 1 } END { exit bad }' \
    "$out/brk/final.csv" || fail "a drop above 7 um after Reitz breakup"
else
  fail "spray $ex/spray_breakup.ini failed"
fi
# [reitz] enable = 0 turns Reitz off wherever it stands in the section
# (the keys after it used to turn it on again)
sed "s|^output = .*|output = $out/brk0|; s|^\[reitz\]|[reitz]\nenable = 0|" \
  "$ex/spray_breakup.ini" > "$out/brk0.ini"
if "$sb" spray "$out/brk0.ini" 2>/dev/null; then
  grep -q '"reitz_children": 0$' "$out/brk0/summary.json" \
    || fail "[reitz] enable = 0 first: Reitz ran"
else
  fail "spray $out/brk0.ini failed"
fi
rm -rf "$out"
[ "$fails" -eq 0 ] && echo "spray cli: all checks passed"
exit $((fails > 0))
