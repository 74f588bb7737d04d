"""A real projector_host process under test (the binary `rosrun rviz_projector projector_host`
runs), and the pixels of its output window read from the X server.

Shared by host_test.py; the windows are found with rviz_process.XWindows. Nothing here waits a
fixed time: every wait polls a condition until a deadline.
"""
import os
import signal
import subprocess

import roslib.packages
from Xlib import X

from rviz_process import sanitize_run, wait_for


class HostProcess(object):
    """`projector_host [args] CONFIG __name:=node_name`, output in a log file."""

    def __init__(self, config, args=(), node_name="projector_host", label="host", env_changes=None):
        self.node_name = node_name
        binaries = roslib.packages.find_node("rviz_projector", "projector_host")
        if not binaries:
            raise RuntimeError("projector_host binary not found (rosrun rviz_projector projector_host)")
        ros_home = os.environ.get("ROS_HOME", os.path.expanduser("~/.ros"))
        log_dir = os.path.join(ros_home, "log")
        os.makedirs(log_dir, exist_ok=True)
        self.log_path = os.path.join(log_dir, "process_test_%s_%d.log" % (label, os.getpid()))
        env = dict(os.environ)
        env["ROSCONSOLE_STDOUT_LINE_BUFFERED"] = "1"
        if sanitize_run():
            # projector_host itself is instrumented; leaks of rviz/OGRE/Mesa are not ours, and a
            # leak check at exit would slow the exit the tests time.
            env["ASAN_OPTIONS"] = (env.get("ASAN_OPTIONS", "") + ":detect_leaks=0").lstrip(":")
            env["LC_ALL"] = "C"  # see rviz_process.RvizProcess
        for key, value in (env_changes or {}).items():
            if value is None:
                env.pop(key, None)
            else:
                env[key] = value
        self.log = open(self.log_path, "w")
        command = [binaries[0]] + list(args) + ([config] if config else []) + ["__name:=" + node_name]
        self.proc = subprocess.Popen(command, stdin=subprocess.DEVNULL, stdout=self.log,
                                     stderr=subprocess.STDOUT, env=env)
        self.pid = self.proc.pid

    def alive(self):
        return self.proc.poll() is None

    def wait_exit(self, timeout):
        """Seconds until the process exited, or None if it still runs after timeout."""
        import time
        start = time.monotonic()
        if wait_for(lambda: not self.alive(), max(0.0, timeout), period=0.01):
            return time.monotonic() - start
        return None

    def returncode(self):
        return self.proc.poll()

    def signal(self, sig):
        self.proc.send_signal(sig)

    def log_text(self):
        self.log.flush()
        try:
            with open(self.log_path) as f:
                return f.read()
        except OSError:
            return ""

    def log_tail(self, lines=25):
        return "".join(self.log_text().splitlines(True)[-lines:])

    def stop(self):
        if self.alive():
            self.proc.send_signal(signal.SIGTERM)
            if not wait_for(lambda: not self.alive(), 5.0):
                self.proc.kill()
                self.proc.wait()
        self.log.close()


class Pixels(object):
    """An RGB grab of a screen rectangle: lit (non-black) pixels and colour counts."""

    def __init__(self, xwindows, x, y, width, height):
        image = xwindows.root.get_image(x, y, width, height, X.ZPixmap, 0xffffffff)
        self.width = width
        self.height = height
        self.data = image.data  # BGRX, 4 bytes per pixel (24-bit depth)

    def rgb(self, px, py):
        i = 4 * (py * self.width + px)
        return self.data[i + 2], self.data[i + 1], self.data[i]

    def lit(self, threshold=40):
        """Indices of pixels brighter than threshold in any channel."""
        d = self.data
        n = self.width * self.height
        return [i for i in range(n) if d[4 * i] > threshold or d[4 * i + 1] > threshold or d[4 * i + 2] > threshold]

    def count_colour(self, rgb, tolerance=40):
        r, g, b = rgb
        d = self.data
        count = 0
        for i in range(0, len(d), 4):
            if abs(d[i + 2] - r) <= tolerance and abs(d[i + 1] - g) <= tolerance and abs(d[i] - b) <= tolerance:
                count += 1
        return count

    def count_light(self, step=1, minimum=180):
        """Pixels (every `step`-th) whose three channels are all at least `minimum`: white or light
        grey, never one of the saturated test colours (magenta, cyan, green)."""
        d = self.data
        count = 0
        for i in range(0, len(d), 4 * step):
            if d[i] >= minimum and d[i + 1] >= minimum and d[i + 2] >= minimum:
                count += 1
        return count

    def reddish(self, step=2):
        """Indices of red pixels (a lit red marker: red high, green and blue low), every `step`-th
        row and column."""
        d = self.data
        out = []
        for py in range(0, self.height, step):
            row = py * self.width
            for px in range(0, self.width, step):
                i = 4 * (row + px)
                if d[i + 2] > 120 and d[i + 1] < 60 and d[i] < 60:
                    out.append(row + px)
        return out

    def centroid(self, indices):
        if not indices:
            return None
        sx = sum(i % self.width for i in indices)
        sy = sum(i // self.width for i in indices)
        return (sx / float(len(indices)) + 0.5, sy / float(len(indices)) + 0.5)


def grab_window(xwindows, window):
    return Pixels(xwindows, window["x"], window["y"], window["width"], window["height"])
