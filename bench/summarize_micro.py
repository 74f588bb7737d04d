#!/usr/bin/env python3
"""Prints Google Benchmark JSON output of rviz_projector_microbench as a compact table.

A row whose label is "vs=<baseline name>" is compared with that baseline at the same size:
ratio = our time / the baseline's time (below 1: faster than the reference pipeline).
With repetitions, the median aggregate is used.

usage: summarize_micro.py RESULTS.json
"""
import json
import sys

UNITS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def human_time(seconds):
    for unit, scale in (("s", 1.0), ("ms", 1e-3), ("us", 1e-6)):
        if seconds >= scale:
            return "%.3g %s" % (seconds / scale, unit)
    return "%.3g ns" % (seconds / 1e-9)


def human_rate(per_second):
    for suffix, scale in (("G", 1e9), ("M", 1e6), ("k", 1e3)):
        if per_second >= scale:
            return "%.3g %s/s" % (per_second / scale, suffix)
    return "%.3g /s" % per_second


def load(path):
    with open(path) as f:
        data = json.load(f)
    rows = {}
    order = []
    for b in data.get("benchmarks", []):
        if b.get("error_occurred"):
            name = b.get("run_name", b["name"])
            rows[name] = {"error": b.get("error_message", "error")}
            order.append(name)
            continue
        kind = b.get("run_type", "iteration")
        if kind == "aggregate" and b.get("aggregate_name") != "median":
            continue
        name = b.get("run_name", b["name"])
        if kind == "iteration" and name in rows:
            continue  # repetitions without aggregates: keep the first
        # CPU time of the benchmark thread: robust against other load on a shared machine (items/s
        # are computed from it too).
        seconds = b["cpu_time"] * UNITS[b.get("time_unit", "ns")]
        if name not in rows:
            order.append(name)
        rows[name] = {
            "seconds": seconds,
            "items": b.get("items_per_second"),
            "arrows": b.get("arrows"),
            "label": b.get("label", ""),
        }
    return data.get("context", {}), rows, order


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    context, rows, order = load(sys.argv[1])
    table = []
    for name in order:
        row = rows[name]
        base, _, size = name.rpartition("/")
        if "error" in row:
            table.append((base, size, "ERROR", row["error"], "", ""))
            continue
        ratio = ""
        label = row["label"]
        if label.startswith("vs="):
            other = rows.get(label[3:] + "/" + size)
            if other and "seconds" in other and other["seconds"] > 0:
                ratio = "%.3f" % (row["seconds"] / other["seconds"])
        table.append((
            base,
            size,
            human_time(row["seconds"]),
            human_rate(row["items"]) if row["items"] else "",
            "%d" % row["arrows"] if row["arrows"] is not None else "",
            ratio,
        ))
    header = ("benchmark", "size", "time", "items/s", "arrows", "ours/baseline")
    widths = [max(len(str(r[i])) for r in table + [header]) for i in range(len(header))]
    aligns = ["<", ">", ">", ">", ">", ">"]

    def fmt(r):
        return "  ".join("{:{}{}}".format(str(c), a, w) for c, a, w in zip(r, aligns, widths))

    build = context.get("library_build_type", "")
    print("microbenchmarks (%s CPUs at %s MHz; load %s; Google Benchmark library build: %s)" % (
        context.get("num_cpus", "?"), context.get("mhz_per_cpu", "?"),
        " ".join("%.2f" % x for x in context.get("load_avg", [])), build or "?"))
    print("size: poses (Spacer, PathUpdate), arrows (ArrowOutline) or measured points (MountSolve); items/s likewise;")
    print("time: CPU time per call;")
    print("ours/baseline: time ratio against the reference pipeline's algorithm on the same input (< 1 is faster)")
    print(fmt(header))
    print("  ".join("-" * w for w in widths))
    for r in table:
        print(fmt(r))


if __name__ == "__main__":
    main()
