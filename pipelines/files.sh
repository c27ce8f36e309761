#!/usr/bin/env bash
# A recorded stereo pair -> handtracker -> JSON lines and an annotated H.264 video.
# Each input is a video file (any container and codec GStreamer decodes) or a printf
# pattern of an image sequence (PNG or JPEG) numbered from 0 or 1.
# Usage: pipelines/files.sh LEFT RIGHT [OUT_DIR] [CALIBRATION]
#   e.g. pipelines/files.sh rec-left.mp4 rec-right.mp4 out/rec
#        pipelines/files.sh 'rec/left/%05d.png' 'rec/right/%05d.png' out/rec rig.yml
# Environment: FRAMES (track the first N pairs only: N JSON lines; default: all), FPS (the
# frame rate of an image sequence, default 30).
set -euo pipefail
. "$(dirname "$0")/lib/plugin.sh"
gesturecam_use_plugin

usage="usage: pipelines/files.sh LEFT RIGHT [OUT_DIR] [CALIBRATION]"
left=${1:?$usage}
right=${2:?$usage}
out=${3:-out/files}
calibration=${4:-}
frames=${FRAMES:-}
fps=${FPS:-30}

fail() { echo "files.sh: $*" >&2; exit 1; }

# The first index of an image sequence: 0 or 1, whichever file exists.
first_index() {
  local pattern=$1 i
  for i in 0 1; do
    # shellcheck disable=SC2059
    [ -f "$(printf "$pattern" "$i")" ] && { echo "$i"; return; }
  done
  return 1
}

# The gst-launch description of one view, decoded to raw video. $1: left|right, $2: input.
source_of() {
  local eye=$1 input=$2 caps start
  if [[ $input == *%* ]]; then
    case ${input,,} in
      *.png) caps=image/png ;;
      *.jpg | *.jpeg) caps=image/jpeg ;;
      *) fail "$eye input '$input': an image sequence must be PNG or JPEG files" ;;
    esac
    # shellcheck disable=SC2059
    start=$(first_index "$input") ||
      fail "$eye input '$input': no image numbered 0 or 1 ($(printf "$input" 0) or $(printf "$input" 1))"
    # imagesizelimit refuses a picture over 8192 pixels a side from its header, naming its
    # size: a decoder would decode it whole before anything downstream could refuse it.
    echo "multifilesrc location=$input index=$start caps=$caps,framerate=$fps/1 ! imagesizelimit ! decodebin name=${eye}_input"
  else
    [ -f "$input" ] || fail "$eye input '$input': no such file"
    echo "filesrc location=$input ! decodebin name=${eye}_input"
  fi
  echo "! videoconvert"
}

left_source=$(source_of left "$left")
right_source=$(source_of right "$right")
[ -z "$calibration" ] || [ -f "$calibration" ] || fail "calibration '$calibration': no such file"
# FRAMES: identity ends the stream on the tracker's Nth output frame, once its JSON line is
# written (that frame is not encoded). A limit before the tracker would not hold: a decoder
# that drains at end of stream pushes later frames through identity.
limit=${frames:+! identity eos-after=$frames}
mkdir -p "$out"
log=$(mktemp)
trap 'rm -f "$log"' EXIT
# shellcheck disable=SC2086
if ! gst-launch-1.0 -e \
  $left_source ! t.sink_left \
  $right_source ! t.sink_right \
  handtracker name=t draw=true output=left message-updates=none json-location="$out/track.jsonl" \
    ${calibration:+calibration="$calibration"} \
  $limit ! videoconvert ! x264enc tune=zerolatency speed-preset=veryfast ! mp4mux \
  ! filesink location="$out/annotated.mp4" >"$log" 2>&1; then
  error=$(grep -m1 -A1 '^ERROR' "$log" || true)
  case $error in
    *left_input*) fail "cannot decode the left input '$left': ${error#*: }" ;;
    *right_input*) fail "cannot decode the right input '$right': ${error#*: }" ;;
    *) cat "$log" >&2; fail "the pipeline failed" ;;
  esac
fi
echo "wrote $out/track.jsonl ($(wc -l <"$out/track.jsonl") frames) and $out/annotated.mp4"
