#!/usr/bin/env bash
# Installs gusuku's build and run dependencies from Debian 12's packages (run as root). Skips apt entirely when
# everything is already installed, so repeated runs are fast and need no network.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools
  libglm-dev libtinygltf-dev nlohmann-json3-dev
  libopenimageio-dev openimageio-tools libopencolorio-dev libgeographiclib-dev libmeshoptimizer-dev
  libastcenc-dev  # the baker encodes the pack's ASTC 4x4 HDR lightmaps with Arm's astcenc
  libgtest-dev
  universal-ctags  # the function-length check lists the sources' functions with it
  libglfw3-dev  # gusuku-view's window and Vulkan surface (bench/view)
  xvfb  # xvfb-run: the viewer's test opens its window on a virtual X server
  webp  # img2webp: the README's animation (scripts/render-composites.sh assembles gusuku-view's frames)
)

# --fuzz: also clang-14 and its compiler runtime (libFuzzer, sanitizers), for scripts/fuzz.sh only.
if [ "${1:-}" = "--fuzz" ]; then packages+=(clang-14 libclang-rt-14-dev); fi
# --cross: also Debian's AArch64 cross compilers and the arm64 Vulkan loader (multiarch: the arm64 architecture is
# added to dpkg first), for scripts/cross-build-aarch64.sh only.
cross=false
if [ "${1:-}" = "--cross" ]; then
  cross=true
  packages+=(gcc-aarch64-linux-gnu g++-aarch64-linux-gnu libvulkan-dev:arm64 file)
fi

# The web recipes' tests (tests/web_recipes: docs/export.md's three.js and Babylon.js recipes in headless Chromium)
# want Debian's chromium, node and npm, and the pinned npm packages in build/web-recipes. Best effort: a machine
# without them still builds, and those tests skip saying what is missing.
install_web_recipes() {
  # By command: a node from elsewhere brings its own npm, which Debian's npm package would conflict with.
  local web_missing=()
  command -v chromium > /dev/null || web_missing+=(chromium)
  command -v node > /dev/null || web_missing+=(nodejs)
  command -v npm > /dev/null || web_missing+=(npm)
  if [ "${#web_missing[@]}" -gt 0 ]; then
    if [ "$(id -u)" -ne 0 ]; then
      echo "install-deps: web recipes: missing ${web_missing[*]} (not root; their tests will skip)" >&2
    elif ! (export DEBIAN_FRONTEND=noninteractive; apt-get update -qq &&
            apt-get install -y -qq --no-install-recommends "${web_missing[@]}"); then
      echo "install-deps: web recipes: could not install ${web_missing[*]}; their tests will skip" >&2
    fi
  fi
  local folder=build/web-recipes
  if command -v npm > /dev/null && ! cmp -s tests/web_recipes/package-lock.json "$folder/package-lock.json"; then
    mkdir -p "$folder"
    cp tests/web_recipes/package.json tests/web_recipes/package-lock.json "$folder/"
    if ! (cd "$folder" && npm ci --no-audit --no-fund --ignore-scripts --loglevel=error > /dev/null); then
      rm -f "$folder/package-lock.json"  # so that the next run tries again
      echo "install-deps: web recipes: npm ci failed in $folder; their tests will skip" >&2
    fi
  fi
}
(cd "$(dirname "$0")/.." && install_web_recipes) || true

# SwiftShader, the runtime's second Vulkan driver in the tests (tests/drivers/Drivers.cmake): Debian's chromium
# package ships it (/usr/lib/chromium/libvk_swiftshader.so and its ICD manifest), so it is installed for that too,
# whether or not a chromium command exists. Best effort: without it the swiftshader_* tests skip saying so.
install_swiftshader() {
  local icd=/usr/lib/chromium/vk_swiftshader_icd.json
  [ -f "$icd" ] && return 0
  if [ "$(id -u)" -ne 0 ]; then
    echo "install-deps: SwiftShader: $icd is missing (not root; the swiftshader_* tests will skip)" >&2
  elif ! (export DEBIAN_FRONTEND=noninteractive; apt-get update -qq &&
          apt-get install -y -qq --no-install-recommends chromium) || [ ! -f "$icd" ]; then
    echo "install-deps: SwiftShader: could not install Debian's chromium for $icd; the swiftshader_* tests will skip" >&2
  fi
}
install_swiftshader || true

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if [ "${#missing[@]}" -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages already installed"
  exit 0
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "install-deps: missing packages: ${missing[*]}; run this script as root (or with sudo)" >&2
  exit 1
fi
echo "install-deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
if $cross && ! dpkg --print-foreign-architectures | grep -qx arm64; then dpkg --add-architecture arm64; fi
apt-get update -qq
apt-get install -y -qq --no-install-recommends "${missing[@]}"
