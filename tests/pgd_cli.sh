#!/bin/sh
# `smolbridge pgd`: the example INI files run and give the right answers
# (checked here against the closed forms, computed independently in awk)
# without warnings, input errors give file:line, the key and the valid
# values with exit status 2, keys without effect a warning, and a new run
# does not leave a previous run's files behind.
set -u
sb="${top_builddir:-.}/smolbridge"
src="${srcdir:-.}"
out="${top_builddir:-.}/tests/pgd-cli-out"
# shellcheck source=tests/cli_common.sh
. "$src/tests/cli_common.sh"
rm -rf "$out"
mkdir -p "$out"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
# run an example with its output redirected into $out/NAME
run_example() {  # run_example FILE NAME [sed expressions...]
  f=$1; name=$2; shift 2
  sed -e "s|^output = .*|output = $out/$name|" "$@" "$src/examples/$f" \
    > "$out/$name.ini"
  "$sb" pgd "$out/$name.ini" >"$out/$name.log" 2>&1 || \
    { fail "$f ($name) exited $?: $(cat "$out/$name.log")"; return 1; }
}

# --- delta-shock: excess mass and centroid against the generalised
# Rankine-Hugoniot values sigma = (sqrt(rl) ul + sqrt(rr) ur)/(sqrt(rl) +
# sqrt(rr)), w = sqrt(rl rr)(ul - ur) t
if run_example pgd_delta_shock.ini delta; then
  awk -F, 'NR > 1 { x = $1; r = $2; h = 1 / 400
      sig = (sqrt(1) * 2 + sqrt(0.25) * -1) / (1 + sqrt(0.25))
      xd = 0.5 + sig * 0.2; w = sqrt(0.25) * 3 * 0.2
      if (x > xd - 0.05 && x < xd + 0.05) {
        bg = x < xd ? 1 : 0.25; m += (r - bg) * h; mx += (r - bg) * h * x } }
    END { c = mx / m; d = m - w; if (d < 0) d = -d; e = c - xd; if (e < 0) e = -e
      if (d > 1e-6 * w || e > 5 * h) {
        printf "delta mass %.10g (exact %.10g), centroid %.6f (exact %.6f)\n", m, w, c, xd
        exit 1 } }' "$out/delta/fields.csv" || fail "delta-shock answer"
  head -n 1 "$out/delta/fields.csv" | grep -qx 'x,rho,u' || fail "fields.csv header"
  [ "$(wc -l < "$out/delta/fields.csv")" -eq 401 ] || fail "fields.csv rows"
  [ -s "$out/delta/exact.csv" ] || fail "exact.csv missing"
  # exact.csv holds the delta (on a cell face at t_end) once: its mass is
  # the grid's (both 1.075), and its L1 distance to fields.csv is the
  # summary's l1
  paste -d, "$out/delta/exact.csv" "$out/delta/fields.csv" | awk -F, '
    NR > 1 { me += $2; mf += $5; d = $2 - $5; l1 += d < 0 ? -d : d; n++ }
    END { h = 1 / n; if ((me - mf) * h > 1e-9 || (mf - me) * h > 1e-9) {
            printf "exact.csv mass %.10g, fields.csv %.10g\n", me * h, mf * h
            exit 1 }
          printf "%.12g\n", l1 * h }' > "$out/delta/l1" ||
    fail "exact.csv lost the delta's mass"
  l1=$(sed -n 's/.*"l1": \([^,]*\),.*/\1/p' "$out/delta/summary.json")
  awk -v a="$(cat "$out/delta/l1")" -v b="$l1" \
    'BEGIN { exit !(a - b < 1e-9 && b - a < 1e-9) }' ||
    fail "L1 of exact.csv against fields.csv $(cat "$out/delta/l1"), summary $l1"
  grep -q '"wave": "delta"' "$out/delta/summary.json" || fail "summary.json wave"
fi

# --- vacuum with drag: edges at 0.5 -+ tau (1 - exp(-t/tau))
if run_example pgd_vacuum.ini vacuum; then
  awk -F, 'NR > 1 { x = $1; r = $2; e = 0.5 * (1 - exp(-0.4))
      if (x > 0.5 - e + 0.06 && x < 0.5 + e - 0.06 && r > 1e-3) bad++
      if ((x < 0.5 - e - 0.06 || x > 0.5 + e + 0.06) && (r < 0.999 || r > 1.001)) bad++ }
    END { exit bad > 0 }' "$out/vacuum/fields.csv" || fail "vacuum edges"
fi

# --- crossing jets, Euler: mass budget closes; the merged jet moves at
# (1/2, 1/2) (momentum of two equal perpendicular jets) near the corner
if run_example pgd_crossing_jets.ini jets; then
  awk -F, 'NR > 1 && $1 > 0.75 && $2 > 0.75 { m += $3; px += $3 * $4; py += $3 * $5 }
    END { ux = px / m; uy = py / m
      if (ux < 0.47 || ux > 0.51 || uy < 0.47 || uy > 0.51) {
        printf "merged jet velocity (%g, %g)\n", ux, uy; exit 1 } }' \
    "$out/jets/fields.csv" || fail "Eulerian jets do not merge at (1/2, 1/2)"
  [ -s "$out/jets/fields.vtk" ] || fail "fields.vtk missing"
  awk '/"mass"/ { gsub(/[,]/, ""); m = $2 }
       /"inflow"/ { gsub(/[][,]/, " "); i = $2 }
       /"outflow"/ { gsub(/[][,]/, " "); o = $2 }
       END { d = m - (i - o); if (d < 0) d = -d; exit !(d < 1e-13) }' \
    "$out/jets/summary.json" || fail "jets mass budget"
fi
# --- the same jets with weighted particles: they cross; the west jet
# leaves through the east side at (1, 0) with rho = 1
if run_example pgd_crossing_jets.ini jetsL -e 's|^method = .*|method = lagrange|'; then
  awk -F, 'NR > 1 && $1 > 0.9 && $2 > 0.46 && $2 < 0.54 {
      n++; if ($3 < 0.99 || $3 > 1.01 || $4 < 0.99 || $4 > 1.0) bad++ }
    END { exit !(n > 0 && bad == 0) }' "$out/jetsL/fields.csv" \
    || fail "Lagrangian jets do not cross"
  grep -q '"particles"' "$out/jetsL/summary.json" || fail "particle count"
fi
# --- decomposition (Lagrangian centre block, the section of the
# example's comment): the mass budget closes
if run_example pgd_crossing_jets.ini jetsD -e 's|^method = .*|method = decomposition|' \
    -e '$s|$|\n[decomposition]\nblocks = 3 3\nkinds = EEEELEEEE|'; then
  awk '/"mass"/ { gsub(/[,]/, ""); m = $2 }
       /"inflow"/ { gsub(/[][,]/, " "); i = $2 }
       /"outflow"/ { gsub(/[][,]/, " "); o = $2 }
       END { d = m - (i - o); if (d < 0) d = -d; exit !(d < 1e-13) }' \
    "$out/jetsD/summary.json" || fail "decomposition mass budget"
fi

# --- the examples (and the decomposition above) warn about nothing
for name in delta vacuum jets jetsD; do
  grep warning "$out/$name.log" && fail "$name: a warning"
done

# --- keys that have no effect in the configuration: a warning naming the
# file, line, section and key (as collide), the exit status unchanged;
# none where the key matters
unused() {  # unused NAME WANT INI-LINES...: WANT after "FILE:" ("": none)
  name=$1; want=$2; shift 2
  printf '%s\n' "$@" > "$out/w.ini"
  warned pgd "$name" "$want"
}
r1="[run]
nx = 10
t_end = 0.01
output = $out/w"                               # lines 1-4, 1-D
r2="[run]
dim = 2
nx = 6
t_end = 0.01
output = $out/w"                               # lines 1-5, 2-D
rp="[riemann]
rho_l = 1"
unused "1-D ny" "5: [run] ny ignored: dim = 1" "$r1" "ny = 5" "$rp"
unused "2-D ny" "" "$r2" "ny = 4"
unused "1-D Ly" "5: [run] Ly ignored: dim = 1" "$r1" "Ly = 2" "$rp"
unused "2-D Ly" "" "$r2" "Ly = 2"
unused "1-D origin y" "5: [run] origin ignored in y: dim = 1" "$r1" "origin = 0 3" "$rp"
unused "1-D origin x" "" "$r1" "origin = 0.5" "$rp"
unused "2-D origin" "" "$r2" "origin = 0 3"
unused "1-D south" "8: [boundary] south ignored: dim = 1" "$r1" "$rp" "[boundary]" "south = outflow"
unused "1-D north" "8: [boundary] north ignored: dim = 1" "$r1" "$rp" "[boundary]" "north = outflow"
unused "1-D west" "" "$r1" "$rp" "[boundary]" "west = outflow"
unused "2-D south" "" "$r2" "[boundary]" "south = outflow"
unused "1-D drag U y" "9: [drag] U ignored in y: dim = 1" "$r1" "$rp" "[drag]" "tau = 1" "U = 0.5 2"
unused "1-D drag U x" "" "$r1" "$rp" "[drag]" "tau = 1" "U = 0.5"
unused "2-D drag U" "" "$r2" "[drag]" "tau = 1" "U = 0.5 2"
unused "U without drag" "8: [drag] U ignored: no drag" "$r1" "$rp" "[drag]" "U = 0.5"
unused "U with tau = inf" "9: [drag] U ignored: no drag" "$r1" "$rp" "[drag]" "tau = inf" "U = 0.5"
unused "1-D initial u y" "7: [initial] u ignored in y: dim = 1" "$r1" "[initial]" "rho = 1" "u = 1 2"
unused "2-D initial u" "" "$r2" "[initial]" "rho = 1" "u = 1 2"
unused "[particles] with euler" "7: [particles] inject_time ignored: method = euler has no particles" \
  "$r2" "[particles]" "inject_time = 3"
unused "[particles] with lagrange" "" "$r2" "method = lagrange" "[particles]" "inject_time = 3"
unused "[particles], no L block" "11: [particles] inject_face ignored: [decomposition] kinds has no L block" \
  "$r2" "method = decomposition" "[decomposition]" "blocks = 2 2" "kinds = EEEE" "[particles]" "inject_face = 3"
unused "[particles], an L block" "" \
  "$r2" "method = decomposition" "[decomposition]" "blocks = 2 2" "kinds = EELE" "[particles]" "inject_face = 3"
unused "[decomposition] with euler" "7: [decomposition] blocks ignored: method = euler" \
  "$r2" "[decomposition]" "blocks = 2 2"
unused "[decomposition] with lagrange" "9: [decomposition] kinds ignored: method = lagrange" \
  "$r2" "method = lagrange" "[decomposition]" "blocks = 2 2" "kinds = EELE"
unused "scheme with lagrange" "7: [run] scheme ignored: method = lagrange" "$r2" "method = lagrange" "scheme = upwind"
unused "scheme with euler" "" "$r2" "scheme = muscl"
unused "[initial] with lagrange" "8: [initial] rho ignored: method = lagrange starts empty" \
  "$r2" "method = lagrange" "[initial]" "rho = 0"

# --- a previous run's snapshots do not survive a new run
run_example pgd_vacuum.ini snaps -e 's|^t_end = .*|t_end = 0.2\noutput_every = 0.05|'
[ -f "$out/snaps/fields_00002.csv" ] || fail "no snapshots written"
run_example pgd_vacuum.ini snaps
[ -f "$out/snaps/fields_00000.csv" ] && fail "old snapshots left in the output"

# --- input errors: exit 2, file:line, key and valid values
bad() {  # bad EXPECTED-TEXT INI-LINES...
  want=$1; shift
  printf '%s\n' "$@" > "$out/bad.ini"
  msg=$("$sb" pgd "$out/bad.ini" 2>&1 >/dev/null)
  rc=$?
  [ $rc -eq 2 ] || fail "'$*' exited $rc, want 2"
  case "$msg" in *"$want"*) ;; *) fail "message '$msg' lacks '$want'" ;; esac
}
bad "bad.ini:3: [run] scheme = 'weno': must be upwind or muscl" \
  "[run]" "nx = 10" "scheme = weno" "t_end = 1"
bad "bad.ini:2: [run]: unknown key 'nz'" "[run]" "nz = 10"
bad "bad.ini:3: [boundary] west = 'wall': must be transmissive, outflow or periodic" \
  "[run]" "[boundary]" "west = wall"
bad "[run] nx is required" "[run]" "t_end = 1" "[riemann]" "rho_l = 1"
bad "cfl = 0.8: must be in (0, 0.5]" \
  "[run]" "nx = 10" "t_end = 1" "scheme = muscl" "cfl = 0.8" "[riemann]" "rho_l = 1"
bad "bad.ini:4: [inflow a] side = 'up'" \
  "[run]" "dim = 2" "[inflow a]" "side = up"
bad "bad.ini:1: unknown section [foo]" "[foo]" "a = 1"
# an [inflow NAME] header without keys would add no inflow (the run went
# on without it)
bad "bad.ini:8: [inflow b] has no keys: an inflow needs side, count and rho" \
  "[run]" "dim = 2" "nx = 10" "t_end = 0.01" "output = $out/empty-inflow" \
  "[initial]" "rho = 1" "[inflow b]"
# also without keys under it (a misspelt section is not left out silently)
bad "bad.ini:4: unknown section [boundaries] (run, riemann," \
  "[run]" "nx = 10" "t_end = 0.1" "[boundaries]" "[riemann]" "rho_l = 1"
bad "[riemann] x0 = 5: outside the domain (0, 1)" \
  "[run]" "nx = 10" "t_end = 0.1" "[riemann]" "x0 = 5" "rho_l = 1"
bad "[riemann] and [initial]: give one initial state" \
  "[run]" "nx = 10" "t_end = 0.1" "[riemann]" "rho_l = 1" "[initial]" "rho = 1"
bad "[run] output_every = 1e-09: 1e+08 snapshots up to t_end = 0.1" \
  "[run]" "nx = 10" "t_end = 0.1" "output_every = 1e-9" "[riemann]" "rho_l = 1"
# nothing replaced or merged silently: a key given twice, a section
# repeated, L with Lx or Ly (as collide)
bad "bad.ini:5: [riemann] rho_l given twice (first at $out/bad.ini:4); give each key once" \
  "[run]" "nx = 10" "[riemann]" "rho_l = 1" "rho_l = 2" "[run]" "t_end = 0.1"
bad "bad.ini:5: section [run] repeated (first at $out/bad.ini:1); put its keys in one section" \
  "[run]" "nx = 10" "[riemann]" "rho_l = 1" "[run]" "t_end = 0.1"
bad "bad.ini:6: [inflow a] rho given twice (first at $out/bad.ini:5)" \
  "[run]" "dim = 2" "[inflow a]" "side = west" "rho = 1" "rho = 2"
bad "bad.ini:5: [run] Lx conflicts with L (at $out/bad.ini:4): L sets both edges" \
  "[run]" "dim = 2" "nx = 10" "L = 2" "Lx = 1" "t_end = 0.1" "[initial]" "rho = 1"
# the checks of <smolbridge/ini.h> (sb_ini_read), as collide and spray
bad "bad.ini:3: the line starts with a blank" "[run]" "nx = 10" "  t_end = 1"
bad "bad.ini:2: not 'key = value', '[section]' or a comment" "[run]" "nx 10"
bad "bad.ini:1: section header without ']'" "[run" "nx = 10"
"$sb" pgd "$out/no-such.ini" >/dev/null 2>&1; [ $? -eq 2 ] || fail "missing file"
"$sb" pgd >/dev/null 2>&1; [ $? -eq 2 ] || fail "no argument"
"$sb" pgd --help >/dev/null 2>&1 || fail "--help"
# an output that cannot be created: a failed run (1)
printf '[run]\nnx = 10\nt_end = 0.1\noutput = /proc/none/x\n[riemann]\nrho_l = 1\n' > "$out/io.ini"
"$sb" pgd "$out/io.ini" >/dev/null 2>&1; [ $? -eq 1 ] || fail "unwritable output"

[ $fails -eq 0 ] && echo "pgd cli: all checks passed" && rm -rf "$out"
exit $((fails > 0))
