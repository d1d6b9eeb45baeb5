#!/bin/sh
# End-to-end checks of `smolbridge spray`: help and exit codes, input
# errors naming file, line and key, warnings about keys without effect,
# the example configurations (BKW check, breakup with volume
# conservation; no warnings), and a failing check exiting 1.
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
# shellcheck source=tests/cli_common.sh
. "${srcdir:-.}/tests/cli_common.sh"
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
# an unknown section is an error naming it, also without keys under it
# (a misspelt [reitz] would otherwise leave its model out silently); so is
# a [droplets NAME] header without keys (it would add no population), and
# a [check] header without keys (it checked nothing, silently), naming
# the keys it takes
for c in "unknown section|[run]\nvolume = 1\ndt = 1\nsteps = 2\n${pop}[bogus]\nx = 1\n|sect.ini:8: unknown section [bogus] (valid: run," \
         "empty unknown section|[run]\nvolume = 1\ndt = 1\nsteps = 2\n${pop}[reiz]\n|sect.ini:8: unknown section [reiz] (valid: run," \
         "empty droplets|[run]\nvolume = 1\ndt = 1\nsteps = 2\n${pop}[droplets b]\n|sect.ini:8: [droplets b] has no keys: a population needs count and radius (m)" \
         "empty check|[run]\nvolume = 1\ndt = 1\nsteps = 2\n${pop}[check]\n|sect.ini:8: [check] has no keys: it checks nothing; valid keys: bkw = 1" \
         "empty check, keys after|[run]\nvolume = 1\ndt = 1\nsteps = 2\n[check]\n${pop}|sect.ini:5: [check] has no keys" ; do
  name=${c%%|*}; rest=${c#*|}; ini=${rest%|*}; want=${rest##*|}
  printf "$ini" > "$out/sect.ini"
  msg=$("$sb" spray "$out/sect.ini" 2>&1 >/dev/null)
  rc=$?
  [ $rc -eq 2 ] || fail "$name: exit $rc, want 2"
  case "$msg" in *"$want"*) ;; *) fail "$name message: $msg" ;; esac
done
printf '[reitz]\nblob = 2\n' > "$out/badblob.ini"
msg=$("$sb" spray "$out/badblob.ini" 2>&1 >/dev/null)
case "$msg" in *badblob.ini:2*blob*) ;; *) fail "bad blob message: $msg" ;; esac

# keys that have no effect in the configuration: a warning naming the
# file, line, section and key (as collide), the exit status unchanged;
# none where the key matters
base="[run]\nvolume = 1\ndt = 1e-3\nsteps = 1\noutput = $out/w\n"  # lines 1-5
drops='[droplets a]\ncount = 10\nradius = 1e-5\n'              # lines 6-8
unused() {  # unused NAME WANT INI: WANT after "FILE:" ("": no warning)
  printf "$3" > "$out/w.ini"
  warned spray "$1" "$2"
}
unused "B0 with hard spheres" "6: [run] B0 ignored: cross = hard-sphere" \
  "${base}B0 = 1e-4\n$drops"
unused "B0 with maxwell" "" "${base}B0 = 1e-4\ncross = maxwell\n$drops"
unused "K0 with maxwell" "9: [droplets a] K0 ignored: distribution = maxwell" \
  "$base${drops}K0 = 0.7\n"
unused "K0 with bkw" "" "$base${drops}K0 = 0.7\ndistribution = bkw\ntheta = 1\n"
unused "nse without bkw" "10: [check] nse ignored: no BKW check" \
  "$base$drops[check]\nnse = 3\n"
unused "nse with bkw = 0" "11: [check] nse ignored: no BKW check" \
  "$base$drops[check]\nbkw = 0\nnse = 3\n"
unused "nse with bkw = 1" "" "${base}cross = maxwell\nB0 = 1e-4\n${drops}distribution = bkw\ntheta = 1\n[check]\nbkw = 1\nnse = 1e9\n"
unused "g without settling" "10: [gas] g ignored: nothing settles" \
  "$base$drops[gas]\ng = 0 0 -1\n"
unused "g with settling drops" "" "$base${drops}settling = 1\n[gas]\ng = 0 0 -1\n"
unused "g with merge_velocity = settling" "" \
  "${base}merge_velocity = settling\ntheta_cr = 1\n$drops[gas]\ng = 0 0 -1\n"
# [tab] / [reitz] enable = 0 wherever it stands: every other key warned
unused "[tab] enable = 0 after" "10: [tab] Cd ignored: enable = 0 turns TAB off" \
  "$base$drops[tab]\nCd = 10\nenable = 0\n"
unused "[tab] enable = 0 before" "11: [tab] child_tag ignored: enable = 0" \
  "$base$drops[tab]\nenable = 0\nchild_tag = 3\n"
case "$msg" in *"[tab] enable ignored"*) fail "[tab] enable itself warned: $msg" ;; esac
unused "[tab] on" "" "$base$drops[tab]\nCd = 10\n"
unused "[reitz] enable = 0" "11: [reitz] B1 ignored: enable = 0 turns Reitz breakup off" \
  "$base$drops[reitz]\nenable = 0\nB1 = 5\n"
unused "[reitz] on" "" "$base$drops[reitz]\nB1 = 5\n"
unused "[run] weight with nanbu" "6: [run] weight ignored: method = nanbu" \
  "${base}weight = 3\nmethod = nanbu\n$drops"
unused "[run] weight with bird" "" "${base}weight = 3\n$drops"
unused "theta_cr with orourke" "6: [run] theta_cr ignored: coalescence = orourke" \
  "${base}theta_cr = 0.5\ncoalescence = orourke\n$drops"
unused "theta_cr with theta" "" "${base}theta_cr = 0.5\ncoalescence = theta\n$drops"
unused "merge_velocity without coalescence" \
  "6: [run] merge_velocity ignored: no collision coalesces" \
  "${base}merge_velocity = momentum\n$drops"
unused "merge_velocity with theta_cr" "" \
  "${base}merge_velocity = momentum\ntheta_cr = 0.5\n$drops"
unused "merge_velocity with orourke" "" \
  "${base}merge_velocity = momentum\ncoalescence = orourke\n$drops"
unused "merge_velocity = settling without coalescence: g" \
  "8: [gas] g ignored: nothing settles" \
  "${base}merge_velocity = settling\n[gas]\ng = 0 0 -1\n$drops"
# [gas] and [liquid]: used by the breakup models, settling and O'Rourke
gl='[gas]\nu = 1 0 0\nrho_g = 2\nmu_g = 2e-5\n[liquid]\nsigma = 0.05\nmu_l = 2e-3\n'
for k in "10: [gas] u ignored: no breakup model" \
         "11: [gas] rho_g ignored: no breakup model" \
         "12: [gas] mu_g ignored: nothing settles and no Reitz stripping" \
         "14: [liquid] sigma ignored: no breakup model" \
         "15: [liquid] mu_l ignored: no breakup model"; do
  unused "no breakup" "$k" "$base$drops$gl"
done
unused "[reitz] with stripping" "" "$base$drops$gl[reitz]\nstripping = 1\n"
unused "[tab]: mu_g" "12: [gas] mu_g ignored" "$base$drops$gl[tab]\nCd = 5\n"
unused "settling: rho_g, mu_g" "" \
  "$base${drops}settling = 1\n[gas]\nrho_g = 2\nmu_g = 2e-5\n"
unused "orourke: sigma" "" "${base}coalescence = orourke\n$drops[liquid]\nsigma = 0.05\n"
unused "emit_fraction, bird children" \
  "10: [reitz] emit_fraction ignored: the children are particles" \
  "$base$drops[reitz]\nemit_fraction = 0.1\n"
unused "emit_fraction, nanbu children" "" \
  "${base}method = nanbu\n$drops[reitz]\nemit_fraction = 0.1\n"

# BKW example: the run checks itself (exit 0), writes its files, and
# warns about nothing
sed "s|^output = .*|output = $out/bkw|" "$ex/spray_bkw.ini" > "$out/bkw.ini"
if "$sb" spray "$out/bkw.ini" 2>"$out/bkw.err"; then
  grep warning "$out/bkw.err" && fail "spray_bkw.ini warns"
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
if "$sb" spray "$out/brk.ini" 2>"$out/brk.err"; then
  grep warning "$out/brk.err" && fail "spray_breakup.ini warns"
  awk -F, 'NR == 2 { v = $9 } END { d = ($9 - v) / v; if (d < 0) d = -d;
    exit !(d < 1e-13) }' "$out/brk/series.csv" || fail "volume not conserved"
  awk -F, 'NR > 1 && $2 >= 7e-6 { bad = 1 } END { exit bad }' \
    "$out/brk/final.csv" || fail "a drop above 7 um after Reitz breakup"
  # the collisions printed at the end are every accepted pair, bounced or
  # merged (they used to be the bounces alone)
  nb=$(sed -n 's/^  "bounces": \([0-9]*\),$/\1/p' "$out/brk/summary.json")
  nm=$(sed -n 's/^  "merges": \([0-9]*\),$/\1/p' "$out/brk/summary.json")
  [ -n "$nb" ] && [ -n "$nm" ] && [ "$nm" -gt 0 ] \
    || fail "breakup summary.json: bounces '$nb', merges '$nm'"
  grep -q "parcels, $((nb + nm)) collisions ($nb bounces, $nm merges)," \
    "$out/brk.err" || fail "collisions printed: $(grep done "$out/brk.err"),
    want $((nb + nm)) = $nb bounces + $nm merges"
else
  fail "spray $ex/spray_breakup.ini failed"
fi
# [reitz] enable = 0 turns Reitz off wherever it stands in the section
# (the keys after it used to turn it on again)
sed "s|^output = .*|output = $out/brk0|; s|^\[reitz\]|[reitz]\nenable = 0|" \
  "$ex/spray_breakup.ini" > "$out/brk0.ini"
if "$sb" spray "$out/brk0.ini" 2>/dev/null; then
  grep -q '"reitz_children": 0,$' "$out/brk0/summary.json" \
    || fail "[reitz] enable = 0 first: Reitz ran"
else
  fail "spray $out/brk0.ini failed"
fi
# a bare [reitz] header enables Reitz breakup with its defaults (the
# model used to be switched on only by a key in the section)
sed "s|^output = .*|output = $out/brk1|; /^B0 = /d; /^B1 = /d; /^child_tag = /d; /^emit_fraction = /d" \
  "$ex/spray_breakup.ini" > "$out/brk1.ini"
grep -A1 '^\[reitz\]' "$out/brk1.ini" | grep -q '^\[droplets\|^$' \
  || fail "brk1.ini: [reitz] not bare"
if "$sb" spray "$out/brk1.ini" 2>/dev/null; then
  grep -q '"reitz_children": 0$' "$out/brk1/summary.json" \
    && fail "a bare [reitz] section: Reitz did not run"
else
  fail "spray $out/brk1.ini failed"
fi
rm -rf "$out"
[ "$fails" -eq 0 ] && echo "spray cli: all checks passed"
exit $((fails > 0))
