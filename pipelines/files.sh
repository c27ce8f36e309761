#!/usr/bin/env bash
# A recorded stereo pair (two image sequences or two video files) -> handtracker -> JSON
# lines and an annotated video. The same frames give the same JSON as gesturecam-track.
# Usage: pipelines/files.sh LEFT_PATTERN RIGHT_PATTERN [OUT_DIR]
#   e.g. pipelines/files.sh 'rec/left/%05d.png' 'rec/right/%05d.png' out/rec
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
export GST_PLUGIN_PATH="$root/build/gst-plugin${GST_PLUGIN_PATH:+:$GST_PLUGIN_PATH}"
left=${1:?left image pattern}
right=${2:?right image pattern}
out=${3:-out/files}
mkdir -p "$out"
# imagesizelimit refuses a picture over 8192 pixels a side from its header, naming its size:
# pngdec would decode it whole before anything downstream could refuse it.
source_of() {
  echo "multifilesrc location=$1 index=0 caps=image/png,framerate=30/1 ! imagesizelimit ! pngdec ! videoconvert"
}
# shellcheck disable=SC2046
gst-launch-1.0 -e \
  $(source_of "$left") ! t.sink_left \
  $(source_of "$right") ! t.sink_right \
  handtracker name=t draw=true output=left json-location="$out/track.jsonl" \
  ! videoconvert ! x264enc tune=zerolatency speed-preset=veryfast ! mp4mux \
  ! filesink location="$out/annotated.mp4"
echo "wrote $out/track.jsonl and $out/annotated.mp4"
