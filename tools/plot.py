#!/usr/bin/env python3
"""grainflow plots (python3 + matplotlib, Debian's python3-matplotlib).

Called by the grainflow executable; it decides what to plot, this script only draws:
  plot.py monitors OUTPUT_DIR        one PNG per monitor CSV of a run (OUTPUT_DIR/<monitor>.png),
                                     every column against time, units from the "name [unit]" headers
  plot.py validation SPEC.json ...   one figure per spec written by `grainflow validate`:
                                     {"output", "title", "x_label", "y_label", "log_x", "log_y", "note",
                                      "series": [{"label", "style": line|points|linepoints|dashed, "x", "y"}]}
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

plt.rcParams.update({"font.size": 9, "axes.grid": True, "grid.alpha": 0.3, "figure.dpi": 110})


def read_csv(path):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    if not rows:
        return [], []
    header, data = rows[0], []
    for r in rows[1:]:
        try:
            data.append([float(c) for c in r])
        except ValueError:
            continue
    columns = [[row[i] for row in data if i < len(row)] for i in range(len(header))]
    return header, columns


def plot_monitor(path):
    header, columns = read_csv(path)
    if len(header) < 2 or not columns[0]:
        print(f"plot: {path}: no data, skipped")
        return None
    n = len(header) - 1
    fig, axes = plt.subplots(n, 1, sharex=True, figsize=(6.4, 1.2 + 1.6 * n), squeeze=False)
    for i in range(n):
        ax = axes[i][0]
        ax.plot(columns[0], columns[i + 1], lw=1.2)
        ax.set_ylabel(header[i + 1])
    axes[-1][0].set_xlabel(header[0])
    axes[0][0].set_title(os.path.splitext(os.path.basename(path))[0])
    fig.tight_layout()
    out = os.path.splitext(path)[0] + ".png"
    fig.savefig(out)
    plt.close(fig)
    return out


def finite_pairs(x, y, log_x, log_y):
    pairs = [(a, b) for a, b in zip(x, y)
             if a is not None and b is not None and math.isfinite(a) and math.isfinite(b)
             and (not log_x or a > 0) and (not log_y or b > 0)]
    return [p[0] for p in pairs], [p[1] for p in pairs]


def plot_validation(spec_path):
    with open(spec_path) as f:
        spec = json.load(f)
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    styles = {
        "line": dict(ls="-", lw=1.6),
        "dashed": dict(ls="--", lw=1.2, color="k"),
        "points": dict(ls="none", marker="o", ms=5, mfc="none", mew=1.3),
        "linepoints": dict(ls="-", marker="s", ms=4, lw=1.2),
    }
    for s in spec["series"]:
        x, y = finite_pairs(s["x"], s["y"], spec.get("log_x"), spec.get("log_y"))
        if not x:
            continue
        style = dict(styles.get(s.get("style", "line"), styles["line"]))
        if s.get("style") == "points" and s.get("label", "").startswith("reference"):
            style["color"] = "k"
        ax.plot(x, y, label=s.get("label", ""), **style)
    if spec.get("log_x"):
        ax.set_xscale("log")
    if spec.get("log_y"):
        ax.set_yscale("log")
    ax.set_xlabel(spec.get("x_label", ""))
    ax.set_ylabel(spec.get("y_label", ""))
    ax.set_title(spec.get("title", ""), fontsize=10)
    if spec["series"]:
        ax.legend(fontsize=8, loc="best")
    note = spec.get("note", "")
    lines = note.split("\n") if note else []
    if len(lines) > 8:
        lines = lines[:8] + [f"... ({len(lines) - 8} more)"]
    fig.tight_layout()
    if lines:  # the compared numbers as a caption under the axes
        height = fig.get_figheight()
        extra = 0.12 * len(lines) + 0.08
        fig.set_figheight(height + extra)
        params = fig.subplotpars
        fig.subplots_adjust(bottom=(params.bottom * height + extra) / (height + extra),
                            top=(params.top * height + extra) / (height + extra))
        fig.text(0.01, 0.01, "\n".join(lines), fontsize=7, va="bottom", ha="left", family="monospace")
    fig.savefig(spec["output"])
    plt.close(fig)
    return spec["output"]


def main(argv):
    if len(argv) < 3 or argv[1] not in ("monitors", "validation"):
        print(__doc__, file=sys.stderr)
        return 2
    written = []
    if argv[1] == "monitors":
        directory = argv[2]
        for name in sorted(os.listdir(directory)):
            if name.endswith(".csv"):
                out = plot_monitor(os.path.join(directory, name))
                if out:
                    written.append(out)
    else:
        for spec in argv[2:]:
            written.append(plot_validation(spec))
    for w in written:
        print(f"plot: wrote {w}")
    return 0 if written else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv))
