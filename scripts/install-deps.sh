#!/usr/bin/env bash
# Installs the Debian 12 packages vplkit builds and tests with, only those missing.
set -euo pipefail

packages=(
  cmake ninja-build g++ pkg-config
  glslang-tools glslang-dev          # shader compiler + its CMake config
  spirv-cross libspirv-cross-c-shared-dev  # reflection (ships the C++ headers and static libs)
  libglm-dev libvulkan-dev
  mesa-vulkan-drivers                # lavapipe: the CPU Vulkan driver used when no GPU is present
  vulkan-validationlayers            # always on in tests
  libtinygltf-dev libstb-dev doctest-dev
  clang-format                       # the C++ style (.clang-format), checked by ctest format/cpp
  libasan8 libubsan1                 # the asan preset's sanitizer runtimes (CI runs the CLI and scene tests under it)
  libopenexr-dev nlohmann-json3-dev  # layered EXR output, --stats JSON
  libcli11-dev                       # the vplkit command line's parser
  libglfw3-dev libimgui-dev          # `vplkit view`: window and panel
  xvfb xauth                         # the viewer's test runs under xvfb-run
  python3-matplotlib                 # the benches' plots (CSV and JSON are written without it)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
