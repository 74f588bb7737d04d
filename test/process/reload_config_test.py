#!/usr/bin/env python3
"""rviz survives its configs being reloaded while the projector renders (issue 11, defect 2).

rviz's `~load_config_discarding_changes` service deletes every display, the ProjectorCamera
included, and builds the new config's displays. A display that runs ROS callbacks inside its own
methods (ros::spinOnce() while rendering) can have that service run in the middle of its render:
it is deleted under its own feet (use after free). Here a real rviz with a ProjectorCamera and a
ProjectedPath renders a path streaming at 20 Hz while the test calls the service 20 times in a
row, alternating two configs that both hold a ProjectorCamera; rviz must stay alive, keep
answering, and show the output window again. In `scripts/test --sanitize` the plugin runs under
ASan+UBSan, and any report fails the run. The CameraInfo and the tf come from reload_config.test.
"""
import math
import os
import sys
import threading
import time
import unittest

import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path
from rviz.srv import SendFilePath
from std_msgs.msg import String

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rviz_process import RvizProcess, XWindows, describe, wait_for  # noqa: E402

PKG = "rviz_projector"
NODE = "rviz_under_test"
RELOADS = 20
START_TIMEOUT = 40.0
WINDOW_TIMEOUT = 15.0
CALL_TIMEOUT = 20.0  # one config load (a new projector window and render window) on software GL
CONFIGS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "configs")


def make_path(t):
    """A path on the floor in front of the projector, bending a little over time (it changes)."""
    msg = Path()
    msg.header.frame_id = "map"
    msg.header.stamp = rospy.Time.now()
    for i in range(40):
        pose = PoseStamped()
        pose.header = msg.header
        x = 0.3 + 0.05 * i
        pose.pose.position.x = x
        pose.pose.position.y = 0.2 * math.sin(x + t)
        pose.pose.orientation.w = 1.0
        msg.poses.append(pose)
    return msg


class ReloadConfigTest(unittest.TestCase):
    def setUp(self):
        self.x = XWindows()
        self.rviz = None
        self.pub = rospy.Publisher("/process_test/plan", Path, queue_size=1)
        self.published = 0
        self.stop_stream = threading.Event()
        self.stream = threading.Thread(target=self.stream_path)
        self.stream.start()

    def tearDown(self):
        self.stop_stream.set()
        self.stream.join()
        if self.rviz is not None:
            self.rviz.stop()
        self.x.close()

    def stream_path(self):
        start = time.monotonic()
        period = 1.0 / 20
        next_time = start
        while not self.stop_stream.is_set() and not rospy.is_shutdown():
            self.pub.publish(make_path(time.monotonic() - start))
            self.published += 1
            next_time += period
            self.stop_stream.wait(max(0.0, next_time - time.monotonic()))

    def call(self, proxy, path):
        """The service call, with a time limit (a hung rviz must fail the test, not block it)."""
        result = {}

        def run():
            try:
                result["response"] = proxy(String(data=path))
            except Exception as e:  # rospy.ServiceException: rviz gone, connection closed
                result["error"] = e
        t = threading.Thread(target=run, daemon=True)
        t.start()
        t.join(CALL_TIMEOUT)
        if t.is_alive():
            return None, "no answer within %.0f s" % CALL_TIMEOUT
        if "error" in result:
            return None, "%s: %s" % (type(result["error"]).__name__, result["error"])
        return result["response"], None

    def test_reload_configs_while_rendering(self):
        configs = [os.path.join(CONFIGS, "reload_full_screen.rviz"),
                   os.path.join(CONFIGS, "reload_windowed.rviz")]
        self.rviz = RvizProcess(configs[1], node_name=NODE, label="reload_config")
        pid = self.rviz.pid
        shown = wait_for(lambda: not self.rviz.alive() or self.x.mapped_output_windows(pid), START_TIMEOUT, 0.1)
        self.assertTrue(self.rviz.alive(),
                        "rviz ended during start-up (%s):\n%s" % (self.rviz.status(), self.rviz.log_tail()))
        self.assertTrue(shown,
                        "output window not mapped within %.0f s\n%s" % (START_TIMEOUT, self.rviz.log_tail()))
        service = "/%s/load_config_discarding_changes" % NODE
        rospy.wait_for_service(service, timeout=START_TIMEOUT)
        proxy = rospy.ServiceProxy(service, SendFilePath)

        old_windows = set(w["id"] for w in self.x.mapped_output_windows(pid))
        started = time.monotonic()
        published_before = self.published
        for i in range(RELOADS):
            config = configs[i % 2]
            response, error = self.call(proxy, config)
            self.assertIsNone(error, "load %d of %d (%s): %s; rviz %s\n%s"
                              % (i + 1, RELOADS, os.path.basename(config), error, self.rviz.status(),
                                 self.rviz.log_tail()))
            self.assertTrue(response.success, "load %d of %d (%s) reported failure"
                            % (i + 1, RELOADS, os.path.basename(config)))
            # The new config's projector renders (its own, new output window is up) before the
            # next load comes in.
            window = wait_for(lambda: not self.rviz.alive() or
                              [w for w in self.x.mapped_output_windows(pid) if w["id"] not in old_windows],
                              WINDOW_TIMEOUT, 0.02)
            self.assertTrue(self.rviz.alive(), "load %d of %d (%s): rviz %s after the load\n%s"
                            % (i + 1, RELOADS, os.path.basename(config), self.rviz.status(), self.rviz.log_tail()))
            self.assertTrue(window, "load %d of %d (%s): no new output window within %.0f s (rviz %s; mapped "
                            "windows of rviz: %s)" % (i + 1, RELOADS, os.path.basename(config), WINDOW_TIMEOUT,
                                                      self.rviz.status(), describe(self.x.mapped_windows_of(pid))))
            old_windows = set(w["id"] for w in window)
        elapsed = time.monotonic() - started
        print("%d config loads in %.1f s while %d paths were published"
              % (RELOADS, elapsed, self.published - published_before))
        self.assertGreaterEqual(self.published - published_before, int(elapsed * 20 * 0.5),
                                "the path did not stream at 20 Hz during the loads")

        # Still alive and answering: a call that loads nothing (no such file) answers 'false'.
        self.assertTrue(self.rviz.alive(), "rviz ended (%s)\n%s" % (self.rviz.status(), self.rviz.log_tail()))
        response, error = self.call(proxy, os.path.join(CONFIGS, "no_such_config.rviz"))
        self.assertIsNone(error, "rviz stopped answering: %s" % error)
        self.assertFalse(response.success)
        # The last config's projector is up again: its output window is mapped.
        self.assertTrue(wait_for(lambda: self.x.mapped_output_windows(pid), START_TIMEOUT, 0.1),
                        "no output window after the last load (mapped windows of rviz: %s)"
                        % describe(self.x.mapped_windows_of(pid)))
        self.assertTrue(self.rviz.alive())


if __name__ == "__main__":
    import rostest
    rospy.init_node("reload_config_test")
    rostest.rosrun(PKG, "reload_config", ReloadConfigTest)
