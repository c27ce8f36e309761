#!/usr/bin/python3
"""Reads GstHandPointingMeta from Python through GObject introspection (GstGestureCam-1.0).

Runs two synthetic eyes through handtracker into an appsink and prints, for every buffer,
the pointing read from its meta. From a build tree:

    meson devenv -C build python3 pipelines/pointing_meta.py [--frames N]

Exit status: 0 when at least one buffer carried a 3D pointing direction, 1 otherwise.
"""
import argparse
import sys

import gi

gi.require_version("Gst", "1.0")
gi.require_version("GstApp", "1.0")
gi.require_version("GstGestureCam", "1.0")
from gi.repository import Gst, GstApp, GstGestureCam  # noqa: E402

LEFT = GstGestureCam.HandPointingView.LEFT


def describe(meta):
    """One line: frame, state, gesture, image fingertip and the 3D direction when known."""
    text = f"frame {meta.get_frame()} {meta.get_state().value_nick} {meta.get_gesture(LEFT).value_nick}"
    tracked, x, y, pointing_deg = meta.get_fingertip(LEFT)
    if tracked:
        text += f" fingertip ({x:.1f}, {y:.1f}) px at {pointing_deg:+.1f} deg"
    has_3d, azimuth, elevation = meta.get_direction()
    if has_3d:
        text += f" azimuth {azimuth:+.1f} elevation {elevation:+.1f} deg"
    return text, has_3d


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=60, help="frames per eye (default 60)")
    args = parser.parse_args()

    Gst.init(None)
    pipeline = Gst.parse_launch(
        f"handscenesrc eye=left num-buffers={args.frames} ! video/x-raw,width=320,height=240 ! t.sink_left "
        f"handscenesrc eye=right num-buffers={args.frames} ! video/x-raw,width=320,height=240 ! t.sink_right "
        "handtracker name=t ! appsink name=sink sync=false")
    sink = pipeline.get_by_name("sink")
    pipeline.set_state(Gst.State.PLAYING)
    buffers = pointing = 0
    while True:
        sample = sink.pull_sample()
        if sample is None:  # end of stream (or an error, reported below)
            break
        meta = GstGestureCam.HandPointingMeta.from_buffer(sample.get_buffer())
        if meta is None:
            continue
        buffers += 1
        text, has_3d = describe(meta)
        pointing += has_3d
        print(text)
    message = pipeline.get_bus().pop_filtered(Gst.MessageType.ERROR)
    pipeline.set_state(Gst.State.NULL)
    if message:
        error, debug = message.parse_error()
        print(f"pipeline error: {error.message} ({debug})", file=sys.stderr)
        return 1
    print(f"{buffers} buffers with GstHandPointingMeta, {pointing} with a pointing direction")
    return 0 if pointing > 0 else 1


if __name__ == "__main__":
    sys.exit(main())
