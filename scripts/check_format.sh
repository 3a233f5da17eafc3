#!/usr/bin/env bash
# Fails when a tracked C++ file differs from what .clang-format makes of it (clang-format 14, as
# Debian bookworm ships it; scripts/setup.sh installs it). To fix: bash scripts/check_format.sh --fix
set -euo pipefail
cd "$(dirname "$0")/.."
if ! git rev-parse --is-inside-work-tree >/dev/null 2>&1; then
    echo "check_format: not a git checkout; skipped" >&2
    exit 0
fi
mapfile -t files < <(git ls-files '*.cpp' '*.h')
if [ "${1:-}" = "--fix" ]; then
    clang-format-14 -i "${files[@]}"
    exit 0
fi
if ! clang-format-14 --dry-run --Werror "${files[@]}" 2>/tmp/pc_format.$$; then
    grep -m 20 'error:' /tmp/pc_format.$$ >&2 || true
    rm -f /tmp/pc_format.$$
    echo "check_format: files differ from .clang-format; run: bash scripts/check_format.sh --fix" >&2
    exit 1
fi
rm -f /tmp/pc_format.$$
