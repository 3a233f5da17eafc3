#!/usr/bin/env bash
# Installs the Debian packages the project needs, only those that are missing.
# Idempotent and quick on a second run: dpkg is asked first, apt only when something is absent.
set -euo pipefail

packages=(
    build-essential cmake ninja-build ccache pkg-config clang-format-14
    libpcl-dev libflann-dev libeigen3-dev libqhull-dev
    libboost-program-options-dev libgtest-dev libgmock-dev
    nlohmann-json3-dev libopencv-dev
    parallel
)

source "$(dirname "$0")/lib_packages.sh"
install_missing setup "${packages[@]}"
