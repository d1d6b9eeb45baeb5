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
# idle OpenMP threads sleep instead of spinning on cores other work needs
# (docs/engine.md §8, "Threads"); the results do not depend on it
export OMP_WAIT_POLICY="${OMP_WAIT_POLICY:-passive}"
./smolbridge validate --quick --out validate-out "$@"
