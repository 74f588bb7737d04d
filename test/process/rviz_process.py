"""A real rviz process under test, and its windows as the X server sees them (python-xlib).

Shared by the process tests in this folder (quit_test.py, reload_config_test.py). rviz is started
as a user starts it (`rviz -d CONFIG --disable-anti-aliasing`, the binary `rosrun rviz rviz`
runs), with a fixed node name so its services are known. Nothing here waits a fixed time: every
wait polls a condition until a deadline.
"""
import os
import shutil
import signal
import subprocess
import tempfile
import time

import roslib.packages
from Xlib import X, Xatom, display as xdisplay
from Xlib.error import XError
from Xlib.protocol import event as xevent

OUTPUT_TITLE_PREFIX = "Projector: "


def wait_for(condition, timeout, period=0.05):
    """Polls condition() until it returns a true value (returned) or timeout seconds pass (None)."""
    deadline = time.monotonic() + timeout
    while True:
        value = condition()
        if value:
            return value
        if time.monotonic() >= deadline:
            return None
        time.sleep(period)


def sanitize_run():
    """True in `scripts/test --sanitize`: our plugin is built with ASan+UBSan, rviz is not."""
    return os.environ.get("RP_SANITIZE") == "1"


def _asan_runtime():
    out = subprocess.run(["gcc", "-print-file-name=libasan.so"], stdout=subprocess.PIPE,
                         universal_newlines=True, check=True).stdout.strip()
    return os.path.realpath(out)


class XWindows(object):
    """Top-level windows of the X server: titles, owner pid, mapped state, geometry."""

    def __init__(self):
        self.d = xdisplay.Display()
        self.root = self.d.screen().root
        self.NET_WM_NAME = self.d.intern_atom("_NET_WM_NAME")
        self.NET_WM_PID = self.d.intern_atom("_NET_WM_PID")
        self.UTF8_STRING = self.d.intern_atom("UTF8_STRING")
        self.WM_PROTOCOLS = self.d.intern_atom("WM_PROTOCOLS")
        self.WM_DELETE_WINDOW = self.d.intern_atom("WM_DELETE_WINDOW")

    def close(self):
        self.d.close()

    def monitors(self):
        """RandR monitors (x, y, width, height) of the server: one per screen Qt reports."""
        try:
            reply = self.root.xrandr_get_monitors(is_active=True)
            return [(m.x, m.y, m.width_in_pixels, m.height_in_pixels) for m in reply.monitors]
        except Exception:  # no RandR 1.5: one screen as far as we can tell
            g = self.root.get_geometry()
            return [(0, 0, g.width, g.height)]

    def _title(self, w):
        prop = w.get_full_property(self.NET_WM_NAME, self.UTF8_STRING)
        if prop is not None and prop.value:
            v = prop.value
            return v.decode("utf-8", "replace") if isinstance(v, bytes) else str(v)
        name = w.get_wm_name()
        if isinstance(name, bytes):
            name = name.decode("latin-1")
        return name or ""

    def _pid(self, w):
        prop = w.get_full_property(self.NET_WM_PID, Xatom.CARDINAL)
        return int(prop.value[0]) if prop is not None and len(prop.value) else None

    def tree(self, window_id, depth=0):
        """Lines describing window `window_id` and every window below it, titled or not (OGRE draws
        into an untitled child window): id, geometry on the root, map state, title."""
        lines = []
        try:
            w = self.d.create_resource_object("window", window_id)
            geo = w.get_geometry()
            pos = self.root.translate_coords(w, 0, 0)
            attrs = w.get_attributes()
            title = self._title(w)
            children = w.query_tree().children
        except XError as e:
            return ["%s0x%x: gone (%s)" % ("  " * depth, window_id, e.__class__.__name__)]
        state = {X.IsViewable: "viewable", X.IsUnviewable: "unviewable"}.get(attrs.map_state, "unmapped")
        lit = ""
        if attrs.map_state == X.IsViewable:
            # What the window itself holds (read from it, not from the screen): whether a picture
            # drawn into it is there even when a grab of the screen's rectangle shows none.
            try:
                data = w.get_image(0, 0, geo.width, geo.height, X.ZPixmap, 0xffffffff).data
                lit = ", %d lit of its own pixels" % sum(1 for i in range(0, len(data) - 3, 4)
                                                          if data[i] > 40 or data[i + 1] > 40 or data[i + 2] > 40)
            except XError as e:
                lit = ", its pixels unreadable (%s)" % e.__class__.__name__
        lines.append("%s0x%x %dx%d+%d+%d %s %r%s" % ("  " * depth, window_id, geo.width, geo.height, pos.x, pos.y,
                                                     state, title, lit))
        for child in children:
            lines += self.tree(child.id, depth + 1)
        return lines

    def covering(self, window_id):
        """Lines describing the viewable top-level windows stacked above the top-level window that
        holds `window_id` and overlapping it, titled or not (what a grab of its rectangle shows
        instead of it), topmost last."""
        try:
            top = self.d.create_resource_object("window", window_id)
            while True:
                parent = top.query_tree().parent
                if parent.id == self.root.id:
                    break
                top = parent
            g = top.get_geometry()
            pos = self.root.translate_coords(top, 0, 0)
            children = self.root.query_tree().children  # bottom to top
        except XError as e:
            return ["0x%x: gone (%s)" % (window_id, e.__class__.__name__)]
        lines = []
        above = False
        for w in children:
            if w.id == top.id:
                above = True
                continue
            if not above:
                continue
            try:
                a = w.get_attributes()
                wg = w.get_geometry()
                wp = self.root.translate_coords(w, 0, 0)
                title = self._title(w)
            except XError:
                continue
            if a.map_state != X.IsViewable:
                continue
            if (wp.x < pos.x + g.width and pos.x < wp.x + wg.width and
                    wp.y < pos.y + g.height and pos.y < wp.y + wg.height):
                lines.append("0x%x %dx%d+%d+%d %r pid %s%s" % (w.id, wg.width, wg.height, wp.x, wp.y, title,
                                                              self._pid(w), " override-redirect" if a.override_redirect
                                                              else ""))
        return lines

    def windows(self):
        """Every window with a title: dicts of id, title, pid, mapped, x, y, width, height.

        Walks the whole tree (a window manager, if any, reparents clients into frames)."""
        found = []
        stack = [self.root]
        while stack:
            parent = stack.pop()
            try:
                children = parent.query_tree().children
            except XError:
                continue  # destroyed meanwhile
            for w in children:
                stack.append(w)
                try:
                    title = self._title(w)
                    if not title:
                        continue
                    pid = self._pid(w)
                    attrs = w.get_attributes()
                    geo = w.get_geometry()
                    pos = self.root.translate_coords(w, 0, 0)
                except XError:
                    continue  # destroyed meanwhile
                found.append({"id": w.id, "window": w, "title": title, "pid": pid,
                              "mapped": attrs.map_state == X.IsViewable,
                              "x": pos.x, "y": pos.y, "width": geo.width, "height": geo.height})
        return found

    def mapped_output_windows(self, pid=None):
        """Mapped projector output windows ('Projector: <display name>'), of `pid` if given."""
        return [w for w in self.windows() if w["mapped"] and w["title"].startswith(OUTPUT_TITLE_PREFIX)
                and (pid is None or w["pid"] == pid)]

    def main_window(self, pid):
        """rviz's mapped main window ('... RViz') of process `pid`, or None."""
        for w in self.windows():
            if w["mapped"] and w["pid"] == pid and w["title"].endswith("RViz"):
                return w
        return None

    def input_focus(self):
        """Id of the window holding the keyboard focus (0 or 1 for None / PointerRoot)."""
        focus = self.d.get_input_focus().focus
        return focus if isinstance(focus, int) else focus.id

    def mapped_popups(self):
        """Ids of mapped override-redirect top-level windows (menus, tooltips)."""
        ids = set()
        for w in self.root.query_tree().children:
            try:
                a = w.get_attributes()
            except XError:
                continue
            if a.map_state == X.IsViewable and a.override_redirect:
                ids.add(w.id)
        return ids

    def mapped_windows_of(self, pid):
        return [w for w in self.windows() if w["mapped"] and w["pid"] == pid]

    def send_delete_window(self, window):
        """What a window manager sends when the user clicks a window's close button."""
        ev = xevent.ClientMessage(window=window, client_type=self.WM_PROTOCOLS,
                                  data=(32, [self.WM_DELETE_WINDOW, X.CurrentTime, 0, 0, 0]))
        window.send_event(ev, event_mask=X.NoEventMask)
        self.d.flush()


def describe(windows):
    return ", ".join("'%s' %dx%d+%d+%d" % (w["title"], w["width"], w["height"], w["x"], w["y"])
                     for w in windows) or "none"


class ProcessUnderTest(object):
    """A ROS executable of `package` started as a user starts it, its output (stdout and stderr) in
    a log under ROS_HOME/log (scripts/test --sanitize searches those for UBSan reports)."""

    def __init__(self, package, executable, args, label, env):
        binaries = roslib.packages.find_node(package, executable)
        if not binaries:
            raise RuntimeError("%s not found (rosrun %s %s)" % (executable, package, executable))
        ros_home = os.environ.get("ROS_HOME", os.path.expanduser("~/.ros"))
        log_dir = os.path.join(ros_home, "log")
        os.makedirs(log_dir, exist_ok=True)
        self.log_path = os.path.join(log_dir, "process_test_%s_%d.log" % (label, os.getpid()))
        # stdout is a file: line by line, so that a crash does not swallow the last lines.
        env["ROSCONSOLE_STDOUT_LINE_BUFFERED"] = "1"
        self.log = open(self.log_path, "w")
        self.proc = subprocess.Popen([binaries[0]] + list(args), stdin=subprocess.DEVNULL, stdout=self.log,
                                     stderr=subprocess.STDOUT, env=env)
        self.pid = self.proc.pid
        self.exit_time = None

    def alive(self):
        return self.proc.poll() is None

    def returncode(self):
        return self.proc.poll()

    def wait_exit(self, timeout):
        """Seconds until the process exited (polling every 10 ms), or None if it still runs after
        timeout. exit_time: time.monotonic() when the exit was seen."""
        start = time.monotonic()
        if wait_for(lambda: not self.alive(), max(0.0, timeout), period=0.01):
            self.exit_time = time.monotonic()
            return self.exit_time - start
        return None

    def signal(self, sig):
        self.proc.send_signal(sig)

    def status(self):
        """'running', 'exit status N' or 'killed by SIGxxx'."""
        rc = self.proc.poll()
        if rc is None:
            return "running"
        if rc < 0:
            try:
                return "killed by %s" % signal.Signals(-rc).name
            except ValueError:
                return "killed by signal %d" % -rc
        return "exit status %d" % rc

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
        """Ends the process if still running (SIGTERM, then SIGKILL) and cleans up."""
        if self.alive():
            self.proc.send_signal(signal.SIGTERM)
            if not wait_for(lambda: not self.alive(), 5.0):
                self.proc.kill()
                self.proc.wait()
        self.log.close()


class RvizProcess(ProcessUnderTest):
    """`rviz -d config --disable-anti-aliasing __name:=node_name`, output in a log file."""

    def __init__(self, config, node_name="rviz_under_test", label="rviz"):
        self.node_name = node_name
        # A home of its own: rviz keeps persistent settings (recent configs) in ~/.rviz.
        self.home = tempfile.mkdtemp(prefix="rviz_process_test_home_")
        env = dict(os.environ)
        env["HOME"] = self.home
        if sanitize_run():
            # The plugin is instrumented, the rviz binary is not: the ASan runtime must come first.
            env["LD_PRELOAD"] = _asan_runtime()
            # Leaks of rviz itself (uninstrumented, third-party) are not ours to report, and a leak
            # check at exit would also slow the exit the quit tests time.
            env["ASAN_OPTIONS"] = (env.get("ASAN_OPTIONS", "") + ":detect_leaks=0").lstrip(":")
            # Seen here: with the runtime preloaded into rviz and a UTF-8 locale, Mesa's driconf
            # (regcomp while the first GL window is created) deadlocks on glibc's locale lock.
            # The C locale needs no conversion module loaded, so that lock is never taken.
            env["LC_ALL"] = "C"
        ProcessUnderTest.__init__(self, "rviz", "rviz",
                                  ["-d", config, "--disable-anti-aliasing", "__name:=" + node_name], label, env)

    def stop(self):
        ProcessUnderTest.stop(self)
        shutil.rmtree(self.home, ignore_errors=True)


def xdotool(*args):
    subprocess.run(["xdotool"] + [str(a) for a in args], check=True, timeout=10)
