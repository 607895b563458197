#!/usr/bin/env bash
# Installs the Debian 12 packages the project needs, and Mesa 25's lavapipe
# from bookworm-backports. Idempotent: does nothing when everything is
# already installed, so it is cheap to call first in every entry-point script.
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
