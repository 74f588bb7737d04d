#!/usr/bin/env python3
"""Checks the robot deployment files offline (doc/guide/running-on-the-robot.md):

- launch/projector_host.launch, loaded by roslaunch's own loader: config is required; the node is
  projector_host with the config (and --watch, --all-displays) as arguments, respawned by default, DISPLAY set
  only when display:= is given; the executable is found in the package.
- config/robot/*.service: `systemd-analyze verify` (no output, exit 0), the keys the guide
  promises, every `$$NAME` a command uses is set by an Environment= line, and every `bash -c`
  script parses (`bash -n`).
- config/robot/xorg-projector.conf: no blanking, no DPMS, modesetting; the X unit starts Xorg
  with it and -nocursor; Xorg starts with it (the dummy driver swapped in) and its screen saver
  timeout is 0.
- config/robot/rviz-projector-host.desktop: `desktop-file-validate`, starts projector_host.launch.
- rviz/robot_host.rviz: valid YAML with a ProjectedPath (Path timeout > 0) and a ProjectorCamera.

Usage: check_deploy_files.py PACKAGE_DIR. Prints "FAILED ..." and "SKIPPED ..." lines (a tool that
is not installed is a skip, never a pass); exit status 1 on any failure.
Run with /usr/bin/python3 in a sourced workspace (roslaunch, rospkg, yaml).
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

import roslaunch.config
import roslaunch.core
import roslib.packages
import yaml

failures = []
skips = []


def check(condition, what):
    if not condition:
        failures.append(what)
    return condition


def parse_unit(path):
    """{section: [(key, value), ...]} of a systemd unit file (keys may repeat)."""
    sections = {}
    current = None
    with open(path) as f:
        for number, raw in enumerate(f, 1):
            line = raw.strip()
            if not line or line[0] in "#;":
                continue
            if line.startswith("[") and line.endswith("]"):
                current = sections.setdefault(line[1:-1], [])
            elif "=" in line and current is not None:
                key, value = line.split("=", 1)
                current.append((key.strip(), value.strip()))
            else:
                failures.append("%s:%d: not a key=value line: %s" % (path, number, line))
    return sections


def values(unit, section, key):
    return [v for k, v in unit.get(section, []) if k == key]


def words(unit, section, key):
    return " ".join(values(unit, section, key)).split()


def bash_scripts(command):
    """The scripts of `/bin/bash -c '...'` in a systemd command line, with $$ turned into $."""
    return [s.replace("$$", "$") for s in re.findall(r"bash -c '([^']*)'", command)]


def check_launch(package_dir):
    launch = os.path.join(package_dir, "launch", "projector_host.launch")

    def load(args):
        config = roslaunch.config.load_config_default([(launch, args)], 11311, verbose=False)
        check(len(config.nodes) == 1, "projector_host.launch %s: %d nodes, expected 1" % (args, len(config.nodes)))
        return config.nodes[0]

    node = load(["config:=/robot/my p.rviz"])
    check((node.package, node.type, node.name) == ("rviz_projector", "projector_host", "projector_host"),
          "projector_host.launch starts %s/%s as %s" % (node.package, node.type, node.name))
    # roslaunch splits a node's args with shlex.
    check(shlex.split(node.args) == ["/robot/my p.rviz"], "projector_host.launch args %r, expected the config only" % node.args)
    check(node.respawn and node.respawn_delay == 2.0,
          "projector_host.launch: respawn %s after %s s, expected true after 2" % (node.respawn, node.respawn_delay))
    check(dict(node.env_args).get("DISPLAY") is None, "projector_host.launch sets DISPLAY without display:=")
    node = load(["config:=/robot/p.rviz", "watch:=true", "display:=:7", "respawn:=false", "output:=log"])
    check(shlex.split(node.args) == ["--watch", "/robot/p.rviz"], "watch:=true gives args %r" % node.args)
    check(dict(node.env_args).get("DISPLAY") == ":7", "display:=:7 gives env %r" % node.env_args)
    check(not node.respawn, "respawn:=false still respawns")
    check(node.output == "log", "output:=log gives output %r" % node.output)
    node = load(["config:=/robot/p.rviz", "all_displays:=true"])
    check(shlex.split(node.args) == ["--all-displays", "/robot/p.rviz"], "all_displays:=true gives args %r" % node.args)
    node = load(["config:=/robot/p.rviz", "respawn:=false", "required:=true"])
    check(node.required and not node.respawn, "required:=true respawn:=false: required %s, respawn %s" % (node.required, node.respawn))
    try:
        load([])
        failures.append("projector_host.launch loads without config:= (it must be required)")
    except roslaunch.core.RLException as e:
        check("config" in str(e), "projector_host.launch without config:= says %r" % str(e))
    found = roslib.packages.find_node("rviz_projector", "projector_host")
    check(found, "rosrun cannot find rviz_projector/projector_host (is the workspace sourced and built?)")


def check_units(robot_dir):
    host = parse_unit(os.path.join(robot_dir, "rviz-projector-host.service"))
    xorg = parse_unit(os.path.join(robot_dir, "rviz-projector-xorg.service"))
    core = parse_unit(os.path.join(robot_dir, "roscore.service"))
    # The host: after X and the master, restarted on failure, as user robot.
    check("rviz-projector-xorg.service" in words(host, "Unit", "Requires"), "host unit: no Requires= on the X unit")
    after = words(host, "Unit", "After")
    for unit in ("rviz-projector-xorg.service", "roscore.service"):
        check(unit in after, "host unit: not After=%s" % unit)
    check(values(host, "Service", "Restart") == ["on-failure"], "host unit: Restart= is not on-failure")
    check(values(host, "Service", "RestartSec") == ["2"], "host unit: RestartSec= is not 2")
    check(values(host, "Service", "User") == ["robot"], "host unit: User= is not robot")
    environment = dict(v.split("=", 1) for v in values(host, "Service", "Environment") if "=" in v)
    check(environment.get("DISPLAY") == ":0", "host unit: Environment=DISPLAY=:0 missing")
    check(environment.get("ROS_MASTER_URI", "").startswith("http://"), "host unit: Environment=ROS_MASTER_URI missing")
    check(any("rosnode list" in s for s in values(host, "Service", "ExecStartPre")),
          "host unit: ExecStartPre does not wait for the master (rosnode list)")
    check(any("projector_host" in s for s in values(host, "Service", "ExecStart")), "host unit: ExecStart runs no projector_host")
    check(any("/projector_host/reload" in s for s in values(host, "Service", "ExecReload")),
          "host unit: ExecReload does not call /projector_host/reload")
    env_file = os.path.join(robot_dir, "rviz-projector-host.env")
    with open(env_file) as f:
        file_keys = {l.split("=", 1)[0] for l in f.read().splitlines() if "=" in l and not l.startswith("#")}
    # Every variable a command uses is set (in the unit; the env file only overrides).
    for name, unit in (("rviz-projector-host.service", host), ("roscore.service", core)):
        defined = {v.split("=", 1)[0] for v in values(unit, "Service", "Environment")}
        for key in ("ExecStartPre", "ExecStart", "ExecReload"):
            for command in values(unit, "Service", key):
                for var in re.findall(r"\$\$\{?([A-Za-z_][A-Za-z0-9_]*)", command):
                    check(var in defined, "%s: %s uses $%s, which no Environment= line sets" % (name, key, var))
                for script in bash_scripts(command):
                    parsed = subprocess.run(["bash", "-n", "-c", script], capture_output=True, text=True)
                    check(parsed.returncode == 0, "%s: %s script does not parse: %s" % (name, key, parsed.stderr.strip()))
    check(file_keys <= set(environment) | {"ROS_SETUP"},
          "rviz-projector-host.env sets %s, which the host unit does not use" % sorted(file_keys - set(environment)))
    # The X server: the shipped config, no cursor, restarted.
    command = " ".join(values(xorg, "Service", "ExecStart")).split()
    check(command[:2] == ["/usr/bin/Xorg", ":0"], "X unit: ExecStart is not /usr/bin/Xorg :0 ...: %s" % command)
    check("-nocursor" in command, "X unit: Xorg without -nocursor")
    check("-config" in command and command[command.index("-config") + 1] == "xorg-projector.conf",
          "X unit: Xorg without -config xorg-projector.conf")
    check(values(xorg, "Service", "Restart") == ["always"], "X unit: Restart= is not always")

    analyze = shutil.which("systemd-analyze")
    if not analyze:
        skips.append("systemd-analyze verify: not installed (Debian package systemd)")
        return
    with tempfile.TemporaryDirectory() as units:
        for name in ("rviz-projector-host.service", "rviz-projector-xorg.service", "roscore.service"):
            shutil.copy(os.path.join(robot_dir, name), units)
        paths = sorted(os.path.join(units, n) for n in os.listdir(units))
        result = subprocess.run([analyze, "verify", "--man=no"] + paths, capture_output=True, text=True)
        # It warns (exit 0) about unknown keys and bad values: any output is a failure too.
        report = (result.stdout + result.stderr).strip()
        check(result.returncode == 0 and not report, "systemd-analyze verify (exit %d): %s" % (result.returncode, report))


def check_xorg(robot_dir):
    path = os.path.join(robot_dir, "xorg-projector.conf")
    with open(path) as f:
        text = re.sub(r"#.*", "", f.read())
    sections = dict(re.findall(r'Section\s+"(\w+)"(.*?)EndSection', text, re.S))
    for name in ("ServerFlags", "Device", "Monitor", "Screen", "ServerLayout"):
        check(name in sections, "xorg-projector.conf: no %s section" % name)
    options = dict(re.findall(r'Option\s+"(\w+)"\s+"([^"]*)"', sections.get("ServerFlags", "")))
    for option in ("BlankTime", "StandbyTime", "SuspendTime", "OffTime"):
        check(options.get(option) == "0", 'xorg-projector.conf: ServerFlags Option "%s" is not "0"' % option)
    check(re.search(r'Option\s+"DPMS"\s+"false"', sections.get("Monitor", "")), 'xorg-projector.conf: Monitor has no Option "DPMS" "false"')
    check(re.search(r'Driver\s+"modesetting"', sections.get("Device", "")), 'xorg-projector.conf: Device driver is not "modesetting"')


def check_xorg_starts(robot_dir):
    """Xorg starts with xorg-projector.conf, its driver swapped for the dummy one (no graphics card
    here), and its screen saver is off."""
    xorg = shutil.which("Xorg")
    if not xorg or not os.path.exists("/usr/lib/xorg/modules/drivers/dummy_drv.so"):
        skips.append("Xorg with xorg-projector.conf: needs Xorg and xserver-xorg-video-dummy")
        return
    if os.geteuid() != 0:
        skips.append("Xorg with xorg-projector.conf: needs root (Xorg -config with an absolute path)")
        return
    with open(os.path.join(robot_dir, "xorg-projector.conf")) as f:
        text = f.read()
    check('Driver     "modesetting"' in text, "xorg-projector.conf: no modesetting Driver line to swap")
    text = text.replace('Driver     "modesetting"', 'Driver "dummy"\n    VideoRam 256000')
    text = text.replace('Option "DPMS" "false"', 'Option "DPMS" "false"\n    HorizSync 5.0-1000.0\n    VertRefresh 5.0-200.0')
    with tempfile.TemporaryDirectory() as work:
        conf = os.path.join(work, "xorg-projector-dummy.conf")
        log = os.path.join(work, "xorg.log")
        with open(conf, "w") as f:
            f.write(text)
        read_end, write_end = os.pipe()
        server = subprocess.Popen([xorg, "-displayfd", str(write_end), "-config", conf, "-nocursor", "-nolisten", "tcp",
                                   "-noreset", "-logfile", log], pass_fds=(write_end,),
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        os.close(write_end)
        try:
            # Xorg writes its display number to the pipe once it accepts clients (EOF: it died).
            with os.fdopen(read_end) as numbers:
                number = numbers.readline().strip()
            if not check(number.isdigit(), "Xorg did not start with xorg-projector.conf (dummy driver): %s" % tail(log)):
                return
            env = dict(os.environ, DISPLAY=":" + number)
            query = subprocess.run(["xset", "-q"], env=env, capture_output=True, text=True, timeout=20)
            check(re.search(r"timeout:\s+0\b", query.stdout),
                  "Xorg with xorg-projector.conf: screen saver timeout is not 0: %s" % query.stdout.strip())
        finally:
            server.terminate()
            try:
                server.wait(timeout=10)
            except subprocess.TimeoutExpired:
                server.kill()
                server.wait()


def tail(path, lines=8):
    try:
        with open(path) as f:
            return " | ".join(l.rstrip() for l in f.readlines()[-lines:])
    except OSError:
        return "(no log)"


def check_desktop(robot_dir):
    path = os.path.join(robot_dir, "rviz-projector-host.desktop")
    with open(path) as f:
        entries = dict(l.split("=", 1) for l in f.read().splitlines() if "=" in l and not l.startswith("#"))
    check(entries.get("Type") == "Application", "desktop file: Type is not Application")
    check("projector_host.launch" in entries.get("Exec", "") and "config:=" in entries.get("Exec", ""),
          "desktop file: Exec does not start projector_host.launch config:=...")
    check("--wait" in entries.get("Exec", ""), "desktop file: roslaunch without --wait would start a master of its own")
    validate = shutil.which("desktop-file-validate")
    if not validate:
        skips.append("desktop-file-validate: not installed (Debian package desktop-file-utils)")
        return
    result = subprocess.run([validate, path], capture_output=True, text=True)
    report = (result.stdout + result.stderr).strip()
    check(result.returncode == 0 and not report, "desktop-file-validate: %s" % report)


def check_robot_config(package_dir):
    with open(os.path.join(package_dir, "rviz", "robot_host.rviz")) as f:
        config = yaml.safe_load(f)
    displays = config["Visualization Manager"]["Displays"]
    by_class = {d.get("Class"): d for d in displays}
    path = by_class.get("rviz_projector/ProjectedPath", {})
    camera = by_class.get("rviz_projector/ProjectorCamera")
    check(float(path.get("Path timeout", 0)) > 0, "robot_host.rviz: ProjectedPath without a Path timeout > 0")
    check(camera is not None, "robot_host.rviz: no ProjectorCamera")
    check(camera is None or float(camera.get("TF timeout", 0)) > 0, "robot_host.rviz: ProjectorCamera without a TF timeout > 0")


def main():
    package_dir = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    robot_dir = os.path.join(package_dir, "config", "robot")
    for part in (check_launch, check_units, check_xorg, check_xorg_starts, check_desktop, check_robot_config):
        try:
            part(package_dir if part in (check_launch, check_robot_config) else robot_dir)
        except Exception as e:  # a broken file must be a failure with its reason, not a traceback
            failures.append("%s: %s: %s" % (part.__name__, type(e).__name__, e))
    for line in failures:
        print("FAILED " + line)
    for line in skips:
        print("SKIPPED " + line)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
