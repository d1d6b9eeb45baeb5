#!/bin/sh
# `smolbridge validate --write-ini` for the MD-type detector of V3
# (detect = md) and the grid deposit of V15/engine-jets (collide's
# [observe] grid and smolbridge pgd, "; expect-grid" lines): the checks of
# validate_ini.sh on those cases, apart to keep each script short.
VALIDATE_INI_SET=more
export VALIDATE_INI_SET
exec sh "${srcdir:-.}/tests/validate_ini.sh"
