#!/bin/sh
# The dependency direction of the library, checked from the includes:
# every module under lib/ sits on a layer, and a file may include the
# headers (public <smolbridge/X.h> or private "module/X.h") of its own
# module and of modules on lower layers only.  A module's private headers
# (engine_internal.h, pbe_internal.h, validate's cases.h and report.h) stay
# inside its folder; the command-line tool uses public headers only.
#
#   0 common rng                           (rng may use common)
#   1 stats passage bridge langevin        mathematical references
#   2 simulate                             reference simulators
#   3 kernel dlvo                          physics
#   4 pbe engine pgd spray                 solvers
#   5 validate collide                     validation cases and reports;
#                                          engine runs from INI files
#   6 cli                                  the smolbridge command
set -u
src="${srcdir:-.}"
layer() {
  case "$1" in
    common|rng) echo 0 ;;
    stats|passage|bridge|langevin) echo 1 ;;
    simulate) echo 2 ;;
    kernel|dlvo) echo 3 ;;
    pbe|engine|pgd|spray) echo 4 ;;
    validate|collide) echo 5 ;;
    cli) echo 6 ;;
    *) echo -1 ;;
  esac
}
# module owning a public header: smolbridge/engine_bridge.h -> engine
header_module() {
  case "$1" in
    engine_bridge|engine_firsthit|engine_field) echo engine ;;
    langevin_hit|langevin_shear) echo langevin ;;
    version|ini) echo common ;;
    *) echo "$1" ;;
  esac
}
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

for f in "$src"/lib/*/*.[ch] "$src"/cli/*.[ch]; do
  dir=$(basename "$(dirname "$f")")
  [ "$dir" = smolbridge ] && continue
  me=$(layer "$dir")
  [ "$me" -lt 0 ] && { fail "$f: folder '$dir' has no layer in tests/layers.sh"; continue; }
  rel=${f#"$src"/}
  # public headers
  for h in $(sed -n 's|^#include <smolbridge/\([a-z_]*\)\.h>.*|\1|p' "$f"); do
    m=$(header_module "$h")
    l=$(layer "$m")
    [ "$l" -lt 0 ] && { fail "$rel includes unknown <smolbridge/$h.h>"; continue; }
    if [ "$m" != "$dir" ] && [ "$m" != common ] && [ "$l" -ge "$me" ]; then
      fail "$rel ($dir, layer $me) includes <smolbridge/$h.h> ($m, layer $l)"
    fi
  done
  # private headers of another module: "module/file.h"
  for p in $(sed -n 's|^#include "\([a-z_]*\)/[a-z_]*\.h".*|\1|p' "$f"); do
    [ "$dir" = cli ] && { fail "$rel includes private \"$p/...\" (cli uses public headers only)"; continue; }
    [ "$p" != common ] && [ "$p" != "$dir" ] && \
      fail "$rel includes a private header of module $p"
  done
  # a bare "x.h" must be a file of the same folder
  for h in $(sed -n 's|^#include "\([a-z_]*\.h\)".*|\1|p' "$f"); do
    [ -f "$(dirname "$f")/$h" ] || fail "$rel includes \"$h\", not in its folder"
  done
done
# each public header's own includes respect the layers too
for f in "$src"/lib/smolbridge/*.h; do
  own=$(header_module "$(basename "$f" .h)")
  me=$(layer "$own")
  for h in $(sed -n 's|^#include <smolbridge/\([a-z_]*\)\.h>.*|\1|p' "$f"); do
    m=$(header_module "$h")
    l=$(layer "$m")
    if [ "$m" != "$own" ] && [ "$m" != common ] && [ "$l" -ge "$me" ]; then
      fail "lib/smolbridge/$(basename "$f") ($own) includes <smolbridge/$h.h> ($m)"
    fi
  done
done
[ $fails -eq 0 ] && echo "layers: every include points to the same or a lower layer"
exit $((fails > 0))
