#!/bin/sh
# `smolbridge validate --write-ini` for the grid deposit of
# V15/engine-jets (collide's [observe] grid, "; expect-grid" lines): the
# checks of validate_ini.sh on that case, apart to keep each script short.
VALIDATE_INI_SET=grid
export VALIDATE_INI_SET
exec sh "${srcdir:-.}/tests/validate_ini.sh"
