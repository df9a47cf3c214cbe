#!/usr/bin/env bash
# Installs every Debian 12 package the project needs. Idempotent and non-interactive:
# packages already present are skipped, so a second run costs one dpkg query.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev liborocos-kdl-dev liburdfdom-dev liburdfdom-headers-dev
  libgtest-dev libgmock-dev libbenchmark-dev libfuzzylite-dev
  libpagmo-dev libtbb-dev libtomlplusplus-dev libcli11-dev libsdpa-dev
  libopenmpi-dev openmpi-bin
  clang clang-format clang-tidy cppcheck libclang-rt-14-dev
  gcc-arm-none-eabi libstdc++-arm-none-eabi-newlib libnewlib-arm-none-eabi qemu-system-arm
  python3-matplotlib python3-numpy python3-venv
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi

echo "install-deps: installing ${missing[*]}"
sudo_cmd=()
if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
