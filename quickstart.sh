#!/usr/bin/env bash
# Quick start on a fresh Debian 12 machine: install the dependencies, build
# smolbridge and run its main job, the validation suite (`smolbridge validate`,
# quick mode).  The report lands in validate-out/.
set -euo pipefail
cd "$(dirname "$0")"
bash .ci/install-deps
[ -x configure ] || autoreconf -fi
[ -f Makefile ] || ./configure --quiet
make -j"$(nproc)" --quiet
./smolbridge validate --quick --out validate-out "$@"
