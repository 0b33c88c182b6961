#!/usr/bin/env bash
# Peak memory of the server while it answers 10,000-target requests
# (issue "Deploy the result": a 10,000-target request stays under 100 MB).
#
# Starts `robocal serve` (ROBOCAL_BIN, default target/release/robocal) on a
# temporary SQLite database, calibrates a small simulated campaign, then
# for each of forward (10,000 joint rows), compensate and filter (10,000
# targets) resets the server's peak-RSS counter (/proc/PID/clear_refs) and
# reads VmHWM after the request (each on a freshly started server); prints
# the body sizes, wall time and peak.
# compensate and filter are measured twice: the one JSON document, then
# streamed (`Accept: application/x-ndjson`, one line per target).
#
#   bash bench/stream_rss.sh [targets]
set -euo pipefail
cd "$(dirname "$0")/.."
repo=$PWD
n=${1:-10000}
bin=${ROBOCAL_BIN:-$repo/target/release/robocal}
work=$(mktemp -d)
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
export ROBOCAL_URL="http://127.0.0.1:$port"
server=
stop_server() {
  if [ -n "$server" ]; then
    kill "$server" 2>/dev/null || true
    wait "$server" 2>/dev/null || true
  fi
}
# A fresh server process on the same database: each request's peak is its
# own, not the memory the allocator kept from the calibration job or from
# the request before.
start_server() {
  stop_server
  "$bin" serve --bind "127.0.0.1:$port" --database-url "sqlite://$work/robocal.db" \
    >>"$work/server.log" 2>&1 &
  server=$!
  for _ in $(seq 100); do
    curl -sf "$ROBOCAL_URL/healthz" >/dev/null && return
    sleep 0.1
  done
}
cleanup() {
  stop_server
  rm -rf "$work"
}
trap cleanup EXIT
start_server
cd "$work"
"$bin" simulate --robot irb2400 --cal 16 --val 4 camp >/dev/null
session=$("$bin" upload --serial RSS-1 camp)
"$bin" calibrate --serial RSS-1 --session "$session" --wait >/dev/null
set_url="$ROBOCAL_URL/v1/robots/RSS-1/parameter-sets/latest"

# Request bodies: joints near the campaign's first pose; the targets are
# the camera poses forward gives there (all reachable).
python3 - "$n" <<'EOF'
import json, random, sys
n = int(sys.argv[1])
poses = json.load(open("camp/poses.json"))
seed = poses[0]["joints_deg"]
random.seed(1)
rows = [[q + random.uniform(-5, 5) for q in seed] for _ in range(n)]
json.dump({"joints_deg": rows}, open("forward.json", "w"))
json.dump(seed, open("seed.json", "w"))
EOF
rss_kb() { awk '/VmHWM/ {print $2}' "/proc/$server/status"; }
measure() { # name path body [accept] [curl's --limit-rate]
  local accept=${4:-application/json} rate=${5:-0}
  start_server
  echo 5 > "/proc/$server/clear_refs"
  local before after start end bytes
  before=$(awk '/VmRSS/ {print $2}' "/proc/$server/status")
  start=$(date +%s.%N)
  bytes=$(curl -sf -X POST "$set_url/$2" -H 'content-type: application/json' -H "accept: $accept" --limit-rate "$rate" \
    --data-binary "@$3" -o "$1.out" -w '%{size_download}')
  end=$(date +%s.%N)
  after=$(rss_kb)
  printf '%-17s request %6.1f MB, answer %6.1f MB, %6.2f s; server RSS before %5.1f MB, peak %5.1f MB\n' \
    "$1" "$(echo "$(stat -c %s "$3") / 1048576" | bc -l)" "$(echo "$bytes / 1048576" | bc -l)" \
    "$(echo "$end - $start" | bc -l)" "$(echo "$before / 1024" | bc -l)" "$(echo "$after / 1024" | bc -l)"
}
measure forward forward "forward.json"
python3 - <<'EOF'
import json
answer = json.load(open("forward.out"))
targets = [{"translation_mm": p["camera_in_target"]["translation_mm"],
            "rotation_deg": p["camera_in_target"]["rotation_deg"],
            "matrix": p["camera_in_target"]["matrix"]} for p in answer["poses"]]
seed = json.load(open("seed.json"))
json.dump({"targets": targets, "seed_joints_deg": seed}, open("compensate.json", "w"))
EOF
set_json=$(curl -sf "$set_url")
python3 - "$set_json" <<'EOF'
import json, sys
s = json.loads(sys.argv[1])
body = json.load(open("compensate.json"))
body["tool"] = s["flange_to_camera"]
json.dump(body, open("filter.json", "w"))
EOF
measure compensate compensate "compensate.json"
measure filter filter "filter.json"
measure compensate.ndjson compensate "compensate.json" application/x-ndjson
measure filter.ndjson filter "filter.json" application/x-ndjson
# A slow client (1 MB/s): the solver waits for it; memory does not grow.
measure filter.ndjson.slow filter "filter.json" application/x-ndjson 1M
python3 - <<'EOF'
import json
c = json.load(open("compensate.out"))
f = json.load(open("filter.out"))
print("compensate answered", sum(1 for j in c["joints_deg"] if j), "of", len(c["joints_deg"]), "targets with", len(c["errors"]), "errors; filter", sum(1 for t in f["nominal_targets"] if t), "of", len(f["nominal_targets"]), "with", len(f["errors"]), "errors")
for name, whole in [("compensate", c), ("filter", f)]:
    lines = [json.loads(l) for l in open(name + ".ndjson.out")]
    assert [l["index"] for l in lines] == list(range(len(lines))), name
    answered = sum(1 for l in lines if "error" not in l)
    same = all(l.get("joints_deg") == whole["joints_deg"][l["index"]] for l in lines)
    print(name, "streamed", len(lines), "lines,", answered, "answered; joints equal to the whole answer:", same)
EOF
