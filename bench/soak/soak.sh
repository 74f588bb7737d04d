#!/usr/bin/env bash
# Soak of projector_host (issue 13): a private X server and ROS master, demo_navigation replanning
# at 20 Hz with 50 Hz tf (the robot drives), projector_host with the demo config, and
# `rosservice call /projector_host/reload` every reload period. Samples the host's RSS
# (/proc/<pid>/status VmRSS) every few seconds and logs its /diagnostics; at the end prints one
# PASSED / FAILED / SKIPPED line per check (bench/soak/check_soak.py: host alive, RSS growth after
# warm-up <= 2 MB, every reload answered success, no ERROR in its log, OGRE resource counts flat
# when the host publishes them) and exits non-zero on a failure.
#
#   bench/soak/soak.sh [--minutes N] [--reload-seconds S]
#       --minutes N         length of the soak (default 5; the issue's long soak: --minutes 60)
#       --reload-seconds S  seconds between reloads (default 60; 30 when --minutes is under 5)
#
# Run through `scripts/test --soak [--soak-minutes N]` (builds first), or directly with a built
# workspace: RP_WS=<workspace with projector_host and demo_navigation built>.
# Environment: SOAK_OUTPUT (folder for the logs, default $RP_WS/soak-<time>), SOAK_WARMUP_SECONDS
# (60, and at least two reload periods + 10 s), SOAK_SAMPLE_SECONDS (5), SOAK_RSS_LIMIT_MB (2), SOAK_CONFIG (default rviz/demo.rviz),
# SOAK_HEAPTRACK=1 (run the host under heaptrack, Debian package heaptrack, to find where memory
# grows: `heaptrack_print -f $SOAK_OUTPUT/heaptrack.zst`; RSS then includes heaptrack's own).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
ROOT="$(cd "$HERE/../.." && pwd)"

minutes=5
reload_seconds=""
while [ $# -gt 0 ]; do
  case "$1" in
    --minutes) minutes="${2:?--minutes N}"; shift 2 ;;
    --reload-seconds) reload_seconds="${2:?--reload-seconds S}"; shift 2 ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) echo "soak: unknown option $1" >&2; exit 2 ;;
  esac
done
case "$minutes" in ''|*[!0-9.]*) echo "soak: --minutes wants a number" >&2; exit 2 ;; esac
if [ -z "$reload_seconds" ]; then
  reload_seconds=$(awk -v m="$minutes" 'BEGIN { print (m < 5 ? 30 : 60) }')
fi

# shellcheck source=../../scripts/lib/common.sh
source "$ROOT/scripts/lib/common.sh"
rp_source_ros
bin="$RP_WS/devel/lib/rviz_projector"
for exe in projector_host demo_navigation; do
  [ -x "$bin/$exe" ] || { rp_log "soak: $bin/$exe is not built (run scripts/test --soak)"; exit 2; }
done
set +u
# shellcheck disable=SC1091
source "$RP_WS/devel/setup.bash"
set -u

out="${SOAK_OUTPUT:-$RP_WS/soak-$(date +%Y%m%d-%H%M%S)}"
mkdir -p "$out"
config="${SOAK_CONFIG:-$ROOT/rviz/demo.rviz}"
# Warm-up: 60 s, and at least two reloads: the first reloads raise the allocator's high-water mark
# (freed memory glibc keeps), measured flat afterwards (doc/bench/soak-host.txt).
warmup="${SOAK_WARMUP_SECONDS:-$(awk -v r="$reload_seconds" 'BEGIN { w = 2 * r + 10; print (w > 60 ? w : 60) }')}"
sample="${SOAK_SAMPLE_SECONDS:-5}"

# shellcheck source=../../scripts/lib/xserver.sh
source "$ROOT/scripts/lib/xserver.sh"
export XSERVER_LOG_DIR="$out"
xserver_start
port="$(rp_free_port)"
export ROS_MASTER_URI="http://localhost:$port"
export ROS_HOME="$out/ros_home"
mkdir -p "$ROS_HOME"

started=()
stop_pid() { # pid: SIGINT, wait up to 3 s, then SIGTERM / SIGKILL
  local pid=$1 i
  kill -0 "$pid" 2>/dev/null || return 0
  kill -INT "$pid" 2>/dev/null || true
  for i in $(seq 1 30); do kill -0 "$pid" 2>/dev/null || return 0; sleep 0.1; done
  kill -TERM "$pid" 2>/dev/null || true
  for i in $(seq 1 30); do kill -0 "$pid" 2>/dev/null || return 0; sleep 0.1; done
  kill -KILL "$pid" 2>/dev/null || true
}
cleanup() {
  local i
  for ((i = ${#started[@]} - 1; i >= 0; i--)); do stop_pid "${started[i]}"; done
  xserver_stop
}
trap cleanup EXIT

rosmaster --core -p "$port" >"$out/rosmaster.log" 2>&1 &
started+=($!)
deadline=$((SECONDS + 15))
until rostopic list >/dev/null 2>&1; do
  [ "$SECONDS" -lt "$deadline" ] || { rp_log "soak: the ROS master did not answer within 15 s"; exit 1; }
  sleep 0.1
done

"$bin/demo_navigation" _replan_rate:=20 _tf_rate:=50 >"$out/demo_navigation.log" 2>&1 &
started+=($!)
/usr/bin/python3 "$HERE/diagnostics_log.py" "$out/diagnostics.tsv" >"$out/diagnostics_log.log" 2>&1 &
started+=($!)
host_cmd=("$bin/projector_host" "$config")
if [ "${SOAK_HEAPTRACK:-0}" = 1 ]; then
  command -v heaptrack >/dev/null || { rp_log "soak: SOAK_HEAPTRACK=1 needs heaptrack (apt-get install heaptrack)"; exit 2; }
  # The host runs as a child of heaptrack's script (found below); analyse with heaptrack_print.
  host_cmd=(heaptrack -o "$out/heaptrack" "${host_cmd[@]}")
fi
(cd "$out" && exec "${host_cmd[@]}") >"$out/host.log" 2>&1 &
host_pid=$!
started+=("$host_pid")
if [ "${SOAK_HEAPTRACK:-0}" = 1 ]; then
  deadline=$((SECONDS + 30))
  until child="$(pgrep -P "$host_pid" -x projector_host)"; do
    [ "$SECONDS" -lt "$deadline" ] || { rp_log "soak: projector_host did not start under heaptrack"; exit 1; }
    sleep 0.2
  done
  host_pid="$child"
  started+=("$host_pid")
fi
host_start=$SECONDS
rp_log "soak: ${minutes} min, reload every ${reload_seconds} s, warm-up ${warmup} s, RSS every ${sample} s (logs in $out)"

# Wait for the reload service (the host is up and loaded its config).
deadline=$((SECONDS + 60))
until rosservice list 2>/dev/null | grep -qx /projector_host/reload; do
  if [ "$SECONDS" -ge "$deadline" ] || ! kill -0 "$host_pid" 2>/dev/null; then
    tail -n 20 "$out/host.log" >&2
    echo "FAILED soak: projector_host did not offer /projector_host/reload within 60 s"
    exit 1
  fi
  sleep 0.5
done

rss_kb() { awk '/^VmRSS:/ { print $2 }' "/proc/$1/status" 2>/dev/null; }
: >"$out/rss.tsv"
: >"$out/reloads.tsv"
end=$(awk -v s="$SECONDS" -v m="$minutes" 'BEGIN { printf "%d", s + m * 60 }')
next_sample=$SECONDS
next_reload=$((SECONDS + reload_seconds))
while [ "$SECONDS" -lt "$end" ] && kill -0 "$host_pid" 2>/dev/null; do
  if [ "$SECONDS" -ge "$next_sample" ]; then
    kb="$(rss_kb "$host_pid")"
    [ -n "$kb" ] && printf '%d\t%s\n' "$((SECONDS - host_start))" "$kb" >>"$out/rss.tsv"
    next_sample=$((next_sample + sample))
  fi
  if [ "$SECONDS" -ge "$next_reload" ]; then
    answer="$(timeout 30 rosservice call /projector_host/reload 2>&1 || true)"
    ok=0
    grep -q '^success: True' <<<"$answer" && ok=1
    printf '%d\t%d\t%s\n' "$((SECONDS - host_start))" "$ok" "$(tr '\n\t' '  ' <<<"$answer")" >>"$out/reloads.tsv"
    next_reload=$((next_reload + reload_seconds))
  fi
  sleep 1
done
alive=0
kill -0 "$host_pid" 2>/dev/null && alive=1
[ "$alive" -eq 1 ] || tail -n 20 "$out/host.log" >&2

status=0
/usr/bin/python3 "$HERE/check_soak.py" "$out" "$warmup" "${SOAK_RSS_LIMIT_MB:-2}" "$alive" || status=$?
rp_log "soak: logs in $out"
exit "$status"
