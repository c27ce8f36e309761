#!/usr/bin/env bash
# A USB stereo camera that delivers both eyes in one side-by-side frame (e.g. 1280x480 for
# two 640x480 views) -> handtracker's single `sink` pad -> a window.
# Usage: pipelines/side-by-side.sh [DEVICE] [CALIBRATION_FILE]
# input-mode-override says how the frame holds both views; the calibration is for one 640x480 view.
# Environment: SOURCE=scene puts the two eyes of handscenesrc side by side in the camera's
# place (no camera needed), FRAMES stops after that many frames, SINK replaces the window.
set -euo pipefail
. "$(dirname "$0")/lib/plugin.sh"
gesturecam_use_plugin
device=${1:-/dev/video0}
calibration=${2:-}
frames=${FRAMES:-}
case ${SOURCE:-camera} in
  camera) camera="v4l2src device=$device ${frames:+num-buffers=$frames}" ;;
  scene)
    eye="is-live=true truth-messages=false ${frames:+num-buffers=$frames} ! video/x-raw,width=640,height=480"
    camera="handscenesrc eye=left $eye ! pair.sink_0 handscenesrc eye=right $eye ! pair.sink_1
            compositor name=pair sink_1::xpos=640" ;;
  *) echo "side-by-side.sh: SOURCE is camera or scene, not '$SOURCE'" >&2; exit 2 ;;
esac
# shellcheck disable=SC2086
exec gst-launch-1.0 -e \
  $camera ! video/x-raw,width=1280,height=480 \
  ! queue ! t.sink \
  handtracker name=t input-mode-override=side-by-side draw=true output=left ${calibration:+calibration="$calibration"} \
  ! videoconvert ! "${SINK:-autovideosink}" sync=false
