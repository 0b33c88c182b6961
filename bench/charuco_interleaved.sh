#!/bin/bash
# Detection time of robocal and OpenCV's CharucoDetector on the same ChArUco
# PNGs, run after each other N times, so each ratio is taken at one machine
# load (issue 14's time per image; BENCHMARKS.md "Detection").
# Usage: bench/charuco_interleaved.sh DIR [KIND] [N]
# DIR: the output of `charuco_bench --views 20 --out DIR`.
set -euo pipefail
DIR=$1; K=${2:-fronto}; N=${3:-5}
B=${CARGO_TARGET_DIR:-target}/release/examples/charuco_bench
PY=${PYTHON:-python3}
HERE=$(dirname "$0")
echo "$K, $(uptime)"
for i in $(seq 1 "$N"); do
  r=$("$B" --views 20 --from "$DIR" --kind "$K" | grep "^$K" | sed -E 's/.* ([0-9.]+) ms.*/\1/')
  o=$("$PY" "$HERE/charuco_opencv.py" "$DIR" "$K" | grep "^$K" | sed -E 's/.* ([0-9.]+) ms.*/\1/')
  echo "run $i: robocal $r ms; OpenCV $o ms; ratio $(echo "scale=2; $r / $o" | bc)"
done
