#!/bin/sh
# The Python module (python/smolbridge) against the library just built:
# skipped (exit 77) when configure found no python3 or numpy is missing.
set -u
py="${PYTHON:-:}"
if [ "$py" = ":" ] || ! "$py" -c 'import numpy' 2>/dev/null; then
  echo "python: skipped (no python3 with numpy; Debian: apt-get install python3-numpy)"
  exit 77
fi
top="${top_builddir:-.}"
top="$(cd "$top" && pwd)"
src="$(cd "${srcdir:-.}" && pwd)"
lib="$top/.libs/libsmolbridge.so"
[ -f "$lib" ] || { echo "python: no $lib (static-only build?)"; exit 77; }
# an ASan-instrumented library cannot be loaded into an uninstrumented
# python3 (the runtime must come first)
if ldd "$lib" 2>/dev/null | grep -q 'libasan'; then
  echo "python: skipped (sanitizer build)"
  exit 77
fi
SMOLBRIDGE_LIB="$lib" PYTHONPATH="$src/python" "$py" "$src/tests/test_python.py"
