# shellcheck shell=bash
# scripts/lib/xserver.sh -- a private headless X server for tests and demos.
#
# Source it (do not execute it); it works under `set -euo pipefail`:
#
#     source "$(dirname "${BASH_SOURCE[0]}")/lib/xserver.sh"
#     xserver_start              # or: xserver_start --single
#     xserver_stop_on_exit       # or call xserver_stop yourself
#     rviz ...                   # DISPLAY is exported
#     xserver_unplug_projector   # DUMMY1 disappears (Qt: screenRemoved)
#     xserver_replug_projector   # DUMMY1 comes back (Qt: screenAdded)
#
# Servers:
#   dummy  Xorg + dummy video driver, configured by xorg-dummy.conf next to this file.
#          One X screen with two RandR outputs, i.e. two QScreens side by side:
#            DUMMY0  1600x900 at 0,0       (the desktop)
#            DUMMY1  1280x800 at 1600,0    (the projector, can be unplugged/replugged)
#          Needs xserver-xorg-core xserver-xorg-video-dummy x11-xserver-utils, and root
#          (Xorg is started directly, there is no Xorg.wrap/logind session).
#   xvfb   Xvfb with one 1920x1080x24 screen (package xvfb). Used with --single, with
#          XSERVER_FORCE=xvfb, or as fallback when the dummy server is unavailable or fails.
#
# Functions (all return 0 on success, non-zero on failure; none of them exits the shell):
#   xserver_start [--single]   start a server on a free display :90..:199, export DISPLAY,
#                              wait until it answers; sets XSERVER_KIND (dummy|xvfb, exported),
#                              XSERVER_PID, XSERVER_DISPLAY_NUM, XSERVER_LOG, XSERVER_SERVER_LOG.
#                              Prints one info line to stderr; details go to the log files.
#   xserver_unplug_projector   xrandr --output DUMMY1 --off   (returns 1 on xvfb / no server)
#   xserver_replug_projector   DUMMY1 back at 1280x800 right of DUMMY0 (returns 1 on xvfb)
#   xserver_stop               stop the server started by this shell (only that one), remove
#                              its lock file and socket if left behind, restore DISPLAY.
#                              Safe to call several times, or when nothing was started.
#   xserver_stop_on_exit       append xserver_stop to the shell's EXIT trap (keeps an existing
#                              EXIT trap and the exit status). bash runs EXIT traps on normal
#                              exit, on `set -e` failures and on SIGTERM/SIGINT/SIGHUP, not on
#                              SIGKILL. If you later replace the EXIT trap, or your own trap
#                              calls `exit`, call xserver_stop yourself.
#
# Environment (all optional):
#   XSERVER_FORCE        ""/auto: dummy, falling back to xvfb (default)
#                        xvfb:    never try Xorg (e.g. non-root, or to simulate Xorg missing)
#                        dummy:   Xorg/dummy only, fail instead of falling back
#   XSERVER_LOG_DIR      directory for the log files (default /tmp)
#   XSERVER_TIMEOUT      seconds to wait for the server to answer (default 15)
#   XSERVER_DISPLAY_MIN / XSERVER_DISPLAY_MAX   display number range (default 90 / 199)
#   XSERVER_XORG, XSERVER_XVFB   server binaries (default /usr/bin/Xorg, /usr/bin/Xvfb)
#   XSERVER_XORG_CONF    Xorg config (default: xorg-dummy.conf next to this file)
#
# Notes:
#   - Call xserver_start directly in your shell, not in $(...) or a pipeline: it exports
#     DISPLAY and remembers the server in shell variables.
#   - The server is `disown`ed: a plain `wait` in the caller does not wait for it.
#   - Xorg is run as: Xorg :N -noreset -nolisten tcp -novtswitch -sharevts +extension GLX
#     +extension RANDR +extension RENDER -logfile LOG -config xorg-dummy.conf -configdir EMPTY.
#     -sharevts/-novtswitch keep it off the console's virtual terminals (without them it
#     grabs a free VT, which on a workstation switches the screen to it); -configdir points
#     at a private empty dir so /etc/X11/xorg.conf.d snippets are not read. Xvfb gets
#     -noreset as well (no server reset when the last client disconnects).
#   - No X authority is set up (like a bare Xvfb): any local client can connect.
#   - Concurrent starts (several scripts/CI jobs) are serialised with flock on
#     /tmp/.xserver-sh.lock while a display number is picked; a start that still loses a
#     race to a foreign server ("already active") retries on the next number.

# ---- configuration --------------------------------------------------------------------
_XSERVER_LIB_DIR=$(cd -- "$(dirname -- "${BASH_SOURCE[0]}")" && pwd)

XSERVER_MAIN_OUTPUT=DUMMY0
XSERVER_MAIN_MODE=1600x900
XSERVER_PROJECTOR_OUTPUT=DUMMY1
XSERVER_PROJECTOR_MODE=1280x800_60
XSERVER_PROJECTOR_MODELINE=(83.50 1280 1352 1480 1680 800 803 809 831 -hsync +vsync)
XSERVER_XVFB_SCREEN=1920x1080x24

# State of the server started by this shell (not exported: a child shell that sources this
# file starts with a clean state even if its parent started a server).
: "${_XSERVER_PID:=}" "${_XSERVER_NUM:=}" "${_XSERVER_TMPDIR:=}"
: "${_XSERVER_PREV_DISPLAY_SET:=}" "${_XSERVER_PREV_DISPLAY:=}"
: "${XSERVER_PID:=}" "${XSERVER_KIND:=}" "${XSERVER_DISPLAY_NUM:=}"
: "${XSERVER_LOG:=}" "${XSERVER_SERVER_LOG:=}"

# ---- helpers --------------------------------------------------------------------------
_xserver_note() { # message -> stderr (always)
    printf 'xserver.sh: %s\n' "$*" >&2
}

_xserver_log() { # message -> current log file (if any)
    [[ -n ${_XSERVER_CUR_LOG:-} ]] || return 0
    printf '[xserver.sh %(%H:%M:%S)T] %s\n' -1 "$*" >>"$_XSERVER_CUR_LOG" 2>/dev/null || true
}

_xserver_tool() { # name -> absolute path of an X client tool, or fail
    local t
    for t in "/usr/bin/$1" "/bin/$1"; do
        [[ -x $t ]] && { printf '%s\n' "$t"; return 0; }
    done
    t=$(command -v -- "$1" 2>/dev/null) || return 1
    printf '%s\n' "$t"
}

_xserver_display_free() { # N -> 0 if :N looks unused
    local n=$1
    [[ ! -e /tmp/.X11-unix/X$n && ! -e /tmp/.X$n-lock ]] || return 1
    # A server in another mount namespace (container) may still hold the abstract socket.
    if [[ -r /proc/net/unix ]] && grep -q -- " @/tmp/.X11-unix/X$n\$" /proc/net/unix 2>/dev/null; then
        return 1
    fi
    return 0
}

_xserver_pick_display() { # [skip-list...] -> prints a free display number
    local n skip
    local lo=${XSERVER_DISPLAY_MIN:-90} hi=${XSERVER_DISPLAY_MAX:-199}
    for ((n = lo; n <= hi; n++)); do
        for skip in "$@"; do [[ $skip == "$n" ]] && continue 2; done
        if _xserver_display_free "$n"; then
            printf '%s\n' "$n"
            return 0
        fi
    done
    return 1
}

_xserver_alive() { # pid -> 0 if running (not a zombie)
    local pid=$1 stat
    kill -0 "$pid" 2>/dev/null || return 1
    stat=$(cut -d' ' -f3 "/proc/$pid/stat" 2>/dev/null) || return 1
    [[ $stat != Z ]]
}

_xserver_probe() { # N -> 0 if the server on :N answers
    local n=$1 tool
    local to=/usr/bin/timeout
    [[ -x $to ]] || to=""
    if tool=$(_xserver_tool xdpyinfo); then
        DISPLAY=":$n" ${to:+$to 5} "$tool" >/dev/null 2>&1
    elif tool=$(_xserver_tool xrandr); then
        DISPLAY=":$n" ${to:+$to 5} "$tool" --query >/dev/null 2>&1
    else
        [[ -S /tmp/.X11-unix/X$n ]]
    fi
}

_xserver_xrandr() { # args... -> run xrandr on our display, output to the log
    local xr
    xr=$(_xserver_tool xrandr) || { _xserver_log "xrandr not found"; return 1; }
    _xserver_log "xrandr $*"
    DISPLAY=":$_XSERVER_CUR_NUM" "$xr" "$@" >>"$_XSERVER_CUR_LOG" 2>&1
}

_xserver_output_geometry() { # output -> prints WxH+X+Y, or nothing if the output is off
    local xr line re
    xr=$(_xserver_tool xrandr) || return 1
    re="^$1 (dis)?connected (primary )?([0-9]+x[0-9]+\+[0-9]+\+[0-9]+)"
    while IFS= read -r line; do
        if [[ $line =~ $re ]]; then
            printf '%s\n' "${BASH_REMATCH[3]}"
            return 0
        fi
    done < <(DISPLAY=":$_XSERVER_CUR_NUM" "$xr" --query 2>>"$_XSERVER_CUR_LOG")
    return 0
}

_xserver_expect_geometry() { # output expected-geometry|"" -> 0 if matching
    local got
    got=$(_xserver_output_geometry "$1") || return 1
    _xserver_log "$1 geometry: '${got}' (expected '${2}')"
    [[ $got == "$2" ]]
}

_xserver_projector_on() {
    _xserver_xrandr --output "$XSERVER_PROJECTOR_OUTPUT" --mode "$XSERVER_PROJECTOR_MODE" \
        --right-of "$XSERVER_MAIN_OUTPUT" || return 1
    _xserver_expect_geometry "$XSERVER_PROJECTOR_OUTPUT" "1280x800+1600+0"
}

_xserver_configure_dummy() { # two outputs side by side, as in ../shared/README.md
    _xserver_xrandr --newmode "$XSERVER_PROJECTOR_MODE" "${XSERVER_PROJECTOR_MODELINE[@]}" || return 1
    _xserver_xrandr --addmode "$XSERVER_PROJECTOR_OUTPUT" "$XSERVER_PROJECTOR_MODE" || return 1
    _xserver_xrandr --output "$XSERVER_MAIN_OUTPUT" --mode "$XSERVER_MAIN_MODE" --pos 0x0 --primary || return 1
    _xserver_projector_on || return 1
    _xserver_expect_geometry "$XSERVER_MAIN_OUTPUT" "1600x900+0+0"
}

_xserver_kill_pid() { # pid -> TERM, wait up to 5 s, then KILL
    local pid=$1 i
    _xserver_alive "$pid" || return 0
    kill -TERM "$pid" 2>/dev/null || true
    for ((i = 0; i < 50; i++)); do
        _xserver_alive "$pid" || return 0
        sleep 0.1
    done
    _xserver_log "pid $pid ignored SIGTERM, sending SIGKILL"
    kill -KILL "$pid" 2>/dev/null || true
    for ((i = 0; i < 20; i++)); do
        _xserver_alive "$pid" || return 0
        sleep 0.1
    done
    return 1
}

_xserver_cleanup_files() { # N pid -> remove lock/socket left behind by *our* server
    local n=$1 pid=$2 lockpid=""
    if [[ -e /tmp/.X$n-lock ]]; then
        read -r lockpid <"/tmp/.X$n-lock" 2>/dev/null || true
        if [[ $lockpid == "$pid" ]]; then
            rm -f "/tmp/.X$n-lock"
            _xserver_log "removed stale /tmp/.X$n-lock"
        else
            return 0 # someone else's server owns :N now; leave its files alone
        fi
    fi
    if [[ -S /tmp/.X11-unix/X$n ]]; then
        rm -f "/tmp/.X11-unix/X$n"
        _xserver_log "removed stale /tmp/.X11-unix/X$n"
    fi
    return 0
}

# Serialise "pick a display number + let the server create /tmp/.X<N>-lock" between
# concurrent users of this library (flock on /tmp/.xserver-sh.lock; skipped if unusable).
_XSERVER_LOCKFD=""
_xserver_lock() {
    local lockfile=/tmp/.xserver-sh.lock
    _XSERVER_LOCKFD=""
    [[ -x /usr/bin/flock ]] || return 0
    [[ -w $lockfile || ! -e $lockfile ]] || return 0
    { exec {_XSERVER_LOCKFD}>>"$lockfile"; } 2>/dev/null || { _XSERVER_LOCKFD=""; return 0; }
    chmod 0666 "$lockfile" 2>/dev/null || true
    /usr/bin/flock -w 30 "$_XSERVER_LOCKFD" || _xserver_log "flock timed out, going on without it"
}
_xserver_unlock() {
    [[ -n $_XSERVER_LOCKFD ]] || return 0
    exec {_XSERVER_LOCKFD}>&-
    _XSERVER_LOCKFD=""
}

_xserver_launch() { # kind N -> 0 ready, 1 failed, 2 display busy (try another)
    # Called with the lock held; releases it once the server has claimed :N.
    local kind=$1 n=$2 pid i rc=1
    local -a cmd
    _XSERVER_CUR_NUM=$n
    case $kind in
    dummy)
        XSERVER_SERVER_LOG="$_XSERVER_LOGDIR/xserver-$n-dummy.xorg.log"
        cmd=("${XSERVER_XORG:-/usr/bin/Xorg}" ":$n"
            -noreset -nolisten tcp -novtswitch -sharevts
            +extension GLX +extension RANDR +extension RENDER
            -logfile "$XSERVER_SERVER_LOG"
            -config "${XSERVER_XORG_CONF:-$_XSERVER_LIB_DIR/xorg-dummy.conf}"
            -configdir "$_XSERVER_TMPDIR/xorg.conf.d")
        rm -f -- "$XSERVER_SERVER_LOG" # Xorg would keep it as .old; don't grep stale text
        ;;
    xvfb)
        XSERVER_SERVER_LOG=$_XSERVER_CUR_LOG
        cmd=("${XSERVER_XVFB:-/usr/bin/Xvfb}" ":$n" -screen 0 "$XSERVER_XVFB_SCREEN"
            +extension GLX +extension RANDR +extension RENDER -nolisten tcp -noreset)
        ;;
    esac
    _xserver_log "starting: ${cmd[*]}"

    if [[ -n $_XSERVER_LOCKFD ]]; then # the server must not inherit (and keep) the lock
        "${cmd[@]}" </dev/null >>"$_XSERVER_CUR_LOG" 2>&1 {_XSERVER_LOCKFD}>&- &
    else
        "${cmd[@]}" </dev/null >>"$_XSERVER_CUR_LOG" 2>&1 &
    fi
    pid=$!
    disown "$pid" 2>/dev/null || true
    _xserver_log "pid $pid"

    # Keep the lock until the server has claimed :N (its lock file names its pid).
    local lockpid=""
    for ((i = 0; i < 100; i++)); do
        if [[ -e /tmp/.X$n-lock ]]; then
            read -r lockpid <"/tmp/.X$n-lock" 2>/dev/null || true
            [[ $lockpid == "$pid" ]] && break
        fi
        _xserver_alive "$pid" || break
        sleep 0.05
    done
    _xserver_unlock

    # Wait until it answers.
    local deadline=$((SECONDS + ${XSERVER_TIMEOUT:-15}))
    while :; do
        if ! _xserver_alive "$pid"; then
            _xserver_log "server exited during start-up"
            _xserver_cleanup_files "$n" "$pid"
            if grep -qE 'Server is already active for display|Cannot establish any listening sockets' \
                "$_XSERVER_CUR_LOG" "$XSERVER_SERVER_LOG" 2>/dev/null; then
                rc=2
            fi
            return $rc
        fi
        if _xserver_probe "$n"; then
            break
        fi
        if ((SECONDS >= deadline)); then
            _xserver_log "no answer within ${XSERVER_TIMEOUT:-15} s, killing it"
            _xserver_kill_pid "$pid" || true
            _xserver_cleanup_files "$n" "$pid"
            return 1
        fi
        sleep 0.1
    done
    _XSERVER_PID=$pid
    _XSERVER_NUM=$n
    _xserver_log "server :$n (pid $pid) answers"

    if [[ $kind == dummy ]] && ! _xserver_configure_dummy; then
        _xserver_log "could not set up $XSERVER_MAIN_OUTPUT/$XSERVER_PROJECTOR_OUTPUT, stopping it"
        _xserver_kill_pid "$pid" || true
        _xserver_cleanup_files "$n" "$pid"
        _XSERVER_PID="" _XSERVER_NUM=""
        return 1
    fi
    return 0
}

_xserver_try_kind() { # kind -> 0 if started
    local kind=$1 n attempt rc
    local -a tried=()
    _XSERVER_CUR_LOG=""
    case $kind in
    dummy)
        local xorg=${XSERVER_XORG:-/usr/bin/Xorg}
        local conf=${XSERVER_XORG_CONF:-$_XSERVER_LIB_DIR/xorg-dummy.conf}
        if [[ ! -x $xorg ]]; then
            _XSERVER_WHY="$xorg not found (apt-get install xserver-xorg-core)"; return 1
        fi
        if ! compgen -G "/usr/lib/xorg/modules/drivers/dummy_drv.so" >/dev/null; then
            _XSERVER_WHY="dummy video driver not found (apt-get install xserver-xorg-video-dummy)"; return 1
        fi
        if ! _xserver_tool xrandr >/dev/null; then
            _XSERVER_WHY="xrandr not found (apt-get install x11-xserver-utils)"; return 1
        fi
        if [[ ! -r $conf ]]; then
            _XSERVER_WHY="$conf not readable"; return 1
        fi
        ;;
    xvfb)
        if [[ ! -x ${XSERVER_XVFB:-/usr/bin/Xvfb} ]]; then
            _XSERVER_WHY="${XSERVER_XVFB:-/usr/bin/Xvfb} not found (apt-get install xvfb)"; return 1
        fi
        ;;
    esac
    for ((attempt = 1; attempt <= 5; attempt++)); do
        _xserver_lock
        if ! n=$(_xserver_pick_display ${tried[@]+"${tried[@]}"}); then
            _xserver_unlock
            _XSERVER_WHY="no free display in :${XSERVER_DISPLAY_MIN:-90}..:${XSERVER_DISPLAY_MAX:-199}"
            return 1
        fi
        tried+=("$n")
        _XSERVER_CUR_LOG="$_XSERVER_LOGDIR/xserver-$n-$kind.log"
        if ! { : >"$_XSERVER_CUR_LOG"; } 2>/dev/null; then
            _xserver_unlock
            _XSERVER_WHY="cannot write $_XSERVER_CUR_LOG"
            return 1
        fi
        rc=0
        _xserver_launch "$kind" "$n" || rc=$?
        _xserver_unlock
        case $rc in
        0) return 0 ;;
        2) _xserver_log "display :$n is busy, trying another one" ;;
        *) _XSERVER_WHY="$kind server failed, see $_XSERVER_CUR_LOG${XSERVER_SERVER_LOG:+ and $XSERVER_SERVER_LOG}"
           return 1 ;;
        esac
    done
    _XSERVER_WHY="$kind: displays kept being taken by others"
    return 1
}

# ---- public API -----------------------------------------------------------------------
xserver_start() {
    local single=0 arg kind
    for arg in "$@"; do
        case $arg in
        --single) single=1 ;;
        *) _xserver_note "xserver_start: unknown argument '$arg' (usage: xserver_start [--single])"
           return 2 ;;
        esac
    done
    if [[ -n $_XSERVER_PID ]] && _xserver_alive "$_XSERVER_PID"; then
        _xserver_note "xserver_start: already running ($XSERVER_KIND on :$_XSERVER_NUM, pid $_XSERVER_PID)"
        return 1
    fi

    local -a kinds
    case ${XSERVER_FORCE:-auto} in
    auto) kinds=(dummy xvfb) ;;
    dummy) kinds=(dummy) ;;
    xvfb) kinds=(xvfb) ;;
    *) _xserver_note "xserver_start: XSERVER_FORCE must be auto, dummy or xvfb (got '${XSERVER_FORCE}')"
       return 2 ;;
    esac
    ((single)) && kinds=(xvfb)

    _XSERVER_LOGDIR=${XSERVER_LOG_DIR:-/tmp}
    mkdir -p -- "$_XSERVER_LOGDIR" || return 1
    _XSERVER_TMPDIR=$(mktemp -d /tmp/xserver-sh.XXXXXX) || return 1
    # An empty -configdir: no /etc/X11/xorg.conf.d snippets (Xorg wants at least one file).
    mkdir -p "$_XSERVER_TMPDIR/xorg.conf.d"
    printf '# intentionally empty (scripts/lib/xserver.sh)\n' >"$_XSERVER_TMPDIR/xorg.conf.d/00-empty.conf"

    local why=""
    for kind in "${kinds[@]}"; do
        _XSERVER_WHY=""
        if _xserver_try_kind "$kind"; then
            if [[ -n ${DISPLAY+x} ]]; then
                _XSERVER_PREV_DISPLAY_SET=1 _XSERVER_PREV_DISPLAY=$DISPLAY
            else
                _XSERVER_PREV_DISPLAY_SET="" _XSERVER_PREV_DISPLAY=""
            fi
            export DISPLAY=":$_XSERVER_NUM"
            export XSERVER_KIND=$kind
            XSERVER_PID=$_XSERVER_PID
            XSERVER_DISPLAY_NUM=$_XSERVER_NUM
            XSERVER_LOG=$_XSERVER_CUR_LOG
            local what="Xvfb, one screen $XSERVER_XVFB_SCREEN"
            [[ $kind == dummy ]] && what="Xorg dummy, $XSERVER_MAIN_OUTPUT 1600x900+0+0 + $XSERVER_PROJECTOR_OUTPUT 1280x800+1600+0"
            _xserver_note "DISPLAY=$DISPLAY ($what; pid $XSERVER_PID; log $XSERVER_LOG)${why:+ [fallback: $why]}"
            return 0
        fi
        why=$_XSERVER_WHY
        _xserver_log "giving up on $kind: $why"
    done
    _xserver_note "xserver_start: could not start an X server: $why"
    if [[ -n ${_XSERVER_CUR_LOG:-} && -s $_XSERVER_CUR_LOG ]]; then
        tail -n 5 -- "$_XSERVER_CUR_LOG" | sed 's/^/  | /' >&2 || true
    fi
    rm -rf -- "$_XSERVER_TMPDIR"
    _XSERVER_TMPDIR=""
    return 1
}

xserver_unplug_projector() {
    if [[ ${XSERVER_KIND:-} != dummy || -z $_XSERVER_PID ]]; then
        _xserver_log "unplug: no dummy server"
        return 1
    fi
    _XSERVER_CUR_NUM=$_XSERVER_NUM _XSERVER_CUR_LOG=$XSERVER_LOG
    _xserver_xrandr --output "$XSERVER_PROJECTOR_OUTPUT" --off || return 1
    _xserver_expect_geometry "$XSERVER_PROJECTOR_OUTPUT" ""
}

xserver_replug_projector() {
    if [[ ${XSERVER_KIND:-} != dummy || -z $_XSERVER_PID ]]; then
        _xserver_log "replug: no dummy server"
        return 1
    fi
    _XSERVER_CUR_NUM=$_XSERVER_NUM _XSERVER_CUR_LOG=$XSERVER_LOG
    _xserver_projector_on
}

xserver_stop() {
    local pid=$_XSERVER_PID n=$_XSERVER_NUM
    if [[ -n $pid ]]; then
        _XSERVER_CUR_LOG=$XSERVER_LOG
        _xserver_log "stopping :$n (pid $pid)"
        _xserver_kill_pid "$pid" || _xserver_note "xserver_stop: pid $pid would not die"
        _xserver_cleanup_files "$n" "$pid"
        if [[ ${DISPLAY:-} == ":$n" ]]; then
            if [[ -n $_XSERVER_PREV_DISPLAY_SET ]]; then
                export DISPLAY=$_XSERVER_PREV_DISPLAY
            else
                unset DISPLAY
            fi
        fi
    fi
    if [[ -n $_XSERVER_TMPDIR && -d $_XSERVER_TMPDIR ]]; then
        rm -rf -- "$_XSERVER_TMPDIR"
    fi
    _XSERVER_PID="" _XSERVER_NUM="" _XSERVER_TMPDIR=""
    XSERVER_PID="" XSERVER_DISPLAY_NUM=""
    unset XSERVER_KIND # drop the export ...
    XSERVER_KIND=""    # ... but keep it defined for `set -u` callers
    return 0
}

_xserver_exit_hook() { # keeps $? for whatever runs after it in the EXIT trap
    local rc=$?
    xserver_stop || true
    return "$rc"
}

xserver_stop_on_exit() {
    local prev
    prev=$(trap -p EXIT)
    [[ $prev == *_xserver_exit_hook* ]] && return 0
    if [[ -n $prev ]]; then
        eval "set -- $prev" # -> trap -- 'commands' EXIT
        prev=$3
    fi
    # shellcheck disable=SC2064
    trap -- "${prev:+$prev
}_xserver_exit_hook" EXIT
}
