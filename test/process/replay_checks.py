#!/usr/bin/env python3
"""The replay test's three checks (test/process/replay_test.py describes them and their
tolerances): a mixin of ReplaySession, reading what the session saw (self.runs, self.facts,
self.diagnostics, self.first_lit_wall)."""
import os
import sys

from diagnostic_msgs.msg import DiagnosticStatus

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rviz_process import sanitize_run  # noqa: E402
from replay_support import compare, log  # noqa: E402

BLANK_MARGIN = 0.5        # s of running wall time after the first path is due
FIRST_PICTURE_TIMEOUT = 10.0  # s: the host's very first picture (its first render after start-up)
FREEZE_BAG_SECONDS = 0.5
FREEZE_MOTION = (0.05, 5.0)  # m, deg
OLD_PICTURE_AFTER = (0.3, 0.5)  # s of bag time, s of wall time into a new pass


class ReplayChecks(object):
    """Each check returns its problems ([] when it holds)."""

    def check_same_pictures(self):
        problems = []
        reference_run = self.runs[0]
        # The reference of each checkpoint: the first pass at rate 1. The session's very first
        # checkpoint comes 0.3 s into the host's first pass: its first picture may take longer (as
        # check 2 allows, FIRST_PICTURE_TIMEOUT; seen in CI: the first plan waited for its tf). Then
        # pass 2 of rate 1 is the reference, for every rate.
        references = {}
        for k in range(len(self.facts.checkpoints)):
            reference = reference_run.checkpoints.get((1, k))
            if reference is not None and k == 0 and reference[0].blank():
                log("rate %g checkpoint 0 of pass 1 blank (the host's first picture): pass 2 is the reference"
                    % reference_run.rate)
                reference = reference_run.checkpoints.get((2, k))
                if reference is None:
                    problems.append("rate %g: no picture of checkpoint 0 on pass 2" % reference_run.rate)
                    continue
                references[k] = (reference, 2)
            elif reference is None:
                problems.append("rate %g: no picture of checkpoint %d on pass 1" % (reference_run.rate, k))
            else:
                references[k] = (reference, 1)
        for run in self.runs:
            problems += run.problems
            for k, (reference, reference_pass) in sorted(references.items()):
                # Within a rate: every pass against its first (the reference run: against the reference).
                first_pass = reference_pass if run is reference_run else 1
                first = run.checkpoints.get((first_pass, k))
                for p in range(1, run.passes + 1):
                    got = run.checkpoints.get((p, k))
                    if got is None:
                        problems.append("rate %g pass %d: the player never paused at checkpoint %d"
                                        % (run.rate, p, k))
                        continue
                    if run is reference_run and p < first_pass:
                        continue  # the blank first picture, allowed above
                    if first is not None and p != first_pass:
                        for text in compare(first[0], got[0]):
                            problems.append("rate %g checkpoint %d (bag +%.3f s), pass %d vs pass %d: %s"
                                            % (run.rate, k, got[1] - self.facts.start, p, first_pass, text))
                    if run is not reference_run:
                        for text in compare(reference[0], got[0]):
                            problems.append("checkpoint %d (bag +%.3f s), rate %g pass %d vs rate %g pass %d: %s"
                                            % (k, got[1] - self.facts.start, run.rate, p, reference_run.rate,
                                               reference_pass, text))
        return problems

    def check_no_freeze_no_blank(self):
        problems = []
        f = self.facts
        previous_last = None  # the last lit picture before a jump (from the previous pass or run)
        for run in self.runs:
            problems += run.problems
            for p in range(1, run.passes + 1):
                # After the host's start: its first render. After a jump: a path is due.
                due = (FIRST_PICTURE_TIMEOUT if run is self.runs[0] and p == 1
                       else (f.first_path - f.start) / run.rate + BLANK_MARGIN * (3 if sanitize_run() else 1))
                if p not in run.pass_start:
                    problems.append("rate %g: pass %d never started" % (run.rate, p))
                    continue
                start_wall, start_clock = run.pass_start[p]
                samples = [s for s in run.samples if s.pass_index == p]
                # Lit once the pass's first path was replayed (before it, the previous pass's
                # arrows may still show for a moment: rviz resets its displays at its next update).
                lit = [s for s in samples if s.clock >= f.first_path and not s.picture.blank()]
                what = "rate %g pass %d" % (run.rate, p)
                if not lit:
                    problems.append("%s: the picture stayed blank the whole pass (%d grabs)" % (what, len(samples)))
                    continue
                took = run.running_seconds(start_wall, lit[0].wall)
                if took > due:
                    problems.append("%s: blank for %.2f s after the %s (allowed %.2f s: first path at bag +%.2f s, "
                                    "rate %g)" % (what, took, "host's start" if run is self.runs[0] and p == 1
                                                  else "backward jump", due, f.first_path - f.start, run.rate))
                # Frozen after the jump: the previous pass's last picture still shown.
                if previous_last is not None:
                    for s in samples:
                        if (s.clock - start_clock >= OLD_PICTURE_AFTER[0]
                                and s.wall - start_wall >= OLD_PICTURE_AFTER[1]
                                and s.picture.crc == previous_last.picture.crc):
                            problems.append("%s: at bag +%.2f s (%.2f s after the jump) it still shows the last picture "
                                            "of the previous pass" % (what, s.clock - f.start, s.wall - start_wall))
                            break
                # Frozen within the pass while the robot moves.
                frozen = []
                after = [s for s in samples if s.wall >= lit[0].wall]
                for i, a in enumerate(after):
                    b = next((s for s in after[i + 1:] if s.clock >= a.clock + FREEZE_BAG_SECONDS), None)
                    if b is None or run.paused_between(a.wall, b.wall) or a.picture.blank():
                        continue
                    moved, turned = f.motion(a.clock, b.clock)
                    if (moved >= FREEZE_MOTION[0] or turned >= FREEZE_MOTION[1]) and a.picture.crc == b.picture.crc:
                        frozen.append("bag +%.2f..+%.2f s (robot moved %.2f m, turned %.0f deg)"
                                      % (a.clock - f.start, b.clock - f.start, moved, turned))
                if frozen:
                    more = " (%d in all)" % len(frozen) if len(frozen) > 5 else ""
                    problems.append("%s: the picture did not change while the replayed robot moved: %s%s"
                                    % (what, "; ".join(frozen[:5]), more))
                previous_last = lit[-1]
        return problems

    def check_diagnostics(self):
        f = self.facts
        problems = []
        with self.diag_lock:
            received = list(self.diagnostics)
        begin = self.first_lit_wall
        if begin is None:
            return ["projector_host never showed a lit picture: the run did not start"]
        warnings = {}
        errors = {}
        for wall, msg in received:
            if wall < begin:
                continue
            stamp = msg.header.stamp.to_sec()
            for status in msg.status:
                if not status.name.startswith("projector_host:"):
                    continue
                level = {0: "OK", 1: "WARN", 2: "ERROR", 3: "STALE"}.get(status.level, status.level)
                text = "%s [%s] %s" % (status.name, level, status.message)
                if status.level == DiagnosticStatus.WARN:
                    why = self.justify(status, stamp)
                    warnings.setdefault(text, [0, why])[0] += 1
                elif status.level != DiagnosticStatus.OK:  # ERROR or STALE
                    errors.setdefault(text, [0, stamp - f.start])[0] += 1
        for text, (count, first) in sorted(errors.items()):
            log("%s (x%d, first at bag +%.2f s)" % (text, count, first))
            problems.append("%s (x%d, first at bag +%.2f s)" % (text, count, first))
        for text, (count, why) in sorted(warnings.items()):
            log("WARN x%d: %s -- %s" % (count, text, why or "NOT JUSTIFIED"))
            print("WARN x%d: %s -- %s" % (count, text, why or "NOT JUSTIFIED"))
            if why is None:
                problems.append("unexpected WARN (x%d): %s" % (count, text))
        # The statuses must keep coming: at least two in every pass of every rate.
        for run in self.runs:
            for p in range(1, run.passes + 1):
                if p not in run.pass_start:
                    continue
                start = run.pass_start[p][0]
                end = run.pass_start[p + 1][0] if p + 1 in run.pass_start else run.wall[1]
                n = sum(1 for wall, msg in received if start <= wall < end and
                        any(s.name.startswith("projector_host:") for s in msg.status))
                if n < 2:
                    problems.append("rate %g pass %d: %d /diagnostics messages of projector_host in a pass of %.1f s "
                                    "of bag time (%.1f s of wall time; due every second of ROS time)"
                                    % (run.rate, p, n, run.duration or (f.end - f.start), end - start))
        return problems

    def justify(self, status, stamp):
        """Why a WARN status is acceptable in this run, or None."""
        f = self.facts
        if status.name == "projector_host: Projector" and status.message.startswith("Scaling:"):
            return "the test's X screen is not the projector's 1280x800"
        if "Waiting for the transform (" in status.message:
            # ProjectedPath: a path replayed just before the tf of its stamp (a bag plays topics in
            # the order they were recorded); one still waiting after 1 s is an ERROR, checked above.
            return "a path waited a moment for its tf"
        if stamp <= f.start + 1.0 and ("Waiting for tf after ROS time started or jumped back" in status.message or
                                        status.message.startswith("TF (rviz/TF)") or
                                        " (rviz/TF): " in status.message):
            return "tf not replayed yet in this pass (rviz clears its buffer when ROS time jumps back)"
        for text, first, what in (("No path received yet", f.first_path, "path"),
                                  ("No goal status received yet", f.first_status, "goal status"),
                                  ("No scan received yet", f.first_scan, "scan"),
                                  ("No odometry received yet", f.first_odom, "odometry"),
                                  ("No footprint received yet", f.first_footprint, "footprint")):
            if text in status.message and first is not None and stamp <= first + 0.5:
                return "before the pass's first %s (displays are reset when ROS time jumps back)" % what
        return None
