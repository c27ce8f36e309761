#!/usr/bin/env bash
# The main job, on the built-in default input: the whole loop. headsim (the simulated head)
# carries two live handscenesrc cameras; handtracker tracks the hand in both views, steers
# the head to keep the hand in the middle of the view (steer=fixate) and outputs the
# attended view with the tracking overlay -> H.264 -> out/demo.mp4, one JSON line per frame
# in out/demo.jsonl; then the figures of the run. Installs what is missing and builds first.
# OUT names another folder for the three files.
# Environment: FRAMES (default 300, at 30 frames/s in real time), SCENE (clean|light|heavy|
# face-pass|varied, default light), MOTION (static|translate|rotate|scale|yaw|mixed|
# leave-return, default translate), SEED (default 3), PARTICLES (default 1000), STEER
# (off|fixate|point, default fixate). Names are handscenesrc's; face_pass is read as face-pass.
# STEER=point runs the point-and-look loop: the head keeps the hand in view, and once the
# rendered hand has held its pointing for DWELL seconds (default 1) it turns to the point
# TARGET_DISTANCE mm along the ray (default 600: the rendered room's wall is 3 m away), looks
# there for LOOK_TIME seconds (default 3) and comes back to the hand; the steering events
# (look, return, follow) are printed with the figures.
# STEER=frame runs the point-and-frame loop: the head keeps the hand in view (steer=fixate)
# while the rendered hand, held still (MOTION default static), points at AIM (handscenesrc's
# aim, default <900.0,-250.0,2600.0>: right, slightly up, away into the room); once held for
# DWELL seconds (default 1) the attended view (out/demo.mp4) frames the point TARGET_DISTANCE
# mm along the ray (default 2000), TARGET_REGION mm wide (default 500); the picks are printed.
# STEER=director does the same with a second simulated head as the director camera: the hand
# points to one side (AIM default <2000.0,-300.0,1800.0>), the head keeps it in view, and the
# director turns and zooms to the target (handtracker `director`, standing at the head's
# origin); the video is the left view, and the director's commands and its pose at the end
# (headctl status) are printed.
# With STEER=point, frame or director, TARGET_PLANE (handtracker's target-plane, e.g.
# "<0,0,1,-3000>" for the rendered room's wall 3 m ahead) puts the target where the ray meets
# that plane instead of TARGET_DISTANCE along it.
set -euo pipefail
. "$(dirname "$0")/lib/plugin.sh"
gesturecam_build_targets gstgesturecam headsim headctl
gesturecam_use_plugin
cd "$gesturecam_root"
out=${OUT:-out}

frames=${FRAMES:-300}
scene=${SCENE:-light}
scene=${scene//_/-}
steer=${STEER:-fixate}
if [ "$steer" = frame ] || [ "$steer" = director ]; then motion=${MOTION:-static}; else motion=${MOTION:-translate}; fi
motion=${motion//_/-}
seed=${SEED:-3}
particles=${PARTICLES:-1000}
point_options=""
scene_options=""
tracker_steer=$steer
output=attended
if [ "$steer" = point ]; then
  point_options="dwell=${DWELL:-1} target-distance=${TARGET_DISTANCE:-600} look-time=${LOOK_TIME:-3}"
elif [ "$steer" = frame ]; then
  tracker_steer=fixate
  point_options="dwell=${DWELL:-1} target-distance=${TARGET_DISTANCE:-2000} target-region=${TARGET_REGION:-500}"
  scene_options="aim=\"${AIM:-<900.0,-250.0,2600.0>}\""
elif [ "$steer" = director ]; then
  tracker_steer=fixate
  output=left
  point_options="dwell=${DWELL:-1} target-distance=${TARGET_DISTANCE:-2000} target-region=${TARGET_REGION:-500}"
  scene_options="aim=\"${AIM:-<2000.0,-300.0,1800.0>}\""
fi
if [ -n "${TARGET_PLANE:-}" ] && [ -n "$point_options" ]; then
  point_options="$point_options target-plane=\"${TARGET_PLANE// /}\""
fi
mkdir -p "$out"
rm -f "$out/demo.mp4" "$out/demo.jsonl" "$out/demo.bus.txt"

# Simulated heads on free loopback ports; stopped on exit.
headsim_pids=()
headsim_outs=()
trap 'kill "${headsim_pids[@]}" 2>/dev/null || true; wait 2>/dev/null || true; rm -f "${headsim_outs[@]}"' EXIT
start_headsim() {
  local log
  log=$(mktemp)
  headsim_outs+=("$log")
  "$gesturecam_build/gst-plugin/tools/headsim" --listen 127.0.0.1:0 --latency-ms 20 >"$log" &
  headsim_pids+=($!)
  for _ in $(seq 100); do grep -q '^listening' "$log" && break; sleep 0.05; done
  address=$(sed -n 's/^listening //p' "$log")
  [ -n "$address" ] || { echo "headsim did not start" >&2; exit 1; }
}
start_headsim
head="tcp://$address"
if [ "$steer" = director ]; then
  start_headsim
  director="tcp://$address"
  point_options="$point_options director=$director"
  echo "Director: headsim at $director."
fi

caps="video/x-raw,width=640,height=480,framerate=30/1"
eye() {
  echo "handscenesrc name=$1 eye=$1 is-live=true head=$head scene=$scene motion=$motion seed=$seed" \
       "$scene_options num-buffers=$frames truth-messages=$2 ! $caps"
}

echo "Head: headsim at $head. Rendering $frames live stereo frames ($((frames / 30)) s) of the '$scene' scene,"
echo "tracking with $particles particles per eye, steer=$steer..."
start=$(date +%s.%N)
# -m: the bus messages (the scene's ground truth among them) go to out/demo.bus.txt.
# shellcheck disable=SC2046,SC2086
gst-launch-1.0 -m -e \
  $(eye left true) ! t.sink_left \
  $(eye right false) ! t.sink_right \
  handtracker name=t particles="$particles" head="$head" steer="$tracker_steer" $point_options draw=true output=$output \
    message-updates=on-change json-location="$out/demo.jsonl" \
  ! videoconvert ! x264enc tune=zerolatency speed-preset=veryfast ! mp4mux ! filesink location="$out/demo.mp4" \
  >"$out/demo.bus.txt"
end=$(date +%s.%N)
grep -E '^(WARNING|ERROR|INFO)' -A1 "$out/demo.bus.txt" || true

python3 - "$start" "$end" "$steer" "$out" <<'PY'
import json, re, sys
start, end, steer, out = float(sys.argv[1]), float(sys.argv[2]), sys.argv[3], sys.argv[4]
rows = [json.loads(line) for line in open(f"{out}/demo.jsonl")]
n = len(rows)
tracked = sum(r["state"] == "tracking" for r in rows)
first = next((r for r in rows if r["state"] == "tracking"), None)
pointing = sum(1 for r in rows if r.get("pointing"))

def field(line, name, kind="double"):
    m = re.search(name + r"=\(" + kind + r"\)([^,;]+)", line)
    return m.group(1) if m else None

truth = []  # (timestamp ns, visible, palm x, palm y, pan, tilt) of the left view
for line in open(f"{out}/demo.bus.txt"):
    if "hand-truth" not in line or 'element "left"' not in line:
        continue
    truth.append((int(field(line, "timestamp", "guint64")), field(line, "visible", "boolean") == "true",
                  float(field(line, "palm-x")), float(field(line, "palm-y")),
                  float(field(line, "head-pan-deg")), float(field(line, "head-tilt-deg"))))
print(f"frames: {n}")
print(f"tracked: {tracked} ({100.0 * tracked / max(n, 1):.1f} %), first at frame {first['frame'] if first else None}")
print(f"3D pointing ray in {pointing} frames")
if first and truth:
    since = first["pts_ns"] + 1_000_000_000  # from one second after acquisition
    scored = [t for t in truth if t[0] >= since]
    centred = sum(1 for t in scored if t[1] and abs(t[2] - 320) < 640 / 6 and abs(t[3] - 240) < 480 / 6)
    print(f"hand in the central third of the left view: {100.0 * centred / max(len(scored), 1):.1f} % "
          f"of {len(scored)} frames from 1 s after acquisition (steer={steer})")
    pans, tilts = [t[4] for t in truth], [t[5] for t in truth]
    print(f"head pan {min(pans):+.1f} .. {max(pans):+.1f} deg, tilt {min(tilts):+.1f} .. {max(tilts):+.1f} deg")
if steer == "point":
    events = [(field(line, "event", "string"), re.search(r'detail=\(string\)"?((?:[^"\\]|\\.)*)', line))
              for line in open(f"{out}/demo.bus.txt") if "head-steering" in line]
    print(f"steering events: {len(events)}" + ("" if events else " (no pointing held for the dwell time while "
                                                             "the head was steered)"))
    for event, detail in events:
        print(f"  {event}: {detail.group(1).replace(chr(92), '') if detail else ''}")
if steer == "frame":
    picks = [(field(line, "event", "string"), field(line, "frame", "guint64"))
             for line in open(f"{out}/demo.bus.txt") if "attended-target" in line]
    print(f"attended targets: {len(picks)}" + ("" if picks else " (no pointing held for the dwell time)"))
    for event, frame in picks:
        print(f"  {event} at frame {frame}")
if steer == "director":
    picks = [field(line, "frame", "guint64") for line in open(f"{out}/demo.bus.txt")
             if "attended-target" in line and "picked" in line]
    print(f"targets picked: {len(picks)}" + ("" if picks else " (no pointing held for the dwell time)"))
    sent = [line for line in open(f"{out}/demo.bus.txt") if re.search(r"\bdirector, event", line)]
    for line in sent:
        event = field(line, "event", "string")
        if event == "frame":
            print(f"  director sent at frame {field(line, 'frame', 'guint64')}: pan {float(field(line, 'pan-deg')):+.1f} "
                  f"deg, tilt {float(field(line, 'tilt-deg')):+.1f} deg, zoom {float(field(line, 'zoom')):.2f}x")
        else:
            print(f"  director {event} at frame {field(line, 'frame', 'guint64')}")
print(f"wall time: {end - start:.1f} s for {n / 30:.1f} s of video (live)")
print(f"video: {out}/demo.mp4   JSON lines: {out}/demo.jsonl   bus messages: {out}/demo.bus.txt")
PY
if [ "$steer" = director ]; then
  echo "director at the end (headctl status):"
  "$gesturecam_build/gst-plugin/tools/headctl" --uri "$director" status
fi
