#!/usr/bin/env bash
# The main job, on the built-in default input: two handscenesrc eyes of a synthetic scene ->
# handtracker (tracking overlay, attended view) -> H.264 -> out/demo.mp4, with one JSON line
# per frame in out/demo.jsonl, then a summary. Installs what is missing and builds first.
# Environment: FRAMES (default 300), SCENE (clean|light|heavy|face_pass, default light),
# MOTION (default mixed), SEED (default 1), PARTICLES (default 1000).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
. tests/deps.sh
gesturecam_install_deps
gesturecam_setup build -Dbuildtype=release
meson compile -C build -j "$(nproc)"

frames=${FRAMES:-300}
scene=${SCENE:-light}
motion=${MOTION:-mixed}
seed=${SEED:-1}
particles=${PARTICLES:-1000}
export GST_PLUGIN_PATH="$root/build/gst-plugin${GST_PLUGIN_PATH:+:$GST_PLUGIN_PATH}"
mkdir -p out
rm -f out/demo.mp4 out/demo.jsonl

caps="video/x-raw,width=640,height=480,framerate=30/1"
eye() { echo "handscenesrc eye=$1 scene=$scene motion=$motion seed=$seed num-buffers=$frames ! $caps"; }

echo "Rendering $frames stereo frames of the '$scene' scene, tracking with $particles particles per eye..."
start=$(date +%s.%N)
# shellcheck disable=SC2046
gst-launch-1.0 -q -e \
  $(eye left) ! t.sink_left \
  $(eye right) ! t.sink_right \
  handtracker name=t particles="$particles" draw=true output=attended json-location=out/demo.jsonl \
  ! videoconvert ! x264enc tune=zerolatency speed-preset=veryfast ! mp4mux ! filesink location=out/demo.mp4
end=$(date +%s.%N)

python3 - "$start" "$end" <<'PY'
import json, sys
start, end = float(sys.argv[1]), float(sys.argv[2])
rows = [json.loads(line) for line in open("out/demo.jsonl")]
n = len(rows)
tracked = sum(r["state"] == "tracking" for r in rows)
first = next((r["frame"] for r in rows if r["state"] == "tracking"), None)
pointing = [r["pointing"] for r in rows if r.get("pointing")]
print(f"frames: {n}")
print(f"tracked: {tracked} ({100.0 * tracked / max(n, 1):.1f} %), first at frame {first}")
print(f"3D pointing ray in {len(pointing)} frames")
print(f"throughput: {n / (end - start):.1f} stereo frames/s (render + track + draw + encode)")
print("video: out/demo.mp4   JSON lines: out/demo.jsonl")
PY
