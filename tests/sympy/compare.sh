#!/usr/bin/env bash
# The symbolic stage against SymPy on REFERENCE.md's comparison set, measured in one run.
# SymPy comes from PyPI into a temporary virtual environment; mechbook is the release binary.
#   bash tests/sympy/compare.sh [runs]
set -euo pipefail
cd "$(dirname "$0")/../.."
runs="${1:-3}"
venv="$(mktemp -d)"
trap 'rm -rf "$venv"' EXIT
python3 -m venv "$venv"
"$venv/bin/pip" install --quiet sympy==1.14.0
cargo build --release --quiet
sympy_line="$("$venv/bin/python" tests/sympy/derive_set.py "$runs")"
echo "$sympy_line"
best_engine=""
best_wall=""
for _ in $(seq "$runs"); do
    start=$(date +%s.%N)
    line="$(SYMBOLICA_HIDE_BANNER=1 ./target/release/mechbook check tests/sympy/scenes | tail -1)"
    end=$(date +%s.%N)
    engine_ms="$(sed -E 's/.*symbolic stage ([0-9.]+) ms.*/\1/' <<<"$line")"
    wall_s="$(echo "$end - $start" | bc -l)"
    if [ -z "$best_engine" ] || (( $(echo "$engine_ms < $best_engine" | bc -l) )); then best_engine="$engine_ms"; fi
    if [ -z "$best_wall" ] || (( $(echo "$wall_s < $best_wall" | bc -l) )); then best_wall="$wall_s"; fi
done
sympy_s="$(sed -E 's/.*best ([0-9.]+) s.*/\1/' <<<"$sympy_line")"
printf 'mechbook: symbolic stage best %.1f ms of %s; whole process (start-up, derivation, verification) best %.3f s\n' "$best_engine" "$runs" "$best_wall"
printf 'ratio: SymPy / mechbook symbolic stage = %.1f; SymPy / whole mechbook process = %.1f\n' \
    "$(echo "$sympy_s / ($best_engine / 1000)" | bc -l)" "$(echo "$sympy_s / $best_wall" | bc -l)"
