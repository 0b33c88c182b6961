#!/usr/bin/env bash
# Runs the README's command blocks marked `<!-- ci: run -->`, as written and
# in order, in one bash session: against a `robocal serve` started here on a
# free port with a temporary SQLite database, in a temporary directory (the
# README writes relative paths), with `robocal` on PATH (the debug binary
# unless ROBOCAL_BIN is set). Any failing command fails the run; every
# `curl` also fails on an HTTP error status (`--fail-with-body`).
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD

bin=${ROBOCAL_BIN:-$repo/target/debug/robocal}
if [ -z "${ROBOCAL_BIN:-}" ]; then
  cargo build -q --bin robocal
fi
for tool in curl jq zip python3; do
  command -v "$tool" >/dev/null || { echo "readme.sh: $tool is needed" >&2; exit 1; }
done

work=$(mktemp -d)
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
mkdir "$work/bin"
ln -s "$bin" "$work/bin/robocal"
"$bin" serve --bind "127.0.0.1:$port" --database-url "sqlite://$work/robocal.db" \
  >"$work/server.log" 2>&1 &
server=$!
cleanup() {
  kill "$server" 2>/dev/null || true
  wait "$server" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

export ROBOCAL_URL="http://127.0.0.1:$port"
# Blocks that read fixtures of the repository (e.g. calib/tests/data) find it here.
export ROBOCAL_REPO="$repo"
for _ in $(seq 100); do
  curl -sf "$ROBOCAL_URL/healthz" >/dev/null && break
  sleep 0.1
done
curl -sf "$ROBOCAL_URL/healthz" >/dev/null || { cat "$work/server.log" >&2; exit 1; }

{
  echo 'set -euo pipefail'
  echo 'curl() { command curl --fail-with-body "$@"; }'
  python3 "$repo/.ci/readme_blocks.py" "$repo/README.md"
} >"$work/readme-blocks.sh"

start=$(date +%s)
if ! (cd "$work" && PATH="$work/bin:$PATH" bash "$work/readme-blocks.sh" >"$work/out.log" 2>&1); then
  tail -n 60 "$work/out.log" >&2
  echo "--- server log (tail)" >&2
  tail -n 20 "$work/server.log" >&2
  echo "readme.sh: a README command failed" >&2
  exit 1
fi
echo "readme.sh: README blocks ran in $(( $(date +%s) - start )) s"
