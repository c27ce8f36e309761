#!/usr/bin/env python3
"""Turns gesturecam-bench --json output into the plots and tables of docs/benchmarks.md.

    build/gst-plugin/tools/gesturecam-bench --json > docs/plots/bench.json
    python3 docs/plots/make_plots.py

Writes docs/plots/snr_vs_particles.png, docs/plots/ms_vs_particles.png,
docs/plots/peers_iou.png and rewrites the part of docs/benchmarks.md between the
'<!-- bench:begin -->' and '<!-- bench:end -->' markers. Needs matplotlib
(Debian: apt-get install python3-matplotlib); only the documentation needs it.
"""
import argparse
import json
import math
import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
DOC = HERE.parent / "benchmarks.md"

# The thesis's figures (Zhu 2003, Tables 4.1 and 4.2).
THESIS_SNR = {
    "no clutter (0.03% skin)": ([20, 50, 100, 500, 1000, 2000, 3000, 5000],
                                [6.03, 6.73, 9.14, 10.59, 10.73, 11.75, 11.76, 11.80]),
    "high clutter (9.35% skin)": ([20, 50, 100, 500, 1000, 2000, 3000, 5000],
                                  [4.74, 6.16, 7.80, 8.61, 8.74, 8.82, 8.21, 9.75]),
}
THESIS_MS = ([20, 50, 100, 200, 500, 1000, 2000, 3000],
             [360, 540, 700, 980, 2210, 4110, 7670, 12040])


def load(path):
    rows = {}
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            line = line.strip()
            if not line:
                continue
            try:
                obj = json.loads(line)
            except json.JSONDecodeError as e:
                sys.exit(f"{path}:{n}: not JSON: {e}")
            rows.setdefault(obj.get("kind"), []).append(obj)
    for kind in ("machine", "baseline", "tracker"):
        if kind not in rows:
            sys.exit(f"{path}: no '{kind}' line; is it gesturecam-bench --json output?")
    return rows


def detector_of(row):
    # Lines written before the bench measured both detectors carry none.
    return row.get("detector", "")


def detectors(rows):
    names = []
    for r in rows:
        if detector_of(r) not in names:
            names.append(detector_of(r))
    return names


def by_scene(rows):
    scenes = {}
    for r in rows:
        scenes.setdefault(r["scene"], []).append(r)
    for rs in scenes.values():
        rs.sort(key=lambda r: r["particles"])
    return scenes


def by_scene_and_detector(rows):
    """{(scene, detector): rows by particle count}, scenes and detectors in file order."""
    out = {}
    for r in rows:
        out.setdefault((r["scene"], detector_of(r)), []).append(r)
    for rs in out.values():
        rs.sort(key=lambda r: r["particles"])
    return out


LINESTYLES = ["-", ":", "-.", (0, (1, 3))]  # thesis curves are dashed


def curve_label(scene, detector, extra=""):
    who = f"GestureCAM {detector}" if detector else "GestureCAM"
    return f"{who}, {scene}{extra}"


def fmt(v, digits):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "n/a"
    return f"{v:.{digits}f}"


def plots(data, out_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scenes = by_scene(data["tracker"])
    curves = by_scene_and_detector(data["tracker"])
    dets = detectors(data["tracker"])
    colours = {name: f"C{i}" for i, name in enumerate(scenes)}

    def style(scene, detector):
        return dict(color=colours[scene], linestyle=LINESTYLES[dets.index(detector) % len(LINESTYLES)])

    fig, ax = plt.subplots(figsize=(7, 6))
    for (name, det), rs in curves.items():
        pts = [(r["particles"], r["snr_db"]) for r in rs if r["snr_db"] is not None]
        if pts:
            ax.plot(*zip(*pts), marker="o", **style(name, det),
                    label=curve_label(name, det, f" ({rs[0]['skin_pct']:.2f}% skin)"))
    for label, (x, y) in THESIS_SNR.items():
        ax.plot(x, y, linestyle="--", marker="s", color="grey" if "no" in label else "black",
                label=f"thesis, {label}")
    ax.set_xscale("log")
    ax.set_xlabel("particles per eye")
    ax.set_ylabel("SNR (dB)")
    ax.set_title("Tracking accuracy against the number of particles")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
    fig.tight_layout()
    fig.savefig(out_dir / "snr_vs_particles.png", dpi=110)
    plt.close(fig)

    # CPU time where the bench gave it: on a shared machine it moves far less than wall time.
    cost = "cpu_ms_per_frame" if all("cpu_ms_per_frame" in r for r in data["tracker"]) else "ms_per_frame"
    fig, ax = plt.subplots(figsize=(7, 6))
    for (name, det), rs in curves.items():
        ax.plot([r["particles"] for r in rs], [r[cost] for r in rs], marker="o",
                **style(name, det), label=curve_label(name, det))
    ax.plot(*THESIS_MS, linestyle="--", marker="s", color="black",
            label="thesis (2003 desktop, whole iteration)")
    conv = data["baseline"][0]["convert_ms"]
    ax.axhline(conv, color="grey", linestyle=":", label=f"one BGR->RGB pass ({conv:.3f} ms)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("particles per eye")
    ax.set_ylabel(("CPU " if cost.startswith("cpu") else "") + "ms per frame per eye")
    machine = data["machine"][0]
    ax.set_title(f"Cost per frame ({machine['cpu']}, one thread)", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
    fig.tight_layout()
    fig.savefig(out_dir / "ms_vs_particles.png", dpi=110)
    plt.close(fig)

    peers = data.get("peer", [])
    if peers:
        scene_names = sorted({p["scene"] for p in peers}, key=lambda s: list(scenes).index(s)
                             if s in scenes else 99)
        trackers = sorted({p["tracker"] for p in peers}, key=lambda t: (t != "gesturecam", t))
        width = 0.8 / len(trackers)
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for i, t in enumerate(trackers):
            ys = []
            for s in scene_names:
                match = [p["box_iou"] for p in peers if p["scene"] == s and p["tracker"] == t]
                ys.append(match[0] if match and match[0] is not None else 0.0)
            ax.bar([k + i * width for k in range(len(scene_names))], ys, width, label=t)
        ax.set_xticks([k + 0.4 - width / 2 for k in range(len(scene_names))])
        ax.set_xticklabels(scene_names)
        ax.set_ylim(0, 1)
        ax.set_ylabel("mean box IoU with the true hand box")
        ax.set_title("OpenCV trackers on the same frames")
        ax.legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(out_dir / "peers_iou.png", dpi=110)
        plt.close(fig)


def synthetic_table(data):
    """Tables 4.1/4.2 with every detector's figure beside the other's in each cell."""
    b = data["baseline"][0]
    dets = detectors(data["tracker"])
    rows = {}
    for r in data["tracker"]:
        rows.setdefault((r["scene"], r["particles"]), {})[detector_of(r)] = r
    pair = " / ".join(d for d in dets if d)
    head = f" ({pair})" if len(dets) > 1 else ""
    out = [f"| scene | skin % | particles | SNR dB{head} | mean IoU{head} | tracked{head} | "
           f"lost frames{head} | ms/frame/eye{head} | x conversion{head} | CPU ms/frame/eye{head} |",
           "|---|---|---|---|---|---|---|---|---|---|"]

    def cell(by_det, fn):
        return " / ".join(fn(by_det[d]) if d in by_det else "n/a" for d in dets)

    def ratio(r):
        return fmt(r["ms_per_frame"] / b["convert_ms"] if b["convert_ms"] else None, 1)

    for (scene, particles), by_det in rows.items():
        first = next(iter(by_det.values()))
        out.append(f"| {scene} | {fmt(first['skin_pct'], 2)} | {particles} | "
                   f"{cell(by_det, lambda r: fmt(r['snr_db'], 2))} | "
                   f"{cell(by_det, lambda r: fmt(r['mean_iou'], 3))} | "
                   f"{cell(by_det, lambda r: fmt(r['tracked_fraction'], 3))} | "
                   f"{cell(by_det, lambda r: fmt(r['lost_frames'], 1))} | "
                   f"{cell(by_det, lambda r: fmt(r['ms_per_frame'], 2))} | {cell(by_det, ratio)} | "
                   f"{cell(by_det, lambda r: fmt(r.get('cpu_ms_per_frame'), 2))} |")
    return out


def peers_table(peers):
    ours = f"{peers[0]['particles']} particles"
    if "detector" in peers[0]:
        ours += f", {peers[0]['detector']} detector"
    out = ["", f"OpenCV's trackers on the same frames (ours at {ours}):",
           "", "| scene | tracker | box IoU | ms/frame | frames scored |", "|---|---|---|---|---|"]
    for p in peers:
        out.append(f"| {p['scene']} | {p['tracker']} | {fmt(p['box_iou'], 3)} | "
                   f"{fmt(p['ms_per_frame'], 2)} | {p['frames']} |")
    return out


def stereo_table(rows):
    s0 = rows[0]
    out = ["", f"Stereo, {s0['scene']} scene, {s0['particles']} particles per eye:", "",
           "| detector | 3D step ms/stereo frame | 3D valid frames | median direction error deg | "
           "median palm error mm | pipeline frames/s (2 threads) | CPU ms/stereo frame | "
           "with rendering frames/s | with rendering CPU ms/stereo frame | network share |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for s in rows:
        out.append(f"| {s.get('detector', 'n/a')} | {fmt(s['estimate_ms'], 2)} | "
                   f"{s['valid_3d']}/{s['frames']} | {fmt(s['direction_error_deg'], 1)} | "
                   f"{fmt(s['palm_error_mm'], 0)} | {fmt(s['pipeline_fps'], 1)} | "
                   f"{fmt(s.get('cpu_ms_per_frame'), 2)} | {fmt(s.get('rendering_fps'), 1)} | "
                   f"{fmt(s.get('rendering_cpu_ms_per_frame'), 2)} | {fmt(s.get('models_share'), 3)} |")
    return out


def real_pair_tables(views, pairs):
    p0 = pairs[0]
    out = ["", f"Real pair, {p0['frames']} stereo frames, {p0['particles']} particles per eye: "
           "the fingertip in each view against the reference key points (\"models\": frames where "
           "the learned models ran; \"carried\": frames the contour carried alone):", "",
           "| detector | view | reference frames | tracked | within 30 px | median px | "
           "median px, models | median px, carried | models share of tracked | pointing frames | "
           "tracked while pointing | median px while pointing |",
           "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for v in views:
        out.append(f"| {v['detector']} | {v['view']} | {v['reference_frames']} | "
                   f"{fmt(v['coverage'], 3)} | {fmt(v['within_30px'], 3)} | {fmt(v['median_px'], 1)} | "
                   f"{fmt(v['median_px_models'], 1)} | {fmt(v['median_px_carried'], 1)} | "
                   f"{fmt(v['models_share'], 3)} | {v['pointing_frames']} | "
                   f"{fmt(v['pointing_coverage'], 3)} | {fmt(v['pointing_median_px'], 1)} |")
    out += ["", f"Real pair in 3D, and its cost (median of {p0['runs']} run(s)):", "",
            "| detector | pointing frames | 3D ray | median angle deg | p90 angle deg | other frames | "
            "false pointing | ms/stereo frame | stereo frames/s | CPU ms/stereo frame |",
            "|---|---|---|---|---|---|---|---|---|---|"]
    for p in pairs:
        fps = 1000.0 / p["ms_per_frame"] if p["ms_per_frame"] else None
        out.append(f"| {p['detector']} | {p['pointing_frames']} | {fmt(p['ray_coverage'], 3)} | "
                   f"{fmt(p['angle_median_deg'], 1)} | {fmt(p['angle_p90_deg'], 1)} | "
                   f"{p['other_frames']} | {fmt(p['false_pointing'], 3)} | "
                   f"{fmt(p['ms_per_frame'], 2)} | {fmt(fps, 1)} | {fmt(p.get('cpu_ms_per_frame'), 2)} |")
    return out


def windows_table(windows):
    out = ["", "One view of the real pair alone, through narrower windows scaled to 640x480 that the "
           "hand enters from the edge of (\"cut\": frames with reference key points outside the "
           "window):", "",
           "| detector | window | reference frames | cut | tracked | within 30 px | median px | "
           "models share of tracked |",
           "|---|---|---|---|---|---|---|---|"]
    for w in windows:
        out.append(f"| {w['detector']} | {w['window']} | {w['reference_frames']} | {w['cut_frames']} | "
                   f"{fmt(w['coverage'], 3)} | {fmt(w['within_30px'], 3)} | {fmt(w['median_px'], 1)} | "
                   f"{fmt(w['models_share'], 3)} |")
    return out


def models_table(models):
    out = ["", "The learned models' cost per call (one thread, median CPU time of alternating calls "
           "on the same random input; the ratio is the figure to compare across machines):", "",
           "| model | input | OpenCV's layers ms | with the product's depthwise convolution ms | "
           "ratio | largest output difference |",
           "|---|---|---|---|---|---|"]
    for m in models:
        out.append(f"| {m['model']} | {m['input_side']}x{m['input_side']} | {fmt(m['opencv_cpu_ms'], 2)} | "
                   f"{fmt(m['product_cpu_ms'], 2)} | {fmt(m['ratio'], 2)} | {m['max_abs_diff']:.1e} |")
    return out


def tables(data):
    m = data["machine"][0]
    b = data["baseline"][0]
    out = [
        f"Measured on: {m['cores']} cores, {m['cpu']}, load average {fmt(m['load_1min'], 2)} "
        f"at start; OpenCV {m['opencv']}; {m['width']}x{m['height']}, {m['frames']} frames per "
        f"sequence, motion `{m['motion']}`, seeds {m['seeds']}, median of {m['runs']} run(s).",
        "",
        f"Baseline per frame: copy {fmt(b['copy_ms'], 3)} ms, BGR->RGB conversion "
        f"{fmt(b['convert_ms'], 3)} ms.",
        "",
    ] + synthetic_table(data)
    if data.get("peer"):
        out += peers_table(data["peer"])
    if data.get("stereo"):
        out += stereo_table(data["stereo"])
    if data.get("real_pair") and data.get("real_view"):
        out += real_pair_tables(data["real_view"], data["real_pair"])
    if data.get("real_window"):
        out += windows_table(data["real_window"])
    if data.get("models"):
        out += models_table(data["models"])
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("bench_json", nargs="?", default=str(HERE / "bench.json"))
    ap.add_argument("--no-doc", action="store_true", help="do not rewrite docs/benchmarks.md")
    args = ap.parse_args()
    data = load(args.bench_json)
    plots(data, HERE)
    if not args.no_doc:
        begin, end = "<!-- bench:begin -->", "<!-- bench:end -->"
        text = DOC.read_text(encoding="utf-8")
        if begin not in text or end not in text:
            sys.exit(f"{DOC}: the {begin} / {end} markers are missing")
        head, rest = text.split(begin, 1)
        _, tail = rest.split(end, 1)
        DOC.write_text(f"{head}{begin}\n{tables(data)}\n{end}{tail}", encoding="utf-8")


if __name__ == "__main__":
    main()
