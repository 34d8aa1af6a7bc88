#!/usr/bin/env bash
# run_on_driver.sh ICD_JSON PROGRAM [ARGUMENTS...]: runs PROGRAM with the Vulkan loader restricted to the one driver
# that ICD_JSON describes (VK_ICD_FILENAMES), so that a test executable written for the default driver runs on
# another. Exits 77, ctest's skip code, saying what is missing when ICD_JSON is absent.
set -euo pipefail
icd=$1
shift
if [ ! -f "$icd" ]; then
  echo "SKIP: $icd is absent: this test runs on SwiftShader, which Debian's chromium package provides" \
       "(scripts/install-deps.sh installs it best effort)"
  exit 77
fi
export VK_ICD_FILENAMES="$icd"
# Nothing else may add or pick a driver: the loader's other driver variables, and gusuku's device filter.
unset VK_DRIVER_FILES VK_ADD_DRIVER_FILES GUSUKU_DEVICE
exec "$@"
