#!/usr/bin/env python3
"""Logs projector_host's /diagnostics for the soak (bench/soak/soak.sh).

usage: diagnostics_log.py OUT.tsv

Writes one line per value of interest of every /diagnostics message, tab separated:
seconds since start (wall clock), status name, key, value. Kept: the level and message of every
"projector_host: ..." status (key "level" / "message") and, from "projector_host: config", the keys
that start with "OGRE " (resource counts, when the host publishes them). Runs until SIGINT/SIGTERM.
"""
import sys
import time

import rospy
from diagnostic_msgs.msg import DiagnosticArray


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = open(sys.argv[1], "w", buffering=1)
    start = time.monotonic()

    def on_diagnostics(msg):
        now = time.monotonic() - start
        for status in msg.status:
            if not status.name.startswith("projector_host"):
                continue
            out.write("%.2f\t%s\tlevel\t%d\n" % (now, status.name, status.level))
            out.write("%.2f\t%s\tmessage\t%s\n" % (now, status.name, status.message.replace("\t", " ")))
            if status.name.endswith(": config"):
                for kv in status.values:
                    if kv.key.startswith("OGRE "):
                        out.write("%.2f\t%s\t%s\t%s\n" % (now, status.name, kv.key, kv.value))

    rospy.init_node("soak_diagnostics_log", anonymous=True, disable_signals=False)
    rospy.Subscriber("/diagnostics", DiagnosticArray, on_diagnostics, queue_size=50)
    rospy.spin()
    out.close()


if __name__ == "__main__":
    main()
