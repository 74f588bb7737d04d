#!/usr/bin/env python3
"""Judges a soak run of projector_host (bench/soak/soak.sh): prints one PASSED / FAILED / SKIPPED
line per check, the RSS figures, and exits 1 when a check failed.

usage: check_soak.py DIR WARMUP_SECONDS RSS_LIMIT_MB HOST_ALIVE(0|1)

DIR holds the soak's files:
  rss.tsv          seconds since the host started, VmRSS in kB (one sample every few seconds)
  reloads.tsv      seconds, 1/0 (the service answered success: True), the answer's message
  diagnostics.tsv  from diagnostics_log.py: seconds, status name, key, value
  host.log         the host's stdout and stderr
Checks:
  - the host is still running at the end
  - RSS growth after warm-up <= RSS_LIMIT_MB: mean of the last 3 samples minus mean of the 3
    samples around the end of the warm-up (the first WARMUP_SECONDS)
  - every reload answered success (and at least one reload happened)
  - no ERROR line in the host's log (ROS_ERROR: "[ERROR]"; also "[FATAL]")
  - OGRE resource counts flat after warm-up ("OGRE meshes", "OGRE materials", "OGRE textures",
    "OGRE scene nodes" in the "projector_host: config" status): the last value <= the first value
    after the warm-up; SKIPPED when the host does not publish them
"""
import statistics
import sys

OGRE_KEYS = ("OGRE meshes", "OGRE materials", "OGRE textures", "OGRE scene nodes")


def read_tsv(path, columns):
    rows = []
    try:
        with open(path) as f:
            for line in f:
                parts = line.rstrip("\n").split("\t")
                if len(parts) >= columns:
                    rows.append(parts)
    except FileNotFoundError:
        pass
    return rows


def main():
    if len(sys.argv) != 5:
        sys.exit(__doc__)
    folder, warmup, limit_mb, alive = sys.argv[1], float(sys.argv[2]), float(sys.argv[3]), sys.argv[4] == "1"
    results = []  # (verdict, text)

    def check(ok, text):
        results.append(("PASSED" if ok else "FAILED", text))

    check(alive, "soak: projector_host still running at the end")

    # ---- RSS
    rss = [(float(t), float(kb) / 1024.0) for t, kb in read_tsv(folder + "/rss.tsv", 2)]
    after = [r for r in rss if r[0] >= warmup]
    if len(rss) < 3 or len(after) < 6:
        check(False, "soak: RSS growth after warm-up: too few samples after %.0f s (%d) - run longer" % (
            warmup, len(after)))
    else:
        start_mb = statistics.mean(m for _, m in after[:3])
        end_mb = statistics.mean(m for _, m in after[-3:])
        growth = end_mb - start_mb
        minutes = (after[-1][0] - after[0][0]) / 60.0
        # Least-squares slope over the samples after the warm-up, MB per minute.
        ts, ms = [t for t, _ in after], [m for _, m in after]
        tm, mm = statistics.mean(ts), statistics.mean(ms)
        den = sum((t - tm) ** 2 for t in ts)
        slope = 60.0 * sum((t - tm) * (m - mm) for t, m in zip(ts, ms)) / den if den > 0 else 0.0
        print("soak: RSS %.1f MB after the first sample, %.1f MB after warm-up (%.0f s), %.1f MB at the end "
              "(%.1f min later), max %.1f MB; growth after warm-up %+.2f MB, trend %+.3f MB/min (%d samples)" % (
                  rss[0][1], start_mb, warmup, end_mb, minutes, max(m for _, m in rss), growth, slope, len(rss)))
        check(growth <= limit_mb, "soak: RSS growth after warm-up %+.2f MB (limit %.1f MB)" % (growth, limit_mb))

    # ---- reloads
    reloads = read_tsv(folder + "/reloads.tsv", 3)
    failed = [r for r in reloads if r[1] != "1"]
    if not reloads:
        check(False, "soak: no reload was called (run longer than one reload period)")
    else:
        check(not failed, "soak: %d of %d reloads answered success%s" % (
            len(reloads) - len(failed), len(reloads),
            "" if not failed else " (first failure at %s s: %s)" % (failed[0][0], failed[0][2])))

    # ---- log
    errors = []
    try:
        with open(folder + "/host.log", errors="replace") as f:
            errors = [line.rstrip() for line in f if "[ERROR]" in line or "[FATAL]" in line]
    except FileNotFoundError:
        errors = ["no host.log"]
    check(not errors, "soak: no ERROR in the host's log" + ("" if not errors else " (%d, first: %s)" % (
        len(errors), errors[0][:200])))

    # ---- OGRE resource counts
    counts = {}
    for t, _name, key, value in read_tsv(folder + "/diagnostics.tsv", 4):
        if key in OGRE_KEYS:
            try:
                counts.setdefault(key, []).append((float(t), float(value)))
            except ValueError:
                pass
    for key in OGRE_KEYS:
        series = [v for t, v in counts.get(key, []) if t >= warmup]
        if not series:
            results.append(("SKIPPED", "soak: %s flat: the host does not publish \"%s\" in \"projector_host: "
                                       "config\" on /diagnostics" % (key, key)))
            continue
        check(series[-1] <= series[0], "soak: %s flat after warm-up: %g -> %g (min %g, max %g)" % (
            key, series[0], series[-1], min(series), max(series)))

    for verdict, text in results:
        print("%s %s" % (verdict, text))
    n = {v: sum(1 for r in results if r[0] == v) for v in ("PASSED", "FAILED", "SKIPPED")}
    print("soak: %d passed, %d failed, %d skipped" % (n["PASSED"], n["FAILED"], n["SKIPPED"]))
    sys.exit(1 if n["FAILED"] else 0)


if __name__ == "__main__":
    main()
