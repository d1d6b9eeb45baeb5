#!/bin/sh
# The installed shared library must export only sb_* symbols (libtool
# -export-symbols-regex), and must export the public API.  It must not
# import what acts on the whole process: abort/exit, printing to stdout,
# assert, or GSL's process-wide error handler (switching it off inside the
# library would race with other threads and the application).
set -u
lib="${top_builddir:-.}/.libs/libsmolbridge.so"
[ -f "$lib" ] || { echo "no $lib (static-only build?)"; exit 77; }
command -v nm >/dev/null 2>&1 || { echo "nm not found"; exit 77; }
syms=$(nm -D --defined-only "$lib" | awk '$2 ~ /^[TDRBVW]$/ {print $3}')
bad=$(printf '%s\n' "$syms" | grep -v '^sb_' | grep -v '^_' || true)
if [ -n "$bad" ]; then
  echo "symbols exported without the sb_ prefix:"; printf '%s\n' "$bad"
  exit 1
fi
for s in sb_strerror sb_last_error sb_version sb_bb_cross_prob \
         sb_bes3b_hit_quantile sb_bm_fpt_cdf sb_bm_fpt_logmass sb_ks_test \
         sb_collide_run sb_collide_read_string sb_collide_key; do
  printf '%s\n' "$syms" | grep -qx "$s" || { echo "missing export: $s"; exit 1; }
done
if printf '%s\n' "$syms" | grep -q '^sbi_'; then
  echo "internal sbi_ symbols leaked"; exit 1
fi
imports=$(nm -D --undefined-only "$lib" | awk '{print $NF}' | sed 's/@.*//')
bad=$(printf '%s\n' "$imports" | grep -xE 'abort|exit|_exit|_Exit|quick_exit|printf|vprintf|puts|putchar|perror|__assert_fail|gsl_set_error_handler(_off)?' || true)
if [ -n "$bad" ]; then
  echo "the library imports process-wide actions:"; printf '%s\n' "$bad"
  exit 1
fi
n=$(printf '%s\n' "$syms" | grep -c '^sb_')
echo "exports: $n sb_ symbols, no others"
