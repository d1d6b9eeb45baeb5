#!/bin/sh
# Every public header compiles on its own (self-contained, includes what it
# uses) with strict warnings, as C11 and as C++ when a C++ compiler exists,
# and the umbrella header pulls them all in.
set -u
: "${CC:=cc}"
src="${srcdir:-.}/lib"
bld="${top_builddir:-.}/lib"
tmp=$(mktemp -d) || exit 99
trap 'rm -rf "$tmp"' EXIT
fails=0
gslcf=$(pkg-config --cflags gsl 2>/dev/null)
for h in "$src"/smolbridge/*.h smolbridge.h; do
  name=${h#"$src"/}
  [ "$h" = smolbridge.h ] && name=smolbridge.h
  printf '#include <%s>\n#include <%s>\nint main(void) { return 0; }\n' \
    "$name" "$name" > "$tmp/t.c"
  if ! $CC -std=c11 -Wall -Wextra -Werror -pedantic -I"$src" -I"$bld" $gslcf \
       -c "$tmp/t.c" -o "$tmp/t.o" 2> "$tmp/err"; then
    echo "FAIL: <$name> does not compile on its own:"; cat "$tmp/err"
    fails=$((fails + 1))
  fi
  if command -v c++ >/dev/null 2>&1; then
    cp "$tmp/t.c" "$tmp/t.cc"
    if ! c++ -Wall -Wextra -Werror -I"$src" -I"$bld" $gslcf -c "$tmp/t.cc" \
         -o "$tmp/t.o" 2> "$tmp/err"; then
      echo "FAIL: <$name> does not compile as C++:"; cat "$tmp/err"
      fails=$((fails + 1))
    fi
  fi
done
[ $fails -eq 0 ] && echo "headers: all compile standalone (C11, C++)"
exit $((fails > 0))
