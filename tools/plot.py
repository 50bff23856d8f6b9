#!/usr/bin/env python3
"""grainflow plots (python3 + matplotlib, Debian's python3-matplotlib).

Called by the grainflow executable; it decides what to plot, this script only draws:
  plot.py monitors OUTPUT_DIR        one PNG per monitor CSV of a run (OUTPUT_DIR/<monitor>.png),
                                     every column against time, units from the "name [unit]" headers;
                                     a profile CSV (rows of one sample share its time, as written by
                                     fluid_line_profile) is drawn against its position column instead
  plot.py validation SPEC.json ...   one figure per spec written by `grainflow validate`:
                                     {"output", "title", "note", "panels": [{"title", "x_label", "y_label",
                                      "log_x", "log_y", "swap_axes", "series": [{"label", "reference",
                                      "style": line|points|linepoints|dashed, "x", "y"}]}]}
                                     (panels side by side; swap_axes draws x on the vertical axis)
"""
import csv
import json
import math
import os
import sys
import textwrap

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


def wrapped(text, width_inches, font_size):
    """Text broken into lines that fit width_inches at font_size (about 0.55 em per character)."""
    if not text:
        return ""
    chars = max(20, int(width_inches * 72.0 / (0.55 * font_size)))
    return "\n".join(textwrap.fill(line, chars) for line in text.split("\n"))


def plot_profile(path, header, columns):
    """Rows of one sample share its time: each value column against the position (column 1), at the
    last sample time and, lighter, at up to four earlier ones."""
    times = sorted(set(columns[0]))
    shown = times[-1:] if len(times) == 1 else [times[int(round(i * (len(times) - 1) / 4))] for i in range(5)]
    shown = sorted(set(shown))
    n = len(header) - 2
    fig, axes = plt.subplots(n, 1, sharex=True, figsize=(6.4, 1.2 + 1.6 * n), squeeze=False)
    for i in range(n):
        ax = axes[i][0]
        for t in shown:
            rows = sorted((x, v) for tt, x, v in zip(columns[0], columns[1], columns[i + 2]) if tt == t)
            last = t == times[-1]
            ax.plot([r[0] for r in rows], [r[1] for r in rows], lw=1.6 if last else 0.9, alpha=1.0 if last else 0.45,
                    label=f"t = {t:g} s")
        ax.set_ylabel(header[i + 2])
    axes[0][0].legend(fontsize=7, loc="best")
    axes[-1][0].set_xlabel(header[1])
    name = os.path.splitext(os.path.basename(path))[0]
    axes[0][0].set_title(wrapped(f"{name}: profile along {header[1]}", 6.4, 10), fontsize=10)
    fig.tight_layout()
    out = os.path.splitext(path)[0] + ".png"
    fig.savefig(out)
    plt.close(fig)
    return out


def plot_monitor(path):
    header, columns = read_csv(path)
    if len(header) < 2 or not columns[0]:
        print(f"plot: {path}: no data, skipped")
        return None
    if len(header) >= 3 and len(set(columns[0])) < len(columns[0]):
        return plot_profile(path, header, columns)
    n = len(header) - 1
    fig, axes = plt.subplots(n, 1, sharex=True, figsize=(6.4, 1.2 + 1.6 * n), squeeze=False)
    for i in range(n):
        ax = axes[i][0]
        ax.plot(columns[0], columns[i + 1], lw=1.2)
        ax.set_ylabel(header[i + 1])
    axes[-1][0].set_xlabel(header[0])
    axes[0][0].set_title(wrapped(os.path.splitext(os.path.basename(path))[0], 6.4, 10), fontsize=10)
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


STYLES = {
    "line": dict(ls="-", lw=1.6),
    "dashed": dict(ls="--", lw=1.2, color="k"),
    "points": dict(ls="none", marker="o", ms=5, mfc="none", mew=1.3),
    "linepoints": dict(ls="-", marker="s", ms=4, lw=1.2),
}


def draw_panel(ax, panel, width_inches):
    swap = panel.get("swap_axes", False)
    log_x, log_y = panel.get("log_x", False), panel.get("log_y", False)
    for s in panel.get("series", []):
        x, y = finite_pairs(s["x"], s["y"], log_x, log_y)
        if not x:
            continue
        style = dict(STYLES.get(s.get("style", "line"), STYLES["line"]))
        if s.get("reference"):
            style["color"] = "k"
        if swap:
            x, y = y, x
        ax.plot(x, y, label=s.get("label", ""), **style)
    if log_x:
        ax.set_yscale("log") if swap else ax.set_xscale("log")
    if log_y:
        ax.set_xscale("log") if swap else ax.set_yscale("log")
    x_label, y_label = panel.get("x_label", ""), panel.get("y_label", "")
    if swap:
        x_label, y_label = y_label, x_label
    ax.set_xlabel(x_label)
    ax.set_ylabel(y_label)
    if panel.get("title"):
        ax.set_title(wrapped(panel["title"], width_inches, 9), fontsize=9)
    if panel.get("series"):
        ax.legend(fontsize=8, loc="best")


def plot_validation(spec_path):
    with open(spec_path) as f:
        spec = json.load(f)
    panels = spec.get("panels")
    if panels is None:  # a one-panel spec: the panel's keys at the top level
        panels = [dict(spec, title="")]
    n = max(1, len(panels))
    panel_width = 6.4 if n == 1 else 5.0
    width = panel_width * n
    fig, axes = plt.subplots(1, n, figsize=(width, 4.4 if n == 1 else 4.8), squeeze=False)
    for ax, panel in zip(axes[0], panels):
        draw_panel(ax, panel, panel_width)
    # Titles and captions are wrapped to the figure's width, so no text runs off its edges.
    title = wrapped(spec.get("title", ""), width, 10)
    if n == 1:
        axes[0][0].set_title(title, fontsize=10)
    elif title:
        fig.suptitle(title, fontsize=10)
    note = spec.get("note", "")
    lines = note.split("\n") if note else []
    if len(lines) > 8:
        lines = lines[:8] + [f"... ({len(lines) - 8} more)"]
    # monospace at 7 pt: about 0.6 em per character
    chars = max(40, int(width * 72.0 / (0.6 * 7)))
    lines = [w for line in lines for w in (textwrap.wrap(line, chars, subsequent_indent="  ") or [""])]
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
