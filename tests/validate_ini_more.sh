#!/bin/sh
# `smolbridge validate --write-ini` for the MD-type detector of V3
# (detect = md), the grid deposit of V15/engine-jets (collide's
# [observe] grid and smolbridge pgd, "; expect-grid" lines) and the batch
# means of V15/dense-jets ([observe] batch_steps, "; expect-batches"
# lines), among others: the checks of
# validate_ini.sh on those cases, apart to keep each script short.
VALIDATE_INI_SET=more
export VALIDATE_INI_SET
exec sh "${srcdir:-.}/tests/validate_ini.sh"
