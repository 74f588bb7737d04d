#!/usr/bin/env python3
"""Issue 24, parts 2 and 3: `calibrate_projector --camera` end to end, through the user's path.

camera_calibration.test launches the projector rig with a WRONG mount (5 cm forward, 3 deg more
pitch than the truth) and a calibration without distortion, and demo_camera, which simulates a
camera on the robot from the projector's published Image through the TRUE mount and a wide-angle
TRUE lens (k1 = -0.2, k2 = 0.05) that the calibration does not know. This test starts
projector_host (the Pattern topic and the Image output of a ProjectorCamera), runs the real
calibrate_projector binary and judges what it writes:

  - the mount within 2 mm and 0.05 deg of the truth, k1 and k2 near the truth;
  - the floor error of the written calibration over the lit area against the truth: median <= 1 mm,
    max <= 3 mm (the floor point of each projector pixel of a grid, computed here by hand: the
    pinhole, OpenCV's distortion model inverted by iteration, the mount convention of
    projector.launch);
  - the refusals: no projector on the Pattern topic, no tf to the floor frame, a camera that sees
    none of the projection: exit status 1, one clear message, nothing written;
  - --board: a third demo_camera sees a checkerboard standing 45 deg in the lit patch; from a
    calibration file whose fx, fy are 3 % and cx, cy 15 px off, the written K and P come out near the
    truth (fx, fy within 0.3 %, cx, cy within 3 px) and the floor error stays within 1 / 3 mm.

The oracle is the truth the .test file hands demo_camera, never the code under test.
"""
import math
import os
import re
import subprocess
import sys
import tempfile
import time
import unittest

import roslib.packages
import rospy
import rostest
import yaml
from sensor_msgs.msg import Image

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from host_process import HostProcess  # noqa: E402

PKG = "rviz_projector"
HERE = os.path.dirname(os.path.abspath(__file__))
CONFIG = os.path.join(HERE, "configs", "camera_calibration.rviz")
CALIBRATION = os.path.join(os.path.dirname(os.path.dirname(HERE)), "config", "demo_projector.yaml")

# The truth (camera_calibration.test gives demo_camera the same numbers).
TRUE_MOUNT = dict(x=0.15, y=0.0, z=1.2, roll=0.0, pitch=0.8760580505981934, yaw=0.0)
TRUE_D = [-0.2, 0.05, 0.0, 0.0, 0.0]
# The projector's lens (config/demo_projector.yaml: K = P).
WIDTH, HEIGHT, FX, FY, CX, CY = 1280, 800, 1300.0, 1300.0, 639.5, 399.5


def distort(x, y, d):
    """OpenCV's plumb_bob model on ideal normalised coordinates."""
    k1, k2, p1, p2, k3 = (list(d) + [0.0] * 5)[:5]
    r2 = x * x + y * y
    radial = 1.0 + k1 * r2 + k2 * r2 * r2 + k3 * r2 * r2 * r2
    return (x * radial + 2.0 * p1 * x * y + p2 * (r2 + 2.0 * x * x),
            y * radial + p1 * (r2 + 2.0 * y * y) + 2.0 * p2 * x * y)


def undistort(xd, yd, d):
    """The ideal normalised coordinates whose distortion is (xd, yd): Newton's method on distort."""
    x, y = xd, yd
    for _ in range(50):
        fx, fy = distort(x, y, d)
        ex, ey = fx - xd, fy - yd
        h = 1e-7
        ax, ay = distort(x + h, y, d)
        bx, by = distort(x, y + h, d)
        j11, j21 = (ax - fx) / h, (ay - fy) / h
        j12, j22 = (bx - fx) / h, (by - fy) / h
        det = j11 * j22 - j12 * j21
        x -= (j22 * ex - j12 * ey) / det
        y -= (-j21 * ex + j11 * ey) / det
    return x, y


def rotation(roll, pitch, yaw):
    """R = Rz(yaw) Ry(pitch) Rx(roll), row-major 3x3 (projector.launch's fixed-axis convention)."""
    cr, sr, cp, sp, cy, sy = math.cos(roll), math.sin(roll), math.cos(pitch), math.sin(pitch), math.cos(yaw), math.sin(yaw)
    return [[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr]]


def floor_point(mount, d, u, v, lens=(FX, FY, CX, CY)):
    """Where projector pixel (u, v) lands on the floor z = 0 through `lens` (fx, fy, cx, cy), or None
    (ray not going down)."""
    fx, fy, cx, cy = lens
    x, y = undistort((u - cx) / fx, (v - cy) / fy, d)
    body = (1.0, -x, -y)  # optical (x right, y down, z ahead) in the body frame (x ahead, z up)
    r = rotation(mount["roll"], mount["pitch"], mount["yaw"])
    ray = [sum(r[i][j] * body[j] for j in range(3)) for i in range(3)]
    if ray[2] >= -1e-9:
        return None
    s = -mount["z"] / ray[2]
    return (mount["x"] + s * ray[0], mount["y"] + s * ray[1])


def floor_errors_mm(mount, d):
    """Distances between the true and the calibrated floor point of a 17 x 11 grid of projector
    pixels (edges included), mm."""
    return floor_errors_with_lens(mount, d, (FX, FY, CX, CY))


def floor_errors_with_lens(mount, d, lens):
    """floor_errors_mm with the calibrated lens (fx, fy, cx, cy)."""
    errors = []
    for i in range(17):
        for j in range(11):
            u = i * (WIDTH - 1) / 16.0
            v = j * (HEIGHT - 1) / 10.0
            truth = floor_point(TRUE_MOUNT, TRUE_D, u, v)
            fitted = floor_point(mount, d, u, v, lens)
            if truth is None:
                continue
            if fitted is None:
                errors.append(float("inf"))
                continue
            errors.append(1000.0 * math.hypot(truth[0] - fitted[0], truth[1] - fitted[1]))
    return sorted(errors)


def calibrate(args, timeout=90):
    binary = roslib.packages.find_node(PKG, "calibrate_projector")[0]
    proc = subprocess.run([binary] + args, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, timeout=timeout, universal_newlines=True)
    return proc.returncode, proc.stdout, proc.stderr


class CameraCalibrationTest(unittest.TestCase):
    host = None

    @classmethod
    def setUpClass(cls):
        rospy.init_node("camera_calibration_test", anonymous=True)
        cls.host = HostProcess(CONFIG, label="camera_calibration_host")
        cls.tmp = tempfile.mkdtemp(prefix="camera_calibration_")
        # The rig is up once the host publishes what it shows (demo_camera subscribed to it long
        # before): a pattern published earlier could reach the screen but not the simulated camera.
        received = []
        sub = rospy.Subscriber("/projector/rendered/image", Image, lambda m: received.append(m.header.stamp))
        deadline = time.monotonic() + 60.0
        while len(received) < 3 and time.monotonic() < deadline and cls.host.alive():
            time.sleep(0.05)
        sub.unregister()
        if len(received) < 3:
            raise RuntimeError("projector_host published no Image output within 60 s:\n" + cls.host.log_tail())

    @classmethod
    def tearDownClass(cls):
        if cls.host:
            cls.host.stop()

    def files(self, name):
        return os.path.join(self.tmp, name + "_mount.yaml"), os.path.join(self.tmp, name + "_calibration.yaml")

    def run_calibration(self, name, extra, image="/demo_camera/image_raw"):
        mount_file, calibration_file = self.files(name)
        args = ["--camera", "--camera-info", CALIBRATION, "--image", image, "--output", mount_file,
                "--output-calibration", calibration_file] + extra
        rc, out, err = calibrate(args)
        return rc, out, err, mount_file, calibration_file

    def test_1_calibrates_a_wrong_mount_and_an_unknown_wide_angle_lens(self):
        rc, out, err, mount_file, calibration_file = self.run_calibration("good", [])
        self.assertEqual(rc, 0, "calibrate_projector failed:\n%s\n%s\nhost:\n%s" % (out, err, self.host.log_tail()))
        sys.stdout.write(out)
        with open(mount_file) as f:
            mount = yaml.safe_load(f)
        with open(calibration_file) as f:
            calibration = yaml.safe_load(f)
        self.assertEqual(mount["parent_frame"], "base_link")
        position_mm = 1000.0 * math.sqrt(sum((mount[k] - TRUE_MOUNT[k]) ** 2 for k in ("x", "y", "z")))
        angles_deg = [abs(math.degrees(mount[k] - TRUE_MOUNT[k])) for k in ("roll", "pitch", "yaw")]
        print("mount: %.2f mm, roll/pitch/yaw %.4f %.4f %.4f deg from the truth" % tuple([position_mm] + angles_deg))
        self.assertLessEqual(position_mm, 2.0, "mount position off the truth")
        for name, error in zip(("roll", "pitch", "yaw"), angles_deg):
            self.assertLessEqual(error, 0.05, "mount %s off the truth" % name)
        d = calibration["distortion_coefficients"]["data"]
        self.assertEqual(calibration["distortion_model"], "plumb_bob")
        print("k1 %.5f (truth %.2f), k2 %.5f (truth %.2f)" % (d[0], TRUE_D[0], d[1], TRUE_D[1]))
        self.assertAlmostEqual(d[0], TRUE_D[0], delta=0.01)
        self.assertAlmostEqual(d[1], TRUE_D[1], delta=0.02)
        k = calibration["camera_matrix"]["data"]
        self.assertEqual((k[0], k[2], k[4], k[5]), (FX, CX, FY, CY), "fx, fy, cx, cy must stay the prior's")
        errors = floor_errors_mm(mount, d)
        median = errors[len(errors) // 2]
        print("floor error over the lit area: median %.2f mm, max %.2f mm (%d pixels)" % (median, errors[-1], len(errors)))
        self.assertLessEqual(median, 1.0)
        self.assertLessEqual(errors[-1], 3.0)
        # Ignoring the lens (the file as it was, with the solved mount): the error the issue measured.
        ignored = floor_errors_mm(mount, [0.0] * 5)
        print("the same mount without D: median %.1f mm, max %.1f mm" % (ignored[len(ignored) // 2], ignored[-1]))
        took = re.search(r"Took ([0-9.]+) s", out)
        self.assertIsNotNone(took, "no 'Took' line in the report")
        print("calibration took %s s" % took.group(1))

    def test_5_a_tilted_board_fits_the_lens(self):
        # The file's lens off the truth: fx, fy 3 % more, cx, cy 15 px more (K and P).
        with open(CALIBRATION) as f:
            wrong = yaml.safe_load(f)
        k = wrong["camera_matrix"]["data"]
        k[0], k[4], k[2], k[5] = 1.03 * FX, 1.03 * FY, CX + 15.0, CY + 15.0
        p = wrong["projection_matrix"]["data"]
        p[0], p[5], p[2], p[6] = k[0], k[4], k[2], k[5]
        wrong_file = os.path.join(self.tmp, "wrong_lens.yaml")
        with open(wrong_file, "w") as f:
            yaml.safe_dump(wrong, f)
        mount_file, calibration_file = self.files("board")
        rc, out, err = calibrate(["--camera", "--camera-info", wrong_file, "--image", "/board_camera/image_raw",
                                  "--board", "7x5:0.06", "--output", mount_file, "--output-calibration",
                                  calibration_file], timeout=150)
        self.assertEqual(rc, 0, "calibrate_projector --board failed:\n%s\n%s\nhost:\n%s" % (out, err, self.host.log_tail()))
        sys.stdout.write(out)
        with open(mount_file) as f:
            mount = yaml.safe_load(f)
        with open(calibration_file) as f:
            calibration = yaml.safe_load(f)
        k = calibration["camera_matrix"]["data"]
        p = calibration["projection_matrix"]["data"]
        print("fitted fx %.2f fy %.2f cx %.2f cy %.2f (truth %.1f %.1f %.1f %.1f)" % (k[0], k[4], k[2], k[5], FX, FY, CX, CY))
        self.assertAlmostEqual(k[0], FX, delta=0.003 * FX)
        self.assertAlmostEqual(k[4], FY, delta=0.003 * FY)
        self.assertAlmostEqual(k[2], CX, delta=3.0)
        self.assertAlmostEqual(k[5], CY, delta=3.0)
        self.assertEqual((p[0], p[2], p[5], p[6]), (k[0], k[2], k[4], k[5]), "P must be [K | 0]")
        d = calibration["distortion_coefficients"]["data"]
        self.assertAlmostEqual(d[0], TRUE_D[0], delta=0.01)
        # The floor error of the written lens and mount against the truth (this oracle's own maths).
        errors = floor_errors_with_lens(mount, d, (k[0], k[4], k[2], k[5]))
        print("--board floor error: median %.2f mm, max %.2f mm" % (errors[len(errors) // 2], errors[-1]))
        self.assertLessEqual(errors[len(errors) // 2], 1.0)
        self.assertLessEqual(errors[-1], 3.0)

    def test_2_refuses_without_a_projector(self):
        rc, out, err, mount_file, calibration_file = self.run_calibration(
            "no_projector", ["--pattern-topic", "/nobody/pattern"])
        self.assertEqual(rc, 1, out + err)
        self.assertIn("nothing listens on /nobody/pattern", err)
        self.assertFalse(os.path.exists(mount_file) or os.path.exists(calibration_file), "a file was written")

    def test_3_refuses_without_tf_to_the_floor(self):
        rc, out, err, mount_file, calibration_file = self.run_calibration("no_tf", ["--frame", "no_such_frame"])
        self.assertEqual(rc, 1, out + err)
        self.assertIn("no tf from the camera's frame", err)
        self.assertFalse(os.path.exists(mount_file) or os.path.exists(calibration_file), "a file was written")

    def test_4_refuses_a_camera_that_sees_too_little(self):
        rc, out, err, mount_file, calibration_file = self.run_calibration(
            "blind", [], image="/blind_camera/image_raw")
        self.assertEqual(rc, 1, out + err)
        self.assertIn("sees too little of the projection", err)
        self.assertFalse(os.path.exists(mount_file) or os.path.exists(calibration_file), "a file was written")


if __name__ == "__main__":
    rostest.rosrun(PKG, "camera_calibration", CameraCalibrationTest)
