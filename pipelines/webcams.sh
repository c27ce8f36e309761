#!/usr/bin/env bash
# Two V4L2 webcams (left and right eye of the stereo head) -> handtracker -> a window.
# Usage: pipelines/webcams.sh [LEFT_DEVICE] [RIGHT_DEVICE] [CALIBRATION_FILE]
# Both cameras must deliver the same size; YUY2 and NV12 are taken as they come (no
# videoconvert before the tracker). A calibration file (gesturecam-calibrate) makes the 3D
# pointing ray metric; without one the nominal rig is assumed.
# Environment: SOURCE=scene puts two live handscenesrc eyes in the cameras' place (no camera
# needed), FRAMES stops after that many frames, SINK replaces the window (e.g. fakesink).
set -euo pipefail
. "$(dirname "$0")/lib/plugin.sh"
gesturecam_use_plugin
left=${1:-/dev/video0}
right=${2:-/dev/video2}
calibration=${3:-}
frames=${FRAMES:-}
caps="video/x-raw,width=640,height=480,framerate=30/1"
camera() {
  case ${SOURCE:-camera} in
    camera) echo "v4l2src device=$2" ;;
    scene) echo "handscenesrc eye=$1 is-live=true truth-messages=false" ;;
    *) echo "webcams.sh: SOURCE is camera or scene, not '$SOURCE'" >&2; exit 2 ;;
  esac
}
left_camera=$(camera left "$left")
right_camera=$(camera right "$right")
# shellcheck disable=SC2086
exec gst-launch-1.0 -e \
  $left_camera ${frames:+num-buffers=$frames} ! "$caps" ! queue ! t.sink_left \
  $right_camera ${frames:+num-buffers=$frames} ! "$caps" ! queue ! t.sink_right \
  handtracker name=t draw=true output=attended message-updates=on-change \
    ${calibration:+calibration="$calibration"} latency=33333333 \
  ! videoconvert ! "${SINK:-autovideosink}" sync=false
