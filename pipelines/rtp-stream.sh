#!/usr/bin/env bash
# Streams the attended view (a smoothed digital pan/zoom around where the hand points) as
# H.264 over RTP/UDP, here from the built-in synthetic scene, to HOST:PORT (default the
# local machine). Receive it with:
#   gst-launch-1.0 udpsrc port=5000 caps="application/x-rtp,media=video,encoding-name=H264,clock-rate=90000" \
#     ! rtph264depay ! avdec_h264 ! videoconvert ! autovideosink
# Usage: pipelines/rtp-stream.sh [HOST] [PORT]
# Environment: FRAMES stops after that many frames (default: until interrupted).
set -euo pipefail
. "$(dirname "$0")/lib/plugin.sh"
gesturecam_use_plugin
host=${1:-127.0.0.1}
port=${2:-5000}
frames=${FRAMES:-}
caps="video/x-raw,width=640,height=480,framerate=30/1"
exec gst-launch-1.0 -e \
  handscenesrc eye=left is-live=true ${frames:+num-buffers=$frames} ! "$caps" ! t.sink_left \
  handscenesrc eye=right is-live=true ${frames:+num-buffers=$frames} ! "$caps" ! t.sink_right \
  handtracker name=t output=attended draw=false \
  ! video/x-raw,width=1280,height=720 ! videoconvert \
  ! x264enc tune=zerolatency speed-preset=veryfast key-int-max=30 ! rtph264pay config-interval=1 \
  ! udpsink host="$host" port="$port"
