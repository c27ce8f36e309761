#!/usr/bin/env python3
"""pipelines/files.sh as a user runs it: a real MP4 pair, image sequences numbered from 0 and
from 1, and inputs that are missing or cannot be decoded.

Usage: files_script.py SOURCE_ROOT BUILD_ROOT (GESTURECAM_BUILD_DIR and GST_PLUGIN_PATH from
the environment)."""
import json
import os
import subprocess
import sys
import tempfile
import unittest

SOURCE_ROOT, BUILD_ROOT = sys.argv[1], sys.argv[2]
SCRIPT = os.path.join(SOURCE_ROOT, "pipelines", "files.sh")
PAIR = os.path.join(SOURCE_ROOT, "tests", "data", "handpose3d")
FRAMES = 24


def run_files(*args, frames=FRAMES):
    env = dict(os.environ, FRAMES=str(frames), GESTURECAM_BUILD_DIR=BUILD_ROOT)
    return subprocess.run(["bash", SCRIPT, *args], env=env, capture_output=True, text=True, timeout=240)


def json_lines(path):
    with open(path) as f:
        return [json.loads(line) for line in f]


def record_scene(folder, first_index, frames):
    """The scene's two views as PNG files numbered from first_index; returns the patterns."""
    patterns = []
    description = []
    for eye in ("left", "right"):
        os.makedirs(os.path.join(folder, eye), exist_ok=True)
        pattern = os.path.join(folder, eye, "%03d.png")
        description += [f"handscenesrc eye={eye} scene=light seed=2 truth-messages=false num-buffers={frames}",
                        "!", "video/x-raw,format=RGB", "!", "pngenc", "!",
                        f"multifilesink index={first_index} location={pattern}"]
        patterns.append(pattern)
    subprocess.run(["gst-launch-1.0", "-q", *" ".join(description).split()], check=True, timeout=120)
    return patterns


class FilesScript(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.out = os.path.join(self.tmp.name, "out")

    def tearDown(self):
        self.tmp.cleanup()

    def assert_tracked(self, result, frames):
        self.assertEqual(result.returncode, 0, result.stderr + result.stdout)
        rows = json_lines(os.path.join(self.out, "track.jsonl"))
        self.assertEqual([r["frame"] for r in rows], list(range(frames)))
        pts = [r["pts_ns"] for r in rows]
        self.assertTrue(all(b > a for a, b in zip(pts, pts[1:])), pts)
        self.assertGreater(os.path.getsize(os.path.join(self.out, "annotated.mp4")), 1000)
        return rows

    def test_mp4_pair_with_its_calibration(self):
        result = run_files(os.path.join(PAIR, "handpose3d_cam0.mp4"), os.path.join(PAIR, "handpose3d_cam1.mp4"),
                           self.out, os.path.join(PAIR, "handpose3d_calib.yml"))
        rows = self.assert_tracked(result, FRAMES)
        # 30 frames per second: frame i at i/30 s.
        self.assertAlmostEqual(rows[-1]["pts_ns"] - rows[0]["pts_ns"], (FRAMES - 1) * 1e9 / 30, delta=2e6)
        self.assertIn(f"({FRAMES} frames)", result.stdout)

    def test_image_sequences_numbered_from_one(self):
        left, right = record_scene(os.path.join(self.tmp.name, "rec"), 1, 12)
        self.assert_tracked(run_files(left, right, self.out, frames=""), 12)

    def test_image_sequences_numbered_from_zero(self):
        left, right = record_scene(os.path.join(self.tmp.name, "rec"), 0, 12)
        self.assert_tracked(run_files(left, right, self.out, frames=""), 12)

    def test_missing_video_is_named(self):
        missing = os.path.join(self.tmp.name, "nowhere.mp4")
        result = run_files(missing, os.path.join(PAIR, "handpose3d_cam1.mp4"), self.out)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn(f"left input '{missing}': no such file", result.stderr)

    def test_sequence_without_a_first_image_is_named(self):
        pattern = os.path.join(self.tmp.name, "empty", "%05d.png")
        result = run_files(os.path.join(PAIR, "handpose3d_cam0.mp4"), pattern, self.out)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn(f"right input '{pattern}': no image numbered 0 or 1", result.stderr)

    def test_undecodable_file_is_named(self):
        bogus = os.path.join(self.tmp.name, "notes.mp4")
        with open(bogus, "w") as f:
            f.write("not a video\n" * 100)
        result = run_files(os.path.join(PAIR, "handpose3d_cam0.mp4"), bogus, self.out)
        self.assertNotEqual(result.returncode, 0)
        self.assertIn(f"cannot decode the right input '{bogus}'", result.stderr)


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
