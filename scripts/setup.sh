#!/usr/bin/env bash
# Installs the Debian packages the project needs, only those that are missing.
# Idempotent and quick on a second run: dpkg is asked first, apt only when something is absent.
set -euo pipefail

packages=(
    build-essential cmake ninja-build ccache pkg-config clang-format-14
    libpcl-dev libflann-dev libeigen3-dev libqhull-dev
    libboost-program-options-dev libgtest-dev libgmock-dev
    nlohmann-json3-dev libopencv-dev
)

missing=()
for p in "${packages[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
        missing+=("$p")
    fi
done

if ((${#missing[@]})); then
    echo "setup: installing ${missing[*]}" >&2
    sudo_cmd=()
    if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
    export DEBIAN_FRONTEND=noninteractive
    "${sudo_cmd[@]}" apt-get update -qq
    "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
