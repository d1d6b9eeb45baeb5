#!/bin/sh
# compare_lammps.sh — the same Brownian suspension run by LAMMPS and by
# `smolbridge collide`, side by side: particle-steps per second of each
# (whole process, one core), their ratio, and the collision kernel each run
# implies.
#
#   bench/compare_lammps.sh [N] [STEPS]         (defaults 100000 1000)
#   SMOLBRIDGE=./smolbridge LMP=lmp bench/compare_lammps.sh 1000000 1000
#
# The system (Mohaupt 2011, Table 3.2 physics, at phi = 1e-3): spheres of
# d = 1 um, rho_p = 1000 kg/m^3 in a fluid at rest, T = 296.15 K, mu =
# 1.83245e-5 Pa s (Stokes tau_p = 3.03e-6 s), periodic cube holding N of them
# at volume fraction 1e-3, dt = tau_p/10, STEPS steps, uniform random start
# with Maxwellian velocities, elastic collisions.
#
#  * LAMMPS (units si): atom_style sphere, fix nve/sphere + fix langevin
#    (damp = tau_p), pair_style gran/hooke with no damping and no friction
#    (elastic) and a normal stiffness giving a contact time of 10 dt (the
#    soft-sphere contact is resolved by the time steps).  Contacts are
#    counted with compute contact/atom every 10 steps; with a linear spring
#    the contact lasts t_c = pi sqrt(m_eff/k_n) whatever the impact speed,
#    so K = 2 V <pairs in contact> / (t_c N^2) (approximate: the Langevin
#    forces act during the contact).
#  * smolbridge: the exact Langevin step (Mohaupt 2011, eq 1.16), linked
#    cells, contact-time detection (detect = ballistic) and elastic outcome
#    — the defaults of `smolbridge collide`; K_e from the counted
#    collisions (summary.json, with its 95% interval).
# Both start uniform, so both kernels include the start-up transient
# K(t) = K_inf (1 + d/sqrt(pi D_12 t)) over the run (docs/engine.md, V2);
# the continuum reference 8kT/(3 mu) is printed for scale.
#
# Installs nothing: without `lmp` on PATH (Debian: apt-get install lammps)
# it says so and exits 0 after the smolbridge run.  Timings are whole
# processes (start-up and particle placement included) on one core
# (taskset -c 0 when available), wall and CPU (user + sys, from
# /usr/bin/time when present: the fairer figure on a shared machine).
# Compare within one run.  KEEP=DIR keeps the generated inputs and logs.
set -eu
N=${1:-100000}
STEPS=${2:-1000}
here=$(cd "$(dirname "$0")/.." && pwd)
SB=${SMOLBRIDGE:-}
if [ -z "$SB" ]; then
  for c in ./smolbridge "$here/smolbridge" smolbridge; do
    if command -v "$c" >/dev/null 2>&1; then SB=$c; break; fi
  done
fi
[ -n "$SB" ] || { echo "compare_lammps: no smolbridge (build it, or set SMOLBRIDGE=)"; exit 1; }
LMP=${LMP:-lmp}
pin=""
command -v taskset >/dev/null 2>&1 && pin="taskset -c 0"
if [ -n "${KEEP:-}" ]; then  # KEEP=DIR keeps the inputs, logs and outputs
  mkdir -p "$KEEP"
  work=$(cd "$KEEP" && pwd)
else
  work=$(mktemp -d "${TMPDIR:-/tmp}/sb-lammps.XXXXXX")
  trap 'rm -rf "$work"' EXIT
fi
# timed CMD...: run it, leave "wall cpu" seconds in $work/time (cpu =
# user + sys from /usr/bin/time when present: the fairer figure on a shared
# machine; else the wall time twice)
timed() {
  if [ -x /usr/bin/time ]; then
    /usr/bin/time -f "%e %U %S" -o "$work/time.raw" "$@" || return 1
    awk '{ printf "%.3f %.3f\n", $1, $2 + $3 }' "$work/time.raw" > "$work/time"
  else
    t0=$(now)
    "$@" || return 1
    t1=$(now)
    awk -v a="$t0" -v b="$t1" 'BEGIN { printf "%.3f %.3f\n", b - a, b - a }' > "$work/time"
  fi
}

# the physics, in SI (awk for the arithmetic)
eval "$(awk -v N="$N" 'BEGIN {
  pi = 3.14159265358979323846; kB = 1.380649e-23
  d = 1e-6; rho = 1000; mu = 1.83245e-5; T = 296.15; phi = 1e-3
  m = rho * pi * d^3 / 6; tau = rho * d^2 / (18 * mu); dt = tau / 10
  V = N * (pi * d^3 / 6) / phi; L = V^(1/3)
  meff = m / 2; tc = 10 * dt; kn = pi^2 * meff / tc^2
  Kc = 8 * kB * T / (3 * mu)
  printf "D=%.17g RHO=%.17g MU=%.17g TK=%.17g M=%.17g TAU=%.17g DT=%.17g ", d, rho, mu, T, m, tau, dt
  printf "V=%.17g L=%.17g TC=%.17g KN=%.17g KC=%.17g\n", V, L, tc, kn, Kc
}')"

now() { date +%s.%N; }
echo "# N = $N spheres (d = 1 um, phi = 1e-3, box L = $L m), dt = $DT s = tau_p/10, $STEPS steps"

# ------------------------------------------------------------ smolbridge
cat > "$work/sb.ini" <<EOF
[run]
seed = 1
L = $L
dt = $DT
steps = $STEPS
output = $work/sb-out

[fluid]
type = rest

[species colloid]
diameter = $D
density = $RHO
mu = $MU
T = $TK
count = $N
EOF
timed $pin "$SB" collide "$work/sb.ini" > "$work/sb.log" 2>&1 \
  || { cat "$work/sb.log"; echo "compare_lammps: smolbridge failed"; exit 1; }
read sb_wall sb_cpu < "$work/time"
sb_K=$(sed -n 's/^  "kernel": {"K": \([^,]*\),.*/\1/p' "$work/sb-out/summary.json")
sb_ci=$(sed -n 's/^  "kernel": {"K": [^,]*, "ci95": \[\([^]]*\)\].*/\1/p' "$work/sb-out/summary.json")
sb_n=$(sed -n 's/^  "collisions": \([0-9]*\),/\1/p' "$work/sb-out/summary.json")

# --------------------------------------------------------------- LAMMPS
if ! command -v "$LMP" >/dev/null 2>&1; then
  echo "smolbridge: $sb_wall s wall, $sb_cpu s CPU, $(awk -v n="$N" -v s="$STEPS" -v w="$sb_cpu" 'BEGIN { printf "%.3g", n * s / w }') particle-steps per CPU second; K_e = $sb_K m^3/s [$sb_ci] from $sb_n collisions"
  echo "compare_lammps: LAMMPS ('$LMP') not found: skipped (Debian: apt-get install lammps; or LMP=/path/to/lmp)"
  exit 0
fi
cat > "$work/in.lmp" <<EOF
# generated by bench/compare_lammps.sh
units           si
atom_style      sphere
dimension       3
boundary        p p p
atom_modify     map array
region          box block 0 $L 0 $L 0 $L
create_box      1 box
create_atoms    1 random $N 4821 NULL
set             type 1 diameter $D
set             type 1 density $RHO
pair_style      gran/hooke $KN NULL 0.0 NULL 0.0 0
pair_coeff      * *
neighbor        $(awk -v d="$D" 'BEGIN { printf "%.6g", 0.3 * d }') bin
neigh_modify    delay 0 every 1 check yes
comm_modify     vel yes
# random placement may overlap (about 4 N phi pairs): remove one sphere of
# each overlapping pair (no overlap keyword for create_atoms before 2022)
delete_atoms    overlap $D all all
variable        natoms equal count(all)
print           "NATOMS \${natoms}"
velocity        all create $TK 9173 dist gaussian mom yes
fix             integ all nve/sphere
fix             bath all langevin $TK $TK $TAU 5531
compute         nc all contact/atom
compute         ncsum all reduce sum c_nc
thermo_style    custom step c_ncsum
thermo          10
thermo_modify   norm no
timestep        $DT
run             $STEPS
EOF
timed $pin "$LMP" -nocite -log "$work/lmp.log" -screen none -in "$work/in.lmp" \
  || { tail -n 20 "$work/lmp.log"; echo "compare_lammps: LAMMPS failed"; exit 1; }
read lmp_wall lmp_cpu < "$work/time"
NL=$(sed -n 's/^NATOMS \([0-9]*\)$/\1/p' "$work/lmp.log" | tail -n 1)
# mean number of pairs in contact over the printed steps after the first
lmp_K=$(awk -v V="$V" -v tc="$TC" -v N="$NL" '
  /^ *Step/ { on = 1; next }
  /^Loop time/ { on = 0 }
  on && $1 ~ /^[0-9]+$/ && $1 > 0 { s += $2 / 2; n++ }
  END { if (n) printf "%.4g %.4g", 2 * V * (s / n) / (tc * N * N), s / n; else print "nan nan" }' "$work/lmp.log")
lmp_pairs=${lmp_K#* }
lmp_K=${lmp_K% *}

awk -v N="$N" -v NL="$NL" -v S="$STEPS" -v sw="$sb_wall" -v sl="$sb_cpu" -v lw="$lmp_wall" \
    -v ll="$lmp_cpu" -v sK="$sb_K" -v sci="$sb_ci" -v sn="$sb_n" -v lK="$lmp_K" \
    -v lp="$lmp_pairs" -v Kc="$KC" 'BEGIN {
  ps = N * S
  printf "%-11s %10s %10s %16s %16s\n", "code", "wall s", "CPU s", "steps/s (wall)", "steps/CPU s"
  printf "%-11s %10.2f %10.2f %16.4g %16.4g\n", "smolbridge", sw, sl, ps / sw, ps / sl
  pl = NL * S
  printf "%-11s %10.2f %10.2f %16.4g %16.4g\n", "LAMMPS", lw, ll, pl / lw, pl / ll
  if (NL != N) printf "(LAMMPS: %d spheres after removing the overlaps of its random placement)\n", NL
  printf "ratio smolbridge/LAMMPS (particle-steps per second): %.2f wall, %.2f CPU\n", (ps / sw) / (pl / lw), (ps / sl) / (pl / ll)
  printf "kernel: smolbridge K_e = %.4g m^3/s [%s] (%d collisions); LAMMPS %.4g m^3/s (%.4g pairs in contact on average, t_c = 10 dt); 8kT/(3mu) = %.4g\n", sK, sci, sn, lK, lp, Kc
}'
