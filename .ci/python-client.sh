#!/usr/bin/env bash
# The Python client (clients/python) from outside: a fresh venv under /tmp,
# `pip install ./clients/python` with its test tools, then
#   1. the committed generated code matches openapi/openapi.json (the
#      generator, pinned in generate.sh and kept in its own venv,
#      GENERATOR_VENV or /tmp/robocal-pyclient-gen, is run again in a copy);
#   2. pytest: the client against the real server (the tests start it, on
#      a free port with a temporary database; binary from ROBOCAL_BIN, else
#      target/debug/robocal), the README's examples included;
#   3. mypy --strict on the hand-written layer, the tests and the README's
#      examples.
# Any change to the OpenAPI document that the committed client or its
# examples no longer fit fails one of these.
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
t0=$(date +%s)
step() { echo "python-client.sh: $1 ($(( $(date +%s) - t0 )) s)"; }

export ROBOCAL_BIN=${ROBOCAL_BIN:-$repo/target/debug/robocal}
[ -x "$ROBOCAL_BIN" ] || { echo "python-client.sh: no server binary at $ROBOCAL_BIN (set ROBOCAL_BIN)" >&2; exit 1; }

work=$(mktemp -d /tmp/robocal-pyclient.XXXXXX)
trap 'rm -rf "$work"' EXIT
# A copy of the package and the document: pip builds in the source tree
# and generate.sh rewrites it; neither touches the repository.
copy=$work/repo
mkdir -p "$copy/clients" "$copy/openapi"
cp -a clients/python "$copy/clients/python"
cp openapi/openapi.json "$copy/openapi/"
python3 -m venv "$work/venv"
"$work/venv/bin/pip" install -q "$copy/clients/python[test]"
step "installed into a fresh venv"

# 1. Regenerate in the copy and compare: the committed code is what the
#    document generates (else run clients/python/generate.sh and commit).
"$copy/clients/python/generate.sh" >/dev/null
if ! diff -r clients/python/robocal_client/_generated "$copy/clients/python/robocal_client/_generated" \
  -x __pycache__ >"$work/regen.diff"; then
  head -n 40 "$work/regen.diff" >&2
  echo "python-client.sh: robocal_client/_generated is stale: run clients/python/generate.sh and commit" >&2
  exit 1
fi
step "the generated code matches openapi/openapi.json"

# 2. and 3. With clients/python's pyproject.toml (pytest and mypy settings)
#    but run from outside the source tree, so the installed package is the
#    one imported and type-checked.
config=$repo/clients/python/pyproject.toml
tests=$repo/clients/python/tests
"$work/venv/bin/python" "$tests/readme_blocks.py" >"$work/readme_example.py"
cd "$work"
"$work/venv/bin/pytest" -q -p no:cacheprovider -c "$config" --rootdir "$repo/clients/python" "$tests"
step "pytest passed against the real server"
"$work/venv/bin/mypy" --config-file "$config" --strict --no-incremental -p robocal_client
"$work/venv/bin/mypy" --config-file "$config" --strict --no-incremental "$tests" "$work/readme_example.py"
step "mypy --strict passed (layer, tests, README examples)"
