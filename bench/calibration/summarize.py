#!/usr/bin/env python3
"""The table of scripts/bench --calibration: each run's seconds (from calibrate_projector's 'Took'
line) and its mount error against the rig's truth (test/process/camera_calibration_rig.launch:
x 0.15, y 0, z 1.2, roll 0, pitch 0.8760580505981934, yaw 0), next to the protocol's lower bound.

    summarize.py RESULTS_DIR RUNS
"""
import math
import os
import re
import sys

import yaml

TRUTH = dict(x=0.15, y=0.0, z=1.2, roll=0.0, pitch=0.8760580505981934, yaw=0.0)
PATTERNS = 44          # white, black, 2 x (11 + 10) Gray code frames for 1280x800
SETTLE = 0.15          # calibrate_projector's default --settle
CAMERA_FRAME = 1 / 30  # demo_camera at 30 fps
PROJECTOR_FRAME = 1 / 60


def main():
    out, runs = sys.argv[1], int(sys.argv[2])
    bound = PATTERNS * (SETTLE + CAMERA_FRAME + PROJECTOR_FRAME)
    print("# calibrate_projector --camera on the simulated rig, %d runs" % runs)
    print("%-4s %9s %11s %11s %11s %11s" % ("run", "total s", "capture s", "solve s", "mount mm", "max deg"))
    totals = []
    for i in range(1, runs + 1):
        text = open(os.path.join(out, "run-%d.txt" % i)).read()
        took = re.search(r"Took ([0-9.]+) s \(showing and capturing \d+ patterns ([0-9.]+) s, decoding and solving ([0-9.]+) s\)", text)
        mount = yaml.safe_load(open(os.path.join(out, "mount-%d.yaml" % i)))
        mm = 1000 * math.sqrt(sum((mount[k] - TRUTH[k]) ** 2 for k in ("x", "y", "z")))
        deg = max(abs(math.degrees(mount[k] - TRUTH[k])) for k in ("roll", "pitch", "yaw"))
        total, capture, solve = (float(took.group(n)) for n in (1, 2, 3))
        totals.append(total)
        print("%-4d %9.1f %11.1f %11.2f %11.3f %11.4f" % (i, total, capture, solve, mm, deg))
    totals.sort()
    print()
    print("median total %.1f s; the protocol's lower bound (%d patterns x (settle %.2f s + a camera frame "
          "%.3f s + a projector frame %.3f s)) is %.1f s; the issue's limit is 30 s."
          % (totals[len(totals) // 2], PATTERNS, SETTLE, CAMERA_FRAME, PROJECTOR_FRAME, bound))


if __name__ == "__main__":
    main()
