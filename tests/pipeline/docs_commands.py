#!/usr/bin/env python3
"""Every shell example in docs/*.md and every script in pipelines/ runs as written, short and
without a camera or a display.

The examples (```sh blocks) run as one bash script each, in a scratch folder where build/,
pipelines/ and tests/ lead to the tree under test, with these changes only:
  - a V4L2 camera becomes videotestsrc and a window becomes fakesink;
  - every num-buffers is at most FRAMES, and a source without one gets num-buffers=FRAMES;
  - `headctl ... watch` without a count reads the head a few times;
  - commands left in the background end with their block;
  - FRAMES is set, which the scripts in pipelines/ take as a frame limit.
The scripts run with the environment the table SCRIPTS gives (FRAMES, SOURCE=scene, SINK),
and again with each option of the table VARIANTS (demo.sh STEER=point).
A run fails on a non-zero exit, an ERROR line, a timeout, or a sink's warning that the
pipeline's latency cannot be met ("Pipeline construction is invalid, please add queues").

Usage: docs_commands.py SOURCE_ROOT BUILD_ROOT"""
import glob
import os
import re
import signal
import subprocess
import sys
import tempfile
import unittest

SOURCE_ROOT, BUILD_ROOT = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
FRAMES = 30
PAIR = os.path.join(SOURCE_ROOT, "tests", "data", "handpose3d")

# Examples that are measurements, minutes long by design: what they measure is checked elsewhere.
SKIPPED = {"gesturecam-bench": "the benchmark itself (docs/benchmarks.md)",
           "meson setup": "a build of its own, minutes long: the tests build the tree"}

# Each script in pipelines/: (arguments, environment), short and camera-free.
SCRIPTS = {
    "demo.sh": ([], {"FRAMES": str(FRAMES), "SCENE": "face_pass", "MOTION": "leave_return"}),
    "files.sh": ([f"{PAIR}/handpose3d_cam0.mp4", f"{PAIR}/handpose3d_cam1.mp4", "out/files",
                  f"{PAIR}/handpose3d_calib.yml"], {"FRAMES": "10"}),
    "rtp-stream.sh": ([], {"FRAMES": str(FRAMES)}),
    "side-by-side.sh": ([], {"SOURCE": "scene", "FRAMES": str(FRAMES), "SINK": "fakesink"}),
    "webcams.sh": ([], {"SOURCE": "scene", "FRAMES": str(FRAMES), "SINK": "fakesink"}),
    "throughput.sh": (["100", "1", "20"], {}),
}
# Further short runs of a script with another option.
VARIANTS = [
    ("demo.sh", [], {"FRAMES": str(FRAMES), "STEER": "point"}),
]


def examples():
    """(file, block) for every ```sh block of docs/*.md."""
    for path in sorted(glob.glob(os.path.join(SOURCE_ROOT, "docs", "*.md"))):
        with open(path) as f:
            for block in re.findall(r"```sh\n(.*?)```", f.read(), re.S):
                yield os.path.relpath(path, SOURCE_ROOT), block


def shorten_sources(line):
    """num-buffers at most FRAMES on every source element of a gst-launch line."""
    line = re.sub(r"num-buffers=(\d+)", lambda m: f"num-buffers={min(int(m.group(1)), FRAMES)}", line)

    def limit(m):
        element = m.group(0).rstrip()
        return m.group(0) if "num-buffers=" in element else f"{element} num-buffers={FRAMES} "
    return re.sub(r"\b(?:handscenesrc|videotestsrc)\b[^!]*", limit, line)


def runnable(block):
    """The block as the test runs it (see the module's text)."""
    text = block.replace("\\\n", " ")
    text = re.sub(r"v4l2src device=\S+", "videotestsrc is-live=true", text)
    text = text.replace("autovideosink", "fakesink")
    lines = []
    for line in text.splitlines():
        if "gst-launch-1.0" in line:
            line = shorten_sources(line)
        line = re.sub(r"(headctl\b.*\bwatch)\s*($|#)", r"\1 100 5 \2", line)
        lines.append(line)
    return "trap 'kill $(jobs -p) 2>/dev/null || true' EXIT\n" + "\n".join(lines) + "\n"


class Scratch:
    """A folder where build/, pipelines/ and tests/ lead to the tree under test."""

    def __init__(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.path = self.tmp.name
        os.symlink(BUILD_ROOT, os.path.join(self.path, "build"))
        for name in ("pipelines", "tests", "core"):
            os.symlink(os.path.join(SOURCE_ROOT, name), os.path.join(self.path, name))

    def run(self, argv, env=None, timeout=240):
        full_env = dict(os.environ, GESTURECAM_BUILD_DIR=BUILD_ROOT, **(env or {}))
        # A session of its own, so a run that times out ends with everything it started.
        with subprocess.Popen(argv, cwd=self.path, env=full_env, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                              text=True, start_new_session=True) as process:
            try:
                stdout, stderr = process.communicate(timeout=timeout)
            except subprocess.TimeoutExpired:
                os.killpg(process.pid, signal.SIGKILL)
                stdout, stderr = process.communicate()
                return subprocess.CompletedProcess(argv, "timeout", stdout, stderr)
        return subprocess.CompletedProcess(argv, process.returncode, stdout, stderr)

    def close(self):
        self.tmp.cleanup()


def failure(result):
    """Why a run counts as failed, or None."""
    output = result.stdout + result.stderr
    if result.returncode != 0:
        return f"exit status {result.returncode}\n{output}"
    errors = [line for line in output.splitlines() if line.startswith("ERROR") or "please add queues" in line]
    if errors:
        return "\n".join(errors)
    return None


class DocsCommands(unittest.TestCase):
    def setUp(self):
        self.scratch = Scratch()

    def tearDown(self):
        self.scratch.close()

    def test_examples_in_docs(self):
        ran = 0
        for path, block in examples():
            if any(word in block for word in SKIPPED):
                continue
            with self.subTest(doc=path, example=block.splitlines()[0]):
                result = self.scratch.run(["bash", "-euo", "pipefail", "-c", runnable(block)],
                                          env={"FRAMES": str(FRAMES)})
                self.assertIsNone(failure(result), f"{path}:\n{block}")
                ran += 1
        self.assertGreater(ran, 0)

    def test_every_script_in_pipelines(self):
        scripts = sorted(os.path.basename(p) for p in glob.glob(os.path.join(SOURCE_ROOT, "pipelines", "*.sh")))
        self.assertEqual(scripts, sorted(SCRIPTS), "each script in pipelines/ needs its short run here")
        for name, (args, env) in SCRIPTS.items():
            with self.subTest(script=name):
                result = self.scratch.run(["bash", os.path.join("pipelines", name), *args], env=env)
                self.assertIsNone(failure(result), name)

    def test_script_variants(self):
        for name, args, env in VARIANTS:
            with self.subTest(script=name, env=env):
                result = self.scratch.run(["bash", os.path.join("pipelines", name), *args], env=env)
                self.assertIsNone(failure(result), f"{name} {env}")


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
