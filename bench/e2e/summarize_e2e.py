#!/usr/bin/env python3
"""Turns the probe's measurements (scripts/bench --e2e) into the comparison table.

usage: summarize_e2e.py RESULTS.tsv [MACHINE.txt]

RESULTS.tsv lines: pipeline, phase, trial, metric, value (tab separated), from
rviz_projector_bench_probe. Prints min / median / max over the trials of each pipeline, the ratio
of the medians (ours / baseline) and the issue's targets with PASS/FAIL.
"""
import collections
import statistics
import sys

PIPELINES = []  # in the order they appear in the results

# (metric, label, unit format) rows shared by the sections.
RVIZ_CPU = [
    ("cpu.total", "CPU, all pipeline processes [cores]", "%.2f"),
    ("cpu.rviz", "  rviz", "%.2f"),
    ("cpu.rviz.main", "    main thread (Qt, rviz update, OGRE)", "%.2f"),
    ("cpu.rviz.llvmpipe", "    llvmpipe rasterizer threads", "%.2f"),
    ("cpu.rviz.other", "    other threads (ROS, tf)", "%.2f"),
    ("cpu.host", "  projector_host", "%.2f"),
    ("cpu.host.main", "    main thread (Qt, display updates, OGRE)", "%.2f"),
    ("cpu.host.llvmpipe", "    llvmpipe rasterizer threads", "%.2f"),
    ("cpu.host.other", "    other threads (ROS, tf)", "%.2f"),
    ("cpu.image_view", "  image_view", "%.2f"),
]
MACHINE_LOAD = [
    ("cpu.others", "  (other processes on the machine)", "%.2f"),
    ("cpu.steal", "  (hypervisor steal: CPU time this VM did not get)", "%.2f"),
]

# (title, phase, [(metric, label, unit format)])
SECTIONS = [
    ("Robot driving (demo scene)", "drive", [
        ("fps", "frames/s delivered to the output window", "%.1f"),
        ("draws_per_s", "  draws/s reaching the window (changed or not)", "%.1f"),
    ] + RVIZ_CPU + [
        ("cpu.demo", "  demo_navigation", "%.3f"),
        ("cpu.xorg", "  X server", "%.3f"),
        ("cpu.probe", "  (probe, not counted)", "%.3f"),
    ] + MACHINE_LOAD),
    ("Robot stopped, same plan (nothing changing)", "idle", [
        ("fps", "frames/s delivered (content changes)", "%.1f"),
        ("draws_per_s", "  draws/s reaching the window", "%.1f"),
    ] + RVIZ_CPU + [
        ("cpu.demo", "  demo_navigation (stopped)", "%.3f"),
        ("cpu.xorg", "  X server", "%.3f"),
    ] + MACHINE_LOAD),
    ("Path to photon (new path -> first changed pixel of the output window)", None, [
        ("latency:latency_ms", "{poses}-pose path [ms]", "%.1f"),
        ("latency100k:latency_ms", "100,000-pose path [ms]", "%.1f"),
        ("latency:latency_timeout", "  trials without a change within 5 s", "%d"),
    ]),
    ("Robot driving under a 100,000-pose plan (~10,000 arrows)", "drive10k", [
        ("fps", "frames/s delivered", "%.1f"),
        ("cpu.total", "CPU, all pipeline processes [cores]", "%.2f"),
        ("cpu.rviz", "  rviz", "%.2f"),
        ("cpu.rviz.main", "    main thread", "%.2f"),
        ("cpu.rviz.llvmpipe", "    llvmpipe threads", "%.2f"),
        ("cpu.host", "  projector_host", "%.2f"),
        ("cpu.host.main", "    main thread", "%.2f"),
        ("cpu.host.llvmpipe", "    llvmpipe threads", "%.2f"),
    ] + MACHINE_LOAD),
    ("Memory: resident set size (VmRSS) [MB], after the first frame -> after the last phase", None, [
        ("memory_start:rss_mb.rviz", "rviz at start", "%.1f"),
        ("memory_end:rss_mb.rviz", "rviz at the end", "%.1f"),
        ("memory_start:rss_mb.host", "projector_host at start", "%.1f"),
        ("memory_end:rss_mb.host", "projector_host at the end", "%.1f"),
        ("memory_start:rss_mb.image_view", "image_view at start", "%.1f"),
        ("memory_end:rss_mb.image_view", "image_view at the end", "%.1f"),
    ]),
]


def load(path):
    data = collections.defaultdict(list)
    with open(path) as f:
        for line in f:
            parts = line.rstrip("\n").split("\t")
            if len(parts) != 5:
                continue
            pipeline, phase, _trial, metric, value = parts
            if pipeline not in PIPELINES:
                PIPELINES.append(pipeline)
            try:
                data[(pipeline, phase, metric)].append(float(value))
            except ValueError:
                pass
    return data


def stats(values):
    values = [v for v in values if v == v]  # drop NaN
    if not values:
        return None
    return min(values), statistics.median(values), max(values), len(values)


def cell(s, fmt):
    if s is None:
        return "-"
    lo, med, hi, _n = s
    return "%s / %s / %s" % (fmt % lo, fmt % med, fmt % hi)


CONFIGURATIONS = {
    "": "rviz as installed (its render windows use 4x multisampling)",
    "noaa": "rviz --disable-anti-aliasing (no multisampling in any render window)",
}


HOST_REFERENCE = "ours+noaa"


def groups_of(pipelines):
    """[(title, ours, baseline)]: ours<suffix> with baseline<suffix>; host* (projector_host) with
    rviz --disable-anti-aliasing + ProjectorCamera (issue 13's reference); anything else on its own."""
    groups = collections.OrderedDict()
    for p in pipelines:
        base, _, suffix = p.partition("+")
        if base.startswith("host"):
            reference = HOST_REFERENCE if HOST_REFERENCE in pipelines else None
            groups[("host", p)] = {
                "title": "projector_host (no rviz GUI; %s) vs %s" % (
                    "projector Anti-aliasing on" if base == "host" else
                    "projector Anti-aliasing off" if "aaoff" in p else "config bench/e2e/%s.rviz" % base,
                    "rviz --disable-anti-aliasing + ProjectorCamera" if reference else "nothing (no ours+noaa run)"),
                "ours": p, "baseline": reference}
            continue
        if base.startswith("ours-"):
            # A variant of ours (e.g. ours-marching: a cue animating) against ours with the same options.
            reference = "ours" + ("+" + suffix if suffix else "")
            groups[("variant", p)] = {
                "title": "%s vs %s (same scene, same options)" % (p, reference if reference in pipelines else "nothing"),
                "ours": p, "baseline": reference if reference in pipelines else None}
            continue
        if base in ("ours", "baseline"):
            key = ("pair", suffix)
            title = CONFIGURATIONS.get(suffix, "rviz with +" + suffix)
        else:
            key = ("single", p)
            title = p
        g = groups.setdefault(key, {"title": title, "ours": None, "baseline": None})
        g["baseline" if base == "baseline" else "ours"] = p
    return [(g["title"], g["ours"], g["baseline"]) for g in groups.values()]


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    data = load(sys.argv[1])
    if len(sys.argv) > 2:
        with open(sys.argv[2]) as f:
            print(f.read().rstrip())
        print()

    def get(pipeline, phase, metric):
        if pipeline is None:
            return None
        if ":" in metric:
            phase, metric = metric.split(":")
        values = data.get((pipeline, phase, metric))
        if metric == "latency_timeout":
            trials = len(data.get((pipeline, phase, "latency_ms"), [])) + len(values or [])
            return (sum(values or []),) * 3 + (trials,) if trials else None
        return stats(values) if values else None

    poses = [get(p, "setup", "latency_poses") for p in PIPELINES]
    poses = {int(v[1]) for v in poses if v}
    poses_text = "/".join(str(n) for n in sorted(poses)) if poses else "45"  # older probes: 45

    print("ours = ProjectorCamera full-screen window on the projector screen; baseline = the same scene "
          "through its Image output (sensor_msgs/Image) shown 1:1 in image_view on the projector screen.")
    print("min / median / max over the trials; ratio = median ours / median baseline (host: median host / median "
          "ours+noaa). CPU in cores (1.00 = one core busy), from /proc/<pid>/stat over each trial.")
    warnings = []
    for title, ours, baseline in groups_of(PIPELINES):
        print()
        print("=" * 100)
        print(title)
        for p in (ours, baseline):
            geometry = [get(p, "setup", "watched_" + k) for k in ("width", "height", "x", "y")]
            if p and None not in geometry:
                print("  %s: output watched at %dx%d+%d+%d of the X screen" % ((p,) + tuple(int(g[1]) for g in geometry)))
            on_top = get(p, "setup", "window_on_top_at_end")
            if on_top is not None and on_top[1] < 1:
                warnings.append("%s: its output window was not on top at the end: pixels of another window "
                                "may have been counted" % p)
        print("=" * 100)
        rows = []
        for section, phase, metrics in SECTIONS:
            rows.append((section,))
            for metric, label, fmt in metrics:
                cells = [get(ours, phase, metric), get(baseline, phase, metric)]
                if all(c is None for c in cells):
                    continue
                ratio = ""
                comparable = metric not in ("cpu.others", "cpu.steal", "cpu.probe") and "timeout" not in metric
                if comparable and cells[0] and cells[1] and cells[1][1] > 0:
                    ratio = "%.2f" % (cells[0][1] / cells[1][1])
                n = "/".join(sorted({str(c[3]) for c in cells if c}))
                rows.append((label.format(poses=poses_text), cell(cells[0], fmt), cell(cells[1], fmt), ratio, n))
        header = ("", "%s: min / median / max" % (ours or "-"), "%s: min / median / max" % (baseline or "-"),
                  "ratio", "trials")
        body = [r for r in rows if len(r) > 1]
        widths = [max(len(r[i]) for r in body + [header]) for i in range(len(header))]
        print("  ".join("{:<{}}".format(h, w) for h, w in zip(header, widths)).rstrip())
        for row in rows:
            if len(row) == 1:
                print()
                print(row[0])
                continue
            print("  ".join("{:<{}}".format(c, w) for c, w in zip(row, widths)).rstrip())
        if ours and ours.startswith("host"):
            print_host_targets(get, ours, baseline)
        elif ours and not ours.startswith("ours-"):
            print_targets(get, ours, baseline)
        for metric, what in (("cpu.others", "other processes used"), ("cpu.steal", "the hypervisor stole")):
            values = [get(p, ph, metric) for p in (ours, baseline) for ph in ("drive", "idle", "drive10k")]
            values = [v[1] for v in values if v is not None]
            if values and max(values) > 0.15:
                warnings.append("%s: %s up to %.2f cores during the trials (median of a phase)" % (
                    title, what, max(values)))
    print()
    print("Notes: frames/s = content changes of the watched rectangle per second (XDamage-triggered "
          "MIT-SHM grabs compared pixel by pixel);")
    print("  a driving trial reads 0 while the robot stands at a goal (its plan then ends under it: the "
          "projector shows black). draws/s = drawing")
    print("  operations reaching the rectangle, changed or not. Latency: robot stopped, a %s-pose (or "
          "100,000-pose) path published in base_link," % poses_text)
    print("  timed from just before publish() to the damage event of the first changed grab. host = projector_host "
          "(bench/e2e/host.rviz: the ours scene, projector Anti-aliasing on).")
    if warnings:
        print()
        print("WARNING: the machine was not idle, figures are pessimistic:")
        for w in warnings:
            print("  " + w)


# The targets (issue 5). Absolute: (text, phase, metric, statistic 1 = median / 2 = max,
# format, met). Relative to the baseline's median CPU: (text, phase, largest ratio allowed).
TARGETS = [
    ("latency median <= 35 ms", "latency", "latency_ms", 1, "%.1f ms", lambda v: v <= 35),
    ("latency max <= 60 ms", "latency", "latency_ms", 2, "%.1f ms", lambda v: v <= 60),
    ("latency, 100,000-pose path, median <= 50 ms", "latency100k", "latency_ms", 1, "%.1f ms", lambda v: v <= 50),
    ("driving: >= 55 frames/s delivered", "drive", "fps", 1, "%.1f /s", lambda v: v >= 55),
    ("10,000 arrows: >= 30 frames/s", "drive10k", "fps", 1, "%.1f /s", lambda v: v >= 30),
]
CPU_TARGETS = [
    ("driving: CPU <= baseline's", "drive", 1.0),
    ("nothing changing: CPU <= 0.3 x baseline's", "idle", 0.3),
]


def print_targets(get, ours, baseline):
    """The targets, checked against the medians / maxima above: PASS, FAIL or n/a."""
    checks = []
    for text, phase, metric, statistic, fmt, met in TARGETS:
        s = get(ours, phase, metric)
        value = None if s is None else s[statistic]
        checks.append((text, "n/a" if value is None else fmt % value,
                       "-" if value is None else ("PASS" if met(value) else "FAIL")))
    for text, phase, limit in CPU_TARGETS:
        ours_cpu, baseline_cpu = get(ours, phase, "cpu.total"), get(baseline, phase, "cpu.total")
        if ours_cpu is None or baseline_cpu is None or baseline_cpu[1] <= 0:
            checks.append((text, "n/a", "-"))
            continue
        ratio = ours_cpu[1] / baseline_cpu[1]
        checks.append((text, "%.2f vs %.2f cores (%.2fx)" % (ours_cpu[1], baseline_cpu[1], ratio),
                       "PASS" if ratio <= limit else "FAIL"))
    print()
    print("Targets (issue 5) for %s" % ours)
    w = max(len(c[0]) for c in checks)
    for text, value, verdict in checks:
        print("  {:<{}}  {:<4}  {}".format(text, w, verdict, value))


# Issue 13's targets for projector_host, same shapes as TARGETS / CPU_TARGETS; the CPU ratio is
# against rviz --disable-anti-aliasing + ProjectorCamera (ours+noaa) in the same run.
HOST_TARGETS = [
    ("driving: >= 58 frames/s delivered (Anti-aliasing on)", "drive", "fps", 1, "%.1f /s", lambda v: v >= 58),
    ("latency median <= 12 ms", "latency", "latency_ms", 1, "%.1f ms", lambda v: v <= 12),
    ("latency max <= 25 ms", "latency", "latency_ms", 2, "%.1f ms", lambda v: v <= 25),
    ("latency, 100,000-pose path, median <= 30 ms", "latency100k", "latency_ms", 1, "%.1f ms", lambda v: v <= 30),
    ("nothing changing: CPU <= 0.05 core", "idle", "cpu.total_gui", 1, "%.3f cores", lambda v: v <= 0.05),
    ("driving: CPU <= 0.35 core", "drive", "cpu.total_gui", 1, "%.2f cores", lambda v: v <= 0.35),
]
HOST_CPU_TARGETS = [
    ("driving: CPU <= 0.75 x rviz --disable-anti-aliasing + ProjectorCamera", "drive", 0.75),
]


def print_host_targets(get, host, reference):
    """Issue 13's targets. CPU = the projector_host process (the reference: the rviz process)."""
    checks = []
    for text, phase, metric, statistic, fmt, met in HOST_TARGETS:
        if metric == "cpu.total_gui":
            metric = "cpu.host"
        s = get(host, phase, metric)
        value = None if s is None else s[statistic]
        checks.append((text, "n/a" if value is None else fmt % value,
                       "-" if value is None else ("PASS" if met(value) else "FAIL")))
    for text, phase, limit in HOST_CPU_TARGETS:
        host_cpu, ref_cpu = get(host, phase, "cpu.host"), get(reference, phase, "cpu.rviz")
        if host_cpu is None or ref_cpu is None or ref_cpu[1] <= 0:
            checks.append((text, "n/a (needs %s in the same run)" % HOST_REFERENCE, "-"))
            continue
        ratio = host_cpu[1] / ref_cpu[1]
        checks.append((text, "%.2f vs %.2f cores (%.2fx)" % (host_cpu[1], ref_cpu[1], ratio),
                       "PASS" if ratio <= limit else "FAIL"))
    print()
    print("Targets (issue 13) for %s (CPU: the projector_host process vs the rviz process)" % host)
    w = max(len(c[0]) for c in checks)
    for text, value, verdict in checks:
        print("  {:<{}}  {:<4}  {}".format(text, w, verdict, value))


if __name__ == "__main__":
    main()
