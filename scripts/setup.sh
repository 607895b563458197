#!/usr/bin/env bash
# Installs the Debian 12 packages the project needs. Idempotent: does nothing
# when every package is already installed, so it is cheap to call first in
# every entry-point script.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-dev glslang-tools spirv-tools
  libglfw3-dev libglm-dev libtinygltf-dev libstb-dev nlohmann-json3-dev
  libcli11-dev doctest-dev libtinyexr-dev libfmt-dev libimgui-dev
  xvfb xauth
  # clang with its sanitizer and libFuzzer runtimes (scripts/build-sanitized.sh)
  clang-14 libclang-rt-14-dev
  clang-format
)

missing=()
for pkg in "${PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$pkg")
done

if ((${#missing[@]} == 0)); then
  exit 0
fi

echo "setup: installing ${missing[*]}" >&2
SUDO=""
if [[ $(id -u) -ne 0 ]]; then
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
