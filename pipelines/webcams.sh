#!/usr/bin/env bash
# Two V4L2 webcams (left and right eye of the stereo head) -> handtracker -> a window.
# Usage: pipelines/webcams.sh [LEFT_DEVICE] [RIGHT_DEVICE] [CALIBRATION_FILE]
# Both cameras must deliver the same size; YUY2 and NV12 are taken as they come (no
# videoconvert before the tracker). A calibration file (gesturecam-calibrate) makes the 3D
# pointing ray metric; without one the nominal rig is assumed.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
export GST_PLUGIN_PATH="$root/build/gst-plugin${GST_PLUGIN_PATH:+:$GST_PLUGIN_PATH}"
left=${1:-/dev/video0}
right=${2:-/dev/video2}
calibration=${3:-}
caps="video/x-raw,width=640,height=480,framerate=30/1"
exec gst-launch-1.0 -e \
  v4l2src device="$left" ! "$caps" ! queue ! t.sink_left \
  v4l2src device="$right" ! "$caps" ! queue ! t.sink_right \
  handtracker name=t draw=true output=attended message-updates=on-change \
    ${calibration:+calibration="$calibration"} latency=33333333 \
  ! videoconvert ! autovideosink sync=false
