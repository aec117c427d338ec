#!/usr/bin/env bash
# viewer_tmux.sh BINARY [ARGS...] — the interactive viewer in a real terminal: starts
# `BINARY ARGS...` in a detached 80×24 tmux session (its own server socket), sends keys, captures
# the pane with escapes (`tmux capture-pane -p -e`), checks for half blocks, 24-bit colours and the
# status line, sends q and checks that the process exited with status 0 and left the alternate
# screen. Exit 0 = pass, 1 = fail (also without tmux: scripts/setup.sh installs it).
set -uo pipefail
[ $# -ge 1 ] || { echo "usage: $0 BINARY [ARGS...]" >&2; exit 2; }
command -v tmux >/dev/null || { echo "FAIL: tmux not installed (scripts/setup.sh installs it)"; exit 1; }

bin=$(realpath "$1"); shift
work=$(mktemp -d)
sock="$work/tmux.sock"
status="$work/status"
t() { tmux -S "$sock" "$@"; }
cleanup() { t kill-server >/dev/null 2>&1; rm -rf "$work"; }
trap cleanup EXIT
fail() { echo "viewer_tmux: FAIL: $*"; echo "--- pane ---"; t capture-pane -p -t v 2>/dev/null; exit 1; }

# Waits until the pane (with escapes) contains $1, up to 5 s.
wait_for() {
    for _ in $(seq 50); do
        t capture-pane -p -e -t v 2>/dev/null | grep -qF -- "$1" && return 0
        sleep 0.1
    done
    return 1
}

# Step 1: start the viewer in a 80×24 pane; the shell records its exit status, then waits.
cmd=$(printf '%q ' "$bin" "$@")
t -f /dev/null new-session -d -s v -x 80 -y 24 \
    "env TERM=tmux-256color $cmd; echo \$? > $status; sleep 30" || fail "tmux new-session"
t set-option -t v -g remain-on-exit on >/dev/null 2>&1
wait_for "hybrid az" || fail "no status line"

# Step 2: the first screen: half blocks with 24-bit colours, status at the bottom (row 24).
pane=$(t capture-pane -p -e -t v)
grep -qF "▀" <<<"$pane" || fail "no half-block characters"
grep -qE $'\x1b\\[(38|48);2;[0-9]+;[0-9]+;[0-9]+' <<<"$pane" || fail "no 24-bit colour escapes"
last=$(t capture-pane -p -t v | sed -n 24p)
grep -qF "hybrid az 0° el 0° dist 1 off 0° t 5" <<<"$last" || fail "status line not on the last row: $last"

# Step 3: keys change the view: an arrow (escape sequence), a mode key, zoom.
t send-keys -t v Right || fail "send-keys"
wait_for "az 5°" || fail "Right arrow did not turn the view"
t send-keys -t v Up 3 + || fail "send-keys"
wait_for "static-em az 5° el 5° dist 0.9 off 0° t 5" || fail "Up / 3 / + not applied"
grep -q "fps" <<<"$(t capture-pane -p -t v)" || fail "no FPS in the status line"

# Step 4: a resize redraws at the new size (SIGWINCH).
# The demo renderer reports the pixel size it was asked for: 70 × 2·(12 − 1).
grep -qF "demo 80x46" <<<"$last" || fail "renderer not asked for 80x46 pixels: $last"
t resize-window -t v -x 70 -y 12 >/dev/null 2>&1 || fail "resize-window"
wait_for "demo 70x22" || fail "no redraw after resize"
t capture-pane -p -t v | sed -n 12p | grep -qF "static-em az 5°" || fail "status not on row 12"

# Step 5: q quits with status 0 and leaves the alternate screen.
t send-keys -t v q
for _ in $(seq 50); do [ -s "$status" ] && break; sleep 0.1; done
[ -s "$status" ] || fail "viewer still running after q"
[ "$(cat "$status")" = 0 ] || fail "exit status $(cat "$status")"
sleep 0.2
t capture-pane -p -t v | grep -qF "▀" && fail "half blocks left on the normal screen"
echo "viewer_tmux: ok"
exit 0
