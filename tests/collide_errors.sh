#!/bin/sh
# Bad inputs to `smolbridge collide` and the messages they must give:
# exit status 2, the file and line (or the --set option), the section,
# key and value, and the valid values; warnings for keys that do not
# apply; outputs that never mix across runs.  One line per case:
#   check "what" RC 'expected substring' [sed script applied to base.ini]
set -u
sb="${top_builddir:-.}/smolbridge"
dir="${top_builddir:-.}/tests/collide-errors-out"
rm -rf "$dir"
mkdir -p "$dir"
fails=0
n=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
cat > "$dir/base.ini" <<EOF
[run]
L = 1e-5
dt = 1e-7
steps = 10
output = $dir/out
[species a]
radius = 1e-7
density = 1000
mu = 1e-3
T = 300
count = 10
EOF
# check WHAT RC SUBSTRING SED [extra args...]
check() {
  what=$1 rc=$2 want=$3 script=$4
  shift 4
  n=$((n + 1))
  sed "$script" "$dir/base.ini" > "$dir/t.ini"
  msg=$("$sb" collide "$dir/t.ini" "$@" 2>&1 >/dev/null)
  got=$?
  [ "$got" -eq "$rc" ] || { fail "$what: exit $got, want $rc: $msg"; return; }
  case "$msg" in
    *"$want"*) ;;
    *) fail "$what: message lacks '$want': $msg" ;;
  esac
}
A='/^T = 300/a\'   # append after the species' T line (sed a\ form)

# unknown names: file:line, key, value, valid values
check "detect" 2 't.ini:5: [run] detect = brige: unknown; valid: ballistic, overlap, langevin, bridge, exact, none, md' '4a\
detect = brige'
check "neigh" 2 '[run] neigh = cell: unknown; valid: cells, sweep, brute' '4a\
neigh = cell'
check "outcome" 2 '[run] outcome = stick: unknown; valid: elastic, reinsert, count, correction, merge, dlvo' '4a\
outcome = stick'
check "fluid type" 2 't.ini:13: [fluid] type = shaer: unknown; valid: rest, uniform, shear, ou-field, kraichnan' '$a\
[fluid]\
type = shaer'
# the random fields: required keys and the runs they cannot serve
ou='$a\
[fluid]\
type = ou-field\
u2 = 1e-4\
T_L = 1e-6'
check "ou-field keys" 2 't.ini:13: [fluid] type = ou-field needs u2 (m^2/s^2) and T_L (s)' '$a\
[fluid]\
type = ou-field\
u2 = 1e-4'
check "ou-field placement" 2 't.ini:13: [run] placement = random (the default) with [fluid] type = ou-field' "$ou"
check "ou-field outcome" 2 't.ini:5: [run] outcome = reinsert with [fluid] type = ou-field' "4a\\
outcome = reinsert\\
placement = uniform
$ou"
check "ou-field walls" 2 't.ini:18: [walls] x_lo = absorb with [fluid] type = ou-field' "4a\\
placement = uniform
$ou\\
[walls]\\
x_lo = absorb\\
x_hi = absorb"
check "ou-field runs" 0 '' "4a\\
placement = uniform\\
outcome = count
$ou\\
seed = 7"
check "kraichnan keys" 2 't.ini:13: [fluid] type = kraichnan needs eps_nu (1/s^2)' '$a\
[fluid]\
type = kraichnan'
check "kraichnan box" 2 '[fluid] type = kraichnan is periodic in a cube' 's/^L = 1e-5/Lx = 1e-5\
Ly = 1e-5\
Lz = 2e-5/
$a\
[fluid]\
type = kraichnan\
eps_nu = 1e4'
check "field seed unused" 0 't.ini:14: [fluid] seed ignored: only the random fields' '$a\
[fluid]\
type = rest\
seed = 3'
check "growth" 2 '[agglo] growth = fractal: unknown; valid: stokes, constant' '$a\
[agglo]\
growth = fractal'
check "rng" 2 '[run] rng = ranlux: unknown; valid: mt19937, taus2' '4a\
rng = ranlux'
check "placement" 2 '[run] placement = grid: unknown; valid: random, lattice, uniform' '4a\
placement = grid'
check "ends" 2 '[bridge] ends = middle: unknown; valid: position, diffusive' '$a\
[bridge]\
ends = middle'
check "unknown key" 2 't.ini:5: [run] bogus: unknown key; valid: seed,' '4a\
bogus = 1'
check "unknown species key" 2 '[species a] colour: unknown key; valid: radius,' '$a\
colour = red'
check "unknown section" 2 'unknown section [bogus]; valid: [run]' '$a\
[bogus]\
x = 1'
# also without keys under it (a misspelt [walls] would be left out)
check "empty unknown section" 2 't.ini:12: unknown section [wall]; valid: [run]' '$a\
[wall]'
check "empty species without name" 2 't.ini:12: [species]: a species section needs a name' '$a\
[species]'
# a named species header without keys would add no species (silently,
# beside another species)
check "empty species beside another" 2 't.ini:12: [species b] has no keys: a species needs radius (or diameter), mass (or density), tau (or mu) and count, phi, particle or inflow' '$a\
[species b]'
check "empty species before another" 2 't.ini:6: [species b] has no keys' '5a\
[species b]'
check "key before section" 2 't.ini:1: x = 1 before any section' '1i\
x = 1'
check "species without name" 2 'a species section needs a name' 's/\[species a\]/[species]/'
# duplicates and conflicts
check "duplicate key" 2 't.ini:4: [run] dt given twice (first at ' '3a\
dt = 2e-7'
check "duplicate section" 2 't.ini:12: section [species a] repeated (first at ' '$a\
[species a]\
count = 5'
check "count and phi" 2 '[species a] phi conflicts with count' '$a\
phi = 0.01'
check "radius and diameter" 2 '[species a] diameter conflicts with radius' '$a\
diameter = 2e-7'
check "density and mass" 2 '[species a] mass conflicts with density' '$a\
mass = 1e-18'
check "tau and mu" 2 '[species a] tau conflicts with mu' '$a\
tau = 1e-6'
check "B and T" 2 '[species a] B conflicts with T' '$a\
B = 1'
check "L and Lx" 2 '[run] Lx conflicts with L' '4a\
Lx = 1e-5'
check "steps and t_end" 2 '[run] t_end conflicts with steps' '4a\
t_end = 1e-6'
check "wmax and wmax_kT" 2 '[agglo] wmax_kT conflicts with wmax' '4a\
outcome = merge
$a\
[agglo]\
wmax = 1e-21\
wmax_kT = 1'
# keys that do not apply: warnings (the run goes on), or errors
check "agglo without merging" 0 '[agglo] ignored: outcome is not merge or dlvo' '$a\
[agglo]\
growth = constant'
check "U with rest" 0 '[fluid] U ignored: type = rest' '$a\
[fluid]\
U = 1 0 0'
check "stop_every sign" 2 't.ini:5: [run] stop_every = -1' '4a\
stop_every = -1'
check "stop_every below dt" 2 't.ini:5: [run] stop_every = 1e-08 s: shorter than the step (dt = 1e-07 s); valid: >= dt' '4a\
stop_every = 1e-8\
outcome = merge'
check "stop_every unused" 0 't.ini:5: [run] stop_every ignored: it samples sizes.csv' '4a\
stop_every = 5e-7'
check "merging bridge without stop_every" 0 't.ini:5: [run] detect = bridge with outcome = merge and no [run] stop_every: the bridge reach' '4a\
detect = bridge\
outcome = merge'
sed '4a\
detect = bridge\
outcome = merge\
stop_every = 5e-7' "$dir/base.ini" > "$dir/t.ini"
msg=$("$sb" collide "$dir/t.ini" 2>&1 >/dev/null) \
  || fail "merging bridge with stop_every: exit $?: $msg"
case "$msg" in *"bridge reach"*) fail "merging bridge with stop_every warned: $msg" ;; esac
check "G with uniform" 0 '[fluid] G ignored: type = uniform' '$a\
[fluid]\
type = uniform\
U = 0 0 0\
G = 1'
check "eta with count" 0 '[run] eta ignored' '4a\
outcome = count\
eta = 0.5'
# the walls' detector and deposition without the faces they act on, the
# fluid's density and viscosity without the forces that use them: warned
# about; where they act, not
quiet() {  # quiet WHAT SED: runs, and warns about nothing
  n=$((n + 1))
  sed "$2" "$dir/base.ini" > "$dir/t.ini"
  msg=$("$sb" collide "$dir/t.ini" 2>&1 >/dev/null) || { fail "$1: exit $?: $msg"; return; }
  case "$msg" in *warning*) fail "$1 warned: $msg" ;; esac
}
check "walls detect without walls" 0 't.ini:13: [walls] detect ignored: no absorbing or open face' '$a\
[walls]\
detect = ballistic'
check "walls deposit between reflecting walls" 0 't.ini:15: [walls] deposit ignored: no absorbing face' '$a\
[walls]\
z_lo = reflect\
z_hi = reflect\
deposit = reinsert'
check "walls detect between reflecting walls" 0 't.ini:15: [walls] detect ignored: no absorbing or open face' '$a\
[walls]\
z_lo = reflect\
z_hi = reflect\
detect = langevin'
check "walls deposit with open faces" 0 't.ini:16: [walls] deposit ignored: no absorbing face' '$a\
[walls]\
z_lo = open\
z_hi = open\
detect = ballistic\
deposit = remove'
quiet "walls detect and deposit with absorbing faces" '$a\
[walls]\
z_lo = absorb\
z_hi = reflect\
detect = ballistic\
deposit = reinsert'
check "fluid rho without gravity" 0 't.ini:13: [fluid] rho ignored: no gravity ([fluid] g) and no nonlinear drag law' '$a\
[fluid]\
rho = 1000'
check "fluid rho with zero gravity" 0 't.ini:14: [fluid] rho ignored: no gravity' '$a\
[fluid]\
g = 0 0 0\
rho = 1000'
quiet "fluid rho with gravity" '$a\
[fluid]\
g = 0 0 -9.81\
rho = 1000'
check "fluid mu without nonlinear drag" 0 't.ini:15: [fluid] mu ignored: no species with a nonlinear drag law' '$a\
[fluid]\
g = 0 0 -9.81\
rho = 1000\
mu = 1e-3'
check "fluid mu beside the species mu" 0 't.ini:15: [fluid] mu ignored: every species with a nonlinear drag law gives its own mu' 's/^T = 300/B = 0\
drag = schiller-naumann/; $a\
[fluid]\
rho = 1000\
mu = 1e-3'
quiet "fluid rho and mu with a nonlinear drag" 's/^mu = 1e-3/tau = 1e-7/; s/^T = 300/B = 0\
drag = schiller-naumann/; $a\
[fluid]\
rho = 1000\
mu = 1e-3'
check "z walls in 2-D" 0 't.ini:14: [walls] z_lo ignored: dim = 2 (no z direction)' '4a\
dim = 2
$a\
[walls]\
z_lo = absorb\
z_hi = absorb'
grep -q deposits "$dir/out/series.csv" && fail "z walls in 2-D: deposit columns"
check "g of 3 numbers in 2-D" 2 't.ini:15: [fluid] g: 3 numbers for dim = 2' '4a\
dim = 2
$a\
[fluid]\
rho = 1000\
g = 0 0 -9.81'
check "g of 2 numbers in 3-D" 2 't.ini:13: [fluid] g: 2 numbers for dim = 3' '$a\
[fluid]\
g = 0 -9.81'
check "region without count" 0 't.ini:12: [species a] region ignored: no count or phi' 's/^count = 10/particle = 1e-6 1e-6 1e-6 0 0 0/; $a\
region = 0 1e-5 0 1e-5 0 1e-5'
check "drift without count" 0 't.ini:12: [species a] drift ignored: no count or phi' 's/^count = 10/particle = 1e-6 1e-6 1e-6 0 0 0/; $a\
drift = 1 0 0'
quiet "region and drift with count" '$a\
region = 0 1e-5 0 1e-5 0 1e-5\
drift = 1 0 0'
check "lees_edwards without shear" 0 't.ini:14: [fluid] lees_edwards ignored: only type = shear uses it' '$a\
[fluid]\
type = rest\
lees_edwards = no'
check "shear without G" 2 '[fluid] type = shear needs G' '$a\
[fluid]\
type = shear'
check "uniform without U" 2 '[fluid] type = uniform needs U' '$a\
[fluid]\
type = uniform'
check "correction without bridge" 2 'outcome = correction (the correction step of the bridge detectors) needs detect = bridge' '4a\
outcome = correction'
check "bridge with elastic" 2 'outcome = elastic with detect = bridge' '4a\
detect = bridge'
check "bridge in 2-D" 2 'detect = bridge needs dim = 3' '4a\
dim = 2\
detect = bridge\
outcome = count'
check "turbulence without bridge" 2 '[turbulence] needs detect = bridge' '$a\
[turbulence]\
eps = 1e-4\
nu = 1e-6'
check "first_hit without count" 2 '[observe] first_hit needs outcome = count' '$a\
[observe]\
first_hit = yes'
check "first_hit in 2-D" 2 '[observe] first_hit needs dim = 3' '4a\
dim = 2\
outcome = count
$a\
[observe]\
first_hit = yes'
check "two first_hit reference radii" 2 'first_hit_capacitance conflicts with first_hit_radius' '4a\
outcome = count
$a\
[observe]\
first_hit = yes\
first_hit_radius = 2e-7\
first_hit_capacitance = yes'
check "first_hit_radius in a mixture" 2 't.ini:21: [observe] first_hit_radius with 2 species: one reference radius serves one pair type; leave it out' '4a\
outcome = count
$a\
[species b]\
radius = 1e-7\
density = 1000\
mu = 1e-3\
T = 300\
count = 5\
[observe]\
first_hit = yes\
first_hit_radius = 2e-7'
check "first_hit in a mixture runs" 0 '' '4a\
outcome = count
$a\
[species b]\
radius = 2e-7\
density = 1000\
mu = 1e-3\
T = 300\
count = 5\
[observe]\
first_hit = yes\
first_hit_capacitance = yes'
grep -q '{"species": \["a", "b"\], "hits": ' "$dir/out/summary.json" \
  || fail "first_hit in a mixture: no a-b entry in first_hit.pairs"
check "hit_times without bridge" 2 '[observe] hit_times records bridge hits' '$a\
[observe]\
hit_times = 10'
# [observe] batch_steps and region
check "region without batch_steps" 2 't.ini:13: [observe] region: its mass is reported per batch; give [observe] batch_steps' '$a\
[observe]\
region = 0 1e-6 0 1e-6 0 1e-6'
check "region_every without region" 2 't.ini:13: [observe] region_every without a region and batch_steps' '$a\
[observe]\
region_every = 5'
check "batch_steps not a divisor" 2 't.ini:13: [observe] batch_steps = 3: the run measures 10 steps, not a whole number of batches; valid: a divisor of 10' '$a\
[observe]\
batch_steps = 3'
check "region outside the box" 2 't.ini:14: [observe] region: y0 = 0, y1 = 2e-05 m; valid: 0 <= y0 < y1 <= 1e-05 (the box)' '$a\
[observe]\
batch_steps = 5\
region = 0 1e-6 0 2e-5 0 1e-6'
check "region of 2-D in 3-D" 2 't.ini:14: [observe] region has 4 numbers in 3-D; valid: x0 x1 y0 y1 z0 z1' '$a\
[observe]\
batch_steps = 5\
region = 0 1e-6 0 1e-6'
check "region of 5 numbers" 2 't.ini:14: [observe] region = 0 1 0 1 0: 5 numbers; valid: 4 (2-D: x0 x1 y0 y1) or 6' '$a\
[observe]\
batch_steps = 5\
region = 0 1 0 1 0'
check "region_every not a divisor" 2 't.ini:14: [observe] region_every = 2 does not divide batch_steps = 5' '$a\
[observe]\
batch_steps = 5\
region_every = 2\
region = 0 1e-5 0 1e-5 0 1e-5'
check "batches" 0 '' '$a\
[observe]\
batch_steps = 5\
region_every = 5\
region = 0 1e-5 0 1e-5 0 1e-5'
# two batches; the region is the box: its mass is every particle's
awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) c[$i] = i; next }
  { n++; if ($c["region_samples"] != 1 || $c["n_start"] != 10 ||
             $c["region1"] <= 0) bad = 1 }
  END { exit !(n == 2 && !bad) }' "$dir/out/batches.csv" \
  || fail "batches: batches.csv rows"
# values
check "not a number" 2 't.ini:3: [run] dt = abc: not a number; valid: > 0 s' 's/^dt = .*/dt = abc/'
check "negative dt" 2 '[run] dt = -1: out of range; valid: > 0 s' 's/^dt = .*/dt = -1/'
check "eta range" 2 '[run] eta = 2: out of range; valid: 0 .. 1' '4a\
eta = 2'
check "dim range" 2 '[run] dim = 4: out of range; valid: integer 2 .. 3' '4a\
dim = 4'
check "seed nan" 2 '[run] seed = nan: not a finite number' '4a\
seed = nan'
check "seed negative" 2 '[run] seed = -1: out of range' '4a\
seed = -1'
check "seed fraction" 2 '[run] seed = 1.5: not an integer' '4a\
seed = 1.5'
check "inline # comment" 2 "'#' starts a comment only at the beginning of a line" 's/^dt = 1e-7/dt = 1e-7 # s/'
check "indented key" 2 't.ini:3: the line starts with a blank' 's/^dt/  dt/'
check "long line" 2 't.ini:3: line longer than' "s/^dt = 1e-7/dt = 1e-7 ; $(printf '%0200d' 0)/"
check "region numbers" 2 '[species a] region: 4 numbers for dim = 3' '$a\
region = 0 1e-6 0 1e-6'
check "particle numbers" 2 '[species a] particle: 4 numbers for dim = 3' 's/^count = 10/particle = 1e-6 1e-6 0 0/'
# errors found when the run is built: the real cause
check "radius 1e300" 2 '[species a] radius = 1e+300 m: the particle does not fit the box' 's/^radius = .*/radius = 1e300/'
check "radius > box" 2 'the particle does not fit the box' 's/^radius = .*/radius = 4e-6/'
check "T = 0" 2 '[species a] T = 0 K gives no Brownian motion' 's/^T = 300/T = 0/'
check "no T" 2 'a Langevin species (finite tau) needs T' '/^T = 300/d'
check "free flight T = 0" 2 'free flight (tau = inf) needs T > 0' 's/^mu = .*/tau = inf/; s/^T = 300/T = 0/'
check "particle outside" 2 '[species a] particle: z = 2e-05 m is outside the box' 's/^count = 10/particle = 1e-6 1e-6 2e-5 0 0 0/'
check "particles overlap" 2 'particle overlaps the particle at' 's/^count = 10/particle = 1e-6 1e-6 1e-6 0 0 0\
particle = 1.1e-6 1e-6 1e-6 0 0 0/'
check "random too dense" 2 'random addition jams' 's/^L = .*/L = 2e-6/; s/^count = 10/phi = 0.45/; 4a\
placement = random'
# what the engine refuses when the run is built (sb_engine_set_walls,
# sb_engine_fill_box): the lines of the keys that caused it
check "wall on one face" 2 't.ini:13: [walls] x_lo = reflect with x_hi = periodic: a walled direction needs walls on both faces' '$a\
[walls]\
x_lo = reflect'
check "walls with Lees-Edwards" 2 "t.ini:13: [walls] y_lo = absorb with [fluid] type = shear ($dir/t.ini:16): its Lees-Edwards sliding boundaries need x and y periodic" '$a\
[walls]\
y_lo = absorb\
y_hi = absorb\
[fluid]\
type = shear\
G = 10'
check "walls with Lees-Edwards off" 0 '' '$a\
[walls]\
y_lo = absorb\
y_hi = absorb\
[fluid]\
type = shear\
G = 10\
lees_edwards = no'
check "region outside the box" 2 't.ini:12: [species a] region: z0 = 0, z1 = 2e-05 m; valid: 0 <= z0 < z1 <= 1e-05 (the box)' '$a\
region = 0 1e-5 0 1e-5 0 2e-5'
check "region outside the box, uniform placement" 2 't.ini:13: [species a] region: x0 = 3e-06, x1 = 2e-06 m; valid: 0 <= x0 < x1 <= 1e-05 (the box)' '4a\
placement = uniform
$a\
region = 3e-6 2e-6 0 1e-5 0 1e-5'
check "region between walls" 2 "t.ini:12: [species a] region: z0 = 0, z1 = 1e-07 m leaves no room for centres between the z walls ($dir/t.ini:14)" '$a\
region = 0 1e-5 0 1e-5 0 1e-7\
[walls]\
z_lo = reflect\
z_hi = reflect'
check "region too full" 2 't.ini:11: [species a] count: sb_engine_fill_box: no free position after 10000 tries (box too full) (the region is too full' 's/^L = .*/L = 2e-6/; s/^count = 10/count = 300/; $a\
region = 0 2e-6 0 2e-6 0 4e-7'
check "warm-up past the end" 2 'nothing to measure' 's/^steps = 10/t_end = 1e-6\
warmup = 2e-6/'
check "missing L" 2 '[run] L (or Lx, Ly, Lz) is required' '/^L = /d'
check "missing dt" 2 '[run] dt is required' '/^dt = /d'
check "missing steps" 2 '[run] t_end or steps is required' '/^steps = /d'
check "no species" 2 'no [species NAME] section' '6,$d'
check "empty species" 2 "t.ini:6: [species a] has no keys: a species needs radius" '7,$d'
check "unwritable output" 2 '[run] output = /proc/nope: cannot create the directory' 's|^output = .*|output = /proc/nope|'
# an input error found when the output is prepared leaves the previous
# run's files
"$sb" collide "$dir/base.ini" --set "run.output=$dir/keep" > /dev/null 2>&1 ||
  fail "the run before the bad checkpoint failed"
check "unwritable checkpoint" 2 '[run] checkpoint = /proc/x.ck: not writable' '4a\
checkpoint = /proc/x.ck' --set "run.output=$dir/keep"
grep -q '"status": "ok"' "$dir/keep/summary.json" 2>/dev/null ||
  fail "a bad checkpoint path removed the previous run's summary.json"
# a run whose numbers overflow still writes valid JSON (null, not inf)
"$sb" collide "$dir/base.ini" --set "run.output=$dir/huge" \
  --set "species.a.particle=5e-6 5e-6 5e-6 1e300 0 0" > /dev/null 2>&1
[ -s "$dir/huge/summary.json" ] || fail "overflow: no summary.json"
grep -Eq '(: |\[|, )-?(inf|nan)' "$dir/huge/summary.json" &&
  fail "overflow: inf or nan in summary.json"
check "species name" 2 "t.ini:6: [species a,b]: the species name 'a,b' may hold only letters, digits, '_' and '-'" 's/^\[species a\]/[species a,b]/'
check "negative velocity_scale" 2 '[species a] velocity_scale = 1 -1 1: -1 out of range; valid: numbers >= 0' "$A"'
velocity_scale = 1 -1 1'
check "free flight without T" 2 '[species a]: free flight (tau = inf) needs T > 0' 's/^mu = 1e-3/tau = inf/; s/^density = 1000/mass = 1e-18/; /^T = 300/d; s/^count = 10/particle = 1e-6 1e-6 1e-6 0 0 0/'
# --set with blanks around '=' (as in an INI line) sets the key
"$sb" collide "$dir/base.ini" --set "run.output=$dir/blank" \
  --set "run.steps = 7" > /dev/null 2>&1 || fail "--set 'run.steps = 7' refused"
grep -q '"steps": 7,' "$dir/blank/summary.json" 2>/dev/null ||
  fail "--set 'run.steps = 7' did not set steps"
check "count_variance with reinsert" 0 "[observe] count_variance with outcome = reinsert: its variance assumes a fixed population" '4a\
outcome = reinsert
$a\
[observe]\
count_variance = yes'
# a 2-D run's z faces are none of the box's: an open z_lo leaves [observe]
# exits without an open face and count_variance without one to warn of
check "exits with an open z face in 2-D" 0 '[observe] exits ignored: no [walls] face is open' '2a\
dim = 2
$a\
[walls]\
z_lo = open\
[observe]\
exits = yes\
count_variance = yes'
case "$msg" in
  *"count_variance with an open face"*)
    fail "count_variance in 2-D warned of an open z face: $msg" ;;
esac
check "msd_fit past the run" 2 '[observe] msd_fit = 2 20: the run takes 11 samples of msd_every = 1 steps (lags 0 .. 10)' '$a\
[observe]\
msd_every = 1\
msd_fit = 2 20'
# msd_every against the faces of the box: absorbing or open ones are
# refused; a 2-D box has no z faces (their keys are warned as ignored, as
# everywhere in 2-D), and [walls] deposit acts at absorbing faces only,
# so reflecting walls keep the particles whatever it says
check "msd_every with open walls" 2 't.ini:16: [observe] msd_every with [walls] y_lo = open: particles leave or jump; valid walls: periodic, reflect' '$a\
[walls]\
y_lo = open\
y_hi = open\
[observe]\
msd_every = 2'
check "msd_every with open z faces in 2-D" 0 't.ini:14: [walls] z_lo ignored: dim = 2 (no z direction)' '4a\
dim = 2
$a\
[walls]\
z_lo = open\
z_hi = open\
[observe]\
msd_every = 2'
check "msd_every between reflecting walls with deposit = reinsert" 0 't.ini:15: [walls] deposit ignored: no absorbing face' '$a\
[walls]\
z_lo = reflect\
z_hi = reflect\
deposit = reinsert\
[observe]\
msd_every = 2'
# a merging run goes on from a checkpoint only with its sizes written
# beside it (CHECKPOINT.agglo), a first-contact count only with the
# observer's counts (CHECKPOINT.firsthit), a random field only with its
# state (CHECKPOINT.field), the contacts' velocities only with those
# recorded (CHECKPOINT.contacts)
"$sb" collide "$dir/base.ini" --set "run.checkpoint=$dir/nofh.ck" \
  --set "run.output=$dir/nofh" > /dev/null 2>&1 ||
  fail "a checkpoint without first_hit could not be written"
check "merging restart without its sizes" 2 "[run] outcome = merge with restart: no $dir/nofh.ck.agglo beside the checkpoint" '4a\
outcome = merge\
restart = '"$dir"'/nofh.ck'
check "first_hit restart without its counts" 2 "no $dir/nofh.ck.firsthit beside the checkpoint" '4a\
outcome = count\
restart = '"$dir"'/nofh.ck
$a\
[observe]\
first_hit = yes'
check "bridge restart without its counters" 2 "[run] detect = bridge with restart: no $dir/nofh.ck.bridge beside the checkpoint (it is written with the checkpoint of a run with a bridge detector): what it counted before is unknown" '4a\
detect = bridge\
outcome = count\
restart = '"$dir"'/nofh.ck'
check "field restart without its state" 2 "[fluid] type = ou-field with restart: no $dir/nofh.ck.field beside the checkpoint (it is written with the checkpoint of a run with that field): the field's state is unknown" '4a\
restart = '"$dir"'/nofh.ck
$a\
[fluid]\
type = ou-field\
u2 = 1e-4\
T_L = 1e-6'
# the [species] sections of a restart name the saved species: required,
# in the first run's order and with its radius, mass, tau and T
check "restart without species" 2 "[run] restart: give the first run's [species] sections (the checkpoint has 1 species)" '4a\
restart = '"$dir"'/nofh.ck
6,$d'
check "restart with another species" 2 "t.ini:7: [species a] is not the checkpoint's species 1 (its radius differs" '4a\
restart = '"$dir"'/nofh.ck
s/^radius = 1e-7/radius = 2e-7/'
check "restart with another T" 2 "(its T differs" '4a\
restart = '"$dir"'/nofh.ck
s/^T = 300/T = 310/'
# the Lees-Edwards boundaries of a checkpoint: walls in x are refused as
# a new run with [fluid] type = shear refuses them, named by their line
# (the engine's sb_engine_set_walls message before)
"$sb" collide "$dir/base.ini" --set fluid.type=shear --set fluid.G=10 \
  --set "run.checkpoint=$dir/shear.ck" --set "run.output=$dir/shear" \
  > /dev/null 2>&1 || fail "a checkpoint of a sheared run could not be written"
check "walls on restart with Lees-Edwards" 2 "t.ini:14: [walls] x_lo = reflect with [fluid] type = shear (the restart checkpoint's): its Lees-Edwards sliding boundaries need x and y periodic; put the walls in z, or give [fluid] lees_edwards = no" '4a\
restart = '"$dir"'/shear.ck
$a\
[walls]\
x_lo = reflect\
x_hi = reflect'
# walls in x the checkpoint keeps (the file does not give them) with
# [fluid] type = shear given: refused at set-up with the new run's
# message, naming the keys (the engine's at the first step before);
# the faces given periodic replace them
"$sb" collide "$dir/base.ini" --set walls.x_lo=reflect \
  --set walls.x_hi=reflect --set "run.checkpoint=$dir/wx.ck" \
  --set "run.output=$dir/wx" > /dev/null 2>&1 ||
  fail "a checkpoint with walls in x could not be written"
check "shear on restart against the checkpoint's walls" 2 "t.ini:14: [fluid] type = shear with the restart checkpoint's walls x_lo = reflect, x_hi = reflect: its Lees-Edwards sliding boundaries need x and y periodic; give [walls] x_lo = periodic and x_hi = periodic, or [fluid] lees_edwards = no" '4a\
restart = '"$dir"'/wx.ck
$a\
[fluid]\
type = shear\
G = 10'
check "shear on restart replacing the checkpoint's walls" 0 '' '4a\
restart = '"$dir"'/wx.ck
$a\
[fluid]\
type = shear\
G = 10\
[walls]\
x_lo = periodic\
x_hi = periodic'
# the z faces of a 2-D checkpoint are warned as ignored, as in a new
# 2-D run (they were silently unused)
"$sb" collide "$dir/base.ini" --set run.dim=2 \
  --set "run.checkpoint=$dir/d2.ck" --set "run.output=$dir/d2" \
  > /dev/null 2>&1 || fail "a 2-D checkpoint could not be written"
check "z walls on a 2-D restart" 0 "t.ini:14: [walls] z_lo ignored: the restart checkpoint's dim = 2 (no z direction)" '4a\
restart = '"$dir"'/d2.ck
$a\
[walls]\
z_lo = absorb\
z_hi = absorb'
# on restart msd_every and [walls] detect and deposit meet the faces of
# the run: the checkpoint's dim, and its walls where the file gives none
# (they were checked against the file's walls, and detect and deposit
# not at all).  unwarned WHAT TEXT SED: runs, without TEXT in its messages
unwarned() {
  n=$((n + 1))
  sed "$3" "$dir/base.ini" > "$dir/t.ini"
  msg=$("$sb" collide "$dir/t.ini" 2>&1 >/dev/null) ||
    { fail "$1: exit $?: $msg"; return; }
  case "$msg" in *"$2"*) fail "$1: warned '$2': $msg" ;; esac
}
"$sb" collide "$dir/base.ini" --set walls.x_lo=open --set walls.x_hi=open \
  --set "run.checkpoint=$dir/ox.ck" --set "run.output=$dir/ox" \
  > /dev/null 2>&1 || fail "a checkpoint with open x faces could not be written"
"$sb" collide "$dir/base.ini" --set walls.x_lo=absorb \
  --set walls.x_hi=absorb --set "run.checkpoint=$dir/ax.ck" \
  --set "run.output=$dir/ax" > /dev/null 2>&1 ||
  fail "a checkpoint with absorbing x faces could not be written"
check "msd_every on restart with the checkpoint's open faces" 2 "t.ini:14: [observe] msd_every with the restart checkpoint's [walls] x_lo = open: particles leave or jump; valid walls: periodic, reflect: give [walls] x_lo and x_hi one of them" '4a\
restart = '"$dir"'/ox.ck
$a\
[observe]\
msd_every = 2' --set "run.output=$dir/ox_msd"
[ ! -e "$dir/ox_msd" ] ||
  fail "msd_every on restart with the checkpoint's open faces: outputs were written"
check "msd_every on restart replacing the checkpoint's open faces" 0 '' '4a\
restart = '"$dir"'/ox.ck
$a\
[walls]\
x_lo = reflect\
x_hi = reflect\
[observe]\
msd_every = 2'
check "msd_every on a 2-D restart with open z faces" 0 "t.ini:14: [walls] z_lo ignored: the restart checkpoint's dim = 2 (no z direction)" '4a\
restart = '"$dir"'/d2.ck
$a\
[walls]\
z_lo = open\
z_hi = open\
[observe]\
msd_every = 2'
check "walls detect on restart without walls" 0 't.ini:14: [walls] detect ignored: no absorbing or open face' '4a\
restart = '"$dir"'/nofh.ck
$a\
[walls]\
detect = ballistic'
check "walls deposit on restart with the checkpoint's open faces" 0 't.ini:15: [walls] deposit ignored: no absorbing face' '4a\
restart = '"$dir"'/ox.ck
$a\
[walls]\
detect = ballistic\
deposit = reinsert'
case "$msg" in
  *"detect ignored"*)
    fail "walls detect on restart with the checkpoint's open faces: $msg" ;;
esac
check "walls deposit on a 2-D restart with absorbing z faces" 0 't.ini:16: [walls] deposit ignored: no absorbing face' '4a\
restart = '"$dir"'/d2.ck
$a\
[walls]\
z_lo = absorb\
z_hi = absorb\
deposit = reinsert'
unwarned "walls detect and deposit on restart with the checkpoint's absorbing faces" 'walls] de' '4a\
restart = '"$dir"'/ax.ck
$a\
[walls]\
detect = ballistic\
deposit = reinsert'
# the Kraichnan field against the checkpoint's box, not the file's cube
sed 's/^L = 1e-5/Lx = 1e-5\
Ly = 1e-5\
Lz = 2e-5/' "$dir/base.ini" > "$dir/rect.ini"
"$sb" collide "$dir/rect.ini" --set "run.checkpoint=$dir/rect.ck" \
  --set "run.output=$dir/rect" > /dev/null 2>&1 ||
  fail "a checkpoint of a box could not be written"
check "kraichnan restart in the checkpoint's box" 2 "t.ini:14: [fluid] type = kraichnan is periodic in a cube: the restart checkpoint's box is Lx, Ly, Lz = 1e-05, 1e-05, 2e-05 m" '4a\
restart = '"$dir"'/rect.ck
$a\
[fluid]\
type = kraichnan\
eps_nu = 1e4'
# gravity with a free-flight species: refused at set-up, before any
# output, naming the species and [fluid] g (the engine's message at the
# placement or the first step before); on restart the checkpoint's
# species
check "gravity with free flight" 2 "t.ini:13: [fluid] g = 0 -9.81 0 with [species a] tau = inf: a free-flight species has no drag and no settling velocity" 's/^mu = 1e-3/tau = inf/
$a\
[fluid]\
g = 0 -9.81 0'
sed 's/^mu = 1e-3/tau = inf/' "$dir/base.ini" > "$dir/free.ini"
"$sb" collide "$dir/free.ini" --set "run.checkpoint=$dir/free.ck" \
  --set "run.output=$dir/free" > /dev/null 2>&1 ||
  fail "a checkpoint of a free-flight run could not be written"
check "gravity with free flight on restart" 2 "--set fluid.g=0 0 -9.81: [fluid] g = 0 0 -9.81 with [species a] tau = inf (the restart checkpoint's): a free-flight species" 's/^mu = 1e-3/tau = inf/; 4a\
restart = '"$dir"'/free.ck' --set "fluid.g=0 0 -9.81" --set "run.output=$dir/free_g"
[ ! -e "$dir/free_g" ] ||
  fail "gravity with free flight on restart: outputs were written"
check "restart with two species" 2 "[run] restart: 2 [species] sections for the checkpoint's 1 species" '4a\
restart = '"$dir"'/nofh.ck
$a\
[species b]\
radius = 1e-7\
density = 1000\
mu = 1e-3\
T = 300'
check "restart: fluid properties" 0 "t.ini:14: [fluid] rho ignored: the fluid properties and drag laws come from the restart checkpoint" '4a\
restart = '"$dir"'/nofh.ck
$a\
[fluid]\
rho = 1000'
check "restart: placement keys" 0 "[species a] count ignored: the particles come from the restart checkpoint" 's/^steps = 10/t_end = 2e-6/; 4a\
restart = '"$dir"'/nofh.ck'
"$sb" collide "$dir/base.ini" --set run.outcome=count \
  --set observe.first_hit=yes --set "run.checkpoint=$dir/fh.ck" \
  --set "run.output=$dir/fh" > /dev/null 2>&1 ||
  fail "a checkpoint with first_hit could not be written"
check "first_hit_velocities restart without them" 2 "no $dir/fh.ck.contacts beside the checkpoint (it is written with the checkpoint of a run with first_hit_velocities): the contacts recorded before it is unknown" '4a\
outcome = count\
restart = '"$dir"'/fh.ck
$a\
[observe]\
first_hit = yes\
first_hit_velocities = 100'
# the checks that depend on dim take the checkpoint's (the file's is
# ignored): [observe] grid of a 2-D checkpoint has 2 values, not 3; a
# bridge detector and first_hit need a 3-D checkpoint, whatever the file's
# dim (its Lz not warned as ignored for dim = 2 either)
check "grid on a 2-D restart" 0 '' '4a\
restart = '"$dir"'/d2.ck
$a\
[observe]\
grid = 4 4'
check "grid of 3 on a 2-D restart" 2 "t.ini:14: [observe] grid has 3 values in 2-D (the restart checkpoint's); valid: nx ny" '4a\
restart = '"$dir"'/d2.ck
$a\
[observe]\
grid = 4 4 4'
check "bridge on a 2-D restart" 2 "t.ini:6: [run] detect = bridge needs dim = 3 (the restart checkpoint's dim = 2)" '4a\
restart = '"$dir"'/d2.ck\
detect = bridge\
outcome = count'
check "first_hit restart with dim = 2 in the file" 0 '' 's/^L = 1e-5/Lx = 1e-5\
Ly = 1e-5\
Lz = 1e-5/
4a\
dim = 2\
outcome = count\
restart = '"$dir"'/fh.ck
$a\
[observe]\
first_hit = yes'
msg=$("$sb" collide "$dir/t.ini" 2>&1 >/dev/null)
case "$msg" in
  *"Lz ignored: dim = 2"*) fail "Lz on restart warned for the file's dim: $msg" ;;
esac
# --set
check "--set unknown key" 2 '--set run.dtt=1: [run] dtt: unknown key' '' --set run.dtt=1
check "--set bad form" 2 '--set dt=1: expected SECTION.KEY=VALUE' '' --set dt=1
check "--set unknown species" 2 '--set species.b.phi=0.1: no section [species b]; species: a' '' --set species.b.phi=0.1
check "--set bad value" 2 '--set run.dt=-1: [run] dt = -1: out of range' '' --set run.dt=-1

# files that are not configurations
n=$((n + 3))
mkdir -p "$dir/adir"
msg=$("$sb" collide "$dir/adir" 2>&1); rc=$?
[ $rc -eq 2 ] && case "$msg" in *"is a directory"*) ;; *) false ;; esac \
  || fail "directory: $rc $msg"
: > "$dir/empty.ini"
msg=$("$sb" collide "$dir/empty.ini" 2>&1); rc=$?
[ $rc -eq 2 ] && case "$msg" in *"no keys (empty file?)"*) ;; *) false ;; esac \
  || fail "empty file: $rc $msg"
msg=$("$sb" collide "$dir/none.ini" 2>&1); rc=$?
[ $rc -eq 2 ] && case "$msg" in *"cannot read"*) ;; *) false ;; esac \
  || fail "missing file: $rc $msg"

# nothing stale: a second run removes the first run's snapshots
n=$((n + 1))
sed '4a\
snapshot_every = 1' "$dir/base.ini" > "$dir/s.ini"
"$sb" collide "$dir/s.ini" >/dev/null 2>&1
sed '4a\
snapshot_every = 5' "$dir/base.ini" > "$dir/s.ini"
"$sb" collide "$dir/s.ini" >/dev/null 2>&1
nsnap=$(ls "$dir/out" | grep -c '^snap_')
[ "$nsnap" -eq 2 ] || fail "stale snapshots: $nsnap files, want 2"
grep -qx 'snap_000001.csv' "$dir/out/manifest.txt" || fail "manifest lacks snapshots"
# no particles: the kernel is undefined, with the reason
n=$((n + 1))
sed 's/^count = 10/count = 0/' "$dir/base.ini" > "$dir/z.ini"
"$sb" collide "$dir/z.ini" >/dev/null 2>&1 || fail "count = 0 run failed"
grep -q '"kernel": {"K": null, "ci95": null, "why": "fewer than 2 particles' \
  "$dir/out/summary.json" || fail "count = 0: kernel not null with a reason"
# phi = 0.5 (the documented maximum) runs: lattice start, with a warning
n=$((n + 1))
sed 's/^L = .*/L = 2e-6/; s/^count = 10/phi = 0.5/' "$dir/base.ini" > "$dir/p.ini"
msg=$("$sb" collide "$dir/p.ini" 2>&1 >/dev/null) || fail "phi = 0.5: $msg"
case "$msg" in *"start on a lattice"*) ;; *) fail "phi = 0.5: no lattice warning: $msg" ;; esac
# checkpoints of identical runs are byte-identical
n=$((n + 1))
sed "4a\\
checkpoint = $dir/a.ck" "$dir/base.ini" > "$dir/c.ini"
"$sb" collide "$dir/c.ini" >/dev/null 2>&1
sed "4a\\
checkpoint = $dir/b.ck" "$dir/base.ini" > "$dir/c.ini"
"$sb" collide "$dir/c.ini" >/dev/null 2>&1
cmp -s "$dir/a.ck" "$dir/b.ck" || fail "checkpoints of identical runs differ"

[ "$fails" -eq 0 ] && echo "collide_errors: $n cases checked"
[ "$fails" -eq 0 ] && rm -rf "$dir"
exit $((fails > 0))
