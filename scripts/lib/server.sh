# Shared by scripts/e2e.sh and scripts/schemathesis.sh (sourced, not run): a tribosim
# server on a free loopback port with a temporary data directory, stopped on exit.
#
#   start_server EXTRA_ARGS...   sets $work (temporary directory), $server_pid and $base
#   server_status STATUS         prints STATUS, or 1 if the server died or panicked

work="$(mktemp -d)"
server_pid=""
cleanup() {
    if [ -n "$server_pid" ]; then
        kill -TERM "$server_pid" 2>/dev/null || true
        wait "$server_pid" 2>/dev/null || true
    fi
    rm -rf "$work"
}
trap cleanup EXIT

start_server() {
    # Port 0: the kernel picks a free port, and the server logs the one it got.
    "$TRIBOSIM_BIN" serve --addr 127.0.0.1:0 --data-dir "$work/data" "$@" 2>"$work/server.log" &
    server_pid=$!
    base=""
    for _ in $(seq 600); do
        base="$(grep -o 'serving on http://[0-9.:]*' "$work/server.log" | head -n1 | cut -d' ' -f3 || true)"
        [ -n "$base" ] && return 0
        kill -0 "$server_pid" 2>/dev/null || { cat "$work/server.log"; echo "server exited" >&2; exit 1; }
        sleep 0.1
    done
    cat "$work/server.log"
    echo "server did not start" >&2
    exit 1
}

server_status() {
    local status="$1"
    if ! kill -0 "$server_pid" 2>/dev/null; then
        echo "the server died during the run" >&2
        status=1
    fi
    if grep -q "panicked" "$work/server.log"; then
        grep -B2 -A5 "panicked" "$work/server.log" >&2
        status=1
    fi
    echo "$status"
}
