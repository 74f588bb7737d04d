#!/usr/bin/env python3
"""demo_navigation under simulated time (issue 23, defect 6: the demo stall).

The demo once logged "new goal 1" and then nothing for 55 s. Every clock-dependent part of the
node (motion, the start delay, the success dwell, the stamps of its messages) must follow ROS
time, whatever that time does: this test runs demo_navigation with /use_sim_time true, publishes
/clock itself and watches the goal sequence advance through two full rounds (8 goals reached, the
ninth goal published) within a budget of ROS time (the legs take ~71 s at the robot's speed, plus
the pauses; budget 110 s) and a wall-clock timeout:

  fast         /clock at ~10x in 10 ms steps, started together with the node;
  irregular    /clock in random steps (0 to 1 s, time standing still included) at random wall
               intervals, with pauses of up to 0.8 s in which no /clock is published at all;
  late         the node is up (subscribed to /clock, its goal topic advertised) before the first
               /clock, which then starts at 1.7e9 s (a simulator mirroring the epoch, a bag);
  jumps_back   /clock at ~10x, jumping back 300 s right after every new goal and every reached
               goal (a bag replayed in a loop, a simulator reset, the system clock stepped back).

Each scenario starts its own node (its topics remapped under /<scenario>/), and checks: the goals
come in the demo's order; every goal was reported SUCCEEDED on the status topic before the next;
no goal is stamped 0 or before the clock started; except with backward jumps, the robot stands
still (odom -> base_link unchanged) for the start delay after every new goal and from a reached
goal's SUCCEEDED status until the next goal. Nothing waits a fixed time: every wait polls a
condition until a deadline (the clock's own pacing is the stimulus).
"""
import math
import os
import random
import shutil
import signal
import subprocess
import tempfile
import threading
import time
import unittest

import rosgraph
import roslib.packages
import rospy
from actionlib_msgs.msg import GoalStatus, GoalStatusArray
from geometry_msgs.msg import PoseStamped
from rosgraph_msgs.msg import Clock
from tf2_msgs.msg import TFMessage

PKG = "rviz_projector"
# demo_navigation's goal cycle (map frame); the robot starts on the first and drives to the second.
GOALS = [(0.0, 0.0), (4.0, 0.0), (4.0, 2.5), (0.0, 2.5)]
START_DELAY = 0.5    # s of ROS time the robot stands after a new goal became active
SUCCESS_DWELL = 0.3  # s of ROS time it stands at a reached goal
ROUNDS = 2
GOALS_NEEDED = len(GOALS) * ROUNDS + 1  # goal 1 ... goal 9: 8 reached
SIM_BUDGET = 110.0   # s of ROS time for the two rounds (~71 s of driving + 8 x 0.8 s of pauses)
WALL_TIMEOUT = 60.0  # s of wall time for one scenario (~12 s at 10x)
STILL = 1e-6         # m: "did not move"


def wait_for(condition, timeout, period=0.01):
    """Polls condition() until it returns a true value (returned) or timeout seconds pass (None)."""
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if value:
            return value
        if time.monotonic() >= deadline:
            return None
        time.sleep(period)


def fast_steps():
    """~10x: 10 ms of ROS time every ms of wall time."""
    while True:
        yield 0.001, 0.01


def irregular_steps(seed=23):
    """Random steps (time standing still to 1 s) at random intervals, now and then a pause of up
    to 0.8 s without any /clock message. On average ~5-10x."""
    rng = random.Random(seed)
    steps = [0.0, 0.002, 0.01, 0.03, 0.1, 0.25, 0.5, 1.0]
    step_weights = [1, 3, 4, 3, 2, 1, 0.5, 0.3]
    pauses = [0.0, 0.0005, 0.002, 0.01, 0.03]
    pause_weights = [1, 2, 3, 3, 1]
    while True:
        pause = rng.choices(pauses, pause_weights)[0]
        if rng.random() < 0.005:
            pause = rng.uniform(0.3, 0.8)
        yield pause, rng.choices(steps, step_weights)[0]


class ClockSource(threading.Thread):
    """Publishes /clock from a start time, step by step (wall pause, ROS-time step) as `steps`
    says; jump_back(s) makes the next message s seconds earlier instead. Time is kept in integer
    nanoseconds. `advanced` sums the forward steps: the ROS time the scenario has used."""

    def __init__(self, publisher, start, steps):
        super(ClockSource, self).__init__(daemon=True)
        self.publisher = publisher
        self.start_ns = int(round(start * 1e9))
        self.now_ns = self.start_ns
        self.advanced_ns = 0
        self.steps = steps
        self.pending_jump_ns = 0
        self.jumps = 0
        self.published = 0
        self.lock = threading.Lock()
        self.stopped = threading.Event()

    @property
    def advanced(self):
        with self.lock:
            return self.advanced_ns * 1e-9

    def jump_back(self, seconds):
        with self.lock:
            self.pending_jump_ns += int(round(seconds * 1e9))

    def stop(self):
        self.stopped.set()
        if self.is_alive():
            self.join(5.0)

    def run(self):
        first = True
        for pause, step in self.steps:
            if self.stopped.is_set():
                return
            if pause > 0.0 and self.stopped.wait(pause):
                return
            with self.lock:
                if first:
                    first = False
                elif self.pending_jump_ns:
                    self.now_ns -= self.pending_jump_ns
                    self.pending_jump_ns = 0
                    self.jumps += 1
                else:
                    step_ns = int(round(step * 1e9))
                    self.now_ns += step_ns
                    self.advanced_ns += step_ns
                stamp = rospy.Time(self.now_ns // 1000000000, self.now_ns % 1000000000)
            self.publisher.publish(Clock(clock=stamp))
            self.published += 1


def goal_index(x, y):
    """Index in GOALS of the goal at (x, y), None when it is none of them."""
    for i, (gx, gy) in enumerate(GOALS):
        if math.hypot(gx - x, gy - y) < 1e-3:
            return i
    return None


class Observation(object):
    """What the node publishes on its (remapped) goal, status and tf topics."""

    def __init__(self, on_goal=None, on_success=None):
        self.lock = threading.Lock()
        self.goals = []        # (stamp s, goal index or None, x, y)
        self.succeeded = {}    # goal id -> stamp s of the first SUCCEEDED status seen
        self.statuses = 0
        self.poses = []        # (stamp s, x, y) of odom -> base_link, in arrival order
        self.on_goal_hook = on_goal
        self.on_success_hook = on_success

    def on_goal(self, msg):
        p = msg.pose.position
        with self.lock:
            self.goals.append((msg.header.stamp.to_sec(), goal_index(p.x, p.y), p.x, p.y))
        if self.on_goal_hook:
            self.on_goal_hook()

    def on_status(self, msg):
        new_success = False
        with self.lock:
            self.statuses += 1
            for status in msg.status_list:
                if status.status == GoalStatus.SUCCEEDED and status.goal_id.id not in self.succeeded:
                    self.succeeded[status.goal_id.id] = msg.header.stamp.to_sec()
                    new_success = True
        if new_success and self.on_success_hook:
            self.on_success_hook()

    def on_tf(self, msg):
        with self.lock:
            for t in msg.transforms:
                if t.header.frame_id == "odom" and t.child_frame_id == "base_link":
                    self.poses.append((t.header.stamp.to_sec(), t.transform.translation.x,
                                       t.transform.translation.y))

    def goal_count(self):
        with self.lock:
            return len(self.goals)

    def snapshot(self):
        with self.lock:
            return list(self.goals), dict(self.succeeded), list(self.poses), self.statuses


class DemoNavigationClockTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.binary = next((p for p in roslib.packages.find_node(PKG, "demo_navigation") or []
                           if os.access(p, os.X_OK)), None)
        cls.clock_pub = rospy.Publisher("/clock", Clock, queue_size=1000)
        cls.master = rosgraph.Master(rospy.get_name())
        cls.logs = tempfile.mkdtemp(prefix="demo_navigation_clock_")

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.logs, ignore_errors=True)  # a failure message carries the log's tail

    def setUp(self):
        self.assertIsNotNone(self.binary, "demo_navigation is not built")
        self.assertTrue(rospy.get_param("/use_sim_time", False), "the .test file sets /use_sim_time")
        self.node = None
        self.clock = None
        self.subs = []

    def tearDown(self):
        if self.clock is not None:
            self.clock.stop()
        self.stop_node()
        for sub in self.subs:
            sub.unregister()

    # ---- the node ----------------------------------------------------------------------------
    def start_node(self, name):
        ns = "/" + name
        self.node_name = "demo_navigation_" + name
        self.log_path = os.path.join(self.logs, name + ".log")
        self.log = open(self.log_path, "w")
        self.node = subprocess.Popen(
            [self.binary, "__name:=" + self.node_name,
             "_start_delay:=%g" % START_DELAY, "_success_dwell:=%g" % SUCCESS_DWELL,
             "_path_topic:=%s/path" % ns, "_status_topic:=%s/status" % ns,
             "_publish_camera_info:=false",
             "/demo/goal:=%s/goal" % ns, "/tf:=%s/tf" % ns, "/tf_static:=%s/tf_static" % ns],
            stdout=self.log, stderr=subprocess.STDOUT)

    def stop_node(self):
        if self.node is None or self.log.closed:
            return
        if self.node.poll() is None:
            self.node.send_signal(signal.SIGINT)
            try:
                self.node.wait(10.0)
            except subprocess.TimeoutExpired:
                self.node.kill()
                self.node.wait()
        self.log.close()

    def node_log(self, lines=25):
        with open(self.log_path) as f:
            return "".join(f.readlines()[-lines:])

    def node_is_up(self, ns):
        publishers, subscribers, _ = self.master.getSystemState()
        me = "/" + self.node_name
        subscribed = any(topic == "/clock" and me in nodes for topic, nodes in subscribers)
        advertised = any(topic == ns + "/goal" and me in nodes for topic, nodes in publishers)
        return subscribed and advertised

    # ---- one scenario ------------------------------------------------------------------------
    def run_scenario(self, name, steps, start, late=False, jump_back=0.0):
        ns = "/" + name
        self.clock = ClockSource(self.clock_pub, start, steps)
        if jump_back > 0.0:
            def jump():
                self.clock.jump_back(jump_back)
            obs = Observation(on_goal=jump, on_success=jump)
        else:
            obs = Observation()
        self.subs = [rospy.Subscriber(ns + "/goal", PoseStamped, obs.on_goal, queue_size=100),
                     rospy.Subscriber(ns + "/status", GoalStatusArray, obs.on_status, queue_size=1000),
                     rospy.Subscriber(ns + "/tf", TFMessage, obs.on_tf, queue_size=10000)]
        self.start_node(name)
        if late:
            # The node is up and waits for the clock (no /clock has been published yet).
            self.assertTrue(wait_for(lambda: self.node_is_up(ns), 30.0, 0.05),
                            "demo_navigation did not come up:\n" + self.node_log())
            # ... and this test hears it from the first tick on.
            self.assertTrue(wait_for(lambda: all(sub.get_num_connections() > 0 for sub in self.subs), 30.0, 0.05),
                            "no connection to demo_navigation's topics:\n" + self.node_log())
        self.clock.start()
        wall_started = time.monotonic()
        wait_for(lambda: (obs.goal_count() >= GOALS_NEEDED or self.clock.advanced > SIM_BUDGET
                          or self.node.poll() is not None), WALL_TIMEOUT, 0.01)
        wall = time.monotonic() - wall_started
        advanced = self.clock.advanced
        exit_status = self.node.poll()
        self.clock.stop()
        self.stop_node()  # its log is complete once it has stopped
        goals, succeeded, poses, statuses = obs.snapshot()

        timeline = "\n".join("  goal %d: (%.2f, %.2f) stamped %.3f s (clock started at %.3f s)"
                             % (i + 1, g[2], g[3], g[0], start) for i, g in enumerate(goals))
        context = ("scenario %s: %d goals in %.1f s of ROS time (budget %.0f s), %.1f s of wall time, "
                   "%d /clock messages (%d backward jumps), %d status messages, %d robot poses\n%s\n"
                   "---- demo_navigation's log (tail) ----\n%s"
                   % (name, len(goals), advanced, SIM_BUDGET, wall, self.clock.published,
                      self.clock.jumps, statuses, len(poses), timeline, self.node_log()))
        self.assertIsNone(exit_status, "demo_navigation ended (exit status %s)\n%s" % (exit_status, context))
        self.assertGreaterEqual(
            len(goals), GOALS_NEEDED,
            "the goals did not go round %d times (%d of %d goals published) within %.0f s of ROS time"
            " / %.0f s of wall time: the demo stalls\n%s"
            % (ROUNDS, len(goals), GOALS_NEEDED, SIM_BUDGET, WALL_TIMEOUT, context))

        # The demo's order: goal 1, 2, 3, 0, 1, ...
        for i, g in enumerate(goals[:GOALS_NEEDED]):
            self.assertEqual(g[1], (i + 1) % len(GOALS),
                             "goal %d is (%.2f, %.2f), not the demo's next goal\n%s" % (i + 1, g[2], g[3], context))
        # Stamps: never 0 (the time before the clock), never before the clock started (the
        # backward jumps make later stamps earlier).
        for i, g in enumerate(goals[:GOALS_NEEDED]):
            self.assertGreater(g[0], 0.0, "goal %d is stamped 0\n%s" % (i + 1, context))
            if jump_back == 0.0:
                self.assertGreaterEqual(g[0], start, "goal %d is stamped before the clock started\n%s"
                                        % (i + 1, context))
        # Each goal reached, i.e. reported SUCCEEDED (before the next one: checked below, where
        # stamps are ordered).
        for k in range(1, GOALS_NEEDED):
            self.assertIn("demo_goal_%d" % k, succeeded,
                          "goal %d was replaced without a SUCCEEDED status\n%s" % (k, context))
        if jump_back > 0.0:
            return

        # Standing still: start_delay after each new goal, and from SUCCEEDED to the next goal.
        # Poses stamped just after `begin`: one stamped `begin` itself may be from a callback that
        # ran before the control tick of that time (the replan re-broadcasts the pose).
        def still(begin, end, what, min_samples):
            window = [p for p in poses if begin + 1e-4 < p[0] <= end]
            if len(window) < min_samples:
                self.fail("%s: %d robot poses stamped in [%.3f, %.3f] s, expected at least %d\n%s"
                          % (what, len(window), begin, end, min_samples, context))
            moved = max((math.hypot(p[1] - window[0][1], p[2] - window[0][2]) for p in window), default=0.0)
            self.assertLessEqual(moved, STILL, "%s: the robot moved %.4f m in [%.3f, %.3f] s\n%s"
                                 % (what, moved, begin, end, context))

        regular = steps_are_regular(name)
        for i, g in enumerate(goals[:GOALS_NEEDED - 1]):
            # (The first goal's window can pass before the subscriptions connect, unless late.)
            dense = regular and (i > 0 or late)
            still(g[0], g[0] + START_DELAY - 0.005, "start delay of goal %d" % (i + 1), 5 if dense else 0)
            reached = succeeded["demo_goal_%d" % (i + 1)]
            self.assertLessEqual(reached, goals[i + 1][0], "goal %d: SUCCEEDED stamped after the next goal\n%s"
                                 % (i + 1, context))
            still(reached, goals[i + 1][0] - 0.005, "dwell at goal %d" % (i + 1), 0)
        rospy.loginfo("scenario %s: %d goals in %.1f s of ROS time, %.1f s of wall time",
                      name, len(goals), advanced, wall)

    # ---- the scenarios -------------------------------------------------------------------------
    def test_fast_clock(self):
        self.run_scenario("fast", fast_steps(), start=100.0)

    def test_irregular_clock(self):
        self.run_scenario("irregular", irregular_steps(), start=200.0)

    def test_clock_starts_late(self):
        self.run_scenario("late", fast_steps(), start=1.7e9, late=True)

    def test_clock_jumps_back(self):
        self.run_scenario("jumps_back", fast_steps(), start=10000.0, jump_back=300.0)


def steps_are_regular(name):
    """Scenarios whose clock ticks every 10 ms of ROS time (enough robot poses in every window)."""
    return name in ("fast", "late")


if __name__ == "__main__":
    import rostest
    rospy.init_node("demo_navigation_clock_test")
    rostest.rosrun(PKG, "demo_navigation_clock", DemoNavigationClockTest)
