#!/usr/bin/env bash
# Create .venv (Python >= 3.13) with foilbearing[dev,ross,docs] installed: the one environment of
# `make run`, `make test` and the ROSS export.
#
# ROSS >= 3.0 (ross-rotordynamics, an ordinary extra) needs Python >= 3.13, and so does the
# project. Idempotent: a stamp file records the install; it is redone when pyproject.toml or
# the lock file is newer, and the venv is made afresh when its Python is older than 3.13.
# Python 3.13 or newer is looked for, in order, in: $PYTHON313, $PYTHON, `pyenv prefix 3.13*`,
# ~/.pyenv/versions/3.13*/bin/python3.13, and python3.13 or python3 on PATH.
#
# The versions come from constraints.txt (the ones CI passed); `--lock` resolves them afresh
# from pyproject's ranges in a new venv and rewrites that file (`make lock`).
#
# At the end of an install it compiles the film kernels once (python -m foilbearing.warmup).
#
# Usage: bash scripts/setup_venv.sh [--lock]   (from anywhere; works in the repository root)
set -euo pipefail
cd "$(dirname "$0")/.."

VENV=.venv
STAMP="$VENV/.installed"
LOCK=constraints.txt
relock=0
[ "${1:-}" = "--lock" ] && relock=1

say() { printf 'setup_venv: %s\n' "$*"; }

# The installed version, read from the package metadata: importing ross prints CoolProp noise.
ross_version() {
    "$VENV/bin/python" -c 'from importlib.metadata import version as v; print("ross-rotordynamics", v("ross-rotordynamics"))'
}

is_py313() {
    [ -n "${1:-}" ] && [ -x "$1" ] &&
        "$1" -c 'import sys; sys.exit(0 if sys.version_info >= (3, 13) else 1)' 2>/dev/null
}

find_python() {
    local cand
    for cand in "${PYTHON313:-}" "$(command -v "${PYTHON:-}" 2>/dev/null || true)"; do
        if is_py313 "$cand"; then
            echo "$cand"
            return 0
        fi
    done
    if command -v pyenv >/dev/null 2>&1; then
        for v in $(pyenv versions --bare 2>/dev/null | grep -E '^3\.13(\.[0-9]+)?$' | sort -rV); do
            cand="$(pyenv prefix "$v" 2>/dev/null)/bin/python3.13"
            if is_py313 "$cand"; then
                echo "$cand"
                return 0
            fi
        done
    fi
    for cand in /root/.pyenv/versions/3.13*/bin/python3.13 "${HOME:-/root}"/.pyenv/versions/3.13*/bin/python3.13; do
        if is_py313 "$cand"; then
            echo "$cand"
            return 0
        fi
    done
    for name in python3.13 python3; do
        cand="$(command -v "$name" 2>/dev/null || true)"
        if is_py313 "$cand"; then
            echo "$cand"
            return 0
        fi
    done
    return 1
}

if [ "$relock" = 1 ]; then
    rm -rf "$VENV"
elif [ -f "$STAMP" ] && [ "$STAMP" -nt pyproject.toml ] && [ "$STAMP" -nt "$LOCK" ] && is_py313 "$VENV/bin/python"; then
    say "$VENV is up to date ($(ross_version))"
    exit 0
fi

if ! is_py313 "$VENV/bin/python"; then
    if ! PY="$(find_python)"; then
        say "no Python >= 3.13 found (foilbearing and ROSS >= 3.0 need it)." >&2
        say "looked in \$PYTHON313, \$PYTHON, pyenv, ~/.pyenv/versions/3.13*, python3.13 and python3;" >&2
        say "install one (e.g. 'pyenv install 3.13') or set PYTHON313=/path/to/python3.13." >&2
        exit 1
    fi
    rm -rf "$VENV"
    say "creating $VENV with $PY ($("$PY" --version))"
    "$PY" -m venv "$VENV"
fi

# uv installs the packages: it downloads them in parallel and byte-compiles them on every core
# (about 25 s on 2 cores from an empty cache; pip took 50 s, 33 of them compiling one file at a
# time). The .pyc files are written at install because this machine's Python may run with
# PYTHONDONTWRITEBYTECODE, and every process would otherwise compile what it imports. pip does
# it when uv cannot be installed or fails.
install() {
    if "$VENV/bin/python" -m pip install --quiet "$@" uv &&
        "$VENV/bin/uv" pip install --quiet --python "$VENV/bin/python" --compile-bytecode "$@" -e '.[dev,ross,docs]'; then
        return 0
    fi
    say "uv could not install the packages; installing them with pip (about a minute)" >&2
    "$VENV/bin/python" -m pip install --quiet "$@" -e '.[dev,ross,docs]'
}

say "installing -e '.[dev,ross,docs]' into $VENV (first time: about half a minute)"
"$VENV/bin/python" -m pip install --quiet --upgrade pip
if [ "$relock" = 1 ]; then
    install
    { echo "# The versions CI passed, for $("$VENV/bin/python" -V). Refresh: make lock, then .ci/run."
      "$VENV/bin/python" -m pip freeze --exclude-editable; } > "$LOCK"
    say "wrote $LOCK"
else
    install -c "$LOCK"
fi
# foilbearing's own modules too (an editable install: uv compiles only site-packages).
"$VENV/bin/python" -m compileall -q -j 0 src >/dev/null
touch "$STAMP"
# numba compiles the film kernels on first use and caches them beside the sources: compile them
# now (a static solve, the coefficients, a whirl mode and a few orbit steps on a coarse grid),
# so that the first run does not wait for it. Not fatal: a run compiles what is missing.
say "compiling the film kernels once (about 30 s on 2 cores; foilbearing.warmup)"
"$VENV/bin/python" -m foilbearing.warmup || say "warning: the kernels' warm-up failed; the first run compiles them" >&2
say "done: $(ross_version) in $VENV"
