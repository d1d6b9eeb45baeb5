# cli_common.sh — helpers shared by the command-line test scripts
# (sourced by tests/spray_cli.sh and tests/pgd_cli.sh).  They use the
# caller's $sb (the smolbridge program), $out (its output directory) and
# fail MESSAGE (which counts a failure).

# warned CMD NAME WANT: `smolbridge CMD $out/w.ini` (the caller wrote the
# file, with output = $out/w) exits 0 with the warning "CMD: warning:
# $out/w.ini:WANT" on standard error, listed as "$out/w.ini:WANT..." in
# $out/w/summary.json "warnings" (as collide lists its); WANT "": with no
# warning at all, and "warnings": [].  NAME names the check.
warned() {
  w_cmd=$1 w_name=$2 w_want=$3
  rm -rf "$out/w"
  w_msg=$("$sb" "$w_cmd" "$out/w.ini" 2>&1 >/dev/null)
  w_rc=$?
  [ $w_rc -eq 0 ] || fail "$w_name: exit $w_rc, want 0: $w_msg"
  if [ -n "$w_want" ]; then
    case "$w_msg" in *"$w_cmd: warning: $out/w.ini:$w_want"*) ;;
      *) fail "$w_name: no warning '$w_want' in: $w_msg" ;; esac
    grep -qF "\"$out/w.ini:$w_want" "$out/w/summary.json" ||
      fail "$w_name: no warning '$w_want' in $out/w/summary.json"
  else
    case "$w_msg" in
      *warning*) fail "$w_name: unexpected warning: $w_msg" ;; esac
    grep -qF '"warnings": []' "$out/w/summary.json" ||
      fail "$w_name: warnings in $out/w/summary.json"
  fi
}
