#!/usr/bin/env python3
"""A picture of what the robot's camera sees, with where the floor grid really is marked in red.

    camera_snapshot.py OUT.png [IMAGE_TOPIC] [FIXED_FRAME]

Takes one mono8 frame from IMAGE_TOPIC (default /demo_camera/image_raw) and its CameraInfo, looks
up the camera's optical frame in FIXED_FRAME (default base_link) with tf, and draws a small red
cross at every 10 cm grid point of the floor (z = 0 of FIXED_FRAME) that the camera sees, through
its K and D (OpenCV's plumb_bob model, written out here). With the ProjectorCamera's Test pattern on
Metric grid, a calibrated projector draws its grid lines through the red crosses; a wrong mount
draws them beside. scripts/demo --calibration uses it for the before/after pictures. Needs
ImageMagick's convert. Exits 1 when no frame or tf arrives within 15 s.
"""
import math
import os
import subprocess
import sys
import tempfile

import rospy
import tf2_ros
from sensor_msgs.msg import CameraInfo, Image


def rotation_matrix(x, y, z, w):
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]


def project(point, rotation, translation, info):
    """Pixel of a fixed-frame point in the camera (optical frame pose rotation, translation)."""
    d = [point[i] - translation[i] for i in range(3)]
    c = [sum(rotation[j][i] * d[j] for j in range(3)) for i in range(3)]  # R^T (p - t)
    if c[2] <= 0.05:
        return None
    x, y = c[0] / c[2], c[1] / c[2]
    k1, k2, p1, p2, k3 = (list(info.D) + [0.0] * 5)[:5]
    r2 = x * x + y * y
    radial = 1 + k1 * r2 + k2 * r2 * r2 + k3 * r2 * r2 * r2
    xd = x * radial + 2 * p1 * x * y + p2 * (r2 + 2 * x * x)
    yd = y * radial + p1 * (r2 + 2 * y * y) + 2 * p2 * x * y
    return info.K[0] * xd + info.K[2], info.K[4] * yd + info.K[5]


def main():
    out = sys.argv[1]
    topic = sys.argv[2] if len(sys.argv) > 2 else "/demo_camera/image_raw"
    fixed = sys.argv[3] if len(sys.argv) > 3 else "base_link"
    rospy.init_node("camera_snapshot", anonymous=True)
    info_topic = topic.rsplit("/", 1)[0] + "/camera_info"
    try:
        info = rospy.wait_for_message(info_topic, CameraInfo, timeout=15.0)
        image = rospy.wait_for_message(topic, Image, timeout=15.0)
    except rospy.ROSException as e:
        sys.stderr.write("camera_snapshot: %s\n" % e)
        return 1
    if image.encoding != "mono8":
        sys.stderr.write("camera_snapshot: %s is %s, not mono8\n" % (topic, image.encoding))
        return 1
    buffer = tf2_ros.Buffer()
    tf2_ros.TransformListener(buffer)
    try:
        t = buffer.lookup_transform(fixed, image.header.frame_id, rospy.Time(0), rospy.Duration(15.0)).transform
    except tf2_ros.TransformException as e:
        sys.stderr.write("camera_snapshot: %s\n" % e)
        return 1
    rotation = rotation_matrix(t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w)
    translation = [t.translation.x, t.translation.y, t.translation.z]
    w, h = image.width, image.height
    rgb = bytearray(w * h * 3)
    for v in range(h):
        row = image.data[v * image.step:v * image.step + w]
        for u in range(w):
            rgb[3 * (v * w + u):3 * (v * w + u) + 3] = bytes((row[u],) * 3)
    for i in range(-30, 31):
        for j in range(-30, 31):
            pixel = project((0.1 * i, 0.1 * j, 0.0), rotation, translation, info)
            if pixel is None:
                continue
            pu, pv = int(round(pixel[0])), int(round(pixel[1]))
            for du, dv in ((0, 0), (1, 0), (-1, 0), (0, 1), (0, -1), (2, 0), (-2, 0), (0, 2), (0, -2)):
                x, y = pu + du, pv + dv
                if 0 <= x < w and 0 <= y < h:
                    rgb[3 * (y * w + x):3 * (y * w + x) + 3] = b"\xff\x00\x00"
    with tempfile.NamedTemporaryFile(suffix=".ppm", delete=False) as f:
        f.write(b"P6 %d %d 255\n" % (w, h))
        f.write(bytes(rgb))
        ppm = f.name
    try:
        subprocess.check_call(["convert", ppm, out])
    finally:
        os.unlink(ppm)
    return 0


if __name__ == "__main__":
    sys.exit(main())
