#!/bin/sh
# `smolbridge validate --write-ini`: the configurations written for a
# case, run with `smolbridge collide`, give the case's estimates (same
# seed, same estimate).  Checked on four kinds of run: a plain gas with a
# warm-up (V1/dense-long-steps), first-hit counting with exact bridge
# detection and a separate placement generator (VX), explicit particles
# (V9/two-spheres-45), DLVO merging (V8/agglo-dlvo, x = 0.5 and the
# barrier of a DLVO pair as [agglo] wmax), first-hit
# counting of Langevin spheres with the capacitance-radius estimator and
# the Langevin, chord and exact-bridge detectors (V12, Kn_D = 0.05: the
# short runs; the H(Kn_D) record comes from its own expect line) and
# laminar shear with Lees-Edwards images and the case's own placement
# stream (V16/shear, G = 10 and 100), the per-particle OU seen velocity
# with the stationary start (V16/abrahamson: both runs, every pair kernel)
# and the Kraichnan field (V16/saffman-turner, R k = 2: its records are
# means over the 32 realizations of one file run with --sweep,
# "; expect-sweep-mean" lines); merging with
# bridge detection whose reach is recomputed at every output time
# (V8/agglo-constant: [run] stop_every, records read from sizes.csv rows,
# means over the 10 runs) and first-hit counting in shear with
# Lees-Edwards images and a fixed reference radius
# (V16/combined-shear-diffusive, Pe = 0.1); first-hit counting of two
# species, one kernel per species pair (first_hit.pairs): with gravity and
# the settling velocity taken out of the placement by a drift
# (V16/combined, Pe = 1) and with the capacitance radius (V12/mixture);
# the mean-square displacement observer ([observe] msd_every, msd.D) of
# V18/self-diffusion (phi = 0.1: a mean over its 2 replica files); the
# normal velocities at first contact ([observe] first_hit_velocities,
# contacts.csv) of V12's free-molecular run, whose KS distance is
# recomputed from the table ("; expect-ks", tests/validate_ini_stats.py);
# V18/maxwell-relaxation ([species] velocities = antipodal with [run]
# velocity_seed, [run] snapshot_steps): Boltzmann's H, KS and chi-square
# of the speeds pooled over the snapshots of its 4 replica files, and the
# largest kinetic_energy.rel_change; V13/spray-vs-engine ([species]
# velocity_scale: the anisotropic start): mean(stochastic) - mean(engine)
# with the stochastic means as offsets ("; expect-diff-mean"), the engine
# side the anisotropy of the snapshots and kernel.K of its 6 files.
# Engine cases without files must say why in NOT-WRITTEN.txt.
# VALIDATE_INI_SET=more (tests/validate_ini_more.sh, run beside this one
# to keep each under ~90 s): the MD-type detector of V3 (detect = md,
# dt = 100 tau_p) and the grid deposit of V15/engine-jets at tau = 200
# ("; expect-grid" lines: statistics of grid.csv's counts against the
# exact means in RUN_cells.csv, and L1 distances to the fields.csv of
# `smolbridge pgd RUN_euler.ini`); deposition on absorbing walls without
# particle-particle detection (detect = none), its window counts read from
# the deposits columns of series.csv ("series.csv ROW-ROW0 deposits":
# V16/deposition transient, bridge and chord; V16/deposition-langevin,
# chord) and the steady source started from the parabolic profile
# (profile = parabolic, the mean over the 4 replicas); Langevin spheres in
# shear, pass-through counting with a warm-up (V16/combined-shear,
# Pe_k = 0.3); the dense crossing jets with collisions of V15/dense-jets
# (all three densities): batch means of the exits and of the mass in
# three squares ([observe] batch_steps and region, batches.csv; the
# records are statistics over its rows, "; expect-batches").
set -u
sb="${top_builddir:-.}/smolbridge"
sb="$(cd "$(dirname "$sb")" && pwd)/$(basename "$sb")"  # runs cd below
set_=${VALIDATE_INI_SET:-main}
dir="${top_builddir:-.}/tests/validate-ini-out"
[ "$set_" = main ] || dir="$dir-$set_"
rm -rf "$dir"
mkdir -p "$dir"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
if [ "$set_" = more ]; then
  cases="--case V3/diffusive-fail --case V15/engine-jets --case V16/deposition --case V16/combined-shear\$ --case V15/dense-jets\$"
  runs="V3_MD_d1um_dt100tau V15_engine_jets_tau200 \
    V16_deposition_transient_bridge V16_deposition_transient_chord \
    V16_deposition_langevin_chord V16_combined_shear_Pek0.3 \
    V15_dense_jets_nocoll_phi0.2_r1 V15_dense_jets_coll_phi0.02_r1 \
    V15_dense_jets_coll_phi0.2_r1"
  nmin=46
  # shellcheck disable=SC2086
  "$sb" validate $cases --write-ini "$dir/ini" 2>"$dir/w.err" \
    || { fail "write-ini failed"; cat "$dir/w.err"; }
  runs="$runs $(cd "$dir/ini" && ls V16_deposition_steady_r*.ini | sed 's/\.ini$//')"
else
cases="--case V1/dense-long-steps --case VX/exact-detection --case V9/two-spheres-45 --case V8/agglo-dlvo --case V8/agglo-constant --case V12/ --case V16/shear --case V16/abrahamson --case V16/saffman-turner --case V16/combined-shear-diffusive --case V16/combined\$ --case V18/ --case V13/spray-vs-engine"
# shellcheck disable=SC2086
"$sb" validate $cases --write-ini "$dir/ini" 2>"$dir/w.err" \
  || { fail "write-ini failed"; cat "$dir/w.err"; }
[ -f "$dir/ini/V12_mixture.ini" ] || fail "V12_mixture.ini not written"
grep -q 'V12/mixture' "$dir/ini/NOT-WRITTEN.txt" 2>/dev/null \
  && fail "NOT-WRITTEN.txt lists the V12 mixture, which has its file"
# every engine case has its files now (NOT-WRITTEN.txt would say why not)
grep -q ': no file: ' "$dir/ini/NOT-WRITTEN.txt" 2>/dev/null \
  && fail "NOT-WRITTEN.txt lists a case without files"
runs="V1_dense_He_phi0.05 VX_dt100tau V9_two_spheres_45 \
    V8_dlvo_x0.5 V8_dlvo_pair_3mM_10mV \
    V12_Kn0.05_dt1_langevin V12_Kn0.05_dt1_contact-time \
    V12_Kn0.05_dt1_exact-bb3 V16_shear_G100 V16_shear_G10 \
    V16_abrahamson_ou-field V16_abrahamson_langevin-species \
    V16_combined_shear_diffusive_Pe0.1 V16_combined_Pe1 V12_mixture \
    V16_saffman_turner_frozen_Rk2 \
    V18_self_diffusion_phi0.1_r1 V18_self_diffusion_phi0.1_r2 \
    V12_vn_free_molecular \
    $(cd "$dir/ini" && ls V8_agglo-constant_run*.ini \
      V18_maxwell_relaxation_r*.ini V13_spray_vs_engine_r*.ini |
      sed 's/\.ini$//')"
nmin=90
fi
# shellcheck disable=SC2086
"$sb" validate $cases --out "$dir/v" >/dev/null 2>&1
[ -s "$dir/v/validate.csv" ] || { fail "validate run failed"; exit 1; }

# value of a summary.json field: kernel.K, first_hit.K, agglo.X,
# pair_kernels[a,b].K, first_hit.pairs[a,b].K
field() {  # field SUMMARY NAME
  case "$2" in
    pair_kernels*) ab=${2#pair_kernels[}; ab=${ab%%]*}; a=${ab%%,*}; b=${ab#*,}
      sed -n "s/.*\"species\": \[\"$a\", \"$b\"\], \"collisions\": [0-9]*, \"exposure\": [^,]*, \"K\": \([^,]*\),.*/\1/p" "$1" ;;
    kernel.K) sed -n 's/.*"kernel": {"K": \([^,]*\),.*/\1/p' "$1" ;;
    first_hit.pairs*) ab=${2#first_hit.pairs[}; ab=${ab%%]*}; a=${ab%%,*}; b=${ab#*,}
      sed -n "s/.*{\"species\": \[\"$a\", \"$b\"\], \"hits\": .*\"K\": \([^,]*\),.*/\1/p" "$1" ;;
    first_hit.K) sed -n 's/.*"first_hit": {.*"K": \([^,]*\),.*/\1/p' "$1" ;;
    msd.D) sed -n 's/.*"msd": {.*"D": \([^,]*\),.*/\1/p' "$1" ;;
    agglo.*) k=${2#agglo.}
      sed -n "s/.*\"agglo\": {.*\"$k\": \\([^,]*\\),.*/\\1/p" "$1" ;;
  esac
}
ncmp=0
for run in $runs; do
  ini="$dir/ini/$run.ini"
  [ -f "$ini" ] || { fail "$run.ini not written"; continue; }
  # an Eulerian companion (smolbridge pgd) that expect-grid l1 lines read
  if [ -f "$dir/ini/${run}_euler.ini" ]; then
    (cd "$dir/ini" && "$sb" pgd "${run}_euler.ini" >/dev/null 2>&1) \
      || { fail "pgd ${run}_euler.ini failed"; continue; }
  fi
  sweep=
  [ -f "$dir/ini/$run.sweep.txt" ] && sweep="--sweep $run.sweep.txt"
  # shellcheck disable=SC2086
  (cd "$dir/ini" && "$sb" collide "$run.ini" $sweep >/dev/null 2>&1) \
    || { fail "collide $run.ini $sweep failed"; continue; }
  out="$dir/ini/$run-out"
  grep '^; expect' "$ini" | sed 's/^; //' > "$dir/expect.txt"
  while IFS= read -r line; do
    kind=${line%% *}
    line=${line#* }
    rec=${line%% = *}
    rhs=${line#* = }
    case "$kind" in  # recomputed from output tables, pooled over runs
      expect-ks|expect-chi2|expect-max|expect-h-rises|expect-diff-mean|\
      expect-batches)
        printf '%s\t%s\t%s\t%s\n' "$kind" "$rec" "$out" "$rhs" \
          >> "$dir/stats.txt"
        continue ;;
    esac
    fld=${rhs%% \* *}
    fac=1
    case "$rhs" in *" * "*) fac=${rhs##* \* } ;; esac
    if [ "$kind" = expect-sweep-mean ]; then  # the mean over the points
      [ -n "$sweep" ] || { fail "$run: $kind without a sweep file"; continue; }
      np=$(grep -c '^[^#]' "$dir/ini/$run.sweep.txt")
      vals=$(for p in "$out"/point_*/summary.json; do field "$p" "$fld"; done)
      want=$(awk -F, -v r="$rec" '$1 == r { print $2 }' "$dir/v/validate.csv")
      [ -n "$want" ] || { fail "$run: no record $rec in validate.csv"; continue; }
      echo "$vals" | awk -v f="$fac" -v w="$want" -v np="$np" \
        '{ s += $1 * f; n++ } END { g = s / n; d = g - w; if (d < 0) d = -d;
          m = w < 0 ? -w : w; if (m < 1e-300) m = 1;
          exit !(n == np && n >= 2 && d <= 1e-12 * m) }' \
        || fail "$run: $rec = $want, not the mean over the $np points"
      ncmp=$((ncmp + 1))
      continue
    fi
    case "$fld" in
      sizes.csv*|series.csv*) set -- $fld  # FILE ROW[-ROW0] COLUMN
        # data row ROW (from 1), or its difference with row ROW0
        val=$(awk -F, -v r="$2" -v c="$3" 'BEGIN { n = split(r, q, "-") }
          NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i }
          NR == q[1] + 1 { a = $col[c] } n == 2 && NR == q[2] + 1 { b = $col[c] }
          END { if (a == "" || (n == 2 && b == "")) exit
            if (n == 2) printf "%.17g\n", a - b; else print a }' "$out/$1") ;;
      grid.csv\ l1-*) set -- $fld  # grid.csv l1-rho|l1-q FRAME PGD/fields.csv
        val=$(awk -F, -v stat="$2" -v frame="$3" '
          FNR == 1 { next }
          NR == FNR { n++; re[n] = $3; qxe[n] = $3 * $4; qye[n] = $3 * $5; next }
          { row++; if (int((row - 1) / n) + 1 != frame) next
            q = row - (frame - 1) * n; m += $5 / n
            sr += ($5 > re[q] ? $5 - re[q] : re[q] - $5)
            sq += ($6 > qxe[q] ? $6 - qxe[q] : qxe[q] - $6)
            sq += ($7 > qye[q] ? $7 - qye[q] : qye[q] - $7) }
          END { h = 1 / sqrt(n); if (row != 0 && frame * n <= row && m > 0)
            printf "%.17g", (stat == "l1-rho" ? sr : sq) * h * h / m }' \
          "$dir/ini/$4" "$out/grid.csv") ;;
      grid.csv*) set -- $fld  # grid.csv STAT FRAME REF (RUN_cells.csv)
        val=$(awk -F, -v stat="$2" -v frame="$3" -v f="$fac" '
          FNR == 1 { next }
          NR == FNR { n++; lam[n] = $3; out[n] = $4; next }
          { row++; if (int((row - 1) / n) + 1 != frame) next
            q = row - (frame - 1) * n; k = int($5 * f + 0.5)
            if (out[q] == 1) so += k
            if (lam[q] > 0) { c2 += (k - lam[q]) * (k - lam[q]) / lam[q]; sk += k; sl += lam[q] } }
          END { if (row != 0 && frame * n <= row)
            printf "%.17g", stat == "chi2" ? c2 : stat == "ratio" ? (1 / sl) * sk : so }' \
          "$dir/ini/$4" "$out/grid.csv")
        fac=1 ;;  # the factor makes the counts
      snap_*) set -- $fld
        val=$(awk -F, -v id="$3" -v c="$4" 'NR == 1 { for (i = 1; i <= NF; i++) col[$i] = i }
          NR > 1 && $1 == id { print $col[c] }' "$out/$1") ;;
      *) val=$(field "$out/summary.json" "$fld") ;;
    esac
    [ -n "$val" ] || { fail "$run: no $fld in summary.json"; continue; }
    if [ "$kind" = expect-mean ]; then  # a term of a mean over files
      echo "$rec,$val,$fac" >> "$dir/means.txt"
      continue
    fi
    want=$(awk -F, -v r="$rec" '$1 == r { print $2 }' "$dir/v/validate.csv")
    [ -n "$want" ] || { fail "$run: no record $rec in validate.csv"; continue; }
    awk -v v="$val" -v f="$fac" -v w="$want" 'BEGIN { g = v * f; d = g - w;
      if (d < 0) d = -d; m = w < 0 ? -w : w; if (m < 1e-300) m = 1;
      exit !(d <= 1e-12 * m) }' \
      || fail "$run: $rec = $want, collide gives $fld = $val (x $fac)"
    ncmp=$((ncmp + 1))
  done < "$dir/expect.txt"
done
# the records that are means over files
if [ -f "$dir/means.txt" ]; then
  for rec in $(cut -d, -f1 "$dir/means.txt" | sort -u); do
    want=$(awk -F, -v r="$rec" '$1 == r { print $2 }' "$dir/v/validate.csv")
    [ -n "$want" ] || { fail "no record $rec in validate.csv"; continue; }
    # every file with the record's expect-mean line must have given a term
    nf=$(grep -l -F "; expect-mean $rec = " "$dir"/ini/*.ini | wc -l)
    awk -F, -v r="$rec" -v w="$want" -v nf="$nf" '$1 == r { s += $2 * $3; n++ }
      END { g = s / n; d = g - w; if (d < 0) d = -d; m = w < 0 ? -w : w;
        if (m < 1e-300) m = 1; if (n != nf || n < 2 || d > 1e-12 * m) {
          printf "mean of %d files %.17g\n", n, g; exit 1 } }' \
      "$dir/means.txt" || fail "$rec = $want, not the mean of its files"
    ncmp=$((ncmp + 1))
  done
fi
# the records recomputed from output tables (tests/validate_ini_stats.py)
if [ -f "$dir/stats.txt" ]; then
  python3 "$(dirname "$0")/validate_ini_stats.py" "$dir/stats.txt" \
    > "$dir/stats.csv" || fail "validate_ini_stats.py failed"
  for rec in $(cut -f2 "$dir/stats.txt" | sort -u); do
    # pooled over every file that carries the record's line
    kind=$(awk -F'\t' -v r="$rec" '$2 == r { print $1; exit }' "$dir/stats.txt")
    nf=$(grep -l -F "; $kind $rec = " "$dir"/ini/*.ini | wc -l)
    nr=$(awk -F'\t' -v r="$rec" '$2 == r' "$dir/stats.txt" | wc -l)
    [ "$nf" -eq "$nr" ] || fail "$rec: $nr of its $nf files were run"
    want=$(awk -F, -v r="$rec" '$1 == r { print $2 }' "$dir/v/validate.csv")
    got=$(awk -F, -v r="$rec" '$1 == r { print $2 }' "$dir/stats.csv")
    [ -n "$want" ] && [ -n "$got" ] || { fail "no value for $rec"; continue; }
    awk -v g="$got" -v w="$want" 'BEGIN { d = g - w; if (d < 0) d = -d;
      m = w < 0 ? -w : w; if (m < 1e-300) m = 1; exit !(d <= 1e-12 * m) }' \
      || fail "$rec = $want, recomputed from collide's tables: $got"
    ncmp=$((ncmp + 1))
  done
fi
[ "$ncmp" -ge "$nmin" ] || fail "only $ncmp records compared"
[ "$fails" -eq 0 ] && echo "validate_ini: $ncmp records reproduced by collide from the written files"
[ "$fails" -eq 0 ] && rm -rf "$dir"
exit $((fails > 0))
