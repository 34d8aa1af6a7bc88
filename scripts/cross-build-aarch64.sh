#!/usr/bin/env bash
# Cross-compiles the runtime-only configuration (-DGUSUKU_RUNTIME_ONLY=ON: what a phone app links) for AArch64 Linux
# with Debian's cross toolchain, through cmake/toolchains/aarch64-linux-gnu.cmake (the Android NDK's route), and
# checks what it made (docs/platforms.md):
#   1. configures and builds gusuku_formats, gusuku_maths, gusuku_gpu, gusuku_runtime, gusuku_pack_loader and gusuku_weather in
#      build-aarch64/;
#   2. installs them into a prefix and builds tests/consumer against the installed package (the C99 and C++17
#      programs, every runtime header alone as C++17 and C++20), with tests/consumer/install_and_consume.cmake;
#   3. checks with file and readelf that the libraries' objects and the programs are AArch64 ELF, and that the
#      programs need only libvulkan and the C/C++ runtime libraries (NEEDED entries).
#   4. runs them under qemu-user on arm64 lavapipe with scripts/aarch64-qemu-tests.sh: the msaa 4 reproducer, the
#      consumers and a subset of the runtime's GoogleTests (goldens, camera formats, frames in flight), matched with
#      the x86_64 results within one code; it installs the emulator and arm64 driver itself, and skips with a
#      message (the steps above still checked) on a machine that cannot install them.
#   bash scripts/cross-build-aarch64.sh        (root, or the packages of install-deps.sh --cross already there)
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh --cross

build="${GUSUKU_CROSS_BUILD:-build-aarch64}"
toolchain="$PWD/cmake/toolchains/aarch64-linux-gnu.cmake"
launchers=()
if command -v ccache >/dev/null; then
  launchers=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
mkdir -p "$build"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_TOOLCHAIN_FILE="$toolchain" \
  -DGUSUKU_RUNTIME_ONLY=ON "${launchers[@]}" >"$build/configure.log" 2>&1 ||
  { cat "$build/configure.log"; exit 1; }
# A runtime-only configure finds no I/O-stack package: the cache names none of them.
if grep -Eiq '^(OpenImageIO|OpenColorIO|TinyGLTF|nlohmann_json|GeographicLib|meshoptimizer|GTest)_DIR:' \
  "$build/CMakeCache.txt"; then
  echo "cross-build-aarch64: the runtime-only configure found an I/O-stack package" >&2
  exit 1
fi
cmake --build "$build" -j"${GUSUKU_CROSS_JOBS:-2}"

work="$PWD/$build/consume"
cmake -DBUILD_DIR="$PWD/$build" -DCONSUMER_SOURCE_DIR="$PWD/tests/consumer" -DWORK_DIR="$work" -DGENERATOR=Ninja \
  -DTOOLCHAIN_FILE="$toolchain" -DWITH_LOADER=OFF -DRUN_CONSUMERS=OFF \
  -P tests/consumer/install_and_consume.cmake >"$build/consume.log" 2>&1 || { cat "$build/consume.log"; exit 1; }

failures=0
fail() {
  echo "cross-build-aarch64: $1" >&2
  failures=$((failures + 1))
}

# The static libraries: every object inside is AArch64 ELF (readelf -h reads each member of an archive).
for library in libgusuku_formats.a libgusuku_maths.a libgusuku_gpu.a libgusuku_runtime.a libgusuku_pack_loader.a libgusuku_weather.a \
  libgusuku_json.a libgusuku_c_common.a; do
  archive="$work/prefix/lib/$library"
  [ -f "$archive" ] || { fail "$library is missing from the installed prefix"; continue; }
  file "$archive" | grep -q "ar archive" || fail "$library: not an ar archive: $(file -b "$archive")"
  machines=$(readelf -h "$archive" | sed -n 's/^ *Machine: *//p' | sort | uniq -c)
  objects=$(readelf -h "$archive" | grep -c '^ *Machine:')
  if [ "$objects" -eq 0 ] || [ "$(echo "$machines" | wc -l)" -ne 1 ] || ! grep -q AArch64 <<<"$machines"; then
    fail "$library: object machines: $machines"
  fi
  echo "$library: $objects objects, all $(echo "$machines" | awk '{print $2}')"
done

# The C API's last error is one thread-local per process: gusuku_last_error_message is defined in exactly one of
# the installed archives (gusuku_c_common's), so an app that links several of them gets one message, not two.
definitions=$(for archive in "$work"/prefix/lib/libgusuku_*.a; do
  readelf -Ws "$archive" | awk -v name="$(basename "$archive")" \
    '$8 == "gusuku_last_error_message" && $7 != "UND" { print name }'
done)
[ "$(grep -c . <<<"$definitions")" -eq 1 ] && [ "$definitions" = libgusuku_c_common.a ] ||
  fail "gusuku_last_error_message must be defined once, in libgusuku_c_common.a; defined in: $definitions"
echo "gusuku_last_error_message: defined once, in $definitions"

# The programs: AArch64 ELF executables that need libvulkan and the C/C++ runtime only. Those that draw a frame
# need libvulkan; the pack and weather readers call no Vulkan function, so the linker (--as-needed) may drop it.
allowed_needed='^(libvulkan\.so\.1|libstdc\+\+\.so\.6|libm\.so\.6|libgcc_s\.so\.1|libc\.so\.6|ld-linux-aarch64\.so\.1)$'
drawing_programs=" consumer_runtime consumer_runtime_cxx17 "
for program in consumer_runtime consumer_runtime_cxx17 consumer_pack consumer_weather; do
  binary="$work/build/$program"
  [ -f "$binary" ] || { fail "$program was not built"; continue; }
  description=$(file -b "$binary")
  grep -q "ELF 64-bit LSB .*ARM aarch64" <<<"$description" || fail "$program: $description"
  readelf -h "$binary" | grep -Eq '^ *Machine: *AArch64$' || fail "$program: readelf -h does not say AArch64"
  needed=$(readelf -d "$binary" | sed -n 's/.*(NEEDED).*\[\(.*\)\]/\1/p')
  if [[ "$drawing_programs" == *" $program "* ]]; then
    grep -q '^libvulkan\.so\.1$' <<<"$needed" || fail "$program does not need libvulkan.so.1"
  fi
  unexpected=$(grep -Ev "$allowed_needed" <<<"$needed" || true)
  [ -z "$unexpected" ] || fail "$program needs more than libvulkan and the C/C++ runtime: $unexpected"
  echo "$program: ${description%%,*}, $(readelf -h "$binary" | sed -n 's/^ *Machine: *//p'), NEEDED:" $needed
done

if [ "$failures" -ne 0 ]; then
  echo "cross-build-aarch64: $failures check(s) failed" >&2
  exit 1
fi
echo "cross-build-aarch64: the runtime-only build and its consumers are AArch64 and need only libvulkan and libc/libstdc++"

bash scripts/aarch64-qemu-tests.sh "$build"
