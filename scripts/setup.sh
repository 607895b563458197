#!/usr/bin/env bash
# Installs the Debian 12 packages the project needs, and Mesa 25's lavapipe
# from bookworm-backports. Idempotent: does nothing when everything is
# already installed, so it is cheap to call first in every entry-point script.
#   setup.sh [--farm]   (--farm: also rtfarm's virtual environment, see below)
set -euo pipefail
with_farm=false
[[ ${1:-} == --farm ]] && with_farm=true


PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers vulkan-tools
  glslang-dev glslang-tools spirv-tools
  libglfw3-dev libglm-dev libtinygltf-dev libstb-dev nlohmann-json3-dev
  libcli11-dev doctest-dev libtinyexr-dev libfmt-dev libimgui-dev
  libtinyobjloader-dev libdraco-dev
  xvfb xauth
  # clang with its sanitizer and libFuzzer runtimes (scripts/build-sanitized.sh)
  clang-14 libclang-rt-14-dev
  clang-format
  python3-venv  # rtfarm's virtual environment (farm_venv above)
)

SUDO=""
if [[ $(id -u) -ne 0 ]]; then
  SUDO="sudo"
fi
export DEBIAN_FRONTEND=noninteractive
updated=false
apt_update() {
  if ! $updated; then
    $SUDO apt-get update -qq
    updated=true
  fi
}

missing=()
for pkg in "${PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$pkg")
done
if ((${#missing[@]} > 0)); then
  echo "setup: installing ${missing[*]}" >&2
  apt_update
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# Mesa 25's lavapipe from Debian 12's bookworm-backports suite: 2.4-4.3x the
# speed of Debian 12's Mesa 22.3 on this renderer's scenes, and ray queries
# (../shared/notes/lavapipe.md). RT_SYSTEM_MESA=1 keeps the system's driver.
BACKPORTS_SOURCES=/etc/apt/sources.list.d/bookworm-backports.sources
mesa_version=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
codename=$(. /etc/os-release && echo "${VERSION_CODENAME:-}")
if [[ -z "${RT_SYSTEM_MESA:-}" && "$codename" == bookworm ]] &&
  ! dpkg --compare-versions "$mesa_version" ge 25; then
  echo "setup: installing Mesa 25 (lavapipe) from bookworm-backports; RT_SYSTEM_MESA=1 keeps Mesa $mesa_version" >&2
  if ! grep -qs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/*; then
    printf '%s\n' "Types: deb" "URIs: http://deb.debian.org/debian" "Suites: bookworm-backports" \
      "Components: main" "Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg" |
      $SUDO tee "$BACKPORTS_SOURCES" >/dev/null
    updated=false
  fi
  apt_update
  $SUDO apt-get install -y -qq --no-install-recommends -t bookworm-backports mesa-vulkan-drivers
fi

# With --farm: rtfarm (farm/, README "Render farm (Ray)") in build/farm-venv,
# with Debian's python3 (every node of a Ray cluster needs the same Python
# and Ray); made again only when farm/pyproject.toml or farm/constraints.txt
# change. The test command asks for it; the render command does not need Ray.
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

if $with_farm; then farm_venv; fi
