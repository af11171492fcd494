#!/usr/bin/env bash
# Serve's save-to-reload, as serve itself logs it, for comparing two binaries run alternately:
# serves a copy of tests/course, saves problems/11-ball-in-bowl.toml with a new title N times
# (each once the last edit's PDFs are ready) and prints serve's "N ms from the change to telling
# the pages to reload", sorted. The figure includes serve's wait for the rest of a save.
# Usage: bash docs/bench/reload-ab.sh path/to/mechbook [N=7]
set -euo pipefail
repo="$(cd "$(dirname "$0")/../.." && pwd)"
bin="$(realpath "$1")"
n="${2:-7}"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
cp -r "$repo/tests/course" "$dir/course"
cd "$dir"
export SYMBOLICA_HIDE_BANNER=1 XDG_CACHE_HOME="$dir/xdg"
"$bin" serve course --out site --cache cache 2>"$dir/log" &
pid=$!
ready() { grep -c "PDFs are ready" "$dir/log" || true; }
until [ "$(ready)" -gt 0 ]; do sleep 0.2; done
for _ in $(seq 1 "$n"); do
    before="$(ready)"
    sed -i 's/^title = "\(.*\)"$/title = "\1 x"/' course/problems/11-ball-in-bowl.toml
    until [ "$(ready)" -gt "$before" ]; do sleep 0.1; done
done
kill -INT "$pid"
wait "$pid" || true
echo "$(basename "$bin"): $(grep -o '[0-9]* ms from the change' "$dir/log" | awk '{print $1}' | sort -n | tr '\n' ' ')"
