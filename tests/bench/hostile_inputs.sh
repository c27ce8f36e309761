#!/usr/bin/env bash
# Benchmark, not a test: the adversarial inputs of docs/reliability.md run through
# gesturecam-track and through a gst-launch-1.0 pipeline with handtracker, each measured with
# /usr/bin/time -v (wall time, peak resident memory, exit status). A row over 5 s or 500 MB is
# flagged. Prints a Markdown table.
#
#   tests/bench/hostile_inputs.sh [BUILD_DIR]      (default: build; needs gesturecam-track,
#                                                   the plugin, python3, gst-launch-1.0)
set -uo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
track=$build/gst-plugin/tools/gesturecam-track
[ -x "$track" ] || { echo "no $track: build it first" >&2; exit 2; }
[ -x /usr/bin/time ] || { echo "needs /usr/bin/time (apt install time)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
export GST_PLUGIN_PATH=$build/gst-plugin GST_REGISTRY_1_0=$work/registry.bin
max_seconds=5
max_mb=500
limit_seconds=120  # a run still going then is killed and shown as exit 124

# ---- inputs -----------------------------------------------------------------------------
gst() { gst-launch-1.0 -q "$@" > /dev/null 2>&1; }
echo "generating inputs in $work ..." >&2
mkdir -p "$work"/{left,right,cut,big,huge,limit}
gst videotestsrc num-buffers=3 pattern=ball ! video/x-raw,width=640,height=480 ! pngenc ! \
  multifilesink location="$work/left/%03d.png"
cp "$work"/left/*.png "$work/right/"
gst videotestsrc num-buffers=60 pattern=ball ! video/x-raw,width=640,height=480,framerate=30/1 ! pngenc ! \
  multifilesink location="$work/cut/%03d.png"
gst videotestsrc num-buffers=291 pattern=ball ! video/x-raw,width=640,height=480,framerate=30/1 ! x264enc ! \
  mp4mux faststart=true ! filesink location="$work/clip.mp4"
gst videotestsrc num-buffers=291 pattern=ball ! video/x-raw,width=640,height=480,framerate=30/1 ! jpegenc ! \
  avimux ! filesink location="$work/clip.avi"
mkfifo "$work/fifo.yml"
mkdir "$work/directory.yml"
python3 - "$work" <<'EOF'
import struct, sys, zlib
work = sys.argv[1]

def calibration(fx=554.3, cx=319.5, k1=0.0, tx=-120.0):
    m = lambda key, rows, cols, data: (f"{key}: !!opencv-matrix\n   rows: {rows}\n   cols: {cols}\n   dt: d\n"
                                       f"   data: [ {', '.join(str(v) for v in data)} ]\n")
    M1 = [fx, 0, cx, 0, 554.3, 239.5, 0, 0, 1]
    M2 = [554.3, 0, 319.5, 0, 554.3, 239.5, 0, 0, 1]
    return ("%YAML:1.0\n---\nimage_width: 640\nimage_height: 480\n" + m("M1", 3, 3, M1) +
            m("D1", 1, 5, [k1, 0, 0, 0, 0]) + m("M2", 3, 3, M2) + m("D2", 1, 5, [0] * 5) +
            m("R", 3, 3, [1, 0, 0, 0, 1, 0, 0, 0, 1]) + m("T", 3, 1, [tx, 0, 0]))

for name, text in {"fx_tiny": calibration(fx=1e-300), "fx_huge": calibration(fx=1e11),
                   "cx_far": calibration(cx=-1e9), "baseline_huge": calibration(tx=1e11),
                   "k1_huge": calibration(k1=1e11)}.items():
    open(f"{work}/{name}.yml", "w").write(text)

# 100 MB of well-formed keys nobody reads, after a valid calibration.
with open(f"{work}/unknown_keys.yml", "w") as f:
    f.write(calibration())
    block = "".join(f"unknown_{i}: 1\n" for i in range(100000))
    while f.tell() < 100_000_000:
        f.write(block)

def png(path, width, height):
    """A grey RGB PNG, compressed row by row (a 30000x30000 one is 2.6 MB on disk)."""
    chunk = lambda t, d: struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xFFFFFFFF)
    z = zlib.compressobj(9)
    row = b"\x00" + b"\x80" * (3 * width)
    data = b"".join(z.compress(row) for _ in range(height)) + z.flush()
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)))
        f.write(chunk(b"IDAT", data) + chunk(b"IEND", b""))

png(f"{work}/huge/000.png", 30000, 30000)
png(f"{work}/big/000.png", 16384, 16384)
png(f"{work}/limit/000.png", 8192, 8192)

def damage(src, dst, keep=None, at=None, length=4000):
    data = bytearray(open(src, "rb").read())
    if at is not None:
        start = int(len(data) * at)
        data[start:start + length] = b"\xff" * length
    if keep is not None:
        data = data[:int(len(data) * keep)]
    open(dst, "wb").write(data)

damage(f"{work}/clip.mp4", f"{work}/corrupt.mp4", at=1 / 3)
damage(f"{work}/clip.mp4", f"{work}/truncated.mp4", keep=0.5)
damage(f"{work}/clip.avi", f"{work}/corrupt.avi", at=1 / 3, length=20000)
damage(f"{work}/cut/005.png", f"{work}/cut/005.png", keep=0.3)
EOF

# ---- measuring --------------------------------------------------------------------------
echo "| input | run by | exit | wall s | peak RSS MB | flag | message |"
echo "|---|---|---|---|---|---|---|"

# measure INPUT RUNNER COMMAND...: one table row.
measure() {
  local input=$1 runner=$2
  shift 2
  /usr/bin/time -v -o "$work/time.txt" timeout -k 5 "$limit_seconds" "$@" > /dev/null 2> "$work/err.txt"
  local status=$?
  local wall rss_kb rss_mb flag message
  wall=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, p, ":"); s = 0; for (i = 1; i <= n; i++) s = s * 60 + p[i]; printf "%.2f", s}' "$work/time.txt")
  rss_kb=$(awk -F': ' '/Maximum resident set size/ {print $2}' "$work/time.txt")
  rss_mb=$(( ${rss_kb:-0} / 1024 ))
  flag=""
  awk -v w="$wall" -v m="$max_seconds" 'BEGIN {exit !(w > m)}' && flag="> ${max_seconds} s"
  [ "$rss_mb" -gt "$max_mb" ] && flag="${flag:+$flag, }> ${max_mb} MB"
  [ "$status" -eq 124 ] && flag="${flag:+$flag, }killed after ${limit_seconds} s"
  message=$(message_of "$status" < "$work/err.txt" | sed "s|$work/||g; s|/GstPipeline:pipeline0/||g; s/|/\\\\|/g" |
            cut -c1-160)
  echo "| $input | $runner | $status | $wall | $rss_mb | ${flag:-ok} | ${message} |"
}

# The line that says what happened: the tool's error (or its summary when it succeeded), else
# handtracker's error or warning with its reason, else the first error or warning of the run.
message_of() {
  awk -v status="$1" '
    /^gesturecam-track: (error|warning)/ && tool == "" { tool = $0 }
    /^gesturecam-track: [0-9]+ frames/ { summary = $0 }
    reason_in > 0 && --reason_in == 0 { reason = $0 }
    /^(ERROR|WARNING): from element .*GstHandTracker/ && tracker == "" { tracker = $0; reason_in = 3 }
    /^(ERROR|WARNING)/ && other == "" { other = $0 }
    END {
      if (summary != "" && status == 0) print summary
      else if (tool != "") print tool
      else if (tracker != "") print tracker " " reason
      else print other
    }'
}

stereo=(--left "$work/left/%03d.png" --right "$work/right/%03d.png" --particles 200)
pair_src="videotestsrc num-buffers=3 pattern=ball ! video/x-raw,width=640,height=480 ! t.sink_left \
videotestsrc num-buffers=3 pattern=ball ! video/x-raw,width=640,height=480 ! t.sink_right"
tracker="handtracker name=t particles=200 message-updates=none"

for calibration in /dev/zero fifo.yml directory.yml unknown_keys.yml fx_tiny.yml fx_huge.yml cx_far.yml \
                   baseline_huge.yml k1_huge.yml; do
  path=$calibration
  [ "${path#/}" = "$path" ] && path=$work/$calibration
  measure "calibration $calibration" gesturecam-track "$track" "${stereo[@]}" --calibration "$path"
  # shellcheck disable=SC2086
  measure "calibration $calibration" gst-launch-1.0 gst-launch-1.0 $pair_src $tracker calibration="$path" ! fakesink
done

# Every file pipeline puts imagesizelimit before pngdec (pipelines/files.sh), which refuses a
# picture over the limit from its header; "pngdec alone" is what it prevents.
for size in huge big limit; do
  case $size in huge) label="PNG 30000x30000 (2.6 MB)" ;; big) label="PNG 16384x16384" ;; limit) label="PNG 8192x8192 (the limit)" ;; esac
  measure "$label" gesturecam-track "$track" --left "$work/$size/%03d.png" --particles 200
  # shellcheck disable=SC2086
  measure "$label" "gst-launch-1.0 (imagesizelimit)" gst-launch-1.0 filesrc location="$work/$size/000.png" ! \
    imagesizelimit ! pngdec ! t.sink_left $tracker ! fakesink
  [ $size = limit ] && continue
  measure "$label" "pipelines/files.sh" "$root/pipelines/files.sh" "$work/$size/%03d.png" "$work/$size/%03d.png" \
    "$work/files-out"
  # shellcheck disable=SC2086
  measure "$label" "gst-launch-1.0 (pngdec alone)" gst-launch-1.0 filesrc location="$work/$size/000.png" ! pngdec ! \
    t.sink_left $tracker ! fakesink
done
# shellcheck disable=SC2086
measure "raw frames 16384x16384" gst-launch-1.0 gst-launch-1.0 videotestsrc num-buffers=2 ! \
  video/x-raw,format=BGR,width=16384,height=16384 ! t.sink_left $tracker ! fakesink

measure "PNG sequence, frame 5 of 60 cut" gesturecam-track "$track" --left "$work/cut/%03d.png" --particles 200
measure "PNG sequence, frame 5 of 60 cut" "gesturecam-track --skip-bad-frames" "$track" --left "$work/cut/%03d.png" \
  --particles 200 --skip-bad-frames
# shellcheck disable=SC2086
measure "PNG sequence, frame 5 of 60 cut" gst-launch-1.0 gst-launch-1.0 multifilesrc location="$work/cut/%03d.png" \
  stop-index=59 caps=image/png,framerate=30/1 ! imagesizelimit ! pngdec ! t.sink_left $tracker ! fakesink
for video in corrupt.mp4 truncated.mp4 corrupt.avi; do
  measure "$video" gesturecam-track "$track" --left "$work/$video" --particles 200
  measure "$video" "gesturecam-track --skip-bad-frames" "$track" --left "$work/$video" --particles 200 --skip-bad-frames
done
# GStreamer here has no H.264 decoder (no gst-libav): the damaged MJPEG AVI stands for video.
# shellcheck disable=SC2086
measure "corrupt.avi" gst-launch-1.0 gst-launch-1.0 filesrc location="$work/corrupt.avi" ! avidemux ! jpegdec ! \
  t.sink_left $tracker ! fakesink

measure "output to /dev/full" gesturecam-track "$track" "${stereo[@]}" --out /dev/full
# shellcheck disable=SC2086
measure "output to /dev/full" gst-launch-1.0 gst-launch-1.0 $pair_src $tracker json-location=/dev/full ! fakesink
