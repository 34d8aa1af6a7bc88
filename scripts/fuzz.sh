#!/usr/bin/env bash
# Fuzzes the input loaders: builds the libFuzzer targets of tests/fuzz/ (clang-14, -fsanitize=fuzzer,address,
# undefined, only the loaders' sources) into build-fuzz/ and runs each for its share of SECONDS (default 60 in all).
#   bash scripts/fuzz.sh [SECONDS]
# Seeds come from tests/fuzz/corpus/<name>/; what the fuzzer learns goes to build-fuzz/corpus/<name>/ (kept between
# runs). A finding (crash, sanitizer report, exception other than InputError, leak, timeout, out of memory) stops
# the run, leaves the input in build-fuzz/findings/ and exits non-zero.
set -euo pipefail
cd "$(dirname "$0")/.."

total_seconds="${1:-60}"
if ! [[ "$total_seconds" =~ ^[0-9]+$ ]] || [ "$total_seconds" -lt 3 ]; then
  echo "usage: bash scripts/fuzz.sh [SECONDS]   (whole seconds, at least 3; default 60)" >&2
  exit 2
fi

bash scripts/install-deps.sh --fuzz

build="${GUSUKU_FUZZ_BUILD:-build-fuzz}"
launcher=()
if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
cmake -S tests/fuzz -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++-14 \
  "${launcher[@]}" >/dev/null
cmake --build "$build" -j"${GUSUKU_FUZZ_JOBS:-2}"

names=(site_json gltf glb bakeset_manifest bakeset_exr weather_service runtime_pack c_helpers exif ground_control
       ply_mesh obj_mesh)
dictionaries=(site_json gltf gltf bakeset_manifest "" weather_service bakeset_manifest "" exif ground_control
              ply_mesh obj_mesh)
share=$((total_seconds / ${#names[@]}))
mkdir -p "$build/findings"
for i in "${!names[@]}"; do
  name="${names[$i]}"
  mkdir -p "$build/corpus/$name"
  echo "fuzz: fuzz_$name for ${share} s"
  # -timeout: one input taking over 10 s is a finding (a hang); -malloc_limit_mb: so is one allocation over
  # 2.5 GB (a decompression bomb). The process's whole RSS may reach 4 GB: the sanitizer's allocator keeps what
  # hundreds of OpenImageIO opens freed (the EXR target's RSS climbs past 2 GB though no input needs 400 MB).
  dictionary=()
  if [ -n "${dictionaries[$i]}" ]; then dictionary=(-dict="tests/fuzz/${dictionaries[$i]}.dict"); fi
  # A bake set manifest is about 9 KB: room for one whole, and more.
  "$build/fuzz_$name" -max_total_time="$share" -timeout=10 -malloc_limit_mb=2560 -rss_limit_mb=4096 -max_len=16384 \
    "${dictionary[@]}" -artifact_prefix="$build/findings/${name}-" \
    -print_final_stats=1 "$build/corpus/$name" "tests/fuzz/corpus/$name" 2>"$build/fuzz_$name.log" \
    || { tail -60 "$build/fuzz_$name.log" >&2; echo "fuzz: fuzz_$name found a problem; input in $build/findings/" >&2; exit 1; }
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb" "$build/fuzz_$name.log" | sed "s/^/  /"
  echo "  corpus: $(ls "$build/corpus/$name" | wc -l) inputs; no finding"
done
