#!/usr/bin/env bash
# Installs the Debian 12 packages the project needs. Idempotent: does nothing
# when every package is already installed, so it is cheap to call first in
# every entry-point script.
set -euo pipefail

# rtfarm (farm/, README "Render farm (Ray)") in build/farm-venv, with Debian's
# python3 (every node of a Ray cluster needs the same Python and Ray); made
# again only when farm/pyproject.toml or farm/constraints.txt change. It runs
# last (an EXIT trap), once the packages below are in, however the script
# ends well.
farm_venv() {
  local root venv wanted
  root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  venv="$root/build/farm-venv"
  wanted=$(cat "$root/farm/pyproject.toml" "$root/farm/constraints.txt" | sha256sum | cut -d' ' -f1)
  if [[ -x "$venv/bin/rtfarm" && "$(cat "$venv/.rtfarm-installed" 2>/dev/null)" == "$wanted" ]]; then
    return 0
  fi
  echo "setup: installing rtfarm and Ray into $venv" >&2
  /usr/bin/python3 -m venv "$venv"
  "$venv/bin/pip" install -q --disable-pip-version-check --no-input \
    -c "$root/farm/constraints.txt" -e "$root/farm[test]"
  echo "$wanted" >"$venv/.rtfarm-installed"
}
trap 'if (($? == 0)); then farm_venv; fi' EXIT

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
  python3-venv  # rtfarm's virtual environment (farm_venv above)
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
