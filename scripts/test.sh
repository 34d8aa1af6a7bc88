#!/usr/bin/env bash
# Install, build, and run the whole test suite on real Vulkan (lavapipe) with the Khronos validation layer on.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh
cd build
GUSUKU_VALIDATION=1 ctest --output-on-failure --parallel "$(nproc)" --timeout 900
