#!/usr/bin/python3
# Rewrites the two upstream ONNX hand models into graphs that OpenCV 4.6's DNN importer
# loads, and prints the sha256 of what it wrote. Needs Debian's python3-onnx (hence the
# system interpreter above). See README.md in this folder for what changes and why.
#
#   convert_models.py [--from DIR] [--out DIR]
#
# Without --from, the upstream files are downloaded from their pinned commits; either way
# their sha256 must match before anything is written.
import argparse
import hashlib
import os
import sys
import urllib.request

import numpy as np
import onnx
from onnx import helper, numpy_helper

UPSTREAM = {
    "palm_detection.onnx": {
        "url": "https://raw.githubusercontent.com/keijiro/BlazePalmBarracuda/"
               "3499363a87deea6c468ae700f4fb72a2d427cdd6/"
               "Packages/jp.keijiro.mediapipe.blazepalm/ONNX/palm_detection_barracuda.onnx",
        "sha256": "6fa415badf79694c96441b54c911ddb1b693204923a8dcd67af62e14f23730b4",
    },
    "hand_landmark.onnx": {
        "url": "https://raw.githubusercontent.com/keijiro/HandLandmarkBarracuda/"
               "36308f8b8b0ac4116e9de2b6114bd37d0dd5756e/"
               "Packages/jp.keijiro.mediapipe.handlandmark/ONNX/hand_landmark.onnx",
        "sha256": "caeea4465a5b7bf68081d9ba6ce195dcb6dcbaadbe83c339a4f2860e9db7eec2",
    },
}


def sha256(data):
    return hashlib.sha256(data).hexdigest()


def read_upstream(name, source_dir):
    """The upstream bytes of one model, from source_dir (by our name or the upstream one)
    or from the pinned URL, refused unless the sha256 matches."""
    entry = UPSTREAM[name]
    if source_dir:
        candidates = [os.path.join(source_dir, n) for n in (name, os.path.basename(entry["url"]))]
        path = next((p for p in candidates if os.path.isfile(p)), None)
        if path is None:
            sys.exit("no %s in %s (looked for %s)" % (name, source_dir, ", ".join(candidates)))
        with open(path, "rb") as f:
            data = f.read()
        origin = path
    else:
        try:
            with urllib.request.urlopen(entry["url"], timeout=60) as r:
                data = r.read()
        except OSError as e:
            sys.exit("cannot download %s (%s); give the files with --from DIR" % (entry["url"], e))
        origin = entry["url"]
    if sha256(data) != entry["sha256"]:
        sys.exit("%s: sha256 %s, expected %s" % (origin, sha256(data), entry["sha256"]))
    return data


def drop_unused_initializers(graph):
    used = {name for node in graph.node for name in node.input}
    for t in [t for t in graph.initializer if t.name not in used]:
        graph.initializer.remove(t)


def fold_prelu_slopes(model):
    """Each PRelu slope is an Expand of a 1xCx1x1 constant to the full activation shape;
    OpenCV 4.6 cannot import that Expand. The slope becomes one Cx1x1 constant per PRelu
    (per-channel, which is what the expanded tensor holds)."""
    graph = model.graph
    inits = {t.name: t for t in graph.initializer}
    expands = {n.output[0]: n for n in graph.node if n.op_type == "Expand"}
    folded_outputs = set()
    for node in graph.node:
        if node.op_type != "PRelu" or node.input[1] not in expands:
            continue
        expand = expands[node.input[1]]
        alpha = numpy_helper.to_array(inits[expand.input[0]])
        channels = alpha.size
        if alpha.shape != (1, channels, 1, 1):
            sys.exit("PRelu %s: slope of shape %s, expected 1xCx1x1" % (node.name, alpha.shape))
        folded = expand.input[0] + "_per_channel"
        graph.initializer.append(
            numpy_helper.from_array(alpha.reshape(channels, 1, 1).astype(np.float32), folded))
        folded_outputs.add(node.input[1])
        node.input[1] = folded
    kept = [n for n in graph.node if not (n.op_type == "Expand" and n.output[0] in folded_outputs)]
    del graph.node[:]
    graph.node.extend(kept)
    drop_unused_initializers(graph)
    return len(folded_outputs)


def clip_bounds_to_attributes(model):
    """Clip (ReLU6 here) takes min and max as constant inputs since opset 11; OpenCV 4.6
    reads only the attribute form of opset 6. The constants become attributes and the
    model declares opset 10, where that form is the valid one."""
    graph = model.graph
    inits = {t.name: t for t in graph.initializer}
    changed = 0
    for node in graph.node:
        if node.op_type != "Clip" or len(node.input) < 2:
            continue
        bounds = [float(numpy_helper.to_array(inits[i])) if i else None for i in node.input[1:]]
        del node.input[1:]
        for attr_name, value in zip(("min", "max"), bounds):
            if value is not None:
                node.attribute.append(helper.make_attribute(attr_name, value))
        changed += 1
    drop_unused_initializers(graph)
    for opset in model.opset_import:
        if opset.domain in ("", "ai.onnx"):
            opset.version = 10
    return changed


REWRITES = {
    "palm_detection.onnx": (fold_prelu_slopes, "PRelu slopes folded"),
    "hand_landmark.onnx": (clip_bounds_to_attributes, "Clip bounds moved to attributes"),
}


def main():
    parser = argparse.ArgumentParser(description="Convert the upstream hand models for OpenCV 4.6.")
    parser.add_argument("--from", dest="source_dir",
                        help="folder with the upstream files (default: download them)")
    parser.add_argument("--out", default=os.path.dirname(os.path.abspath(__file__)),
                        help="where the converted models go (default: this folder)")
    args = parser.parse_args()
    # Every upstream file is read and checked before anything is written.
    upstream = {name: read_upstream(name, args.source_dir) for name in REWRITES}
    for name, (rewrite, what) in REWRITES.items():
        model = onnx.load_model_from_string(upstream[name])
        count = rewrite(model)
        onnx.checker.check_model(model)
        data = model.SerializeToString()
        with open(os.path.join(args.out, name), "wb") as f:
            f.write(data)
        print("%s  %s  (%s: %d)" % (sha256(data), name, what, count))

if __name__ == "__main__":
    main()
