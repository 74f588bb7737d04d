#!/usr/bin/env python3
"""The replay test's pieces (test/process/replay_test.py describes the test and its tolerances):
what a grab of the projector window shows (Picture) and how two compare, what the recorded bag
holds (BagFacts), the player's /clock (ClockWatch), what happened at one rate (RateRun), command
lines as a user types them (ReplayProcess), and rosunit results that report skips."""
import bisect
import math
import os
import signal
import subprocess
import sys
import threading
import time
import zlib
from xmlrpc.client import ServerProxy

import rosbag
import rosgraph

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rviz_process import ProcessUnderTest  # noqa: E402

# Topics of the demo (and the test's own checkpoints) the bag holds.
PATH_TOPIC = "/move_base/TrajectoryPlannerROS/global_plan"
STATUS_TOPIC = "/move_base/status"
SCAN_TOPIC = "/demo/scan"
CHECKPOINT_TOPIC = "/replay_test/checkpoint"
ODOM_TOPIC = "/demo/odom"  # the demo config's Stop zone
FOOTPRINT_TOPIC = "/demo/robot_footprint"  # the demo config's Corridor

# Comparing pictures of the same bag time (see replay_test.py, check 1).
LIT_MIN = 1000            # px: a picture with fewer lit pixels is blank
CLASS_MIN = 300           # px: a colour class is compared when the reference has this many
COUNT_TOLERANCE = 0.15    # of the reference's count
# A lit pixel matches when the other picture has a lit pixel within this many pixels (a square):
# the paused clock stands up to ~25 ms of bag time apart between passes, in which the robot (and
# the projector on it) moves up to 1 cm at the demo's 0.4 m/s, about 8 px; a wrong pose is 40-200 px.
NEAR_PX = 8
CENTROID_TOLERANCE = 3.0  # px

# Byte -> 0/1 tables: a channel above 40 ("lit"), or at most 40 ("dark").
_ABOVE = bytes(1 if v > 40 else 0 for v in range(256))
_BELOW = bytes(0 if v > 40 else 1 for v in range(256))


def log(text):
    """Progress on the terminal of whoever runs the test (rosunit captures sys.stdout)."""
    sys.__stderr__.write("[replay_test] %s\n" % text)
    sys.__stderr__.flush()


class Picture(object):
    """What a grab of the projector window shows: a hash of its pixels, its lit pixels and (full
    analysis) the count and centroid of each colour class."""

    def __init__(self, pixels, full=False):
        d = pixels.data  # BGRX
        self.width, self.height = pixels.width, pixels.height
        self.crc = zlib.crc32(d)
        n = self.width * self.height
        b, g, r = d[0::4], d[1::4], d[2::4]
        rb, gb, bb = (int.from_bytes(c.translate(_ABOVE), "little") for c in (r, g, b))
        self.lit = rb | gb | bb
        self.lit_count = self.lit.bit_count()
        self.classes = {}
        self.pixels = pixels if full else None
        if not full:
            self.lit = None  # 2 MB each: kept only for the full analysis
            return
        rd, gd, bd = (int.from_bytes(c.translate(_BELOW), "little") for c in (r, g, b))
        for name, mask in (("magenta", rb & bb & gd), ("green", gb & rd & bd)):
            count = mask.bit_count()
            self.classes[name] = (count, self._centroid(mask.to_bytes(n, "little"), count))

    def _centroid(self, mask, count):
        if count == 0:
            return None
        w, h = self.width, self.height
        sy = sum(y * mask[y * w:(y + 1) * w].count(1) for y in range(h))
        sx = sum(x * mask[x::w].count(1) for x in range(w))
        return (sx / float(count) + 0.5, sy / float(count) + 0.5)

    def blank(self):
        return self.lit_count < LIT_MIN

    def describe(self):
        parts = ["%d lit" % self.lit_count]
        for name, (count, c) in sorted(self.classes.items()):
            parts.append("%s %d px" % (name, count) + (" at (%.1f, %.1f)" % c if c else ""))
        return ", ".join(parts)

    def save_ppm(self, path):
        d = self.pixels.data
        rgb = bytearray(self.width * self.height * 3)
        rgb[0::3], rgb[1::3], rgb[2::3] = d[2::4], d[1::4], d[0::4]
        with open(path, "wb") as f:
            f.write(b"P6\n%d %d\n255\n" % (self.width, self.height))
            f.write(rgb)


def _near(mask, width):
    """`mask` grown by NEAR_PX pixels in every direction."""
    for _ in range(NEAR_PX):
        mask |= (mask << 8) | (mask >> 8)
    for _ in range(NEAR_PX):
        mask |= (mask << (8 * width)) | (mask >> (8 * width))
    return mask


def compare(reference, picture):
    """Problems of `picture` against `reference` (same bag time), [] when they match."""
    problems = []
    if reference.blank():
        return ["the reference is blank (%d lit px): nothing to compare" % reference.lit_count]
    # One byte per pixel in the masks (bit 8 i is pixel i): shifts of 8 bits move one pixel sideways,
    # of 8 * width bits one row.
    differing = ((reference.lit & ~_near(picture.lit, picture.width)).bit_count() +
                 (picture.lit & ~_near(reference.lit, reference.width)).bit_count())
    if differing > COUNT_TOLERANCE * reference.lit_count:
        problems.append("%d of %d lit pixels have no lit pixel within %d px in the other picture (> %d %%)"
                        % (differing, reference.lit_count, NEAR_PX, round(100 * COUNT_TOLERANCE)))
    for name, (ref_count, ref_c) in sorted(reference.classes.items()):
        if ref_count < CLASS_MIN:
            continue
        count, c = picture.classes[name]
        if abs(count - ref_count) > COUNT_TOLERANCE * ref_count:
            problems.append("%s: %d px, reference %d px" % (name, count, ref_count))
        if c is None:
            problems.append("%s: none shown, reference at (%.1f, %.1f)" % (name, ref_c[0], ref_c[1]))
            continue
        dist = ((c[0] - ref_c[0]) ** 2 + (c[1] - ref_c[1]) ** 2) ** 0.5
        if dist > CENTROID_TOLERANCE:
            problems.append("%s centroid (%.1f, %.1f), reference (%.1f, %.1f): %.1f px apart"
                            % (name, c[0], c[1], ref_c[0], ref_c[1], dist))
    return problems


class BagFacts(object):
    """What the test needs to know about the recorded bag, read with the rosbag API."""

    def __init__(self, path):
        self.start = self.end = None
        self.first_path = None
        self.first_status = None
        self.first_scan = None
        self.first_odom = None
        self.first_footprint = None
        self.checkpoints = []     # bag times of the checkpoint messages
        self.before = []          # bag time of the message played before each checkpoint (for the log)
        self.robot = []           # (bag time, x, y, yaw) of odom -> base_link
        previous = None
        with rosbag.Bag(path) as bag:
            self.start, self.end = bag.get_start_time(), bag.get_end_time()
            for topic, msg, t in bag.read_messages():
                t = t.to_sec()
                if topic == CHECKPOINT_TOPIC:
                    self.checkpoints.append(t)
                    self.before.append(previous)
                elif topic == PATH_TOPIC and self.first_path is None:
                    self.first_path = t
                elif topic == STATUS_TOPIC and self.first_status is None:
                    self.first_status = t
                elif topic == SCAN_TOPIC and self.first_scan is None:
                    self.first_scan = t
                elif topic == ODOM_TOPIC and self.first_odom is None:
                    self.first_odom = t
                elif topic == FOOTPRINT_TOPIC and self.first_footprint is None:
                    self.first_footprint = t
                elif topic == "/tf":
                    for tr in msg.transforms:
                        if tr.child_frame_id == "base_link":
                            q = tr.transform.rotation
                            yaw = math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))
                            self.robot.append((t, tr.transform.translation.x, tr.transform.translation.y, yaw))
                previous = t
        self.robot_times = [r[0] for r in self.robot]

    def pose(self, t):
        """The robot's pose of the newest tf at or before bag time t (the first one for an earlier t)."""
        i = bisect.bisect_right(self.robot_times, t)
        return self.robot[max(0, i - 1)]

    def motion(self, t0, t1):
        """(metres, degrees) the robot moved between bag times t0 and t1."""
        a, b = self.pose(t0), self.pose(t1)
        turn = abs(math.degrees(math.atan2(math.sin(b[3] - a[3]), math.cos(b[3] - a[3]))))
        return math.hypot(b[1] - a[1], b[2] - a[2]), turn


class ClockWatch(object):
    """The /clock of one player: its latest value, when it last changed, and its backward jumps
    (each starts a new pass). Fed from the subscriber thread."""

    def __init__(self):
        self.lock = threading.Lock()
        self.caller = None
        self.value = None
        self.changed = None       # time.monotonic() of the last change
        self.passes = 0           # 1 from the player's first clock on
        self.pass_start = {}      # pass -> (monotonic, first clock of the pass)

    def follow(self, caller):
        with self.lock:
            self.caller = caller
            self.value = self.changed = None
            self.passes = 0
            self.pass_start = {}

    def on_clock(self, msg):
        now = time.monotonic()
        if msg._connection_header.get("callerid") != self.caller:
            return  # a player of an earlier rate (stopped) or another publisher
        value = msg.clock.to_sec()
        with self.lock:
            if self.value is None or value < self.value - 0.5:
                self.passes += 1
                self.pass_start[self.passes] = (now, value)
            if value != self.value:
                self.changed = now
            self.value = value

    def read(self):
        with self.lock:
            return self.passes, self.value, self.changed


class Sample(object):
    def __init__(self, wall, pass_index, clock, picture):
        self.wall, self.pass_index, self.clock, self.picture = wall, pass_index, clock, picture


class RateRun(object):
    """What happened while the bag played at one rate."""

    def __init__(self, rate, passes, duration):
        self.rate, self.passes, self.duration = rate, passes, duration
        self.samples = []          # continuous grabs while running
        self.checkpoints = {}      # (pass, checkpoint index) -> (Picture, clock, settle seconds)
        self.pauses = []           # (monotonic start, end)
        self.pass_start = {}
        self.problems = []         # things that went wrong while playing (not the checks)
        self.wall = (None, None)

    def running_seconds(self, t0, t1):
        """Wall seconds between t0 and t1, without the checkpoint pauses."""
        paused = sum(max(0.0, min(t1, b) - max(t0, a)) for a, b in self.pauses)
        return (t1 - t0) - paused

    def paused_between(self, t0, t1):
        return any(a < t1 and b > t0 for a, b in self.pauses)


def subscriber_connections(publisher, subscriber):
    """(topics `subscriber` subscribes to that `publisher` publishes, those of them on which the two
    are connected), from the master and the publisher's own bus information; None while the
    publisher is not registered or does not answer."""
    master = rosgraph.Master("/replay_test")
    try:
        pubs, subs, _ = master.getSystemState()
        _, _, bus = ServerProxy(master.lookupNode(publisher)).getBusInfo("/replay_test")
    except Exception:  # not registered yet, or starting
        return None
    wanted = ({t for t, nodes in pubs if publisher in nodes} & {t for t, nodes in subs if subscriber in nodes})
    # getBusInfo rows: [id, destination caller id, direction, transport, topic, connected, ...]
    up = {row[4] for row in bus if row[1] == subscriber and row[2] == "o" and row[5]}
    return wanted, up & wanted


class ReplayProcess(ProcessUnderTest):
    """A command line (`rosbag play ...`, `roslaunch ...`) as a user types it, output in a log."""

    def __init__(self, command, label):
        ros_home = os.environ.get("ROS_HOME", os.path.expanduser("~/.ros"))
        log_dir = os.path.join(ros_home, "log")
        os.makedirs(log_dir, exist_ok=True)
        self.log_path = os.path.join(log_dir, "process_test_%s_%d.log" % (label, os.getpid()))
        self.log = open(self.log_path, "w")
        self.proc = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=self.log, stderr=subprocess.STDOUT)
        self.pid = self.proc.pid
        self.exit_time = None

    def interrupt(self, timeout):
        """SIGINT (Ctrl-C: roslaunch stops its nodes, rosbag record closes the bag), then stop()."""
        if self.alive():
            self.proc.send_signal(signal.SIGINT)
            self.wait_exit(timeout)
        self.stop()


def record_skips_in_results():
    """rosunit's XML result (rosunit.xmlrunner) has no skip: a skipped test is written as passed.
    Write a <skipped message="reason"/> element, as gtest does, for scripts/lib/summarize_results.py."""
    import xml.etree.ElementTree as ET
    from rosunit import xmlrunner

    base = xmlrunner._XMLTestResult

    class Result(base):
        def startTest(self, test):
            base.startTest(self, test)
            self._skip = None

        def addSkip(self, test, reason):
            base.addSkip(self, test, reason)
            self._skip = reason

        def stopTest(self, test):
            base.stopTest(self, test)
            if self._skip is not None and self._tests:
                self._tests[-1]._skip = self._skip

    def xml(info):
        case = original_xml(info)
        reason = getattr(info, "_skip", None)
        if reason is not None:
            ET.SubElement(case, "skipped", message=reason)
        return case
    original_xml = xmlrunner._TestInfo.xml
    xmlrunner._TestInfo.xml = xml
    xmlrunner._XMLTestResult = Result
