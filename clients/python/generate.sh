#!/usr/bin/env bash
# Regenerates robocal_client/_generated from openapi/openapi.json with a
# pinned openapi-python-client. This script is the single source of the
# generated models and endpoints: after any change to the OpenAPI document,
# run it and commit the result (the hand-written layer in robocal_client/
# only wraps what is generated here).
#   GENERATOR_VENV  venv holding the generator (created when missing;
#                   default /tmp/robocal-pyclient-gen)
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../.." && pwd)"
generator=openapi-python-client==0.29.1
venv=${GENERATOR_VENV:-/tmp/robocal-pyclient-gen}
if ! "$venv/bin/pip" show -q openapi-python-client 2>/dev/null \
  || [ "$("$venv/bin/pip" show openapi-python-client | sed -n 's/^Version: //p')" != "${generator#*==}" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q "$generator"
fi
out="$here/robocal_client/_generated"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
rm -rf "$out"
"$venv/bin/openapi-python-client" generate --path "$repo/openapi/openapi.json" \
  --config "$here/generator.yaml" --meta none --output-path "$out" >"$log" 2>&1 \
  || { cat "$log" >&2; exit 1; }
if grep -i 'warning' "$log" >&2; then
  echo "generate.sh: the generator skipped or degraded parts of the document" >&2
  exit 1
fi
# Two defects of the generator (0.29.1) on an operation with two body media
# types (the pose upload: JSON or multipart): `Unset` is used without its
# import, and a fixed `boundary=+++` Content-Type overrides the boundary
# httpx writes. Both are patched here, in the generated code only.
for f in $(grep -rl 'Unset = UNSET' "$out" --include='*.py'); do
  grep -q 'import.*\bUnset\b' "$f" || sed -i 's/^from \.\.\.types import Response, UNSET$/from ...types import Response, UNSET, Unset/' "$f"
done
grep -rl 'boundary=+++' "$out" --include='*.py' | xargs -r sed -i '/boundary=+++/d'
echo "generate.sh: $(find "$out" -name '*.py' | wc -l) files in robocal_client/_generated"
