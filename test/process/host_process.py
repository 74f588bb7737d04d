"""A real projector_host process under test (the binary `rosrun rviz_projector projector_host`
runs), and the pixels of its output window read from the X server.

Shared by host_test.py; the windows are found with rviz_process.XWindows. Nothing here waits a
fixed time: every wait polls a condition until a deadline.
"""
import os

from Xlib import X

from rviz_process import ProcessUnderTest, sanitize_run


class HostProcess(ProcessUnderTest):
    """`projector_host [args] CONFIG __name:=node_name`, output in a log file."""

    def __init__(self, config, args=(), node_name="projector_host", label="host", env_changes=None):
        self.node_name = node_name
        env = dict(os.environ)
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
        command = list(args) + ([config] if config else []) + ["__name:=" + node_name]
        ProcessUnderTest.__init__(self, "rviz_projector", "projector_host", command, label, env)


class Pixels(object):
    """An RGB grab of a screen rectangle: lit (non-black) pixels and colour counts."""

    def __init__(self, xwindows, x, y, width, height):
        image = xwindows.root.get_image(x, y, width, height, X.ZPixmap, 0xffffffff)
        self.width = width
        self.height = height
        self.data = image.data  # BGRX, 4 bytes per pixel (24-bit depth)

    def summary(self, step=2):
        """What the grab shows, for a failure message: lit pixels (any channel > 40, every `step`-th
        row and column), their bounding box, and the commonest lit colours."""
        d = self.data
        lit = 0
        box = None
        colours = {}
        for py in range(0, self.height, step):
            row = py * self.width
            for px in range(0, self.width, step):
                i = 4 * (row + px)
                b, g, r = d[i], d[i + 1], d[i + 2]
                if r > 40 or g > 40 or b > 40:
                    lit += 1
                    box = (px, py, px, py) if box is None else (min(box[0], px), min(box[1], py),
                                                              max(box[2], px), max(box[3], py))
                    key = (r // 32 * 32, g // 32 * 32, b // 32 * 32)
                    colours[key] = colours.get(key, 0) + 1
        common = sorted(colours.items(), key=lambda kv: -kv[1])[:4]
        return "%dx%d grab: %d lit of %d sampled%s%s" % (
            self.width, self.height, lit, ((self.width + step - 1) // step) * ((self.height + step - 1) // step),
            "" if box is None else ", lit box x %d..%d y %d..%d" % (box[0], box[2], box[1], box[3]),
            "" if not common else ", colours (RGB, 32-steps) " + ", ".join("%s x%d" % (c, n) for c, n in common))

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
