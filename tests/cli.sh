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
# a misspelt argument is named, with the function's arguments
msg=$("$sb" eval bb_cross_prob x=1 y=1 a=0 vv=1 2>&1 >/dev/null)
case "$msg" in *"bb_cross_prob has no argument 'vv'; usage: bb_cross_prob x= y= a= v="*) ;;
  *) fail "eval misspelt argument: $msg" ;; esac
expect_rc 2 "$sb" eval bb_cross_prob x=1 y=1 a=zero v=1
expect_rc 2 "$sb" eval bb_cross_prob x=1 x=1 y=1 a=0 v=1
expect_rc 1 "$sb" eval bb_cross_prob x=1 y=1 a=0 v=-1
# numbers strtod flags as out of range: a subnormal is a number, an
# overflow or an underflow to 0 is not
expect_rc 0 "$sb" eval bb_nocross_prob x=1 y=1 a=0 v=1e-316
expect_rc 2 "$sb" eval bb_nocross_prob x=1 y=1 a=0 v=1e-400
expect_rc 2 "$sb" eval bb_nocross_prob x=1 y=1 a=0 v=1e400
msg=$("$sb" eval bes3b_cross_prob x=1 y=1 a=-1 v=1 2>&1 >/dev/null)
[ -n "$msg" ] || fail "no message for a < 0"
# stats functions: the Garwood interval of k = 10 (tabulated values) and
# the chi-square tail at its 95% point
got=$("$sb" eval poisson_ci k=10 level=0.95 | sed -n 's/^lo=//p')
relclose "$got" 4.7953886961324335 1e-12 || fail "poisson_ci lo = $got"
got=$("$sb" eval chi2_sf x=3.841458820694124 dof=1)
relclose "$got" 0.05 1e-10 || fail "chi2_sf = $got"
expect_rc 1 "$sb" eval binomial_ci k=-1 n=10 level=0.95
# the shear bridge without shear: its (u_x, x) block is the OU bridge
shb="tau=4e-7 B=0.9 G=0 cx=0 cy=0 h=8e-7 s=3e-7 uy0=1e-4 y0=2e-9 ux0=-3e-4 \
x0=1e-9 uy1=2e-4 y1=5e-10 ux1=1e-4 x1=-4e-10"
got=$("$sb" eval langevin_shear_bridge_moments $shb | sed -n 's/^mean_x=//p')
want=$("$sb" eval langevin_bridge_moments tau=4e-7 B=0.9 us=0 dt=8e-7 s=3e-7 \
       x0=1e-9 u0=-3e-4 x1=-4e-10 u1=1e-4 | sed -n 's/^mean_x=//p')
relclose "$got" "$want" 1e-9 || fail "shear bridge mean_x $got, OU $want"
got=$("$sb" eval langevin_shear_bridge_moments $shb | sed -n 's/^cov_x_x=//p')
want=$("$sb" eval langevin_bridge_moments tau=4e-7 B=0.9 us=0 dt=8e-7 s=3e-7 \
       x0=1e-9 u0=-3e-4 x1=-4e-10 u1=1e-4 | sed -n 's/^var_x=//p')
relclose "$got" "$want" 1e-9 || fail "shear bridge cov_x_x $got, OU $want"
s1=$("$sb" eval langevin_shear_bridge_sample $shb seed=4)
s2=$("$sb" eval langevin_shear_bridge_sample $shb seed=4)
[ "$s1" = "$s2" ] && [ -n "$s1" ] || fail "shear bridge sample not reproducible"
# a domain error names the function called and its arguments
msg=$("$sb" eval dlvo_energy D=-1 r1=1e-6 r2=1e-6 A=1e-20 T=300 eps_r=78 z=1 \
      kappa=1e8 psi=0.01 model=0 2>&1 >/dev/null)
case "$msg" in *"dlvo_energy(D=-1, r1="*) ;; *) fail "eval domain message: $msg" ;; esac
# seeds are integers 0 .. 2^32-1, as in collide
for s in nan inf -1 1.5 4294967296; do
  expect_rc 2 "$sb" eval bb_hit_sample seed=$s x=2 y=1.5 a=1 sigma2=1 t=1
done

# every `smolbridge eval` command quoted in full in examples/ runs
for f in "${srcdir:-.}"/examples/*.ini; do
  sed -n 's/^;  *smolbridge eval /eval /p' "$f" | while read -r cmd; do
    # shellcheck disable=SC2086
    "$sb" $cmd >/dev/null 2>&1 || echo "FAIL: $f: smolbridge $cmd"
  done
done | grep FAIL && fails=$((fails + 1))

# --- validate: listing, filtering, report files and CSV header
expect_rc 0 "$sb" validate --list
expect_rc 2 "$sb" validate --case NoSuchCase
# --case is a prefix; NAME$ selects one name exactly
n=$("$sb" validate --list --case V16/combined | wc -l)
[ "$n" -ge 2 ] || fail "--case V16/combined should select its longer names too"
n=$("$sb" validate --list --case 'V16/combined$' | wc -l)
[ "$n" -eq 1 ] || fail "--case 'V16/combined\$' should select one case, got $n"
expect_rc 2 "$sb" validate --case 'V16/comb$'
expect_rc 2 "$sb" validate --seed -3
expect_rc 2 "$sb" validate --quick --full --list
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

# --- validate --resume: the runs are saved in OUT/runs and read back; the
# second invocation gives the same CSV and says it read them
rm -rf "$out-r"
if "$sb" validate --resume --case 'V16/combined$' --out "$out-r" >/dev/null 2>&1 &&
   cp "$out-r/validate.csv" "$out-r.csv" &&
   "$sb" validate --resume --case 'V16/combined$' --out "$out-r" >/dev/null 2>"$out-r.err"; then
  [ "$(ls "$out-r/runs" | grep -c '\.run$')" -gt 0 ] || fail "--resume saved no run"
  cmp -s "$out-r.csv" "$out-r/validate.csv" || fail "--resume changed the records"
  grep -q "read back from the saved runs" "$out-r.err" || fail "--resume read no run"
  # a saved run with a byte flipped is refused, saying so, and made again
  r=$(ls "$out-r/runs"/*.run | head -n 1)
  printf 'X' | dd of="$r" bs=1 seek=20 conv=notrunc 2>/dev/null
  "$sb" validate --resume --case 'V16/combined$' --out "$out-r" >/dev/null 2>"$out-r.err" &&
    cmp -s "$out-r.csv" "$out-r/validate.csv" ||
    fail "--resume with a damaged saved run: another result"
  grep -q "saved run refused, made again: .*'$r' is damaged" "$out-r.err" ||
    fail "--resume: no word of the damaged saved run: $(grep -i refused "$out-r.err")"
else
  fail "validate --resume failed"
fi
rm -rf "$out-r" "$out-r.csv" "$out-r.err"

# --- V12 runs its flat sweep's engine runs concurrently on the OpenMP
# threads: the records must not depend on how many there are
rm -rf "$out-t1" "$out-t2"
if OMP_NUM_THREADS=1 "$sb" validate --case 'V12/langevin-detector$' --out "$out-t1" >/dev/null 2>&1 &&
   OMP_NUM_THREADS=2 "$sb" validate --case 'V12/langevin-detector$' --out "$out-t2" >/dev/null 2>&1; then
  cmp -s "$out-t1/validate.csv" "$out-t2/validate.csv" ||
    fail "V12 records differ between 1 and 2 OpenMP threads"
else
  fail "validate --case V12/langevin-detector failed"
fi
rm -rf "$out-t1" "$out-t2"

# --- pbe: constant kernel, monodisperse start: M0 = N0 / (1 + tau/2),
# tau = K N0 t (analytic), file headers as documented
expect_rc 0 "$sb" pbe --help
expect_rc 2 "$sb" pbe --kernel no-such-kernel --n0 1 --init mono --method discrete --sizes 10 --times 1 --out "$out-p.csv"
# input errors exit 2: empty times or fields, bad numbers
expect_rc 2 "$sb" pbe --kernel constant --n0 1 --sizes 10 --times "" --out "$out-p.csv"
expect_rc 2 "$sb" pbe --kernel constant --n0 1 --sizes 10 --times 1,,2 --out "$out-p.csv"
expect_rc 2 "$sb" pbe --kernel constant --n0 -1 --sizes 10 --times 1 --out "$out-p.csv"
expect_rc 2 "$sb" pbe --kernel constant --n0 1 --v1 0 --sizes 10 --times 1 --out "$out-p.csv"
expect_rc 2 "$sb" pbe --kernel constant --n0 1 --rtol 2 --sizes 10 --times 1 --out "$out-p.csv"
expect_rc 2 "$sb" pbe --kernel constant --n0 1 --gain fast --sizes 10 --times 1 --out "$out-p.csv"
# the solution depends on N0 only through the rate K N0: a tiny N0 with a
# large K solves (the concentrations CVODE sees are n/N0), M0 = N0/(1 +
# K N0 t/2); a rate out of the range of doubles is an input error
if "$sb" pbe -q --kernel constant --param K=2e300 --n0 1e-300 --sizes 30 \
     --times 0.5,1 --out "$out-p.csv" 2>/dev/null; then
  m0=$(awk -F, '$1 == 1 {print $2}' "$out-p-moments.csv")
  want=$(awk 'BEGIN { printf "%.17g", 1e-300 / (1 + 2e300 * 1e-300 / 2) }')
  relclose "$m0" "$want" 1e-8 || fail "pbe --n0 1e-300: M0(t=1) = $m0, want $want"
else
  fail "pbe --n0 1e-300 --param K=2e300 failed"
fi
msg=$("$sb" pbe -q --kernel constant --param K=1e10 --n0 1e300 --sizes 10 \
        --times 1 --out "$out-p.csv" 2>&1)
rc=$?
[ $rc -eq 2 ] || fail "pbe --n0 1e300 --param K=1e10: exit $rc, want 2: $msg"
case "$msg" in *"--n0 1e+300: the collision rate n0 K(V1, V1) = inf"*) ;;
  *) fail "pbe --n0 1e300 message: $msg" ;; esac
# a --param key given twice is an input error naming the key (as a key
# given twice in an INI file), not the last value taken silently
msg=$("$sb" pbe -q --kernel brownian-co --param T=300 --param mu=1e-3 \
        --param T=310 --n0 1 --sizes 10 --times 1 --out "$out-p.csv" 2>&1)
rc=$?
[ $rc -eq 2 ] || fail "pbe --param T twice: exit $rc, want 2: $msg"
case "$msg" in *"--param T given twice (T=300, then T=310)"*) ;;
  *) fail "pbe --param T twice: message: $msg" ;; esac
# the tail warning again when its share has grown tenfold (additive
# kernel, 60 sizes: 0.125% at t = 1, all but 0.03% at t = 10)
nw=$("$sb" pbe -q --kernel additive --n0 1 --sizes 60 --times 0.1,1,10 \
       --out "$out-p.csv" 2>&1 | grep -c "lumped tail")
[ "$nw" -eq 2 ] || fail "pbe tail warnings: $nw, want 2"
if "$sb" pbe --kernel constant --param K=2 --n0 3 --init mono --method discrete \
     --sizes 30 --times 0.5,1 --out "$out-p.csv" 2>/dev/null; then
  head -n 1 "$out-p.csv" | grep -qx 't,k,v,n' || fail "pbe csv header"
  head -n 1 "$out-p-moments.csv" | grep -qx 't,M0,M1,M2,tail_n,tail_M1' || fail "pbe moments header"
  # --help gives the headers the files have
  for h in "$(head -n 1 "$out-p.csv")" "$(head -n 1 "$out-p-moments.csv")"; do
    "$sb" pbe --help | tr -s ' \n' '  ' | grep -qF "with header $h " ||
      fail "pbe --help does not give the header $h"
  done
  m0=$(awk -F, '$1 == 1 {print $2}' "$out-p-moments.csv")
  want=$(awk 'BEGIN { tau = 2 * 3 * 1; printf "%.17g", 3 / (1 + tau / 2) }')
  relclose "$m0" "$want" 1e-8 || fail "pbe M0(t=1) = $m0, want $want"
else
  fail "smolbridge pbe failed"
fi
rm -f "$out-p.csv" "$out-p-moments.csv"
# --plot: gnuplot runs after the data are on disk, without a shell (a
# quote in a file name is part of the name)
if command -v gnuplot > /dev/null 2>&1; then
  q="$out-q';touch pbe-injected;'"
  "$sb" pbe -q --kernel constant --n0 1 --sizes 30 --times 0.1,1,10 \
    --out "$q.csv" --plot "$q.png" 2>/dev/null || fail "pbe --plot failed"
  [ -s "$q.png" ] || fail "pbe --plot: no PNG (or an empty one)"
  [ -e pbe-injected ] && fail "pbe --plot: a file name ran as a command"
  rm -f "$q.csv" "$q-moments.csv" "$q.png" "$q.png.gp" pbe-injected
fi
# gelation (multiplicative kernel, t_gel = 1/(K M2(0)) = 1): exit 1 with a
# message, outputs only before it, no negative M0
msg=$("$sb" pbe --kernel multiplicative --n0 1 --sizes 20 --times 0.5,1,2,5 \
        --out "$out-g.csv" -q 2>&1)
rc=$?
[ $rc -eq 1 ] || fail "pbe past gelation exited $rc, want 1"
case "$msg" in *"gelation at t = 1/(K M2(0)) = 1"*) ;; *) fail "pbe gelation message: $msg" ;; esac
awk -F, 'NR > 1 && ($1 >= 1 || $2 < 0) { bad = 1 } END { exit bad }' \
  "$out-g-moments.csv" || fail "pbe wrote moments at or past gelation"
# a short size range: the lumped tail is written (row k = K+1) and
# reported; M0 and M1 of the rows equal the moments file's
msg=$("$sb" pbe --kernel constant --param K=1 --n0 1 --sizes 1000 --times 1000 \
        --out "$out-t.csv" -q 2>&1) || fail "pbe tail run failed"
case "$msg" in *"% of the mass"*"lumped tail"*) ;; *) fail "pbe tail warning: $msg" ;; esac
m1=$(awk -F, 'NR > 1 { m += $3 * $4 } END { printf "%.17g", m }' "$out-t.csv")
relclose "$m1" 1 1e-9 || fail "pbe rows hold M1 = $m1, want 1"
m0=$(awk -F, 'NR > 1 { m += $4 } END { printf "%.17g", m }' "$out-t.csv")
m0f=$(awk -F, 'NR == 2 { print $2 }' "$out-t-moments.csv")
relclose "$m0" "$m0f" 1e-12 || fail "pbe rows M0 = $m0, moments file $m0f"
rm -f "$out-g.csv" "$out-g-moments.csv" "$out-t.csv" "$out-t-moments.csv"
# the kernels of the library that pbe gained: pure diffusion is constant
# for one size, K = 4 pi b2 d, so M0 = N0/(1 + K N0 t/2)
if "$sb" pbe --kernel diffusion --param b2=1e-12 --n0 1e12 --v1 5.2e-19 \
     --sizes 50 --times 100 --out "$out-d.csv" -q 2>/dev/null; then
  m0=$(awk -F, 'NR == 2 { print $2 }' "$out-d-moments.csv")
  want=$(awk 'BEGIN { pi = atan2(0, -1); r = (3 * 5.2e-19 / (4 * pi)) ^ (1 / 3);
    K = 4 * pi * 1e-12 * 2 * r; printf "%.17g", 1e12 / (1 + K * 1e12 * 100 / 2) }')
  relclose "$m0" "$want" 1e-7 || fail "pbe diffusion M0 = $m0, want $want"
else
  fail "pbe --kernel diffusion failed"
fi
for k in kinetic abrahamson; do
  expect_rc 0 "$sb" pbe --kernel $k --n0 1e12 --v1 5.2e-19 --sizes 10 \
    --times 1e-3 --out "$out-k.csv" -q
done
msg=$("$sb" pbe --kernel blah --n0 1 --times 1 --out "$out-k.csv" 2>&1)
case "$msg" in *"valid: constant, additive"*) ;; *) fail "pbe kernel list: $msg" ;; esac
# a --param the kernel has no use for is warned about, as --ratio and --v0
# are where they do not apply; the run goes on
msg=$("$sb" pbe -q --kernel constant --param T=300 --n0 1 --sizes 10 \
        --times 0.1 --out "$out-k.csv" 2>&1) || fail "pbe --param T=300 with constant: $msg"
case "$msg" in *"warning: --param T=300 ignored: --kernel constant has no T (its parameters: K)"*) ;;
  *) fail "pbe --param T=300 with constant: $msg" ;; esac
nw=$("$sb" pbe -q --kernel gravity --param K=1 --param T=300 --param mu=1e-3 \
       --param rho_p=2000 --param rho_f=1000 --param lambda=0 --param g=9.8 \
       --param G=1 --param eps=1e-4 --param nu=1e-6 --param u2=1 \
       --param b2=1e-12 --n0 1e12 --v1 5.2e-19 --sizes 10 --times 1e-3 \
       --out "$out-k.csv" 2>&1 | grep -c "ignored: --kernel gravity has no")
[ "$nw" -eq 8 ] || fail "pbe gravity: $nw --param warnings, want 8 (all but rho_p, rho_f, mu, g)"
msg=$("$sb" pbe -q --kernel brownian-co --param T=300 --param mu=1e-3 \
        --n0 1e12 --v1 5.2e-19 --sizes 10 --times 1e-3 --out "$out-k.csv" 2>&1) \
  || fail "pbe brownian-co: $msg"
case "$msg" in *warning*) fail "pbe brownian-co with its own parameters warned: $msg" ;; esac
rm -f "$out-d.csv" "$out-d-moments.csv" "$out-k.csv" "$out-k-moments.csv"

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
  # the velocities after the 45-degree impact (Thomine 2008, §7)
  awk -F, 'NR > 1 { d = ($1 == 0 ? $8 - 0.05 : $8 + 0.05); e = $7 - 0.05
                    if (d * d + e * e > 1e-24) bad = 1; n++ }
           END { exit !(n == 2 && !bad) }' "$out/collide/snap_000000.csv" ||
    fail "collide: the velocities after the impact"
else
  fail "smolbridge collide $ini failed"
fi
# the Langevin-bridge detector from the INI file (detect = langevin)
nano="${srcdir:-.}/examples/v12_nano_langevin.ini"
sed -e "s|^output = .*|output = $out/nano|" -e "s|^steps = .*|steps = 40|" \
  "$nano" > "$out/nano.ini"
if "$sb" collide "$out/nano.ini" 2>/dev/null; then
  grep -q '"detect": "langevin"' "$out/nano/summary.json" ||
    fail "collide: detect = langevin not in summary.json"
  grep -q '^  "collisions": 0,' "$out/nano/summary.json" &&
    fail "collide: no collision with detect = langevin"
else
  fail "smolbridge collide $nano failed"
fi
# the transition-regime kernel by first-contact counting
# (examples/v12_kernel_firsthit.ini, ~9300 contacts): its 95% interval
# holds the engine's converged value at Kn_D = 0.5, 0.976 of
# Gopalakrishnan & Hogan's kernel (V12 --full: H_e/H_GH 0.972 +- 0.4%;
# converged contact time 0.976), and the run is the same on two threads
kex="${srcdir:-.}/examples/v12_kernel_firsthit.ini"
for t in 1 2; do
  "$sb" collide "$kex" --threads $t --set "run.output=$out/kernel$t" \
    > /dev/null 2>&1 || fail "smolbridge collide $kex --threads $t failed"
done
kgh=$("$sb" eval kernel_brownian_gh r_i=5e-8 r_j=5e-8 \
  m_i=5.235987755982988e-19 m_j=5.235987755982988e-19 tau_i=4e-7 \
  tau_j=4e-7 T=296.15)
py="${PYTHON:-python3}"
"$py" -c 1 2>/dev/null || py=python3  # the JSON is read with Python
"$py" - "$out/kernel1/summary.json" "$kgh" <<'PY' || fail "$kex: K"
import json, sys
fh = json.load(open(sys.argv[1]))["first_hit"]
ref = 0.976 * float(sys.argv[2])
lo, hi = fh["ci95"]
ok = fh["hits"] > 8000 and lo <= ref <= hi
print("kernel example: K/K_GH = %.4f [%.4f, %.4f], %d contacts"
      % (fh["K"] / float(sys.argv[2]), lo / float(sys.argv[2]),
         hi / float(sys.argv[2]), fh["hits"]))
sys.exit(0 if ok else 1)
PY
sed -i -e 's/"wall_seconds": .*/"wall_seconds": T/' \
  -e 's/"overrides": .*/"overrides": O/' \
  "$out/kernel1/summary.json" "$out/kernel2/summary.json" 2>/dev/null
cmp -s "$out/kernel1/summary.json" "$out/kernel2/summary.json" ||
  fail "$kex: summary.json differs on 2 threads"
# open boundaries: inflows and outflows from the INI file; without
# collisions every west drop leaves east, every south drop north
jets="${srcdir:-.}/examples/open_crossing_jets.ini"
sed -e "s|^output = .*|output = $out/jets|" -e "s|^t_end = .*|t_end = 2e-3|" \
  "$jets" > "$out/jets.ini"
if "$sb" collide "$out/jets.ini" --set run.outcome=count \
     --set observe.exits=yes 2>/dev/null; then
  grep -q '"outflows": \[0, [1-9][0-9]*, 0, [1-9][0-9]*, 0, 0\]' \
    "$out/jets/summary.json" ||
    fail "collide open boundaries: $(grep outflows "$out/jets/summary.json")"
  # exits.csv: one row per outflow; in free flight a west drop leaves the
  # east face (x = L) at its inlet height with u = (1, 0), a south drop
  # the north face (y = L) at its inlet abscissa with u = (0, 1)
  nout=$(sed -n 's/.*"outflows": \[0, \([0-9]*\), 0, \([0-9]*\),.*/\1 \2/p' \
    "$out/jets/summary.json")
  awk -F, -v n="$nout" 'NR > 1 { c[$2]++
      d6 = $6 - 1e-3; d7 = $7 - 1e-3  # the exit point on the face
      e = $2 == "x_hi" ? $4 == 0 && d6 * d6 < 1e-30 && $7 >= 4.4444444e-4 && $7 <= 5.5555556e-4 && $9 == 1 && $10 == 0 \
        : $2 == "y_hi" && $4 == 1 && d7 * d7 < 1e-30 && $6 >= 4.4444444e-4 && $6 <= 5.5555556e-4 && $9 == 0 && $10 == 1
      if (!e || $1 < 0 || $1 > 2e-3) { print "bad exit row " NR ": " $0; bad = 1 } }
    END { split(n, m, " "); if (c["x_hi"] != m[1] || c["y_hi"] != m[2]) {
        print "exits.csv rows " c["x_hi"] " " c["y_hi"] ", outflows " n; bad = 1 }
      exit bad }' "$out/jets/exits.csv" || fail "collide exits.csv"
else
  fail "smolbridge collide $jets failed"
fi
printf '[run]\nL = 1e-4\nbogus = 3\n' > "$out/bad.ini"
msg=$("$sb" collide "$out/bad.ini" 2>&1 >/dev/null)
rc=$?
[ $rc -eq 2 ] || fail "collide bad.ini exited $rc, want 2"
case "$msg" in *bad.ini:3*bogus*) ;; *) fail "collide bad key message: $msg" ;; esac
# help and docs in step: every key of `collide --help` is in the
# engine chapter's tables
doc="${srcdir:-.}/docs/engine.md"
for k in $("$sb" collide --help | awk '/^  [A-Za-z_0-9]+ .* default / {print $1}'); do
  grep -q "^| \`$k\`\|^| \`[a-z_]*\` or \`$k\`\|, \`$k\`" "$doc" \
    || fail "collide key '$k' is not in docs/engine.md §9"
done
# [observe] count_variance: the pair kernels' counts get a variance
cat > "$out/gas.ini" <<EOF
[run]
output = $out/gas
seed = 7
L = 6e-9
dt = 1e-14
t_end = 1e-10
thermalize = 300
detect = ballistic
outcome = elastic
[observe]
count_variance = yes
[species He]
radius = 140e-12
mass = 6.64e-27
tau = inf
T = 300
count = 60
EOF
if "$sb" collide "$out/gas.ini" 2>/dev/null; then
  grep -q '"ncoll_var": [0-9]' "$out/gas/summary.json" &&
    grep -q '"dispersion": [0-9]' "$out/gas/summary.json" ||
    fail "collide count_variance: no variance in summary.json"
  "$sb" collide "$out/gas.ini" --set observe.count_variance=no 2>/dev/null &&
    grep -q '"dispersion": null' "$out/gas/summary.json" ||
    fail "collide count_variance = no: a variance in summary.json"
else
  fail "collide count_variance failed"
fi
# --set overrides a key and is recorded in summary.json
sed "s|^output = .*|output = $out/collide|" "$ini" > "$out/two.ini"
if "$sb" collide "$out/two.ini" --set run.dt=2e-5 --set species.sphere.T=301 \
     2>/dev/null; then
  grep -q '"dt": 2.0000000000000002e-05' "$out/collide/summary.json" \
    || fail "--set run.dt not applied"
  grep -q '"overrides": \["run.dt=2e-5", "species.sphere.T=301"\]' \
    "$out/collide/summary.json" || fail "--set not recorded in summary.json"
else
  fail "collide --set failed"
fi
# --sweep with a mixture: a first-contact run has one kernel per species
# pair (no single K: the K columns are empty), listed in the pairs column
# as in summary.json first_hit.pairs
cat > "$out/mix.ini" <<EOF
[run]
seed = 4
L = 2e-5
dt = 1e-6
steps = 100
detect = ballistic
outcome = count
placement = uniform
output = $out/mix
[observe]
first_hit = yes
[species a]
diameter = 1e-6
density = 1000
tau = 1e-7
T = 300
count = 200
[species b]
diameter = 2e-6
density = 1000
tau = 4e-7
T = 300
count = 100
EOF
printf 'run.seed=4\nspecies.b.count=50\n' > "$out/mix.txt"
if "$sb" collide "$out/mix.ini" --sweep "$out/mix.txt" >/dev/null 2>&1; then
  head -n 1 "$out/mix/sweep.csv" | grep -q ',K,K_lo,K_hi,pairs,overrides,' \
    || fail "sweep.csv header: $(head -n 1 "$out/mix/sweep.csv")"
  for k in 0 1; do
    row=$(grep "^$k,ok,.*,first-hit,,,,\"a-a " "$out/mix/sweep.csv") \
      || { fail "sweep mixture row $k: $(sed -n "$((k + 2))p" "$out/mix/sweep.csv")"; continue; }
    # each pair's K as summary.json gives it (%.6g)
    for ab in a-a a-b b-b; do
      a=${ab%-*} b=${ab#*-}
      want=$(sed -n "s/.*{\"species\": \[\"$a\", \"$b\"\], \"hits\": .*\"K\": \([^,]*\),.*/\1/p" \
        "$out/mix/point_00$k/summary.json" | awk '{ printf "%.6g", $1 }')
      case "$row" in *"$ab $want ["*) ;;
        *) fail "sweep row $k: pair $ab, want K = $want: $row" ;; esac
    done
  done
else
  fail "collide --sweep of a mixture failed"
fi

# --- a merging run names each cluster species by its size in summary.json
# (species and pair_kernels; they were all "cluster", so pair_kernels
# listed several different pairs under the same two names)
if OMP_WAIT_POLICY=passive "$sb" collide "${srcdir:-.}/examples/v8_dlvo_gas.ini" \
     --set run.output="$out/dlvo" >/dev/null 2>&1; then
  pk=$(sed -n '/"pair_kernels"/,/^  \]/p' "$out/dlvo/summary.json" |
       grep -o '"species": \[[^]]*\]')
  [ -n "$pk" ] || fail "v8_dlvo_gas: no pair_kernels"
  dup=$(printf '%s\n' "$pk" | sort | uniq -d)
  [ -z "$dup" ] || fail "v8_dlvo_gas: pair_kernels repeat a pair: $dup"
  printf '%s\n' "$pk" | grep -q '^"species": \["grain", "cluster_2"\]$' \
    || fail "v8_dlvo_gas: no grain-cluster_2 pair in: $pk"
else
  fail "collide examples/v8_dlvo_gas.ini failed"
fi

# --- exits.csv names the species as summary.json does: in a merging run
# with open faces every name of its species column is one of
# summary.json's species (clusters cluster_K, K primaries; they were all
# "cluster"), and a cluster_K row's mass is K primary masses
cat > "$out/merge_open.ini" <<EOF
[run]
seed = 3
dim = 2
L = 1e-4
dt = 1e-6
t_end = 2e-3
outcome = merge
output = $out/merge_open
[walls]
x_lo = open
x_hi = open
y_lo = open
y_hi = open
detect = ballistic
[observe]
exits = yes
[agglo]
growth = constant
[species grain]
radius = 2e-6
density = 1000
tau = inf
T = 1e10
phi = 0.3
EOF
if "$sb" collide "$out/merge_open.ini" >/dev/null 2>&1; then
  sed -n 's/.*{"name": "\([^"]*\)", "radius": [^,]*, "mass": \([^,]*\),.*/\1 \2/p' \
    "$out/merge_open/summary.json" > "$out/merge_open.names"
  awk -F, 'NR == FNR { split($0, a, " "); m[a[1]] = a[2]; next }
    FNR > 1 { if (!($3 in m)) {
        print "exits.csv row " FNR ": species " $3 " is not in summary.json"
        bad = 1; next }
      k = 1; if ($3 ~ /^cluster_[0-9]+$/) { k = substr($3, 9) + 0; nc++ }
      r = $5 / (k * m["grain"]) - 1
      if (r * r > 1e-24) { print "exits.csv row " FNR ": mass " $5 " of " $3; bad = 1 } }
    END { if (!nc) { print "no cluster left through an open face"; bad = 1 }
      exit bad }' "$out/merge_open.names" "$out/merge_open/exits.csv" ||
    fail "collide exits.csv of a merging run"
else
  fail "collide of a merging run with open faces failed"
fi

# --- quickstart.sh runs the validation with passive OpenMP waiting (idle
# threads sleep: spinning ones made V2 alone take minutes on a busy
# machine, docs/engine.md §8) unless the user set OMP_WAIT_POLICY.  Run
# on a copy whose dependency step, configure, Makefile and smolbridge
# are stand-ins; the stand-in smolbridge prints the policy it sees.
qs="${srcdir:-.}/quickstart.sh"
if [ -f "$qs" ]; then
  q="$out/quickstart"
  mkdir -p "$q/.ci"
  cp "$qs" "$q/quickstart.sh"
  printf '#!/bin/sh\nexit 0\n' > "$q/.ci/install-deps"
  printf '#!/bin/sh\nexit 0\n' > "$q/configure"
  printf 'all:\n\t@:\n' > "$q/Makefile"
  printf '#!/bin/sh\necho "policy=${OMP_WAIT_POLICY-unset} args=$*"\n' \
    > "$q/smolbridge"
  chmod +x "$q/configure" "$q/smolbridge"
  # (not as a sub-make of make check: under make -j its make prints
  # "Entering directory" on stdout)
  got=$(unset OMP_WAIT_POLICY MAKEFLAGS MFLAGS MAKELEVEL
        bash "$q/quickstart.sh" --case V9 2>/dev/null)
  [ "$got" = "policy=passive args=validate --quick --out validate-out --case V9" ] \
    || fail "quickstart.sh without OMP_WAIT_POLICY: $got"
  got=$(unset MAKEFLAGS MFLAGS MAKELEVEL
        OMP_WAIT_POLICY=active bash "$q/quickstart.sh" 2>/dev/null)
  [ "$got" = "policy=active args=validate --quick --out validate-out" ] \
    || fail "quickstart.sh with OMP_WAIT_POLICY=active: $got"
fi
rm -rf "$out"

[ "$fails" -eq 0 ] && echo "cli: all checks passed"
exit $((fails > 0))
