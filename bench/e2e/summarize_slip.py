#!/usr/bin/env python3
"""Turns the motion slip probe's measurements (scripts/bench --slip) into the table of issue 14.

usage: summarize_slip.py SLIP.tsv [MACHINE.txt] [--note TEXT]...

SLIP.tsv lines (tab separated), from rviz_projector_slip_probe:
  slip  SETTING  LAG_MS  MOTION  T_MS  APPEAR  SLIP_MM  [SPEED_M_PER_S]
  meta  SETTING  LAG_MS  MOTION  KEY   VALUE
Prints, per motion and setting (compensation off/on x projector lag 0/30 ms), median, 95th
percentile and max of |slip|, the mean signed slip and the delay it amounts to (mean slip / mean
speed across the stripes), continuous (every sample) and at appearance (samples where a new frame
showed up), and the targets with compensation.
"""
import collections
import math
import sys

MOTIONS = [
    ("still", "still robot (geometry check)"),
    ("turn", "turn in place, 0.5 rad/s"),
    ("straight", "straight, 1 m/s"),
    ("scurve", "S-curve, 0.7 m/s, 0.6 sin rad/s"),
    ("scurve-steps", "stress: yaw-rate steps +-0.6"),
]
STRESS = {"scurve-steps"}  # reported, not held to the targets: a yaw-rate step cannot be predicted
TARGETS = [  # (label, figure key, limit): with compensation, continuous
    ("continuous median <= 6 mm", "median", 6.0),
    ("continuous p95 <= 12 mm", "p95", 12.0),
    ("|mean signed| <= 2 mm", "abs_mean", 2.0),
]


def percentile(sorted_values, q):
    """Linear interpolation between closest ranks (numpy's default)."""
    if not sorted_values:
        return math.nan
    pos = (len(sorted_values) - 1) * q
    lo = math.floor(pos)
    hi = min(lo + 1, len(sorted_values) - 1)
    return sorted_values[lo] + (sorted_values[hi] - sorted_values[lo]) * (pos - lo)


def figures(values, speeds):
    if not values:
        return None
    magnitudes = sorted(abs(v) for v in values)
    mean = sum(values) / len(values)
    mean_speed = sum(speeds) / len(speeds) if len(speeds) == len(values) else 0.0
    return {
        "delay": mean / mean_speed if mean_speed > 0.05 else math.nan,  # mm / (m/s) = ms
        "median": percentile(magnitudes, 0.5),
        "p95": percentile(magnitudes, 0.95),
        "max": magnitudes[-1],
        "mean": mean,
        "abs_mean": abs(mean),
        "n": len(values),
    }


def load(path):
    # (setting, lag, motion) -> (all slips, at appearance, all speeds, speeds at appearance)
    slips = collections.defaultdict(lambda: ([], [], [], []))
    meta = collections.defaultdict(dict)
    with open(path) as f:
        for line in f:
            parts = line.rstrip("\n").split("\t")
            if parts[0] == "slip" and len(parts) in (7, 8):
                key = (parts[1], float(parts[2]), parts[3])
                value = float(parts[6])
                slips[key][0].append(value)
                if parts[5] == "1":
                    slips[key][1].append(value)
                if len(parts) == 8:
                    slips[key][2].append(float(parts[7]))
                    if parts[5] == "1":
                        slips[key][3].append(float(parts[7]))
            elif parts[0] == "meta" and len(parts) == 6:
                meta[(parts[1], float(parts[2]), parts[3])][parts[4]] = float(parts[5])
    return slips, meta


def fmt(fig, key):
    if fig is None or math.isnan(fig[key]):
        return "-"
    return ("%+.1f" if key in ("mean", "delay") else "%.1f") % fig[key]


def main(argv):
    args, notes = [], []
    i = 1
    while i < len(argv):
        if argv[i] == "--note" and i + 1 < len(argv):
            notes.append(argv[i + 1])
            i += 2
        else:
            args.append(argv[i])
            i += 1
    if not args:
        sys.exit(__doc__)
    slips, meta = load(args[0])
    if len(args) > 1:
        with open(args[1]) as f:
            print(f.read().rstrip())
        print()
    settings = sorted({(k[0], k[1]) for k in slips} | {(k[0], k[1]) for k in meta if k[2] != "setup"},
                      key=lambda s: (s[0] != "off", s[1]))
    print("Motion slip of world-locked floor stripes (issue 14): rviz --disable-anti-aliasing, ProjectorCamera 60 Hz limit,")
    print("robot tf 50 Hz; |slip| in mm across the stripe (median / p95 / max), mean signed slip (+ = lags behind the motion)")
    print("and the delay it amounts to in ms (mean slip / mean speed of the floor across the stripes).")
    print("continuous = every ~1 ms sample of one row of the projector window (what a person sees); at appearance = samples")
    print("where a new frame showed up. lag = simulated projector input lag (added to the truth; 'on, lag 30' sets")
    print("Projector input lag: 30 ms; 'off, lag 0' and 'off, lag 30' are the same run: without compensation the rendering")
    print("does not depend on the projector's lag).")
    for note in notes:
        print("NOTE: " + note)
    print()
    header = "%-30s %-11s %-42s %-41s %-8s %s" % (
        "motion", "setting", "  continuous: med / p95 / max  mean  delay", "appearance: med / p95 / max  mean  delay",
        "frames/s", "targets (with compensation)")
    print(header)
    print("-" * len(header))
    verdicts = []
    for motion, label in MOTIONS:
        printed = False
        for setting, lag in settings:
            key = (setting, lag, motion)
            if key not in slips and key not in meta:
                continue
            printed = True
            cont = figures(slips[key][0], slips[key][2]) if key in slips else None
            appear = figures(slips[key][1], slips[key][3]) if key in slips else None
            fps = meta.get(key, {}).get("frames_per_s", math.nan)
            check = ""
            if setting.startswith("on") and motion != "still" and motion not in STRESS:
                failed = [(t, fig_key, limit) for t, fig_key, limit in TARGETS
                          if cont is None or not cont[fig_key] <= limit]
                check = "PASS" if not failed else "FAIL: " + ", ".join(
                    "%s %s" % (fig_key.replace("abs_mean", "|mean|"), fmt(cont, fig_key)) for _, fig_key, _ in failed)
                verdicts.append((label, lag, check))
            elif setting.startswith("on") and motion in STRESS:
                check = "(stress case, no target)"
            name = "%s, lag %g" % (setting, lag)
            print("%-30s %-17s %6s / %5s / %5s  %6s  %5s    %6s / %5s / %5s  %6s  %5s    %6.1f   %s" % (
                label, name, fmt(cont, "median"), fmt(cont, "p95"), fmt(cont, "max"), fmt(cont, "mean"),
                fmt(cont, "delay"), fmt(appear, "median"), fmt(appear, "p95"), fmt(appear, "max"),
                fmt(appear, "mean"), fmt(appear, "delay"), fps, check))
        if printed:
            print()
    print("Targets with compensation, every motion: continuous median <= 6 mm, p95 <= 12 mm, |mean signed| <= 2 mm.")
    if verdicts:
        passed = sum(1 for v in verdicts if v[2] == "PASS")
        print("  %d of %d motion/lag cases pass" % (passed, len(verdicts)))
    print()
    print("Sampling (per motion and run): samples/s, crossings without a unique nearest stripe (left out), samples with")
    print("no stripe in the row, longest gap between samples:")
    for (setting, lag, motion), m in sorted(meta.items()):
        if motion == "setup" or "samples" not in m:
            continue
        print("  %-8s %-10s %-9s %6.0f/s  ambiguous %4d  empty %4d  max gap %5.1f ms" % (
            setting, "lag %g" % lag, motion, m.get("samples_per_s", math.nan), m.get("crossings_ambiguous", 0),
            m.get("samples_without_stripes", 0), m.get("max_gap_ms", math.nan)))
    print()
    print("Stripes (map frame, 10 mm wide, white on black): still: 0.3 m apart at 45 deg to the row (a pixel of error in")
    print("the sampled column or row shows as ~1 mm); turn: radial every 12 deg around the turning centre; straight: 0.4 m")
    print("apart, normal 20 deg from the travel (across-stripe = 0.94 x the slip along the travel); S-curve: along the mean")
    print("heading, 0.4 m apart (the floor under the row moves sideways, 0.5-1.25 m/s). Crossings farther than 0.4 pitch from")
    print("a stripe are left out (ambiguous). Sampled row: image row 100 (~1.6 m ahead of the projector, ~1.5 mm of floor")
    print("per pixel along the row). Demo projector: 1280x800, fx = fy = 1300, 1.2 m high, beam axis on the floor 1 m ahead.")
    print("Frames: without compensation at the robot's tf rate (50/s: the ProjectorCamera renders only when something shown")
    print("changed); with it every frame's prediction differs, so frames come at the 60 Hz limit.")


if __name__ == "__main__":
    main(sys.argv)
