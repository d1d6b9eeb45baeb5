#!/bin/sh
# Thread-count independence of `smolbridge collide` (docs/engine.md,
# "Threads"): the same summary.json (wall-clock time masked) and
# series.csv with OMP_NUM_THREADS = 1, 2 and 3 and with --threads 3, for
#  - ~6500 Brownian spheres on the keyed streams (rng = philox: transport
#    in parallel) and on the sequential MT19937 (serial transport); the
#    cells are scanned in parallel in both;
#  - a dense hard-sphere gas (phi = 0.05, ~4400 particles, tens of
#    thousands of candidate pairs per step: the parallel detection pass);
#  - first-contact counting with the Langevin detector on the keyed
#    streams (~9800 spheres of 50 nm, phi = 0.01, dt = 2 tau_p: the
#    Langevin search and the observed built-in's first pass, ~2000
#    records a step, in parallel), contacts.csv too;
#  - that first-contact run re-sorted in memory every 3 steps
#    (sort_every, one thread): the same first-contact results and the
#    same contacts.csv (the sums over particles of series.csv and the
#    kinetic energy follow the memory order in their last bits);
#  - both runs with first_hit_velocities = 1400, a cap that falls inside
#    the eighth step: the same contacts.csv, the first 1400 rows of the
#    uncapped
#    one (the earliest contacts; rows in order of time).
# A build without OpenMP runs everything on one thread and passes
# trivially.
set -u
sb="${top_builddir:-.}/smolbridge"
sb="$(cd "$(dirname "$sb")" && pwd)/$(basename "$sb")"
ex="$(cd "${srcdir:-.}/examples" && pwd)"
out="${top_builddir:-.}/tests/threads-out"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
rm -rf "$out"
mkdir -p "$out"
out="$(cd "$out" && pwd)"
cat > "$out/gas.ini" <<'INI'
[run]
seed = 3
L = 1e-8
dt = 2e-13
steps = 25
thermalize = 300
sample_every = 5
output = o
[species he]
radius = 140e-12
mass = 6.642e-27
tau = inf
T = 300
phi = 0.05
INI
cat > "$out/fh.ini" <<'INI'
[run]
seed = 3
L = 4e-6
dt = 8e-8
steps = 60
detect = langevin
outcome = count
rng = philox
output = o
[observe]
first_hit = yes
first_hit_skip_seen = yes
first_hit_capacitance = yes
first_hit_velocities = 5000
[species primary]
diameter = 50e-9
density = 1000
tau = 4e-8
T = 296.15
phi = 1e-2
INI

# run NAME THREADS-SETTING CMD...: in $out/NAME/, outputs in o/
run() {
  d="$out/$1"; shift
  mkdir -p "$d"
  (cd "$d" && env "$@" > log 2>&1) || fail "$d: $(tail -n 3 "$d/log")"
  sed -i 's/"wall_seconds": .*/"wall_seconds": T/' "$d/o/summary.json" 2>/dev/null
}
same() {  # same A B: identical outputs
  for f in summary.json series.csv contacts.csv; do
    [ -e "$out/$1/o/$f" ] || [ $f = contacts.csv ] || fail "$1: no $f"
    [ -e "$out/$1/o/$f" ] || continue
    cmp -s "$out/$1/o/$f" "$out/$2/o/$f" || fail "$f differs between $1 and $2"
  done
}
for cfg in philox mt19937 gas fh; do
  case $cfg in
    gas) args="$out/gas.ini" ;;
    fh) args="$out/fh.ini" ;;
    *) args="$ex/v2_brownian_1um.ini --set run.rng=$cfg --set run.L=7e-5 --set run.steps=150 --set run.output=o" ;;
  esac
  for nt in 1 2 3; do
    run "$cfg-$nt" OMP_NUM_THREADS=$nt "$sb" collide $args
  done
  run "$cfg-opt3" OMP_NUM_THREADS=1 "$sb" collide $args --threads 3
  [ -s "$out/$cfg-1/o/series.csv" ] || fail "$cfg: no series.csv"
  same "$cfg-1" "$cfg-2"
  same "$cfg-1" "$cfg-3"
  same "$cfg-1" "$cfg-opt3"
done
# settling under gravity (examples/v16_settling.ini with B > 0): the keyed
# streams apply the settling velocity too (final momentum p_y as the
# sequential generator's within 2%), whatever the thread count
for cfg in sp1 sp3 smt; do
  case $cfg in smt) r=mt19937 nt=1 ;; *) r=philox nt=${cfg#sp} ;; esac
  run "$cfg" OMP_NUM_THREADS=$nt "$sb" collide "$ex/v16_settling.ini" \
    --set run.rng=$r --set run.output=o --set run.t_end=1 \
    --set species.big.B=1e-4 --set species.small.B=1e-4
done
same sp1 sp3
awk -F, 'FNR == 1 { next } { last[FILENAME] = $8 }
  END { a = last[ARGV[1]]; b = last[ARGV[2]]
        if (!(a < 0 && b < 0 && (a - b) / b < 0.02 && (b - a) / b < 0.02)) {
          print "settling p_y: " a " (philox) vs " b " (mt19937)"; exit 1 } }' \
  "$out/sp1/o/series.csv" "$out/smt/o/series.csv" || fail "settling on streams"
grep -q '"rng": "sb_philox4x32_10"' "$out/philox-1/o/summary.json" || fail "rng = philox not in summary.json"
cmp -s "$out/philox-1/o/series.csv" "$out/mt19937-1/o/series.csv" && fail "philox and mt19937 runs are identical"
grep -q '"collisions": [1-9]' "$out/gas-1/o/summary.json" || fail "gas: no collision"
[ "$(wc -l < "$out/fh-1/o/contacts.csv")" -gt 300 ] || fail "fh: few contacts"
run fh-sort OMP_NUM_THREADS=1 "$sb" collide "$out/fh.ini" --set run.sort_every=3
[ "$(grep '"first_hit"' "$out/fh-1/o/summary.json")" = \
  "$(grep '"first_hit"' "$out/fh-sort/o/summary.json")" ] ||
  fail "fh: sort_every changed the first-contact results"
cmp -s "$out/fh-1/o/contacts.csv" "$out/fh-sort/o/contacts.csv" ||
  fail "fh: sort_every changed contacts.csv"
tail -n +2 "$out/fh-1/o/contacts.csv" | sort -t, -k1,1g -c 2>/dev/null ||
  fail "fh: contacts.csv not in order of time"
for cfg in cap cap-sort; do
  case $cfg in cap) se=0 ;; *) se=3 ;; esac
  run "fh-$cfg" OMP_NUM_THREADS=2 "$sb" collide "$out/fh.ini" \
    --set observe.first_hit_velocities=1400 --set run.sort_every=$se
done
head -n 1401 "$out/fh-1/o/contacts.csv" | cmp -s - "$out/fh-cap/o/contacts.csv" ||
  fail "fh: the capped contacts.csv is not the earliest 1400 contacts"
cmp -s "$out/fh-cap/o/contacts.csv" "$out/fh-cap-sort/o/contacts.csv" ||
  fail "fh: sort_every changed the capped contacts.csv"
"$sb" collide "$out/gas.ini" --threads 0 > /dev/null 2>&1 && fail "--threads 0 accepted"
[ $fails -eq 0 ] || exit 1
rm -rf "$out"
echo "threads: summary.json and series.csv identical with 1, 2 and 3 threads"
