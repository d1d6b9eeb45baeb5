#!/bin/sh
# The reference of the `smolbridge` command in step with its parsers: every
# command-line option and INI section and key a command accepts is in the
# man page (docs/smolbridge.1), in the command's --help and in the chapter
# of docs/ that documents it, and the keys the documents list are accepted.
# The names come from the parsers themselves: the getopt tables and
# strcmp options of cli/*.c, and the valid names each INI reader gives in
# its message for an unknown section or key (each of which is then checked
# to be accepted).  Also: the ranges of numeric options, pbe's kernels
# and parameters, the number of named sections each reader takes, the
# functions docs/langevin.md says eval has, the kinds of the expect lines
# validate --write-ini writes; the links of the installed pages, and the
# scripts they name installed executable; every `smolbridge eval` command
# quoted in docs/ runs.
set -u
sb="${top_builddir:-.}/smolbridge"
src="${srcdir:-.}"
out="${top_builddir:-.}/tests/cli-docs-out"
man="$src/docs/smolbridge.1"
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }
rm -rf "$out"
mkdir -p "$out"

# the man page without roff's escapes (\- is -, \fB...\fR fonts)
sed -e 's/\\-/-/g' -e 's/\\f[BIRP]//g' "$man" > "$out/man.txt"
# the text of the subsection ".SS NAME" of the man page
man_ss() {
  awk -v s="$1" '/^\.SS / { on = ($2 == s) } on' "$out/man.txt"
}
# has_opt TEXT-FILE OPT: OPT (--name or -x) as a word of the file
has_opt() {
  grep -qE -- "(^|[^A-Za-z0-9-])$2([^A-Za-z0-9-]|\$)" "$1"
}

# --- command-line options: the getopt tables (long options, and the short
# letters of the optstring) of pbe and validate, the options collide and
# eval compare argv with; each in CMD --help, the long ones in the man
# page and (collide, validate) in the command's chapter
opts_getopt() {  # the options of the getopt_long call in cli/$1.c
  grep -o '{"[a-z0-9-]*", \(no\|required\)_argument' "$src/cli/$1.c" |
    sed 's/{"\([a-z0-9-]*\)".*/--\1/' | sort -u
  sed -n 's/.*getopt_long(argc, argv, "\([a-zA-Z:]*\)".*/\1/p' \
    "$src/cli/$1.c" | tr -d ':' | fold -w 1 | sed 's/^/-/'
}
for cmd in pbe validate collide eval; do
  if [ "$cmd" = collide ] || [ "$cmd" = eval ]; then  # strcmp(argv[i], ...)
    opts=$(grep -o 'strcmp(argv\[[0-9i]\], "-[-a-z]*")' "$src/cli/$cmd.c" |
      sed 's/.*"\(.*\)")/\1/' | sort -u)
  else
    opts=$(opts_getopt "$cmd")
  fi
  [ -n "$opts" ] || fail "$cmd: no options found in cli/$cmd.c"
  "$sb" "$cmd" --help > "$out/help.txt" 2>&1 || fail "$cmd --help failed"
  man_ss "$cmd" > "$out/ss.txt"
  # the synopsis of the command and its subsection
  { awk -v c="smolbridge $cmd" '/^\.SH/ { syn = $2 == "SYNOPSIS" }
      syn && index($0, c) { on = 1 } /^\.br/ { on = 0 } on' "$out/man.txt"
    cat "$out/ss.txt"; } > "$out/man_cmd.txt"
  for o in $opts; do
    case "$o" in --help|-h) continue ;; esac  # smolbridge COMMAND --help
    has_opt "$out/help.txt" "$o" || fail "$cmd $o is not in '$cmd --help'"
    case "$o" in --*) ;; *) continue ;; esac  # the man page: long forms
    has_opt "$out/man_cmd.txt" "$o" ||
      fail "$cmd $o is not in docs/smolbridge.1 (synopsis or '.SS $cmd')"
    # and in the chapter on the command
    case $cmd in
      collide) awk '/^## 9\. `smolbridge collide/ { on = 1; next }
                    /^## / { on = 0 } on' "$src/docs/engine.md" ;;
      validate) cat "$src/docs/validation.md" ;;
      *) continue ;;  # pbe and eval: docs/pbe.md and the others refer to --help
    esac > "$out/chapter.txt"
    has_opt "$out/chapter.txt" "$o" ||
      fail "$cmd $o is not in its chapter of docs/ (engine.md §9, validation.md)"
  done
done

# the --OPTION=VALUE forms collide accepts (strncmp(argv[i], "--x=", n)):
# each in collide --help, the man page's '.SS collide' and engine.md §9,
# and read as the form with a space (the same message for a bad value)
eqs=$(grep -o 'strncmp(argv\[i\], "--[a-z-]*=", [0-9]*)' "$src/cli/collide.c" |
  sed 's/.*"\(--[a-z-]*=\)".*/\1/' | sort -u)
[ -n "$eqs" ] || fail "collide: no --OPTION= forms found in cli/collide.c"
"$sb" collide --help > "$out/help.txt" 2>&1
man_ss collide > "$out/ss.txt"
awk '/^## 9\. `smolbridge collide/ { on = 1; next } /^## / { on = 0 } on' \
  "$src/docs/engine.md" > "$out/chapter.txt"
printf '[run]\nL = 1\n' > "$out/t.ini"
for o in $eqs; do
  grep -qF -- "$o" "$out/help.txt" || fail "collide ${o}X is not in 'collide --help'"
  grep -qF -- "$o" "$out/ss.txt" ||
    fail "collide ${o}X is not in docs/smolbridge.1 '.SS collide'"
  grep -qF -- "$o" "$out/chapter.txt" ||
    fail "collide ${o}X is not in docs/engine.md §9"
  a=$("$sb" collide "$out/t.ini" "${o%=}" zz 2>&1)
  b=$("$sb" collide "$out/t.ini" "${o}zz" 2>&1)
  [ "$a" = "$b" ] || fail "collide ${o}zz: '$b', but ${o%=} zz: '$a'"
done

# --- the validation cases `validate --write-ini` writes (INI_CASES of
# lib/validate/registry.c): the man page's list of them and the table of
# docs/validation.md ("Reproducing a case") name exactly these; the cases
# the table gives no files and those the sentence after it lists are the
# others.  Lists are "V8/agglo-constant, agglo-brownian" (the set-up
# carried over), a bare "V4" (every case of V4) or "V15/pgd-*" (a glob).
"$sb" validate --list 2>/dev/null | awk '{ print $1 }' | sort -u > "$out/cases"
[ -s "$out/cases" ] || fail "validate --list gave no cases"
sed -n '/INI_CASES\[\] = {/,/NULL};/p' "$src/lib/validate/registry.c" |
  grep -o '"[^"]*"' | tr -d '"' | sort -u > "$out/ini_cases"
[ -s "$out/ini_cases" ] || fail "no INI_CASES in lib/validate/registry.c"
expand_cases() {  # stdin: a list as above; the case names, one a line
  sed -e 's/([^)]*)//g' | tr ',' '\n' | sed -e 's/^ *//' -e 's/ *$//' |
    grep -v '^$' | awk 'NR == FNR { all[++n] = $1; next }
      { if ($0 ~ /^V[0-9X]+$/) { pre = $0 "/"; pat = pre "*" }
        else if (index($0, "/")) { pre = substr($0, 1, index($0, "/"));
                                   pat = $0 }
        else pat = pre $0
        re = "^" pat "$"; gsub(/\*/, ".*", re); hit = 0
        for (i = 1; i <= n; i++) if (all[i] ~ re) { print all[i]; hit = 1 }
        if (!hit) print "no-such-case:" pat }' "$out/cases" - | sort -u
}
same_cases() {  # same_cases FILE WHERE: FILE's names are INI_CASES
  comm -3 "$out/ini_cases" "$1" | while read -r n; do
    if grep -qx "$n" "$out/ini_cases"; then
      echo "FAIL: $2 does not name $n, which --write-ini writes"
    else echo "FAIL: $2 names $n, which --write-ini does not write"; fi
  done | grep FAIL && fails=$((fails + 1))
}
tr '\n' ' ' < "$out/man.txt" |
  sed -n 's/.*the cases with files (\([^;)]*\).*/\1/p' | expand_cases > "$out/man_cases"
same_cases "$out/man_cases" "docs/smolbridge.1 (--write-ini, 'the cases with files')"
awk '/^## Reproducing a case/ { on = 1; next } /^## / { on = 0 }
  on && /^\| V/' "$src/docs/validation.md" > "$out/vtable"
awk -F'|' '$3 !~ /^ *none/ { print $2 }' "$out/vtable" | tr '\n' ',' |
  expand_cases > "$out/doc_cases"
same_cases "$out/doc_cases" "the table of docs/validation.md"
awk -F'|' '$3 ~ /^ *none/ { print $2 }' "$out/vtable" | tr '\n' ',' |
  expand_cases > "$out/none_cases"
awk '/^## Reproducing a case/ { on = 1; next } /^## / { on = 0 } on' \
  "$src/docs/validation.md" | tr '\n' ' ' |
  sed -n 's/.*The other cases have no engine run ([^)]*): \([^.]*\)\. .*/\1/p' |
  expand_cases > "$out/other_cases"
[ -s "$out/other_cases" ] || fail "docs/validation.md: no list of the other cases"
cat "$out/none_cases" "$out/other_cases" | sort -u > "$out/no_ini"
comm -12 "$out/no_ini" "$out/ini_cases" | while read -r n; do
  echo "FAIL: docs/validation.md says $n has no engine run, but --write-ini writes it"
done | grep FAIL && fails=$((fails + 1))
cat "$out/doc_cases" "$out/no_ini" | sort -u | comm -13 - "$out/cases" |
  while read -r n; do echo "FAIL: docs/validation.md does not say whether $n has files"; done |
  grep FAIL && fails=$((fails + 1))

# the kinds of the "; expect" lines --write-ini writes (the literal kinds
# lib/validate passes to expect_line and sbv_ini_expect_stat): each in the
# man page's --write-ini item and in docs/validation.md
grep -ho '\(expect_line\|sbv_ini_expect_stat\)(rep, "expect[-a-z0-9]*"' \
  "$src"/lib/validate/*.c | sed 's/.*"\(.*\)"/\1/' | sort -u > "$out/kinds"
[ "$(wc -l < "$out/kinds")" -ge 2 ] ||
  fail "no expect kinds found in lib/validate/*.c"
awk '/^\.TP/ { on = 0 } /^\.B(I)? --write-ini/ { on = 1 } on' \
  "$out/man.txt" > "$out/writeini.txt"
[ -s "$out/writeini.txt" ] || fail "docs/smolbridge.1: no --write-ini item"
while read -r k; do
  has_opt "$out/writeini.txt" "$k" ||
    fail "the '; $k' lines of --write-ini are not in docs/smolbridge.1 (--write-ini)"
  has_opt "$src/docs/validation.md" "$k" ||
    fail "the '; $k' lines of --write-ini are not in docs/validation.md"
done < "$out/kinds"

# the commands and options of main.c: in `smolbridge --help`; the commands
# in the man page's synopsis and a subsection each, the options in its
# synopsis
"$sb" --help > "$out/help.txt" 2>&1 || fail "smolbridge --help failed"
sed -n '/^\.SH SYNOPSIS/,/^\.SH DESCRIPTION/p' "$out/man.txt" > "$out/syn.txt"
for c in $(grep -o 'strcmp(cmd, "[^"]*")' "$src/cli/main.c" |
           sed 's/.*"\(.*\)")/\1/' | sort -u); do
  has_opt "$out/help.txt" "$c" || fail "'$c' is not in 'smolbridge --help'"
  case "$c" in
    -*|help) has_opt "$out/syn.txt" "$c" ||
        fail "smolbridge $c is not in the synopsis of docs/smolbridge.1" ;;
    *) grep -q "^\.B smolbridge $c" "$out/syn.txt" ||
        fail "smolbridge $c is not in the synopsis of docs/smolbridge.1"
      grep -qx "\.SS $c" "$out/man.txt" ||
        fail "smolbridge $c has no subsection in docs/smolbridge.1" ;;
  esac
done

# --- the guide installed in share/doc/smolbridge (Makefile.am: docs/ in
# guidedir, README.md and NEWS in docdir, examples/ in exampledir, the
# layout of the source tree): every relative link of an installed page
# names an installed file
# (the scripts among them executable: dist_*_SCRIPTS)
sed -e ':a' -e '/\\$/{N; s/\\\n//; ba' -e '}' "$src/Makefile.am" \
  > "$out/Makefile.am"
installed_as() {  # installed_as DATA|SCRIPTS: the files, one a line
  sed -n "s/^dist_\\(guide\\|doc\\|example\\)_$1 *= *//p" "$out/Makefile.am" |
    tr -s ' \t' '\n\n' | grep -v '^$' | sort -u
}
installed_as DATA > "$out/installed.data"
installed_as SCRIPTS > "$out/installed.scripts"
sort -u "$out/installed.data" "$out/installed.scripts" > "$out/installed"
[ -s "$out/installed.data" ] || fail "Makefile.am: no dist_guide_DATA"
grep '\.md$' "$out/installed" | while read -r page; do
  d=$(dirname "$page")
  grep -oE '\]\([A-Za-z0-9_./-]+(#[^)]*)?\)' "$src/$page" |
    sed -e 's/^](//' -e 's/[#)].*//' | sort -u | while read -r t; do
      p="$d/$t"
      while :; do  # a/b/../c -> a/c, ./ dropped
        q=$(printf '%s\n' "$p" | sed -e 's|^\./||' -e 's|/\./|/|g' \
          -e 's|[^/.][^/]*/\.\./||')
        [ "$q" = "$p" ] && break
        p=$q
      done
      grep -qxF "$p" "$out/installed" ||
        echo "FAIL: $page links to $t, which make install does not put beside it ($p)"
    done
done | grep FAIL && fails=$((fails + 1))

# the scripts an installed page names in the guide's or the examples'
# directory (docs/X.py, examples/X.py, or a link to one): each is installed
# as a script (dist_*_SCRIPTS: mode 755), starts with #! and is executable,
# unless the page's paragraph says it is in the source tree (a script that
# rewrites the source's pages or imports its tests/); and no file installed
# as data (mode 644) is a script
grep '\.md$' "$out/installed" | while read -r page; do
  awk -v RS= -v p="$page" '{  # paragraph by paragraph
      t = $0; gsub(/[ \t]*\n[ \t]*/, " ", t)
      src = index(t, "source tree") > 0
      while (match(t, /[A-Za-z0-9_.\/-]*[A-Za-z0-9_-]\.(py|sh)([^A-Za-z0-9_]|$)/)) {
        m = substr(t, RSTART, RLENGTH); t = substr(t, RSTART + RLENGTH)
        sub(/[^A-Za-z0-9_]$/, "", m); print p "|" m "|" src } }' "$src/$page"
done | sort -u | while IFS='|' read -r page m insrc; do
  d=$(dirname "$page") f=
  for c in "$d/$m" "$m"; do  # beside the page, or from the top
    c=$(printf '%s\n' "$c" | sed -e 's|^\./||' -e 's|/\./|/|g')
    [ -f "$src/$c" ] && { f=$c; break; }
  done
  case "$f" in docs/*|examples/*) ;; *) continue ;; esac
  if grep -qxF "$f" "$out/installed.scripts"; then
    head -c 2 "$src/$f" | grep -q '^#!' || echo "FAIL: $f is installed as a script but has no #! line"
    [ -x "$src/$f" ] || echo "FAIL: $f is installed as a script but is not executable"
  elif [ "$insrc" != 1 ]; then
    echo "FAIL: $page names $m: $f is not installed as a script (dist_*_SCRIPTS), nor said to be in the source tree"
  fi
done | sort -u | grep FAIL && fails=$((fails + 1))
while read -r f; do
  head -c 2 "$src/$f" | grep -q '^#!' &&
    echo "FAIL: $f is a script installed as data (mode 644): dist_*_SCRIPTS"
done < "$out/installed.data" | grep FAIL && fails=$((fails + 1))

# --- the ranges of numeric options: --help gives the one the parser
# enforces (from its message for a value below it)
for spec in "validate|--seeds|1" "pbe|--sizes|1" "collide|--threads|0"; do
  cmd=${spec%%|*} r=${spec#*|}; o=${r%%|*} v=${r#*|}
  m=$("$sb" "$cmd" "$o" "$v" 2>&1 >/dev/null)
  lohi=$(printf '%s\n' "$m" | sed -n 's/.* \([0-9][0-9e+]*\)\(\.\.\| to \)\([0-9][0-9e+]*\).*/\1 \3/p')
  [ -n "$lohi" ] || { fail "$cmd $o $v: no range in: $m"; continue; }
  lo=${lohi% *} hi=${lohi#* }
  "$sb" "$cmd" --help | tr -s ' \n' '  ' > "$out/help.txt"
  grep -qF -e "$lo to $hi" -e "$lo <= N <= $hi" "$out/help.txt" ||
    fail "$cmd $o: '$cmd --help' does not give its range $lo to $hi"
done

# --- INI files: the sections and keys of collide, pgd and spray
# valid_list MSG: the names listed in an "unknown ..." message, one a line
valid_list() {
  printf '%s\n' "$1" | sed -e 's/.*(valid: \(.*\))$/\1/' \
    -e 's/.*unknown key.* (\(.*\))$/\1/' -e 's/.*unknown section.* (\(.*\))$/\1/' \
    -e 's/.*; valid: \(.*\)$/\1/' | tr ',' '\n' |
    sed -e 's/^ *//' -e 's/ *$//' -e 's/^\[\(.*\)\]$/\1/' | grep -v '^$'
}
# run CMD INI-TEXT: the message of `smolbridge CMD` on that file
run() {
  printf "$2" > "$out/t.ini"
  "$sb" "$1" "$out/t.ini" 2>&1 >/dev/null
}
for cmd in collide pgd spray; do
  msg=$(run $cmd '[zz_section]\nzz_key = 1\n')
  case "$msg" in *"unknown section [zz_section]"*) ;;
    *) fail "$cmd: no unknown-section message: $msg"; continue ;; esac
  valid_list "$msg" > "$out/$cmd.sections"
  [ -s "$out/$cmd.sections" ] || fail "$cmd: no sections in: $msg"
  man_ss "$cmd" > "$out/ss.txt"
  "$sb" "$cmd" --help > "$out/help.txt" 2>&1
  while read -r s; do
    case "$s" in  # [species NAME], [inflow NAME], [droplets NAME]
      *" NAME") pat="[${s% NAME} " ;;
      *) pat="[$s]" ;;
    esac
    grep -qF "$pat" "$out/ss.txt" ||
      fail "$cmd: section [$s] is not in docs/smolbridge.1 '.SS $cmd'"
    grep -qF "$pat" "$out/help.txt" ||
      fail "$cmd: section [$s] is not in '$cmd --help'"
  done < "$out/$cmd.sections"
done

# the keys of pgd and spray (collide's: tests/cli.sh, from --help, the
# parser's own table); each listed key must be accepted (its message, if
# any, names the key, not an unknown one)
keys_of() {  # keys_of CMD SECTION: the keys, one a line
  k_msg=$(run "$1" "[$2]\nzz_key = 1\n")
  case "$k_msg" in *"unknown key 'zz_key'"*) ;;
    *) fail "$1 [$2]: no unknown-key message: $k_msg"; return ;; esac
  valid_list "$k_msg"
}
for cmd in pgd spray; do
  case $cmd in
    pgd) doc="$src/docs/pgd.md" ;;
    spray) doc="$src/docs/spray.md" ;;
  esac
  "$sb" "$cmd" --help > "$out/help.txt" 2>&1
  man_ss "$cmd" > "$out/ss.txt"
  # the chapter's section on the command: pgd.md §9, spray.md §8
  awk '/^## [0-9]+\. `smolbridge / { on = 1; next } /^## / { on = 0 } on' \
    "$doc" > "$out/doc.txt"
  [ -s "$out/doc.txt" ] || fail "$cmd: no section on the command in $doc"
  while read -r s; do
    sec=${s% NAME}
    [ "$sec" != "$s" ] && sec="$sec x"  # a section with a name
    keys_of "$cmd" "$sec" > "$out/keys"
    [ -s "$out/keys" ] || fail "$cmd [$s]: no keys"
    while read -r k; do
      m=$(run "$cmd" "[$sec]\n$k = @\n")
      case "$m" in *"unknown key '$k'"*)
        fail "$cmd [$s] $k: listed as valid, but refused as unknown" ;; esac
      grep -qw -- "$k" "$out/help.txt" ||
        fail "$cmd [$s] $k is not in '$cmd --help'"
      if [ "$cmd" = pgd ]; then
        # the man page lists the keys of pgd; the table of pgd.md §9
        grep -qw -- "$k" "$out/ss.txt" ||
          fail "pgd [$s] $k is not in docs/smolbridge.1 '.SS pgd'"
        awk -F'|' -v s="[$s]" -v k="$k" '
          $2 ~ /\[/ { cur = $2; gsub(/^ +| +$/, "", cur) }
          cur == s { n = split($3, a, ","); for (i = 1; i <= n; i++) {
            gsub(/^ +| +$/, "", a[i]); if (a[i] == k) found = 1 } }
          END { exit !found }' "$out/doc.txt" ||
          fail "pgd [$s] $k is not in the key table of docs/pgd.md"
      else
        # spray.md §8: `key` in the item of its section
        awk -v s="[$s]" '
          /^- `\[/ { on = index($0, "`" s "`") == 3 } /^$/ { on = 0 } on' \
          "$out/doc.txt" | grep -q "\`$k\`\|\`$k " ||
          fail "spray [$s] $k is not in the item of [$s] in docs/spray.md §8"
      fi
    done < "$out/keys"
  done < "$out/$cmd.sections"
done
# the other way: every key of the table of pgd.md §9 is accepted
awk '/^## [0-9]+\. `smolbridge pgd/ { on = 1; next } /^## / { on = 0 } on' \
  "$src/docs/pgd.md" | awk -F'|' '$2 ~ /\[/ { cur = $2; gsub(/^ +| +$/, "", cur) }
  cur != "" && NF > 4 { n = split($3, a, ","); for (i = 1; i <= n; i++) {
    gsub(/^ +| +$/, "", a[i]); print cur "|" a[i] } }' |
  sed 's/ NAME\]|/ x]|/' | while IFS='|' read -r s k; do
    m=$(run pgd "$s\n$k = @\n")
    case "$m" in *"unknown key"*|*"unknown section"*)
      echo "FAIL: docs/pgd.md: $s $k is not accepted: $m" ;; esac
  done | grep FAIL && fails=$((fails + 1))
# and every key of the tables of engine.md §9 is one of collide --help's
"$sb" collide --help | awk '/^\[/ { s = $1 } /^  [A-Za-z_0-9]+ / { print s, $1 }' |
  sed 's/^\[\([a-z]*\)\]* /\1 /' > "$out/collide.keys"
awk '/^## 9\. `smolbridge collide/ { on = 1; next } /^## / { on = 0 }
  on && /^### \[/ { s = $2; gsub(/[][]/, "", s) }
  on && /^\| `/ { split($0, c, "|"); t = c[2]
    while (match(t, /`[A-Za-z_0-9]+`/)) {
      print s, substr(t, RSTART + 1, RLENGTH - 2); t = substr(t, RSTART + RLENGTH) } }' \
  "$src/docs/engine.md" | while read -r s k; do
    grep -qx "$s $k" "$out/collide.keys" ||
      echo "FAIL: docs/engine.md §9 [$s] $k is not a key of 'collide --help'"
  done | grep FAIL && fails=$((fails + 1))

# --- pbe: every kernel its parser knows is in pbe --help, the man page and
# docs/kernel.md's list of the names; every --param name in pbe --help,
# and accepted
"$sb" pbe --help > "$out/help.txt" 2>&1
man_ss pbe > "$out/ss.txt"
m=$("$sb" pbe -q --kernel zz_kernel --n0 1 --times 1 --out "$out/p.csv" 2>&1)
ks=$(valid_list "$m")
awk '/Types \(their names, as `smolbridge pbe/ { on = 1 } /^$/ { on = 0 } on' \
  "$src/docs/kernel.md" > "$out/kernels.txt"
[ -n "$ks" ] || fail "pbe: no kernel names in: $m"
for k in $ks; do
  grep -qw -- "$k" "$out/help.txt" || fail "pbe --kernel $k is not in 'pbe --help'"
  grep -qw -- "$k" "$out/ss.txt" || fail "pbe --kernel $k is not in docs/smolbridge.1 '.SS pbe'"
  grep -qw -- "$k" "$out/kernels.txt" ||
    fail "pbe --kernel $k is not in the list of names of docs/kernel.md"
done
m=$("$sb" pbe -q --kernel constant --param zz=1 --n0 1 --times 1 --out "$out/p.csv" 2>&1)
ps=$(printf '%s\n' "$m" | sed -n 's/.*; valid: \([^(]*\) (.*/\1/p' | tr -d ',')
[ -n "$ps" ] || fail "pbe: no --param names in: $m"
for p in $ps; do
  grep -qw -- "$p" "$out/help.txt" || fail "pbe --param $p is not in 'pbe --help'"
  m=$("$sb" pbe -q --kernel constant --param "$p=zz" --n0 1 --times 1 --out "$out/p.csv" 2>&1)
  case "$m" in *"unknown parameter"*) fail "pbe --param $p listed, but unknown: $m" ;; esac
done

# --- how many named sections a reader takes, as its chapter says
for spec in "pgd|inflow|side = west|pgd.md|up to N sections" \
            "spray|droplets|count = 1|spray.md|(up to N)" \
            "collide|species|radius = 1e-6|engine.md|(any number, up to N)"; do
  cmd=${spec%%|*} r=${spec#*|}
  sec=${r%%|*} r=${r#*|}
  key=${r%%|*} r=${r#*|}
  doc=${r%%|*} pat=${r#*|}
  ini=$(i=0; while [ $i -lt 40 ]; do printf '[%s s%d]\\n%s\\n' "$sec" $i "$key"
    i=$((i + 1)); done)
  m=$(run "$cmd" "$ini")
  n=$(printf '%s\n' "$m" | sed -n 's/.*more than \([0-9][0-9]*\) .*/\1/p')
  [ -n "$n" ] || { fail "$cmd: no limit on [$sec NAME] sections: $m"; continue; }
  grep -qF "$(printf '%s' "$pat" | sed "s/N/$n/")" "$src/docs/$doc" ||
    fail "$cmd takes up to $n [$sec NAME] sections: docs/$doc does not say '$pat'"
done

# --- docs/langevin.md §6: the functions of its table are in eval --list,
# but those the sentence "All but ... are in `smolbridge eval`" names
"$sb" eval --list | awk 'NR % 2 == 1 { print $1 }' > "$out/eval.fns"
awk '/^## 6\. API/ { on = 1; next } /^## / { on = 0 } on' \
  "$src/docs/langevin.md" > "$out/lapi.txt"
tr '\n' ' ' < "$out/lapi.txt" | sed -n 's/.*All but \(.*\) are in `smolbridge eval`.*/\1/p' |
  grep -o '`[a-z_0-9]*`' | tr -d '`' | sed 's/^sb_langevin//; s/^/langevin/' > "$out/lapi.not"
grep '^| `' "$out/lapi.txt" | sed -n 's/^| `[a-z]* \(sb_[a-z_0-9]*\)(.*/\1/p' |
  sed 's/^sb_//' | while read -r f; do
    grep -qx "$f" "$out/eval.fns" || grep -qx "$f" "$out/lapi.not" ||
      echo "FAIL: docs/langevin.md §6: $f is neither in eval --list nor named as not in it"
  done | grep FAIL && fails=$((fails + 1))

# --- eval: every command quoted in docs/ runs (function and arguments
# accepted, no domain error)
grep -ho 'smolbridge eval [a-z_0-9]*\( [A-Za-z_0-9]*=[^ `]*\)\+' \
  "$src"/docs/*.md "$man" | sort -u | while read -r line; do
    # shellcheck disable=SC2086
    "$sb" ${line#smolbridge } > /dev/null 2>&1 || echo "FAIL: docs: $line"
  done | grep FAIL && fails=$((fails + 1))

rm -rf "$out"
[ "$fails" -eq 0 ] || { echo "$fails failure(s)"; exit 1; }
exit 0
