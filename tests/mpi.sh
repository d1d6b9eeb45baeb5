#!/bin/sh
# Work shared between processes (docs/parallel.md).  Every build:
# `validate --seeds`, `collide --sweep` and three `pgd` decompositions
# (all-Eulerian, all-Lagrangian, mixed) in one process, and a build
# without MPI started as several processes refuses with a message.  A
# build with --with-mpi (SB_TEST_MPI=yes): `mpirun -n 2` and `mpirun -n 3
# --oversubscribe` give the files of the single-process run byte for byte
# (wall-clock and CPU times masked), and the other ranks stay silent; the
# decompositions also under `mpirun -n 1`, and with more ranks than
# blocks they stop with a message.
set -u
sb="${top_builddir:-.}/smolbridge"
sb="$(cd "$(dirname "$sb")" && pwd)/$(basename "$sb")"
ex="$(cd "${srcdir:-.}/examples" && pwd)"
out="${top_builddir:-.}/tests/mpi-out"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
rm -rf "$out"
mkdir -p "$out"
out="$(cd "$out" && pwd)"

# the work: a few fast cases over 3 seeds, 5 of them once, and a sweep of
# four collide points (one of them an input error)
CASES="--case V9/two-spheres-45 --case V11/bb-hit-ks --case V10/ou-short-time"
cat > "$out/points.txt" <<'EOF'
# a sweep: seeds, run length, a bad value
run.seed=1
run.seed=2 run.steps=300
run.dt=bad        # an input error: reported in its row, the others run
run.seed=3 species.colloid.phi=5e-3
EOF

# run_all DIR LAUNCHER...: the three jobs in DIR (relative paths, so that
# the outputs name the same directories)
run_all() {
  d=$1; shift
  mkdir -p "$out/$d"
  (cd "$out/$d" &&
   "$@" "$sb" validate --seeds 3 $CASES --out cal > cal.out 2> cal.err
   echo $? > cal.rc
   "$@" "$sb" validate $CASES --case V8/pbe-discrete --case V15/pgd-drag \
     --out one > one.out 2> one.err
   echo $? > one.rc
   "$@" "$sb" collide "$ex/v2_brownian_1um.ini" --set run.output=sw \
     --set run.steps=200 --sweep "$out/points.txt" > sw.out 2> sw.err
   echo $? > sw.rc)
}

# files of DIR with the wall-clock times masked, one stream
masked() {
  (cd "$out/$1" &&
   for f in cal.out cal.rc cal/all_seeds.csv cal/calibration.csv \
            cal/calibration.md one.out one.rc one/validate.csv \
            one/report.md sw.out sw.rc sw/sweep.csv \
            sw/point_000/series.csv sw/point_000/summary.json \
            sw/point_001/series.csv sw/point_001/summary.json \
            sw/point_003/series.csv sw/point_003/summary.json; do
     echo "== $f"
     [ -f "$f" ] || { echo "(missing)"; continue; }
     sed -e 's/([0-9.]* s)/(T s)/' -e 's/^_[0-9.]* s_$/_T s_/' \
         -e 's/"wall_seconds": .*/"wall_seconds": T/' "$f"
   done)
}

# pgd decompositions of the exercise's crossing jets (27 x 27 cells, 3 x 3
# blocks, drag towards a gas crossing the jets, so that particles cross
# block boundaries both ways): NAME:KINDS:SCHEME
cat > "$out/jets.ini" <<'EOF'
[run]
dim = 2
nx = 27
t_end = 1.6
output_every = 0.7
method = decomposition
[drag]
tau = 3
U = 0.2 -0.3
[boundary]
west = outflow
east = outflow
south = outflow
north = outflow
[inflow west]
side = west
first = 11
count = 5
rho = 1
u = 1 0
[inflow south]
side = south
first = 11
count = 5
rho = 1
u = 0 1
[decomposition]
blocks = 3 3
EOF
PGD_RUNS="alle:EEEEEEEEE:muscl alll:LLLLLLLLL:upwind mixed:ELLLELLLE:muscl"
# pgd_all DIR LAUNCHER...: the three runs in DIR/pgd_NAME
pgd_all() {
  d=$1; shift
  mkdir -p "$out/$d"
  for r in $PGD_RUNS; do
    name=${r%%:*}; rest=${r#*:}; kinds=${rest%%:*}; scheme=${rest#*:}
    # scheme and output in the one [run] section, kinds in the last one
    { sed "s/^\[run\]\$/[run]\\
scheme = $scheme\\
output = pgd_$name/" "$out/jets.ini"; printf 'kinds = %s\n' "$kinds"
    } > "$out/$d/pgd_$name.ini"
    (cd "$out/$d" && "$@" "$sb" pgd "pgd_$name.ini" > "pgd_$name.out" \
       2> "pgd_$name.err"; echo $? > "pgd_$name.rc")
  done
}
# their files, CPU times masked
pgd_masked() {
  (cd "$out/$1" &&
   for r in $PGD_RUNS; do
     name=${r%%:*}
     for f in pgd_$name.rc pgd_$name.out pgd_$name/fields.csv \
              pgd_$name/fields_00000.csv pgd_$name/fields_00001.csv \
              pgd_$name/summary.json; do
       echo "== $f"
       [ -f "$f" ] || { echo "(missing)"; continue; }
       sed -e 's/"cpu_seconds": .*/"cpu_seconds": T/' "$f"
     done
   done)
}

run_all serial
pgd_all serial
for r in $PGD_RUNS; do
  name=${r%%:*}
  [ "$(cat "$out/serial/pgd_$name.rc")" = 0 ] || fail "pgd $name: exit $(cat "$out/serial/pgd_$name.rc"): $(cat "$out/serial/pgd_$name.err")"
  [ "$(wc -l < "$out/serial/pgd_$name/fields.csv")" = 730 ] || fail "pgd $name: fields.csv rows"
  [ -s "$out/serial/pgd_$name/fields_00001.csv" ] || fail "pgd $name: snapshots"
done
grep -q '"particles": 0$' "$out/serial/pgd_alle/summary.json" || fail "pgd all-E: particles"
for name in alll mixed; do
  grep -q '"particles": [1-9]' "$out/serial/pgd_$name/summary.json" || fail "pgd $name: no particles"
done
for f in cal/all_seeds.csv cal/calibration.csv one/validate.csv sw/sweep.csv \
         sw/point_001/summary.json; do
  [ -s "$out/serial/$f" ] || fail "serial: no $f"
done
[ "$(cat "$out/serial/one.rc")" = 0 ] || fail "validate: exit $(cat "$out/serial/one.rc")"
[ "$(cat "$out/serial/sw.rc")" = 1 ] || fail "sweep with a bad point: exit $(cat "$out/serial/sw.rc"), want 1"
[ "$(grep -c '^[0-9]*,ok,' "$out/serial/sw/sweep.csv")" = 3 ] || fail "sweep: 3 ok rows expected"
grep -q '^2,input error,.*run.dt=bad' "$out/serial/sw/sweep.csv" || fail "sweep: the bad point's row"
grep -q '"steps": 300,' "$out/serial/sw/point_001/summary.json" || fail "sweep: the point's override"
[ "$(grep -c '^[0-9]' "$out/serial/cal/all_seeds.csv")" -gt 3 ] || fail "all_seeds.csv rows"

if [ "${SB_TEST_MPI:-no}" != yes ]; then
  # a build without MPI, started as rank 0 of 2 (what mpirun sets)
  msg=$(OMPI_COMM_WORLD_SIZE=2 OMPI_COMM_WORLD_RANK=0 "$sb" validate --list 2>&1 >/dev/null)
  rc=$?
  [ $rc -eq 2 ] || fail "non-MPI build as 2 processes: exit $rc, want 2"
  case "$msg" in *"without MPI"*--with-mpi*) ;; *) fail "message: $msg" ;; esac
  msg=$(PMIX_SIZE=2 PMIX_RANK=1 "$sb" validate --list 2>&1 >/dev/null)
  [ -z "$msg" ] || fail "rank 1 of a non-MPI build should stay silent: $msg"
  SB_NO_MPI=1 OMPI_COMM_WORLD_SIZE=2 "$sb" --version >/dev/null 2>&1 \
    || fail "SB_NO_MPI=1 should run"
  "$sb" --version | grep -q 'MPI: no' || fail "--version: MPI: no"
  [ $fails -eq 0 ] || exit 1
  rm -rf "$out"
  echo "mpi: single-process checks passed (built without MPI: mpirun checks skipped)"
  exit 0
fi

"$sb" --version | grep -q 'MPI: yes' || fail "--version: MPI: yes"
mpirun="${MPIRUN:-mpirun}"
command -v "$mpirun" >/dev/null 2>&1 || { echo "FAIL: built with MPI but no mpirun ($mpirun)"; exit 1; }
# Open MPI refuses root unless told (containers, CI)
if [ "$(id -u)" = 0 ]; then
  OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
  export OMPI_ALLOW_RUN_AS_ROOT OMPI_ALLOW_RUN_AS_ROOT_CONFIRM
fi
if ! "$mpirun" -n 1 "$sb" --version > "$out/probe.out" 2>&1; then
  cat "$out/probe.out"
  echo "FAIL: '$mpirun -n 1 smolbridge --version' does not start"
  exit 1
fi
masked serial > "$out/serial.txt"
pgd_masked serial > "$out/pgd_serial.txt"
for n in 1 2 3; do
  pgd_all "pgd_np$n" "$mpirun" -n $n --oversubscribe
  pgd_masked "pgd_np$n" > "$out/pgd_np$n.txt"
  if ! cmp -s "$out/pgd_serial.txt" "$out/pgd_np$n.txt"; then
    fail "pgd: mpirun -n $n differs from the single process:"
    diff "$out/pgd_serial.txt" "$out/pgd_np$n.txt" | head -n 20
  fi
  [ $n = 1 ] || grep -q "($n ranks)" "$out/pgd_np$n/pgd_mixed.err" ||
    fail "pgd -n $n: no rank count in the progress line"
done
# more ranks than blocks: an input error, said once
sed -e 's/^blocks = .*/blocks = 1 2/' -e 's/^kinds = .*/kinds = EL/' \
  "$out/serial/pgd_mixed.ini" > "$out/pgd_small.ini"
"$mpirun" -n 3 --oversubscribe "$sb" pgd "$out/pgd_small.ini" > /dev/null 2> "$out/pgd_small.err"
rc=$?
[ $rc -ne 0 ] || fail "pgd with 3 ranks for 2 blocks: exit 0"
[ "$(grep -c 'at most one rank per block' "$out/pgd_small.err")" = 1 ] ||
  fail "pgd with 3 ranks for 2 blocks: $(cat "$out/pgd_small.err")"
# an output directory that rank 0 cannot create: every rank stops with
# status 1 (none is left waiting for the others)
sed -e 's|^output = .*|output = /dev/null/x|' "$out/serial/pgd_mixed.ini" \
  > "$out/pgd_bad.ini"
to=""; command -v timeout > /dev/null 2>&1 && to="timeout 300"
$to "$mpirun" -n 2 --oversubscribe "$sb" pgd "$out/pgd_bad.ini" > /dev/null 2> "$out/pgd_bad.err"
rc=$?
[ $rc -eq 1 ] || fail "pgd with a bad output directory under mpirun -n 2: exit $rc, want 1"
grep -q 'cannot create directory' "$out/pgd_bad.err" ||
  fail "pgd with a bad output directory: $(cat "$out/pgd_bad.err")"
# another method runs on rank 0, with a note
sed -e 's/^method = .*/method = euler/' -e 's/^output = .*/output = pgd_e/' \
  "$out/serial/pgd_alle.ini" > "$out/pgd_e.ini"
(cd "$out" && "$mpirun" -n 2 --oversubscribe "$sb" pgd pgd_e.ini > /dev/null 2> pgd_e.err) ||
  fail "pgd method = euler under mpirun -n 2"
grep -q 'rank 0 only' "$out/pgd_e.err" || fail "pgd euler under mpirun: no note"
[ -s "$out/pgd_e/fields.vtk" ] || fail "pgd euler under mpirun: no fields.vtk"
for n in 2 3; do
  run_all "np$n" "$mpirun" -n $n --oversubscribe
  masked "np$n" > "$out/np$n.txt"
  if ! cmp -s "$out/serial.txt" "$out/np$n.txt"; then
    fail "mpirun -n $n differs from the single process:"
    diff "$out/serial.txt" "$out/np$n.txt" | head -n 20
  fi
  # one voice: rank 0's progress only
  grep -q 'rank 1 of' "$out/np$n/one.err" && fail "-n $n: rank 1 printed progress"
  grep -q 'rank 0 of' "$out/np$n/one.err" || fail "-n $n: no rank-0 progress"
done
# a command that does not distribute runs once, with a note
o=$("$mpirun" -n 2 --oversubscribe "$sb" eval bb_cross_prob x=1 y=1 a=0 v=1 2>"$out/eval.err")
[ "$(echo "$o" | grep -c .)" = 1 ] || fail "eval under mpirun -n 2 printed: $o"
grep -q 'rank 0 only' "$out/eval.err" || fail "eval under mpirun: no note"
[ $fails -eq 0 ] || exit 1
rm -rf "$out"
echo "mpi: mpirun -n 2 and -n 3 reproduce the single-process files (pgd also -n 1)"
