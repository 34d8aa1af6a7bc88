#!/usr/bin/env bash
# The runtime on a real GPU (issue 43 item 7): on a machine with any Vulkan device, builds if needed, runs the
# runtime's tests (the executables tests/drivers/Drivers.cmake lists, validation on) on the machine's default device
# (a discrete or integrated GPU before lavapipe; GUSUKU_DEVICE=NAME picks one), then times the runtime's frame at
# 1280 x 720 with gusuku-render (each pass alone and the whole frame, milliseconds), and writes the driver, the tests'
# result and the frame times to one file, which it names. docs/measurements.md, "A real GPU", says how to read it.
#   bash scripts/gpu-check.sh                       (builds build/ when it has no runtime tests yet)
#   GUSUKU_BUILD=DIR bash scripts/gpu-check.sh      (a build folder made already)
#   GUSUKU_BAKESET=DIR                              (the bake set timed; default out/sites/sample/bakeset or
#                                                    out/bakeset, else the sample is baked into the output folder)
#   GUSUKU_GPU_CHECK_OUT=DIR                        (default out/gpu-check; the report is DIR/gpu-check.txt)
# Exit status: 0 when every test passed, 1 otherwise (the report is written either way).
set -uo pipefail
cd "$(dirname "$0")/.."
start_seconds=$SECONDS
build="${GUSUKU_BUILD:-build}"
out="${GUSUKU_GPU_CHECK_OUT:-out/gpu-check}"
mkdir -p "$out"
report="$out/gpu-check.txt"
log="$out/tests.log"

if [[ -z "${GUSUKU_BUILD:-}" && ! -x "$build/tests/test_runtime" ]]; then
  echo "gpu-check: building $build (Release)" >&2
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null || exit 1
  cmake --build "$build" || exit 1
fi
[[ -x "$build/tests/test_runtime" ]] || { echo "gpu-check: $build: has no runtime test executables (build it first)" >&2; exit 1; }

# The runtime's test set: the executables (and GoogleTest filters) Drivers.cmake runs on a second driver.
mapfile -t entries < <(sed -n '/^set(GUSUKU_SWIFTSHADER_TESTS/,/")$/p' tests/drivers/Drivers.cmake |
                       grep -oE '^ *"[^"]+"' | tr -d '"' | sed 's/^ *//')
passed=0; failed=0; failed_names=()
: >"$log"
for entry in "${entries[@]}"; do
  read -r -a words <<<"$entry"
  executable="$build/tests/${words[0]}"
  output=$(GUSUKU_VALIDATION=1 "$executable" "${words[@]:1}" 2>&1); status=$?
  printf '=== %s (exit %d)\n%s\n' "$entry" "$status" "$output" >>"$log"
  # The C programs print validation messages rather than fail on them (as Drivers.cmake's FAIL_REGULAR_EXPRESSION);
  # the GoogleTest ones fail on them themselves, and some print messages they provoke on purpose.
  validation_failed=0
  [[ ${words[0]} =~ ^(test_c_api|readme_example)$ ]] && grep -q "Vulkan validation" <<<"$output" && validation_failed=1
  if [[ $status -eq 0 && $validation_failed -eq 0 ]]; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1)); failed_names+=("${words[0]}")
  fi
done
tests_seconds=$((SECONDS - start_seconds))

bakeset="${GUSUKU_BAKESET:-}"
for candidate in out/sites/sample/bakeset out/bakeset; do
  [[ -z "$bakeset" && -f "$candidate/manifest.json" ]] && bakeset="$candidate"
done
if [[ -z "$bakeset" ]]; then
  echo "gpu-check: no bake set: baking the sample into $out/bakeset" >&2
  "$build/baker/gusuku-bake" sample "$out/sample" --force >/dev/null &&
    "$build/baker/gusuku-bake" bake "$out/sample/site.json" -o "$out/bakeset" --force >/dev/null || exit 1
  bakeset="$out/bakeset"
fi
# A flat grey camera frame (an image, so no path-traced camera is made first), as an 8-bit PNG.
python3 - "$out/grey-1280x720.png" <<'EOF'
import struct, sys, zlib
w, h = 1280, 720
rows = b"".join(b"\0" + bytes([128, 128, 128]) * w for _ in range(h))
chunk = lambda kind, data: struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
open(sys.argv[1], "wb").write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
                              + chunk(b"IDAT", zlib.compress(rows)) + chunk(b"IEND", b""))
EOF
render=$("$build/bench/gusuku-render" "$bakeset" -o "$out/composite.png" --camera "$out/grey-1280x720.png" \
         --frames 20 2>&1); render_status=$?
total_seconds=$((SECONDS - start_seconds))

{
  echo "gpu-check $(date -u +%Y-%m-%dT%H:%M:%SZ), commit $(git rev-parse --short HEAD 2>/dev/null || echo unknown)"
  if command -v vulkaninfo >/dev/null; then
    vulkaninfo --summary 2>/dev/null | grep -E 'deviceName|driverName|driverInfo|apiVersion|deviceType' | sed 's/^ */driver: /'
  fi
  grep -m1 'device ' <<<"$render" | sed 's/^gusuku-render: /driver (gusuku-render): /'
  echo "tests: $passed of ${#entries[@]} runtime test executables passed, validation on (${tests_seconds} s; log $log)"
  [[ $failed -gt 0 ]] && echo "tests failed: ${failed_names[*]}"
  echo "frame times at 1280 x 720, bake set $bakeset (gusuku-render exit $render_status):"
  grep -iE ' ms|ms$' <<<"$render" | sed 's/^/  /'
  echo "total: ${total_seconds} s"
} >"$report"
cat "$report"
echo "gpu-check: wrote $report" >&2
[[ $failed -eq 0 && $render_status -eq 0 ]]
