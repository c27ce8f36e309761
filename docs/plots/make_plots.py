#!/usr/bin/env python3
"""Turns gesturecam-bench --json output into the plots and tables of docs/benchmarks.md.

    build/core/tools/gesturecam-bench --json > docs/plots/bench.json
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


def by_scene(rows):
    scenes = {}
    for r in rows:
        scenes.setdefault(r["scene"], []).append(r)
    for rs in scenes.values():
        rs.sort(key=lambda r: r["particles"])
    return scenes


def fmt(v, digits):
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "n/a"
    return f"{v:.{digits}f}"


def plots(data, out_dir):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    scenes = by_scene(data["tracker"])

    fig, ax = plt.subplots(figsize=(7, 5.5))
    for name, rs in scenes.items():
        pts = [(r["particles"], r["snr_db"]) for r in rs if r["snr_db"] is not None]
        if pts:
            ax.plot(*zip(*pts), marker="o", label=f"GestureCAM, {name} ({rs[0]['skin_pct']:.2f}% skin)")
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

    fig, ax = plt.subplots(figsize=(7, 5.5))
    for name, rs in scenes.items():
        ax.plot([r["particles"] for r in rs], [r["ms_per_frame"] for r in rs], marker="o",
                label=f"GestureCAM, {name}")
    ax.plot(*THESIS_MS, linestyle="--", marker="s", color="black",
            label="thesis (2003 desktop, whole iteration)")
    conv = data["baseline"][0]["convert_ms"]
    ax.axhline(conv, color="grey", linestyle=":", label=f"one BGR->RGB pass ({conv:.3f} ms)")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("particles per eye")
    ax.set_ylabel("ms per frame per eye")
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
        "| scene | skin % | particles | SNR dB | mean IoU | tracked | lost frames | ms/frame/eye | x conversion |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for r in data["tracker"]:
        ratio = r["ms_per_frame"] / b["convert_ms"] if b["convert_ms"] else float("nan")
        out.append(f"| {r['scene']} | {fmt(r['skin_pct'], 2)} | {r['particles']} | "
                   f"{fmt(r['snr_db'], 2)} | {fmt(r['mean_iou'], 3)} | "
                   f"{fmt(r['tracked_fraction'], 3)} | {fmt(r['lost_frames'], 1)} | "
                   f"{fmt(r['ms_per_frame'], 2)} | {fmt(ratio, 1)} |")
    peers = data.get("peer", [])
    if peers:
        out += ["", f"OpenCV's trackers on the same frames (ours at {peers[0]['particles']} particles):",
                "", "| scene | tracker | box IoU | ms/frame | frames scored |", "|---|---|---|---|---|"]
        for p in peers:
            out.append(f"| {p['scene']} | {p['tracker']} | {fmt(p['box_iou'], 3)} | "
                       f"{fmt(p['ms_per_frame'], 2)} | {p['frames']} |")
    for s in data.get("stereo", []):
        out += ["", f"Stereo, {s['scene']} scene, {s['particles']} particles per eye:", "",
                "| 3D step ms/stereo frame | 3D valid frames | median direction error deg | "
                "median palm error mm | pipeline frames/s (2 threads) |",
                "|---|---|---|---|---|",
                f"| {fmt(s['estimate_ms'], 2)} | {s['valid_3d']}/{s['frames']} | "
                f"{fmt(s['direction_error_deg'], 1)} | {fmt(s['palm_error_mm'], 0)} | "
                f"{fmt(s['pipeline_fps'], 1)} |"]
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
