#!/usr/bin/python3
"""docs/elements.md holds gst-inspect-1.0's output for each of the plugin's elements. This
checks that it still matches the built plugin (exit 1 with a diff when not), or with --write
rewrites it. The plugin's file name is written as build/gst-plugin/..., wherever it was built.

Usage: elements_doc.py [--write] SOURCE_ROOT PLUGIN_DIR"""
import difflib, os, re, subprocess, sys

ELEMENTS = ["handtracker", "handscenesrc", "imagesizelimit", "handoverlay"]
HEADER = ("# Element reference\n\n"
          "Generated with `GST_PLUGIN_PATH=build/gst-plugin gst-inspect-1.0 ELEMENT`; "
          "`tests/gst/elements_doc.py --write . build/gst-plugin` rewrites it, and a test checks it.\n")


def inspect(element, plugin_dir):
    env = dict(os.environ, GST_PLUGIN_PATH=plugin_dir, NO_COLOR="1", PAGER="cat")
    out = subprocess.run(["gst-inspect-1.0", "--no-colors", element], env=env, check=True,
                         capture_output=True, text=True).stdout
    out = re.sub(r"(  Filename\s+).*", r"\1build/gst-plugin/libgstgesturecam.so", out)
    return "\n".join(line.rstrip() for line in out.rstrip().splitlines()) + "\n"


def document(plugin_dir):
    parts = [HEADER]
    for element in ELEMENTS:
        parts.append(f"\n## {element}\n\n```\n{inspect(element, plugin_dir)}```\n")
    return "".join(parts)


def main():
    args = sys.argv[1:]
    write = args[:1] == ["--write"]
    if write:
        args = args[1:]
    if len(args) != 2:
        sys.exit(__doc__)
    source_root, plugin_dir = args
    path = os.path.join(source_root, "docs", "elements.md")
    wanted = document(plugin_dir)
    if write:
        with open(path, "w") as f:
            f.write(wanted)
        return 0
    with open(path) as f:
        current = f.read()
    if current == wanted:
        return 0
    sys.stdout.writelines(difflib.unified_diff(current.splitlines(True), wanted.splitlines(True),
                                               "docs/elements.md", "gst-inspect-1.0"))
    print("\ndocs/elements.md is out of date: run tests/gst/elements_doc.py --write . build/gst-plugin")
    return 1


if __name__ == "__main__":
    sys.exit(main())
