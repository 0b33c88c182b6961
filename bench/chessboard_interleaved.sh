#!/bin/bash
# Detection time of robocal and OpenCV on the same chessboard PNGs, run
# after each other N times, so each ratio is taken at one machine load
# (issue 14's time per image; BENCHMARKS.md "Detection").
# Usage: bench/chessboard_interleaved.sh DIR [KIND] [N]
# DIR: the output of `chessboard_bench --views 20 --out DIR`.
set -euo pipefail
DIR=$1; K=${2:-uneven}; N=${3:-5}
B=${CARGO_TARGET_DIR:-target}/release/examples/chessboard_bench
PY=${PYTHON:-python3}
HERE=$(dirname "$0")
for i in $(seq 1 "$N"); do
  r=$("$B" --views 20 --from "$DIR" --kind "$K" | grep boards | sed -E 's/.* ([0-9.]+) ms.*/\1/')
  o=$("$PY" "$HERE/chessboard_opencv.py" "$DIR" "$K" | grep boards | sed -E 's/.* ([0-9.]+) ms.*/\1/' | tr '\n' ' ')
  echo "run $i: robocal $r ms; OpenCV (cornerSubPix 5x5, 11x11) $o ms"
done
