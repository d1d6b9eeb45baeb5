#!/bin/sh
# Every state a `smolbridge collide` run keeps goes through a checkpoint:
# a run stopped part-way ([run] checkpoint, and the states written beside
# it) and continued from there ([run] restart) gives the results of the
# run in one go, to the last bit.  One case per state: the engine's
# collision tally (count_variance), the outputs' part before the
# checkpoint (a mixture's series.csv), the open boundaries' counters, the
# first-contact observer with the recorded contact velocities, the
# agglomeration context (DLVO sticking, whose draws come from the
# engine's generator), both random fields, and a bridge detector's
# counters with the turbulent split of its collisions, and the MD
# detector's reach under the checkpoint's gravity; and the points of
# a sweep each write their own checkpoint; and a restart changes the
# walls' settings and the Lees-Edwards images only where its file says
# so, and checks its keys against the fluid the checkpoint keeps, and
# [observe] exits and count_variance against its dim and walls.
set -u
sb="${top_builddir:-.}/smolbridge"
ex="${srcdir:-.}/examples"
out="${top_builddir:-.}/tests/restart-out"
py="${PYTHON:-python3}"
"$py" -c 1 2>/dev/null || py=python3  # the JSON is read with Python
rm -rf "$out"
mkdir -p "$out"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

# split NAME INI PART REST [--set K=V ...]: NAME_0 the run in one go,
# NAME_1 its first part (--set PART) ending in the checkpoint NAME.ck,
# NAME_2 the rest (--set REST, or "-") from it; the extra settings go to
# all three, before PART and REST.  1 (and a failure) if one of them did
# not run.
split() {
  name=$1 ini=$2 part=$3 rest=$4
  shift 4
  if ! "$sb" collide "$ini" "$@" --set "run.output=$out/${name}_0" \
         > /dev/null 2>&1 ||
     ! "$sb" collide "$ini" "$@" --set "run.output=$out/${name}_1" \
         --set "$part" --set "run.checkpoint=$out/$name.ck" \
         > /dev/null 2>&1; then
    fail "$ini: the run in one go or its first part"
    return 1
  fi
  [ "$rest" = - ] || set -- "$@" --set "$rest"
  "$sb" collide "$ini" "$@" --set "run.output=$out/${name}_2" \
    --set "run.restart=$out/$name.ck" > /dev/null 2>&1 ||
    { fail "$ini: the restart"; return 1; }
}

# bad_copies NAME HOW [SUFFIX]: NAME_bad.ck* copies of the checkpoint
# NAME.ck and the states beside it; HOW = flip: one byte of
# NAME.ck.SUFFIX flipped; HOW = old: every state as version 01 of its
# format wrote it (the version digits of its magic 01, no hash at its end).
bad_copies() {
  "$py" - "$out" "$@" <<'PY' || fail "$1: copying"
import glob, os, sys
out, name, how = sys.argv[1:4]
suf = sys.argv[4] if len(sys.argv) > 4 else ""
ck = os.path.join(out, name + ".ck")
for p in glob.glob(ck + "*"):
    b = bytearray(open(p, "rb").read())
    tail = p[len(ck):]
    if how == "flip" and tail == "." + suf:
        b[len(b) // 2] ^= 0x04
    if how == "old" and tail:
        b[6:8] = b"01"
        del b[-8:]
    open(os.path.join(out, name + "_bad.ck" + tail), "wb").write(b)
PY
}

# hashed NAME INI SUFFIX... [-- --set K=V ...]: the states beside the
# checkpoint NAME.ck end in a hash of their contents.  For each SUFFIX, a
# restart from copies with one byte of NAME.ck.SUFFIX flipped fails,
# saying which file is damaged; a restart from copies with every state of
# version 01 (no hash) runs, and its contacts.csv is NAME_2's.
hashed() {
  name=$1 ini=$2
  shift 2
  sufs=
  while [ $# -gt 0 ] && [ "$1" != -- ]; do sufs="$sufs $1"; shift; done
  [ $# -gt 0 ] && shift
  for suf in $sufs; do
    bad_copies "$name" flip "$suf"
    if "$sb" collide "$ini" "$@" --set "run.output=$out/${name}_bad" \
         --set "run.restart=$out/${name}_bad.ck" > "$out/bad.log" 2>&1
    then
      fail "$name: a restart read $name.ck.$suf with a flipped byte"
    elif ! grep -q "${name}_bad.ck.$suf' is damaged" "$out/bad.log"; then
      fail "$name: a flipped byte of .$suf: $(grep -v warning \
        "$out/bad.log" | head -1)"
    fi
  done
  bad_copies "$name" old
  if "$sb" collide "$ini" "$@" --set "run.output=$out/${name}_3" \
       --set "run.restart=$out/${name}_bad.ck" > "$out/bad.log" 2>&1; then
    cmp -s "$out/${name}_2/contacts.csv" "$out/${name}_3/contacts.csv" ||
      fail "$name: the restart from the states of version 01 differs"
  else
    fail "$name: the states of version 01 do not load: $(grep -v \
      warning "$out/bad.log" | head -1)"
  fi
}

# same NAME WHAT...: in summary.json of NAME_0 and NAME_2, each WHAT
# (a dotted key path) equal, KEY~TOL equal to TOL relative, KEY>MIN
# above MIN in the run in one go (a count: the case measures something)
same() {
  name=$1
  shift
  "$py" - "$out/${name}_0/summary.json" "$out/${name}_2/summary.json" \
    "$name" "$@" <<'PY' || fail "$name: the restarted run differs from the run in one go"
import json, re, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
def get(d, path):
    for k in path.split("."):
        d = d[int(k)] if isinstance(d, list) else d[k]
    return d
ok, shown = True, []
for w in sys.argv[4:]:
    key, op, val = re.match(r"([\w.]+)(?:([~>])(.*))?$", w).groups()
    x, y = get(a, key), get(b, key)
    if op == ">":
        good = x > float(val)
    elif op == "~":
        good = abs(x - y) <= float(val) * abs(x)
    else:
        good = x == y
    ok &= good
    if not isinstance(x, (dict, list)):
        shown.append("%s %s / %s" % (key, x, y))
    if not good:
        print("  %s differs: %s / %s" % (key, json.dumps(x)[:200],
                                        json.dumps(y)[:200]))
print("restart %s: %s" % (sys.argv[3], "; ".join(shown)))
sys.exit(0 if ok else 1)
PY
}

# the collision tally (count_variance) of a kinetic gas: the pair kernel,
# its count variance and widened interval
split he "$ex/v1_kinetic_gas_he.ini" run.t_end=5e-11 - &&
  same he pair_kernels pair_kernels.0.ncoll_var pair_kernels.0.collisions\>1000

# a two-species gas with a warm-up (CHECKPOINT.run): the kinetic energy
# at the measurement start and series.csv with its per-pair kernel
# columns from before the checkpoint
cat > "$out/mix.ini" <<'INI'
[run]
seed = 4
L = 1.2e-8
dt = 1e-14
t_end = 3e-12
warmup = 5e-13
sample_every = 10
[species he]
radius = 1.4e-10
mass = 6.646e-27
tau = inf
T = 300
count = 60
[species xe]
radius = 2.16e-10
mass = 2.18e-25
tau = inf
T = 300
count = 60
INI
split mix "$out/mix.ini" run.t_end=1.5e-12 - &&
  same mix kinetic_energy pair_kernels pair_kernels.1.collisions\>2 &&
  { cmp -s "$out/mix_0/series.csv" "$out/mix_2/series.csv" ||
    fail "mix: the restarted series.csv differs"; }

# the open boundaries (the crossing jets, elastic): the inflows are added
# again from the file, the checkpoint keeps their counters and the
# outflows'
split jets "$ex/open_crossing_jets.ini" run.t_end=2e-3 - &&
  same jets outflows inflows collisions particles kernel \
    kinetic_energy.end outflows.1\>100

# an inflow that fills the box for longer than the first part lasts: the
# restart gets the capacity of the run in one go (the checkpoint holds its
# first part's: room for 111 particles where 379 are in at the end; the
# restart stopped with 'capacity 111 is full'), so the checkpoints that
# the run in one go and the restart write are the same, byte for byte
cat > "$out/fill.ini" <<EOF
[run]
seed = 7
dim = 2
L = 1e-3
dt = 1e-5
t_end = 4e-3
sample_every = 5
detect = ballistic
outcome = count
[walls]
x_lo = open
x_hi = open
detect = ballistic
[species a]
radius = 2e-6
density = 1000
tau = inf
T = 1e-12
inflow = x_lo
inflow_rate = 1e5
inflow_velocity = 0.1 0
EOF
if "$sb" collide "$out/fill.ini" --set "run.output=$out/fill_0" \
     --set "run.checkpoint=$out/fill_0.ck" > /dev/null 2>&1 &&
   "$sb" collide "$out/fill.ini" --set "run.output=$out/fill_1" \
     --set run.t_end=1e-4 --set "run.checkpoint=$out/fill.ck" \
     > /dev/null 2>&1; then
  if "$sb" collide "$out/fill.ini" --set "run.output=$out/fill_2" \
       --set "run.restart=$out/fill.ck" \
       --set "run.checkpoint=$out/fill_2.ck" > "$out/bad.log" 2>&1; then
    same fill particles inflows outflows particles\>300
    cmp -s "$out/fill_0.ck" "$out/fill_2.ck" ||
      fail "fill: the restart's checkpoint differs from the run in one go's"
  else
    fail "fill: the restart: $(grep -o '"error": [^}]*' \
      "$out/fill_2/summary.json")"
  fi
else
  fail "fill: the run in one go or its first part"
fi

# the same with steps: the room up to the end time is truncated to whole
# particles, 25000/s x 1.1 x 400 dt + 100 = 430 on the boundary; the
# restart's time after the checkpoint's 200 steps, summed step by step,
# is below 200 dt in the last place (0.011999999999999983 s for 400 dt
# = 0.012 s), and the room it gave was 429: the restart counts the steps
# as the run in one go does, and the checkpoints are the same, byte for
# byte
sed -e 's/^t_end = .*/steps = 400/' -e 's/^dt = .*/dt = 3e-5/' \
  -e 's/^inflow_rate = .*/inflow_rate = 25000/' "$out/fill.ini" \
  > "$out/fills.ini"
if "$sb" collide "$out/fills.ini" --set "run.output=$out/fills_0" \
     --set "run.checkpoint=$out/fills_0.ck" > /dev/null 2>&1 &&
   "$sb" collide "$out/fills.ini" --set "run.output=$out/fills_1" \
     --set run.steps=200 --set "run.checkpoint=$out/fills.ck" \
     > /dev/null 2>&1 &&
   "$sb" collide "$out/fills.ini" --set "run.output=$out/fills_2" \
     --set run.steps=200 --set "run.restart=$out/fills.ck" \
     --set "run.checkpoint=$out/fills_2.ck" > /dev/null 2>&1; then
  same fills particles inflows outflows particles\>200
  cmp -s "$out/fills_0.ck" "$out/fills_2.ck" ||
    fail "fills: the restart's checkpoint differs from the run in one go's"
else
  fail "fills: the run in one go, its first part or the restart"
fi
# the inflows' keys are checked on restart as for a new run (the inflows
# are added again from the file), with the checkpoint's dim: a third
# velocity component in 2-D is refused, not dropped
"$sb" collide "$out/fills.ini" --set "run.output=$out/fills_3" \
  --set species.a.inflow_velocity="0.1 0 0" --set run.steps=20 \
  --set "run.restart=$out/fills.ck" > "$out/bad.log" 2>&1
rc=$?
[ "$rc" -eq 2 ] && grep -q "\[species a\] inflow_velocity: 3 numbers for \
dim = 2" "$out/bad.log" ||
  fail "fills: inflow_velocity of 3 numbers on a 2-D restart (exit $rc): \
$(grep -v warning "$out/bad.log" | head -1)"
# ... and [fluid] g against the checkpoint's dim, not the file's dim
# (ignored on restart): 2 numbers for the 2-D checkpoint run (they were
# refused as 2 numbers for dim = 3)
"$sb" collide "$out/fills.ini" --set "run.output=$out/fills_3" \
  --set run.dim=3 --set fluid.g="0 0" --set run.steps=20 \
  --set "run.restart=$out/fills.ck" > "$out/bad.log" 2>&1 ||
  fail "fills: [fluid] g of 2 numbers on a 2-D restart with dim = 3: \
$(grep -v warning "$out/bad.log" | head -1)"

# [observe] exits and count_variance on restart see the checkpoint's dim
# and the walls it keeps, not the file's: a file without [walls] keeps
# the checkpoint's open x faces (exits was warned as ignored, with "no
# [walls] face is open", and count_variance not warned of an open face),
# and a file with dim = 3 and open z faces on a periodic 2-D checkpoint
# has no open face (exits was not warned as ignored, count_variance was
# warned of an open face).  The restart warns as the run in one go does,
# its exits.csv continues that of the first part and its tally is the
# run in one go's.
cat > "$out/exits.ini" <<EOF
[run]
seed = 4
dim = 2
L = 2e-5
dt = 1e-5
steps = 400
detect = ballistic
outcome = count
[walls]
x_lo = open
x_hi = open
[species a]
radius = 2e-7
density = 1000
tau = inf
T = 300
count = 300
[observe]
exits = yes
count_variance = yes
EOF
sed '/^\[walls\]/,/^x_hi/d' "$out/exits.ini" > "$out/exits_nowalls.ini"
# observed NAME: the warnings of NAME_0 and NAME_2 about exits and
# count_variance (without the file and line) are the same
observed() {
  "$py" - "$out/${1}_0/summary.json" "$out/${1}_2/summary.json" <<'PY' ||
import json, re, sys
w = [sorted(re.sub(r"^[^:]*:\d+: ", "", m)
            for m in json.load(open(p))["warnings"]
            if "[observe] exits" in m or "count_variance" in m)
     for p in sys.argv[1:3]]
if w[0] != w[1]:
    print("  in one go: %s\n  restart:   %s" % tuple(w))
sys.exit(0 if w[0] == w[1] else 1)
PY
    fail "$1: the restart's warnings about [observe] exits and count_variance differ from the run in one go's"
}
for ws in "" "--set walls.x_lo=periodic --set walls.x_hi=periodic"; do
  name=exits${ws:+p}
  # shellcheck disable=SC2086  # $ws: options
  if ! "$sb" collide "$out/exits.ini" $ws --set "run.output=$out/${name}_0" \
         > /dev/null 2>&1 ||
     ! "$sb" collide "$out/exits.ini" $ws --set "run.output=$out/${name}_1" \
         --set run.steps=200 --set "run.checkpoint=$out/$name.ck" \
         > /dev/null 2>&1; then
    fail "$name: the run in one go or its first part"
    continue
  fi
  if [ -z "$ws" ]; then  # the checkpoint's open x faces
    rs=
  else                   # dim = 3 (ignored) with z faces (ignored)
    rs="--set run.dim=3 --set walls.z_lo=open --set walls.z_hi=open"
  fi
  # shellcheck disable=SC2086  # $rs: options
  if "$sb" collide "$out/exits_nowalls.ini" $rs --set run.steps=200 \
       --set "run.output=$out/${name}_2" --set "run.restart=$out/$name.ck" \
       > "$out/bad.log" 2>&1; then
    observed "$name"
    same "$name" particles outflows pair_kernels pair_kernels.0.ncoll_var
    { cat "$out/${name}_1/exits.csv"
      tail -n +2 "$out/${name}_2/exits.csv"; } |
      cmp -s - "$out/${name}_0/exits.csv" ||
      fail "$name: exits.csv of the two parts differs from the run in one go's"
  else
    fail "$name: the restart: $(grep -v warning "$out/bad.log" | head -1)"
  fi
done
[ "$(wc -l < "$out/exits_0/exits.csv")" -gt 100 ] ||
  fail "exits: fewer than 100 exits in the run in one go"

# first-contact counting with the recorded velocities (CHECKPOINT.firsthit
# and .contacts): the first-contact results and contacts.csv
split kernel "$ex/v12_kernel_firsthit.ini" run.t_end=8e-5 - \
    --set observe.first_hit_velocities=20000 &&
  same kernel first_hit contacts first_hit.hits\>8000 &&
  { cmp -s "$out/kernel_0/contacts.csv" "$out/kernel_2/contacts.csv" ||
    fail "kernel: the restarted contacts.csv differs"; } &&
  hashed kernel "$ex/v12_kernel_firsthit.ini" firsthit contacts run -- \
    --set observe.first_hit_velocities=20000

# a merging run (CHECKPOINT.agglo; DLVO sticking draws from the engine's
# generator): the counts and sizes.csv (the restart keeps the sampling
# period)
split dlvo "$ex/v8_dlvo_gas.ini" run.steps=12 run.steps=11 \
    --set run.sample_every=2 &&
  same dlvo agglo collisions kernel agglo.merges\>500 &&
  { cmp -s "$out/dlvo_0/sizes.csv" "$out/dlvo_2/sizes.csv" ||
    fail "dlvo: the restarted sizes.csv differs"; }

# the random fields (CHECKPOINT.field): the OU field drawing from a
# generator of its own ([fluid] seed: its state saved with it), and a
# time-dependent Kraichnan field drawn from the engine's generator (so it
# cannot be drawn again)
cat > "$out/kr.ini" <<EOF
[run]
seed = 3
L = 1e-3
dt = 1e-5
steps = 200
detect = ballistic
outcome = count
[fluid]
type = kraichnan
eps_nu = 1e4
shell = 2
omega = 300
[species a]
radius = 2e-5
density = 1000
tau = 1e-5
B = 0
count = 3000
EOF
split ou "$ex/v16_abrahamson_ou_field.ini" run.steps=100 run.steps=100 \
    --set run.steps=200 --set fluid.seed=5 &&
  same ou collisions kernel pair_kernels particles kinetic_energy.end \
    collisions\>1000
split kr "$out/kr.ini" run.steps=100 run.steps=100 &&
  same kr collisions kernel particles kinetic_energy.end collisions\>20
# the Kraichnan field of a restart is checked against the checkpoint's
# cubic 3-D box, not the file's dim and L (ignored): without L, or with
# dim = 2, it runs (it was refused)
sed '/^L = /d' "$out/kr.ini" > "$out/kr_nol.ini"
"$sb" collide "$out/kr_nol.ini" --set run.dim=2 --set run.steps=2 \
  --set "run.output=$out/kr_3" --set "run.restart=$out/kr.ck" \
  > "$out/bad.log" 2>&1 ||
  fail "kr: the restart without L: $(grep -v warning "$out/bad.log" | head -1)"

# a bridge detector in turbulence (CHECKPOINT.bridge: its counters) keeps
# the Brownian share of its collisions (the split of the species' b2,
# whose total the checkpoint holds: Mohaupt 2011, eqs 6.20-6.23; it read
# 1 when the restart took all of b2 as Brownian; equal to rounding, b2's
# Brownian part being taken out again)
cat > "$out/turb.ini" <<EOF
[run]
L = 2e-5
dt = 1e-6
steps = 40
detect = bridge
outcome = count
[turbulence]
eps = 1e-2
nu = 1.5e-5
[species a]
radius = 5e-7
density = 1000
mu = 1.8e-5
T = 300
count = 2000
EOF
split turb "$out/turb.ini" run.steps=20 run.steps=20 &&
  same turb bridge.collisions bridge.detections bridge.brownian_share~1e-9 \
    bridge.collisions\>1000

# a restart changes the checkpoint's boundaries only where its file says
# so: the faces given replace its walls; without [walls] detect and deposit it keeps the checkpoint's wall
# detector and deposition outcome (the run in one go, bit for bit), and
# one of the two given alone keeps the checkpoint's other one; [fluid]
# lees_edwards = no switches the checkpoint's Lees-Edwards images off,
# with [fluid] type = shear given or without [fluid] type, and another
# type given leaves none
cat > "$out/walls.ini" <<EOF
[run]
seed = 4
L = 2e-5
dt = 1e-6
steps = 400
detect = ballistic
outcome = count
[walls]
z_lo = absorb
z_hi = absorb
[species a]
radius = 5e-7
density = 1000
mu = 1.8e-5
T = 300
count = 2000
EOF
wset="--set walls.detect=ballistic --set walls.deposit=reinsert"
# shellcheck disable=SC2086  # $wset: two options
if "$sb" collide "$out/walls.ini" $wset --set "run.output=$out/walls_0" \
     > /dev/null 2>&1 &&
   "$sb" collide "$out/walls.ini" $wset --set "run.output=$out/walls_1" \
     --set run.steps=200 --set "run.checkpoint=$out/walls.ck" \
     > /dev/null 2>&1 &&
   "$sb" collide "$out/walls.ini" --set "run.output=$out/walls_2" \
     --set run.steps=200 --set "run.restart=$out/walls.ck" > /dev/null 2>&1
then
  same walls collisions particles deposits deposits.5\>0
else
  fail "walls: the run in one go, its first part or the restart"
fi
# deposit alone keeps the checkpoint's detect = ballistic: the same run
# as with both given, another than with detect = bridge
for d in "" ballistic bridge; do
  "$sb" collide "$out/walls.ini" --set "run.output=$out/walls_3$d" \
    --set walls.deposit=remove ${d:+--set walls.detect=$d} \
    --set "run.restart=$out/walls.ck" > "$out/bad$d.log" 2>&1 ||
    fail "walls: the restart with [walls] deposit ${d:+and detect = $d}"
done
! grep -q "\[walls\]" "$out/bad.log" ||
  fail "walls: a warning with [walls] deposit alone on restart"
"$py" - "$out"/walls_3/summary.json "$out"/walls_3ballistic/summary.json \
  "$out"/walls_3bridge/summary.json <<'PY' ||
import json, sys
a, b, c = (json.load(open(p)) for p in sys.argv[1:4])
key = lambda d: (d["collisions"], d["particles"], d["deposits"])
sys.exit(0 if key(a) == key(b) and key(a) != key(c) else 1)
PY
  fail "walls: [walls] deposit alone on restart did not keep the checkpoint's detect"
# periodic faces given replace the checkpoint's walls: no more deposits
"$sb" collide "$out/walls.ini" --set "run.output=$out/walls_4" \
  --set walls.z_lo=periodic --set walls.z_hi=periodic \
  --set run.steps=200 --set "run.restart=$out/walls.ck" > /dev/null 2>&1 &&
  "$py" - "$out/walls_1/summary.json" "$out/walls_4/summary.json" <<'PY' ||
import json, sys
a, b = (json.load(open(p))["deposits"] for p in sys.argv[1:3])
sys.exit(0 if a == b and sum(a) > 0 else 1)
PY
  fail "walls: z_lo, z_hi = periodic did not remove the checkpoint's walls"
# lees_edwards without [fluid] type applies to the checkpoint's field: at
# rest it does nothing (warned)
"$sb" collide "$out/walls.ini" --set "run.output=$out/walls_5" \
  --set fluid.lees_edwards=no --set run.steps=20 \
  --set "run.restart=$out/walls.ck" > "$out/bad.log" 2>&1 &&
  grep -q "lees_edwards ignored: the restart checkpoint's field is rest" \
    "$out/bad.log" ||
  fail "walls: lees_edwards = no on a checkpoint at rest was not warned about"
if "$sb" collide "$out/walls.ini" --set "run.output=$out/lees_1" \
     --set run.steps=20 --set walls.z_lo=periodic --set walls.z_hi=periodic \
     --set fluid.type=shear --set fluid.G=1e4 \
     --set "run.checkpoint=$out/lees.ck" > /dev/null 2>&1; then
  for how in "fluid.type=shear --set fluid.G=1e4 --set fluid.lees_edwards=no" \
             "fluid.lees_edwards=no" "fluid.type=rest" \
             "fluid.lees_edwards=yes"; do
    # shellcheck disable=SC2086  # $how: one or more --set options
    "$sb" collide "$out/walls.ini" --set run.steps=20 --set $how \
      --set walls.z_lo=periodic --set walls.z_hi=periodic \
      --set "run.output=$out/lees_2" --set "run.restart=$out/lees.ck" \
      > /dev/null 2>&1 || { fail "lees: the restart with $how"; continue; }
    "$py" - "$out/lees_1/summary.json" "$out/lees_2/summary.json" "$how" <<'PY' ||
import json, sys
a, b = (json.load(open(p))["lees_edwards_offset"] for p in sys.argv[1:3])
# on: the offset G L_y t (mod L_x) at twice the first part's end
want = 2 * a if sys.argv[3].endswith("=yes") else 0.0
sys.exit(0 if a > 0 and abs(b - want) <= 1e-9 * a else 1)
PY
      fail "lees: the restart with $how: $(grep -o \
        '"lees_edwards_offset": [^,]*' "$out/lees_2/summary.json")"
  done
  # without [fluid] type the checks see the checkpoint's shear field and
  # images (they took the fluid at rest): msd_every is refused with the
  # images, runs without them, and summary.json names the field; G
  # without type is warned as ignored for what it is (not "type = rest")
  "$sb" collide "$out/walls.ini" --set run.steps=20 \
    --set walls.z_lo=periodic --set walls.z_hi=periodic \
    --set observe.msd_every=2 --set "run.output=$out/lees_3" \
    --set "run.restart=$out/lees.ck" > "$out/bad.log" 2>&1
  rc=$?
  [ "$rc" -eq 2 ] && grep -q "msd_every with Lees-Edwards images (the \
restart checkpoint's \[fluid\] type = shear)" "$out/bad.log" ||
    fail "lees: msd_every against the checkpoint's images (exit $rc): \
$(grep -v warning "$out/bad.log" | head -1)"
  if "$sb" collide "$out/walls.ini" --set run.steps=20 \
       --set walls.z_lo=periodic --set walls.z_hi=periodic \
       --set observe.msd_every=2 --set fluid.lees_edwards=no \
       --set fluid.G=3 --set "run.output=$out/lees_3" \
       --set "run.restart=$out/lees.ck" > "$out/bad.log" 2>&1; then
    grep -q '"fluid": "shear"' "$out/lees_3/summary.json" ||
      fail "lees: the restart does not name the checkpoint's field: \
$(grep -o '"fluid": [^,]*' "$out/lees_3/summary.json")"
    grep -q "G ignored: on restart the checkpoint's field is kept unless \
\[fluid\] type is given" "$out/bad.log" ||
      fail "lees: [fluid] G without type: $(grep 'G ignored' "$out/bad.log")"
  else
    fail "lees: msd_every with lees_edwards = no: $(grep -v warning \
      "$out/bad.log" | head -1)"
  fi
else
  fail "lees: the first part"
fi

# detect = md continued without [fluid] g: the detector's reach takes the
# settling speeds tau g from the checkpoint's gravity, as the run in one
# go took them from its file (its candidates were those of g = 0)
sed '/^g = /d' "$ex/v16_settling.ini" > "$out/nog.ini"
if "$sb" collide "$ex/v16_settling.ini" --set run.detect=md \
     --set run.t_end=1 --set "run.output=$out/mdg_0" > /dev/null 2>&1 &&
   "$sb" collide "$ex/v16_settling.ini" --set run.detect=md \
     --set run.t_end=0.5 --set "run.output=$out/mdg_1" \
     --set "run.checkpoint=$out/mdg.ck" > /dev/null 2>&1 &&
   "$sb" collide "$out/nog.ini" --set run.detect=md --set run.t_end=1 \
     --set "run.output=$out/mdg_2" --set "run.restart=$out/mdg.ck" \
     > /dev/null 2>&1; then
  same mdg candidates collisions pair_kernels collisions\>1000
else
  fail "mdg: a run of detect = md with gravity"
fi

# a sweep whose base configuration writes a checkpoint: every point writes
# its own, in its directory (one file for all would hold the last point's
# alone), unless its line names one
cat > "$out/sweep.ini" <<EOF
[run]
L = 1e-5
dt = 1e-7
steps = 10
output = $out/sweep
checkpoint = $out/shared.ck
[species a]
radius = 1e-7
density = 1000
mu = 1e-3
T = 300
count = 10
EOF
printf 'run.seed=1\nrun.seed=2\nrun.seed=3 run.checkpoint=%s/own.ck\n' \
  "$out" > "$out/points"
if "$sb" collide "$out/sweep.ini" --sweep "$out/points" > /dev/null 2>&1 &&
   [ -s "$out/sweep/point_000/shared.ck" ] &&
   [ -s "$out/sweep/point_001/shared.ck" ] && [ -s "$out/own.ck" ] &&
   [ ! -e "$out/shared.ck" ] && [ ! -e "$out/sweep/point_002/shared.ck" ]
then
  cmp -s "$out/sweep/point_000/shared.ck" "$out/sweep/point_001/shared.ck" &&
    fail "sweep: two points wrote the same checkpoint"
else
  fail "sweep: the points' checkpoints are not where they belong"
fi

rm -rf "$out"
[ "$fails" -eq 0 ] && echo "restart: all checks passed"
exit $((fails > 0))
