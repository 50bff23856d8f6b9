#!/usr/bin/env python3
"""While one thread of a 2-thread run waits, what does the other one do?

Reads `perf script -F tid,time,ip,sym` output of a run recorded with call graphs
(bench/idle_profile.sh) and, for each of the two busiest threads, takes its samples that sit in
a wait (the OpenMP runtime, a gf::TeamBarrier, an unresolved frame) and looks up the other
thread's sample nearest in time (within --window seconds). Prints, per waiting thread, the share
of its samples spent waiting and what the other thread was running then, as the frames just
below gf::app::Simulation::advance (for a worker thread, whose stack starts in the OpenMP
runtime, its outermost gf:: frames: the parallel region).

A wait of one thread while the other runs code is time the team loses on that part: a serial
section, an imbalanced split, or a slower core. Usage:
  python3 bench/idle_profile.py SCRIPT.txt [--window 0.0015] [--top 25] [--depth 4]
"""
import argparse
import bisect
import collections
import re
import sys


def read_samples(path):
    """(tid, time, [frames leaf first]) per sample."""
    samples, current = [], None
    with open(path, errors="replace") as f:
        for line in f:
            if not line.strip():
                if current:
                    samples.append(current)
                current = None
                continue
            if not line.startswith("\t"):  # "  TID  TIME: " (frames follow, one per tab-indented line)
                head = line.split()
                try:
                    current = (int(head[0]), float(head[1].rstrip(":")), [])
                except (IndexError, ValueError):
                    current = None
                continue
            if current is not None:
                parts = line.strip().split(None, 1)
                current[2].append(parts[1] if len(parts) > 1 else "?")
    if current:
        samples.append(current)
    return samples


def waiting(frames):
    """A sample in a wait: OpenMP runtime (libgomp's frames, unresolved: "[unknown]"), a team barrier."""
    if not frames:
        return True
    top = frames[0]
    return top.startswith("[unknown]") or top == "?" or "gomp" in top.lower() or "TeamBarrier" in top


def label(frames, depth):
    short = [re.sub(r"\(.*", "", f)[:70] for f in frames]
    for i, f in enumerate(short):
        if "Simulation::advance" in f or "Simulation::run" in f:
            chain = short[max(0, i - depth):i]
            return " < ".join(reversed(chain)) if chain else f
    # a worker's stack starts in the OpenMP runtime: its outermost gf:: frames (the parallel region)
    ours = [f for f in short if f.startswith("gf::")]
    if ours:
        return " < ".join(reversed(ours[-min(depth, 2):]))
    return short[0] if short else "?"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("script")
    ap.add_argument("--window", type=float, default=0.0015, help="largest time gap of a matched pair (s)")
    ap.add_argument("--top", type=int, default=25)
    ap.add_argument("--depth", type=int, default=4, help="frames below Simulation::advance in a label")
    args = ap.parse_args()
    samples = read_samples(args.script)
    counts = collections.Counter(s[0] for s in samples)
    busiest = [tid for tid, _ in counts.most_common(2)]
    if len(busiest) < 2:
        sys.exit("idle_profile: fewer than two threads in the recording")
    by_thread = {tid: [s for s in samples if s[0] == tid] for tid in busiest}
    for me, other in (busiest, busiest[::-1]):
        mine, theirs = by_thread[me], by_thread[other]
        times = [s[1] for s in theirs]
        histogram, waits, matched = collections.Counter(), 0, 0
        for _, t, frames in mine:
            if not waiting(frames):
                continue
            waits += 1
            k = bisect.bisect_left(times, t)
            best = min((j for j in (k - 1, k) if 0 <= j < len(times)), key=lambda j: abs(times[j] - t), default=None)
            if best is None or abs(times[best] - t) > args.window:
                continue
            matched += 1
            histogram[label(theirs[best][2], args.depth)] += 1
        print(f"thread {me}: {len(mine)} samples, waiting in {waits} ({100.0 * waits / max(1, len(mine)):.1f} %); "
              f"thread {other} meanwhile ({matched} matched), share of thread {me}'s samples:")
        for name, n in histogram.most_common(args.top):
            print(f"  {100.0 * n / len(mine):5.1f} %  {name}")
        print()


if __name__ == "__main__":
    main()
