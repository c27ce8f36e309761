#!/usr/bin/env python3
"""The step-response plot of docs/steering.md: the fixate law against the simulated head.

    python3 docs/plots/make_step_plot.py --build build

runs BUILD/gst-plugin/tools/studies/step_response (simulated time, deterministic), keeps its CSV
in docs/plots/step_response.csv and writes docs/plots/step_response.png. With --csv FILE
it plots an existing CSV instead of running the program. Needs matplotlib (Debian:
apt-get install python3-matplotlib); only the documentation needs it.
"""
import argparse
import csv
import pathlib
import subprocess
import sys

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent.parent
DEAD_BAND_DEG = 1.0  # FixateConfig::dead_band_deg: where the axis stops on purpose


def load(path):
    steps = {}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            s = steps.setdefault(row["step"], {k: [] for k in row if k != "step"})
            for k, v in row.items():
                if k != "step":
                    s[k].append(float(v))
    return steps


def figures(t, x, target):
    """Overshoot, 10-90 % rise time (of the final value), time from which the axis stays
    within the dead band of the target; the definitions of step_response.cpp."""
    sign = 1.0 if target >= 0 else -1.0
    progress = [v * sign for v in x]
    reached = progress[-1]
    overshoot = max(0.0, max(p - abs(target) for p in progress))
    t10 = next(tt for tt, p in zip(t, progress) if p >= 0.1 * reached)
    t90 = next(tt for tt, p in zip(t, progress) if p >= 0.9 * reached)
    settle = 0.0
    for i in range(len(t) - 1, -1, -1):
        if abs(x[i] - target) > DEAD_BAND_DEG:
            settle = t[i + 1] if i + 1 < len(t) else float("nan")
            break
    return overshoot, t90 - t10, settle


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    src = ap.add_mutually_exclusive_group(required=True)
    src.add_argument("--build", help="meson build directory holding gst-plugin/tools/studies/step_response")
    src.add_argument("--csv", help="plot this CSV instead of running the program")
    ap.add_argument("--out", default=str(HERE / "step_response.png"))
    args = ap.parse_args()

    if args.build:
        csv_path = HERE / "step_response.csv"
        exe = pathlib.Path(args.build) / "gst-plugin" / "tools" / "studies" / "step_response"
        if not exe.is_absolute():
            exe = ROOT / exe
        subprocess.run([str(exe), "--csv", str(csv_path)], check=True)
    else:
        csv_path = pathlib.Path(args.csv)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    steps = load(csv_path)
    fig, axes = plt.subplots(2, len(steps), figsize=(5.2 * len(steps), 6.4), sharex=True,
                             gridspec_kw={"height_ratios": [3, 2]}, squeeze=False)
    colours = {"pan": "tab:blue", "tilt": "tab:orange"}
    for col, (name, s) in enumerate(steps.items()):
        top, bottom = axes[0][col], axes[1][col]
        notes = []
        for axis in ("pan", "tilt"):
            target = s[f"target_{axis}_deg"][0]
            c = colours[axis]
            top.axhspan(target - DEAD_BAND_DEG, target + DEAD_BAND_DEG, color=c, alpha=0.12, lw=0)
            top.axhline(target, color=c, ls="--", lw=1)
            top.plot(s["t_s"], s[f"{axis}_deg"], color=c, lw=1.8, label=f"{axis} (target dashed)")
            bottom.step(s["t_s"], s[f"cmd_{axis}_dps"], where="post", color=c, lw=1.4, label=f"{axis} command")
            o, rise, settle = figures(s["t_s"], s[f"{axis}_deg"], target)
            notes.append(f"{axis}: overshoot {o:.2f}°, rise {rise:.2f} s, within 1° at {settle:.2f} s")
            print(f"{name}: {notes[-1]}")
        top.set_title(f"hand appears {name} (deg)\n" + "\n".join(notes), fontsize=9)
        top.set_ylabel("head angle (deg)")
        top.grid(alpha=0.3)
        top.legend(loc="center right", fontsize=8)
        bottom.axhline(0.0, color="grey", lw=0.8)
        bottom.set_ylabel("commanded velocity (deg/s)")
        bottom.set_xlabel("time since the hand appeared (s)")
        bottom.grid(alpha=0.3)
        bottom.legend(loc="upper right", fontsize=8)
    fig.suptitle("Fixate step response: FixateController on the simulated head "
                 "(30 Hz, 10 ms processing, 20 ms head latency; shaded: 1° dead band)", fontsize=10)
    fig.tight_layout()
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
