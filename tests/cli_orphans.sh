#!/usr/bin/env bash
# Worker processes die with their parent: SIGTERM or SIGKILL to the parent alone
# (a service manager, the OOM killer) leaves no worker running with parent 1.
set -u
cli=$1
data=$(cd "$2" && pwd)
source "$(dirname "$0")/cli_lib.sh"

for sig in TERM KILL; do
    # A sparse window that moves with the speed solves each speed afresh, in worker
    # processes (ARPACK is not thread safe).
    "$cli" campbell "$data/fe_rotor.toml" --solver sparse --target-order 1 --jobs 2 --speeds 0:4000:2000 > /dev/null 2>&1 &
    pid=$!
    workers=""
    for _ in $(seq 1 3000); do   # up to 30 s: a sanitized build starts slowly
        workers=$(pgrep -P "$pid" | tr '\n' ' ')
        [ -n "$workers" ] && break
        sleep 0.01
    done
    if [ -z "$workers" ]; then echo "FAIL: no worker process appeared ($sig)"; fail=1; kill -KILL "$pid"; continue; fi
    kill -"$sig" "$pid"
    wait "$pid" 2> /dev/null
    alive=""
    for _ in $(seq 1 1000); do
        alive=""
        for w in $workers; do kill -0 "$w" 2> /dev/null && alive="$alive $w"; done
        [ -z "$alive" ] && break
        sleep 0.01
    done
    if [ -n "$alive" ]; then
        echo "FAIL: workers$alive outlived their parent (SIG$sig)"
        fail=1
        for w in $alive; do kill -KILL "$w" 2> /dev/null; done
    fi
done
exit $fail
