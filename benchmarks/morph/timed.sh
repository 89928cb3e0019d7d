# SPDX-License-Identifier: GPL-3.0-or-later
# Sourced by the morph benchmarks.

#! timed <log> <cmd...>: runs the command with its output in <log>; sets $wall (seconds) and
#! $rss (peak resident MB). Exit 3 (a design or morph refused for invalid cells) is a result
#! the caller reports; any other failure prints the log's tail and fails.
timed() {
    local log=$1
    shift
    local status=0
    /usr/bin/time -f "%e %M" -o "$log.time" "$@" >"$log" 2>&1 || status=$?
    if [ "$status" -ne 0 ] && [ "$status" -ne 3 ]; then
        tail -20 "$log" >&2
        return 1
    fi
    read -r wall rss_kb < <(tail -1 "$log.time")
    rss=$((rss_kb / 1024))
}
