#!/usr/bin/env bash
# Counts the Cortex-M4 instructions of S-curve planning and stepping under an emulator (SPEC §16):
# installs what it needs (the thumbv7em-none-eabihf target, a Python venv with
# tools/requirements.txt), builds the probe (probe/) in release, and runs
# tools/count_instructions.py with the arguments given, e.g.
#
#   tools/cortex_m4_budgets.sh                                   # report only
#   tools/cortex_m4_budgets.sh --verify --plan-budget 20000 --step-budget 40
#
# The venv is target/ci-venv (CORTEX_M4_VENV overrides it); it is reinstalled when
# tools/requirements.txt changes. Exit status: count_instructions.py's (1: over a budget,
# 2: the probe panicked, faulted or ran away).
set -euo pipefail
cd "$(dirname "$0")/.."

target=thumbv7em-none-eabihf
if ! grep -qx "$target" <<<"$(rustup target list --installed)"; then
  rustup target add "$target"
fi

venv="${CORTEX_M4_VENV:-target/ci-venv}"
python="$venv/bin/python"
if ! cmp -s tools/requirements.txt "$venv/requirements.txt"; then
  mkdir -p "$(dirname "$venv")"
  pip_install=(-m pip install --quiet --disable-pip-version-check -r tools/requirements.txt)
  if python3 -m venv --clear "$venv" && "$python" "${pip_install[@]}"; then
    cp tools/requirements.txt "$venv/requirements.txt"
  else
    # No venv module (Debian's python3 without python3-venv): the user's site-packages instead.
    echo "no usable venv at $venv; installing into the user's site-packages" >&2
    rm -rf "$venv"
    python3 "${pip_install[@]}" --user
    python=python3
  fi
fi

(cd probe && cargo build --release --quiet)
"$python" tools/count_instructions.py --elf probe/target/$target/release/probe "$@"
