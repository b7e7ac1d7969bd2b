#!/usr/bin/env bash
# Install Debian's `chromium` package, for the headless-browser check in tests/test_report.py.
#
# Idempotent: does nothing when /usr/bin/chromium (or `chromium` on PATH) is already there.
# Otherwise runs `apt-get update` and `apt-get install -y --no-install-recommends chromium`
# (needs root, or sudo without a password; only Debian's own archive is used).
# Exits non-zero with a message when the install fails.
#
# Usage: bash scripts/setup_chromium.sh
set -euo pipefail

say() { printf 'setup_chromium: %s\n' "$*"; }
die() {
    printf 'setup_chromium: ERROR: %s\n' "$*" >&2
    exit 1
}

find_chromium() {
    if [ -x /usr/bin/chromium ]; then
        echo /usr/bin/chromium
    elif command -v chromium >/dev/null 2>&1; then
        command -v chromium
    else
        return 1
    fi
}

if exe="$(find_chromium)"; then
    say "already installed: $exe ($("$exe" --version 2>/dev/null || echo 'version unknown'))"
    exit 0
fi

command -v apt-get >/dev/null 2>&1 ||
    die "chromium is missing and apt-get is not available (not a Debian-based system?); install chromium by hand"

SUDO=()
if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
        SUDO=(sudo -n)
    else
        die "chromium is missing and installing it needs root (run as root, or with passwordless sudo)"
    fi
fi

export DEBIAN_FRONTEND=noninteractive
say "chromium not found; running: apt-get update"
"${SUDO[@]}" apt-get update ||
    die "apt-get update failed (is the Debian archive reachable?)"
say "running: apt-get install -y --no-install-recommends chromium"
"${SUDO[@]}" apt-get install -y --no-install-recommends chromium ||
    die "apt-get install chromium failed"

exe="$(find_chromium)" || die "apt-get reported success but no chromium executable was found"
"$exe" --version >/dev/null 2>&1 || die "$exe was installed but does not run ('$exe --version' failed)"
say "installed: $exe ($("$exe" --version 2>/dev/null))"
