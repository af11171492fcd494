#!/usr/bin/env bash
# The n-link pendulum (n = 1 to 10) against SymPy's LagrangesMethod + linearize, in one run:
# SymPy 1.14.0 from PyPI into a temporary virtual environment, mechbook the release binary.
#   bash docs/bench/links.sh [repeats]
set -euo pipefail
cd "$(dirname "$0")/../.."
repeats="${1:-3}"
venv="$(mktemp -d)"
trap 'rm -rf "$venv"' EXIT
python3 -m venv "$venv"
"$venv/bin/pip" install --quiet sympy==1.14.0
cargo build --release --quiet
SYMBOLICA_HIDE_BANNER=1 ./target/release/mechbook bench --links-only --python "$venv/bin/python" --repeats "$repeats"
