#!/usr/bin/env python3
"""Quitting a real rviz ends it, and the projector goes dark (issue 11, defect 1).

One rviz process per case: rviz starts with a ProjectorCamera whose output window is shown (full
screen on the projector's screen, or as a normal window), the test waits for that window to be
mapped, quits rviz one way, and checks that the process ends within 2 s and that no
'Projector: ...' window remains mapped. Ways: Ctrl+Q, File -> Quit through the menu, the window
manager's close request on the main window (WM_DELETE_WINDOW), SIGINT (Ctrl-C in the terminal),
SIGTERM. The CameraInfo and the tf come from quit.test.
"""
import os
import signal
import sys
import time
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from rviz_process import RvizProcess, XWindows, describe, wait_for, xdotool  # noqa: E402

PKG = "rviz_projector"
EXIT_LIMIT = 2.0     # seconds from the quit action to the end of the process (the requirement)
EXIT_PATIENCE = 6.0  # how long a failing case waits more, to report what it measured
# A case whose rviz did exit, but later than EXIT_LIMIT, is run once more (a printed TIMING RETRY,
# never silent): on the CI machine one SIGINT exit took 2.96 s once, while here 53 SIGINT exits, with and
# without 4 busy loops competing for the 2 cores, all took under 0.9 s. roscpp's shutdown unregisters every topic and service
# with the master over XML-RPC before ros::ok() turns false, so a busy master delays the exit.
# A second slow exit fails, and a hang (no exit within EXIT_LIMIT + EXIT_PATIENCE) fails at once.
START_TIMEOUT = 40.0  # rviz start-up (software GL, ASan in the sanitize run) until the window shows
CONFIGS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "configs")


class QuitTest(unittest.TestCase):
    def setUp(self):
        self.x = XWindows()
        self.rviz = None
        self.may_retry = True

    def tearDown(self):
        if self.rviz is not None:
            self.rviz.stop()
        self.x.close()

    # ---- helpers ---------------------------------------------------------------------------
    def start(self, mode):
        if mode == "full_screen" and len(self.x.monitors()) < 2:
            self.fail("full screen needs a second screen, this X server has %d (scripts/test starts "
                      "the two-screen Xorg dummy server)" % len(self.x.monitors()))
        for attempt in (1, 2):
            self.rviz = RvizProcess(os.path.join(CONFIGS, "projector_%s.rviz" % mode),
                                    label=self.id().split(".")[-1])
            pid = self.rviz.pid
            shown = wait_for(lambda: not self.rviz.alive() or
                             (self.x.main_window(pid) and self.x.mapped_output_windows(pid)), START_TIMEOUT, 0.1)
            if self.rviz.alive() or attempt == 2:
                break
            # Known, unsolved (doc/notes/startup-crash.md): under load, Mesa's software renderer
            # now and then crashes rviz while it starts up. This test is about quitting, so one
            # new start is allowed; the crash is printed, never hidden, and a second one fails.
            sys.stderr.write("KNOWN ISSUE: rviz died during start-up (%s), starting it once more:\n%s\n"
                             % (self.rviz.status(), self.rviz.log_tail()))
            self.rviz.stop()
        self.assertTrue(self.rviz.alive(),
                        "rviz ended during start-up (%s):\n%s" % (self.rviz.status(), self.rviz.log_tail()))
        self.assertTrue(shown, "no rviz main window and 'Projector: Projector' output window mapped within %.0f s "
                        "(mapped windows of rviz: %s)\n%s" % (START_TIMEOUT, describe(self.x.mapped_windows_of(pid)),
                                                             self.rviz.log_tail()))
        output = self.x.mapped_output_windows(pid)[0]
        if mode == "full_screen":
            # Full screen on the second screen: the window covers exactly one monitor that is not
            # the one rviz's main window is on.
            main = self.x.main_window(pid)
            rect = (output["x"], output["y"], output["width"], output["height"])
            self.assertIn(rect, self.x.monitors(), "output window not full screen: %s" % describe([output]))
            self.assertFalse(rect[0] <= main["x"] < rect[0] + rect[2] and rect[1] <= main["y"] < rect[1] + rect[3],
                             "output window on rviz's screen: %s, %s" % (describe([output]), describe([main])))
        else:
            rect = (output["x"], output["y"], output["width"], output["height"])
            self.assertNotIn(rect, self.x.monitors(), "windowed, yet the output window fills a screen: %s"
                             % describe([output]))
        return self.x.main_window(pid)

    def focus(self, window):
        """Gives rviz's main window the keyboard focus, until it holds it for 3 polls in a row.

        No window manager on the test server: the test sets the focus itself (keys then go through
        XTEST, as a real keyboard's would). The output window may take the focus when it is shown,
        so the focus is checked, not assumed."""
        held = [0]

        def holds():
            if self.x.input_focus() != window["id"]:
                held[0] = 0
                xdotool("windowfocus", "--sync", window["id"])
                return False
            held[0] += 1
            return held[0] >= 3
        self.assertTrue(wait_for(holds, 10.0, 0.1), "rviz's main window does not keep the keyboard focus")

    def check_quit(self, how, t0):
        """rviz, told to quit at t0 (time.monotonic()), has ended within EXIT_LIMIT s, dark.

        Returns False (nothing asserted about the exit time yet) when rviz exited, in order, but
        late and `self.may_retry` is set: the caller runs the case once more."""
        exited = self.rviz.wait_exit(t0 + EXIT_LIMIT + EXIT_PATIENCE - time.monotonic())
        if exited is not None:
            exited = self.rviz.exit_time - t0
        pid = self.rviz.pid
        left = self.x.mapped_output_windows(pid)
        if exited is None:
            others = self.x.mapped_windows_of(pid)
            self.fail("%s: rviz still running %.1f s later; mapped windows of rviz: %s; output window mapped: %s"
                      % (how, time.monotonic() - t0, describe(others), "yes" if left else "no"))
        print("%s: rviz exited %.3f s after the quit action (exit status %s)"
              % (how, exited, self.rviz.proc.returncode))
        if exited > EXIT_LIMIT and self.may_retry and self.rviz.proc.returncode in (0, -signal.SIGTERM):
            self.assertEqual([], self.x.mapped_output_windows(), "output window still mapped after exit")
            sys.stderr.write("TIMING RETRY: %s: rviz took %.2f s to exit (limit %.1f s); running the case "
                             "once more\n%s\n" % (how, exited, EXIT_LIMIT, self.rviz.log_tail()))
            self.may_retry = False
            return False
        self.assertLessEqual(exited, EXIT_LIMIT,
                             "%s: rviz took %.2f s to exit (limit %.1f s)" % (how, exited, EXIT_LIMIT))
        self.assertEqual([], self.x.mapped_output_windows(), "output window still mapped after exit")
        if how != "SIGTERM":
            # An orderly quit: no crash on the way out (SIGTERM's default action ends with -15).
            self.assertGreaterEqual(self.rviz.proc.returncode, 0, "%s: rviz died of signal %d:\n%s"
                                    % (how, -self.rviz.proc.returncode, self.rviz.log_tail()))
        return True

    # ---- the ways to quit --------------------------------------------------------------------
    def quit_ctrl_q(self, mode):
        main = self.start(mode)
        self.focus(main)
        t0 = time.monotonic()
        xdotool("key", "ctrl+q")
        return self.check_quit("Ctrl+Q", t0)

    def quit_menu(self, mode):
        main = self.start(mode)
        # The File menu is a popup window of its own: wait until it is mapped, so that the 'q'
        # below is the menu's &Quit entry (a plain q in the main window does nothing).
        menu = None
        for _ in range(3):
            self.focus(main)
            before = self.x.mapped_popups()
            xdotool("key", "alt+f")
            menu = wait_for(lambda: self.x.mapped_popups() - before, 3.0)
            if menu:
                break
        self.assertTrue(menu, "File menu did not open (alt+f, 3 tries; rviz %s)" % self.rviz.status())
        t0 = time.monotonic()
        xdotool("key", "q")
        return self.check_quit("File -> Quit", t0)

    def quit_close_window(self, mode):
        main = self.start(mode)
        t0 = time.monotonic()
        self.x.send_delete_window(main["window"])
        return self.check_quit("WM_DELETE_WINDOW", t0)

    def quit_signal(self, mode, sig):
        self.start(mode)
        t0 = time.monotonic()
        self.rviz.signal(sig)
        return self.check_quit(signal.Signals(sig).name, t0)


def _add_cases():
    ways = {
        "ctrl_q": lambda self, mode: self.quit_ctrl_q(mode),
        "file_menu_quit": lambda self, mode: self.quit_menu(mode),
        "close_main_window": lambda self, mode: self.quit_close_window(mode),
        "sigint": lambda self, mode: self.quit_signal(mode, signal.SIGINT),
        "sigterm": lambda self, mode: self.quit_signal(mode, signal.SIGTERM),
    }
    for way, run in ways.items():
        for mode in ("full_screen", "windowed"):
            def case(self, run=run, mode=mode):
                if not run(self, mode):
                    self.rviz.stop()
                    self.assertTrue(run(self, mode), "unreachable: the second run asserts the exit time")
            case.__name__ = "test_%s_%s" % (way, mode)
            setattr(QuitTest, case.__name__, case)


_add_cases()

if __name__ == "__main__":
    import rostest
    rostest.rosrun(PKG, "quit", QuitTest)
