#!/bin/sh
# `smolbridge pgd` checkpoints: a run stopped part-way ([run] checkpoint
# at its t_end) and continued from there ([run] restart) writes the files
# of the run in one go, byte for byte (fields.csv, fields.vtk, exact.csv,
# the snapshots fields_NNNNN.csv of both parts together, summary.json but
# its cpu_seconds), for the Eulerian solver with both schemes (1-D delta
# shock, 2-D crossing jets with drag), for the particles and for the
# Euler-Lagrange decomposition; and a
# restart refuses a file whose parameters differ from the checkpoint's, a
# t_end before its time, another method's or a damaged checkpoint.  The
# decomposition (method = decomposition, one process) likewise.
set -u
sb="${top_builddir:-.}/smolbridge"
src="${srcdir:-.}"
out="${top_builddir:-.}/tests/pgd-restart-out"
rm -rf "$out"
mkdir -p "$out"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

# ini EXAMPLE NAME [sed expressions...]: the example as $out/NAME.ini,
# writing to $out/NAME
ini() {
  i_ex=$1; i_name=$2; shift 2
  sed -e "s|^output = .*|output = $out/$i_name|" "$@" "$src/examples/$i_ex" \
    > "$out/$i_name.ini"
}

# split EXAMPLE NAME T_MID [sed expressions...]: NAME_0 the run in one
# go, NAME_1 its part up to T_MID ending in the checkpoint NAME.ck, NAME_2
# the rest from it; compares the outputs of NAME_0 with those of NAME_2
# (and the snapshots with those of NAME_1 and NAME_2).
split() {
  ex=$1 name=$2 mid=$3
  shift 3
  ini "$ex" "${name}_0" "$@"
  ini "$ex" "${name}_1" "$@" -e "s|^t_end = .*|t_end = $mid\\
checkpoint = $out/$name.ck|"
  ini "$ex" "${name}_2" "$@" -e "/^\\[run\\]/a\\
restart = $out/$name.ck"
  for k in 0 1 2; do
    "$sb" pgd "$out/${name}_$k.ini" > "$out/${name}_$k.log" 2>&1 ||
      { fail "$name: part $k exited $?: $(cat "$out/${name}_$k.log")"; return 1; }
  done
  [ -s "$out/$name.ck" ] || { fail "$name: no checkpoint"; return 1; }
  n=0
  for f in "$out/${name}_0"/*; do
    b=$(basename "$f")
    g="$out/${name}_2/$b"
    [ -f "$g" ] || g="$out/${name}_1/$b"  # a snapshot before the checkpoint
    case "$b" in
      summary.json)
        grep -v cpu_seconds "$f" > "$out/a.json"
        grep -v cpu_seconds "$g" > "$out/b.json"
        cmp -s "$out/a.json" "$out/b.json" ||
          fail "$name: summary.json differs: $(diff "$out/a.json" "$out/b.json")" ;;
      *) cmp -s "$f" "$g" || fail "$name: $b differs from the run in one go" ;;
    esac
    n=$((n + 1))
  done
  echo "$name: $n files compared"
  # nothing more than the run in one go
  for f in "$out/${name}_1"/* "$out/${name}_2"/*; do
    [ -f "$out/${name}_0/$(basename "$f")" ] ||
      [ "$(basename "$f")" = fields.csv ] ||
      fail "$name: $(basename "$f") not in the run in one go"
  done
}

# 1-D delta shock, MUSCL, snapshots every 1/32 (the checkpoint's time a
# snapshot time, so that the run in one go ends a step there too)
split pgd_delta_shock.ini delta 0.125 -e 's|^nx = .*|nx = 200|' \
  -e 's|^t_end = .*|t_end = 0.1875|' -e '/^\[run\]/a\
output_every = 0.03125'
[ -f "$out/delta_0/fields_00003.csv" ] && [ -f "$out/delta_2/fields_00003.csv" ] &&
  [ -f "$out/delta_1/fields_00002.csv" ] ||
  fail "delta: the snapshots are not where expected"
# 2-D crossing jets with drag towards a moving gas, both schemes
for sc in upwind muscl; do
  split pgd_crossing_jets.ini "jets_$sc" 0.5 -e '/^ny = /d' -e 's|^nx = .*|nx = 15|' \
    -e 's|^t_end = .*|t_end = 1|' -e "s|^scheme = .*|scheme = $sc|" \
    -e 's|^tau = .*|tau = 0.5|' -e 's|^U = .*|U = 0.1 0.2|' \
    -e 's|^first = .*|first = 5|' -e '/^\[run\]/a\
output_every = 0.25\
cfl = 0.45'
done
# the particles
split pgd_crossing_jets.ini jets_lag 0.5 -e '/^ny = /d' -e 's|^nx = .*|nx = 15|' \
  -e 's|^t_end = .*|t_end = 1.5|' -e 's|^method = .*|method = lagrange|' \
  -e '/^scheme = /d' -e 's|^tau = .*|tau = 5|' -e 's|^U = .*|U = 0.1 0.2|' \
  -e 's|^first = .*|first = 5|' -e '/^\[run\]/a\
output_every = 0.25'
# the decomposition: a Lagrangian block where the jets cross
split pgd_crossing_jets.ini jets_dd 0.5 -e '/^ny = /d' -e 's|^nx = .*|nx = 15|' \
  -e 's|^t_end = .*|t_end = 1.5|' -e 's|^method = .*|method = decomposition|' \
  -e "s|^scheme = .*|scheme = muscl|" -e 's|^tau = .*|tau = 5|' \
  -e 's|^U = .*|U = 0.1 0.2|' -e 's|^first = .*|first = 5|' -e '/^\[run\]/a\
output_every = 0.25\
cfl = 0.45' -e '$a\
[decomposition]\
blocks = 3 3\
kinds = EEEELEEEE'
grep -q '"particles": [1-9]' "$out/jets_dd_2/summary.json" ||
  fail "jets_dd: no particles"
grep -q '"particles": [1-9]' "$out/jets_lag_2/summary.json" ||
  fail "jets_lag: no particles"
grep -q '"outflow": \[0,' "$out/jets_lag_2/summary.json" &&
  fail "jets_lag: no particle left (the removal is not covered)"

# --- refused restarts: exit status 2 and the reason
refused() {  # refused NAME WHAT [sed expressions...]: NAME.ini edited
  name=$1 what=$2
  shift 2
  sed "$@" "$out/$name.ini" > "$out/bad.ini"
  "$sb" pgd "$out/bad.ini" > "$out/bad.log" 2>&1
  st=$?
  [ $st -eq 2 ] || fail "$name ($what): exit $st, not 2: $(cat "$out/bad.log")"
  grep -q -- "$what" "$out/bad.log" ||
    fail "$name: message without '$what': $(cat "$out/bad.log")"
}
refused jets_upwind_2 "nx = 17 here, 15 in the checkpoint" -e 's|^nx = .*|nx = 17|'
refused jets_upwind_2 "scheme = muscl here, upwind" -e 's|^scheme = .*|scheme = muscl|'
refused jets_upwind_2 "tau = 0.75 here" -e 's|^tau = .*|tau = 0.75|'
refused jets_upwind_2 "inflow section 2" -e 's|^u = 0 1|u = 0 0.9|'
refused jets_upwind_2 "\\[boundary\\] north" -e 's|^north = .*|north = transmissive|'
refused jets_upwind_2 "before the time of the restart" -e 's|^t_end = .*|t_end = 0.25|'
refused jets_lag_2 "not a pgd particle checkpoint" -e "s|jets_lag.ck|jets_upwind.ck|"
refused jets_upwind_2 "not a pgd solver checkpoint" -e "s|jets_upwind.ck|jets_lag.ck|"
refused jets_upwind_2 "cannot open" -e "s|jets_upwind.ck|no-such.ck|"
head -c 200 "$out/jets_upwind.ck" > "$out/cut.ck"
refused jets_upwind_2 "damaged" -e "s|jets_upwind.ck|cut.ck|"
refused jets_upwind_2 "another name" -e "/^restart = /p" \
  -e "s|^restart = |checkpoint = |"
refused jets_dd_2 "kinds = EEEEEEEEL here, EEEELEEEE in the checkpoint" \
  -e 's|^kinds = .*|kinds = EEEEEEEEL|'
refused jets_dd_2 "scheme = upwind here, muscl" -e 's|^scheme = .*|scheme = upwind|'
refused jets_dd_2 "inject_time = 3 here, 2 in" -e '$a\
[particles]\
inject_time = 3'
refused jets_dd_2 "not a pgd decomposition checkpoint" -e "s|jets_dd.ck|jets_lag.ck|"
# [initial] has no effect on a restart: warned about
sed -e '$a\
[initial]\
rho = 1' "$out/jets_upwind_2.ini" > "$out/warn.ini"
sed -i "s|^output = .*|output = $out/warn|" "$out/warn.ini"
"$sb" pgd "$out/warn.ini" > "$out/warn.log" 2>&1 ||
  fail "warn: exit $?: $(cat "$out/warn.log")"
grep -q "\\[initial\\] rho ignored: the state comes from the restart" \
  "$out/warn.log" || fail "warn: no warning: $(cat "$out/warn.log")"
# a checkpoint that cannot be written: an input error before the run
# (exit 2), which leaves the previous run's files
refused jets_upwind_1 "checkpoint = $out/no/such/dir.ck: not writable" \
  -e "s|^checkpoint = .*|checkpoint = $out/no/such/dir.ck|"
[ -f "$out/jets_upwind_1/fields.csv" ] ||
  fail "unwritable checkpoint: the previous run's files were removed"

[ $fails -eq 0 ] && rm -rf "$out"
exit $((fails > 0))
