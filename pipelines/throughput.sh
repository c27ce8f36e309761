#!/usr/bin/env bash
# Element throughput: handtracker on 640x480 stereo through fakesink sync=false, next to a
# pass-through of the same two recorded streams, measured in the same run (median of RUNS).
# Frames are recorded once from the built-in scene as raw BGR, so neither rendering nor
# decoding is timed. Usage: pipelines/throughput.sh [PARTICLES] [RUNS] [FRAMES]
set -euo pipefail
. "$(dirname "$0")/lib/plugin.sh"
gesturecam_use_plugin
particles=${1:-1000}
runs=${2:-5}
frames=${3:-300}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
for eye in left right; do
  gst-launch-1.0 -q handscenesrc eye=$eye scene=light seed=4 num-buffers="$frames" \
    ! video/x-raw,format=BGR,width=640,height=480,framerate=30/1 ! filesink location="$work/$eye.bgr"
done
src() { echo "filesrc location=$work/$1.bgr ! rawvideoparse format=bgr width=640 height=480 framerate=30/1"; }
fps() {
  local start end
  start=$(date +%s.%N)
  gst-launch-1.0 -q "$@" > /dev/null
  end=$(date +%s.%N)
  python3 -c "print(f'{$frames / ($end - $start):.1f}')"
}
pass=()
track=()
for _ in $(seq "$runs"); do
  # shellcheck disable=SC2046
  pass+=("$(fps $(src left) ! fakesink sync=false $(src right) ! fakesink sync=false)")
  # shellcheck disable=SC2046
  track+=("$(fps $(src left) ! t.sink_left $(src right) ! t.sink_right \
    handtracker name=t particles="$particles" output=left message-updates=none ! fakesink sync=false)")
done
python3 - "$particles" "$(nproc)" "${pass[*]}" "${track[*]}" <<'PY'
import statistics, sys
particles, cores = sys.argv[1], sys.argv[2]
p = [float(x) for x in sys.argv[3].split()]
t = [float(x) for x in sys.argv[4].split()]
print(f"640x480 stereo, {particles} particles per eye, {cores} cores, median of {len(t)} runs")
print(f"pass-through: {statistics.median(p):.0f} frames/s   handtracker: {statistics.median(t):.0f} frames/s"
      f"   (runs: {', '.join(f'{x:.0f}' for x in t)})")
PY
