#!/usr/bin/env bash
# A USB stereo camera that delivers both eyes in one side-by-side frame (e.g. 1280x480 for
# two 640x480 views) -> handtracker's single `sink` pad -> a window.
# Usage: pipelines/side-by-side.sh [DEVICE] [CALIBRATION_FILE]
# input-mode-override says how the frame holds both views; the calibration is for one 640x480 view.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
export GST_PLUGIN_PATH="$root/build/gst-plugin${GST_PLUGIN_PATH:+:$GST_PLUGIN_PATH}"
device=${1:-/dev/video0}
calibration=${2:-}
exec gst-launch-1.0 -e \
  v4l2src device="$device" ! video/x-raw,width=1280,height=480 \
  ! queue ! t.sink \
  handtracker name=t input-mode-override=side-by-side draw=true output=left ${calibration:+calibration="$calibration"} \
  ! videoconvert ! autovideosink sync=false
