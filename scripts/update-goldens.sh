#!/usr/bin/env bash
# Regenerates the runtime's golden images (tests/golden/runtime_*.png) from the current build, then runs the
# golden test against them. Look at the images (and the diff) before committing them.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake --build build --target test_runtime_golden
GUSUKU_VALIDATION=1 GUSUKU_UPDATE_GOLDEN=1 ./build/tests/test_runtime_golden
GUSUKU_VALIDATION=1 ./build/tests/test_runtime_golden
git status --short tests/golden
