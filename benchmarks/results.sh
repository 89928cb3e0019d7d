# shellcheck shell=bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Sourced by the benchmark scripts (benchmarks/morph/*.sh, scripts/openfoam/checkmesh_sweep.sh):
# writes a run's results table with its context (date, machine, OS, commit, OpenFOAM, the
# command line) to benchmarks/results/<name>.md, the files the docs quote figures from
# (benchmarks/results/README.md). Not run on its own.
#
#   results_init "$@"         first, before the script parses (shifts) its arguments:
#                             records the command line
#   results_file FILE         the script's -results FILE: write there instead, full run or not
#   results_off               the script's -no-results: write nothing
#   results_partial REASON    not a full run (a -cases filter, fewer lifts, ...): the default
#                             file is not written (REASON is printed); -results FILE still is
#   results_write [-openfoam] [-meta "Key: value"]... NAME TITLE [BODY_FILE]
#                             writes the file: TITLE, the context, then BODY_FILE (or stdin)
#                             verbatim; -openfoam adds OpenFOAM's version, -meta more lines
#   results_write_report [-openfoam] [-meta LINE]... NAME REPORT
#                             the same for a script's own Markdown REPORT: its "# title"
#                             line is the TITLE, the rest the table
#   results_body FILE         FILE without its leading "# title" line and the blank lines
#                             after it (for a script's own report, whose title results_write
#                             replaces)
#
# Where results_write writes, first match wins:
#   1. -results FILE or -no-results, whichever came last on the command line;
#   2. MESHMORPH_NO_RESULTS=1 in the environment: nothing (for tests and quick runs);
#   3. a run marked by results_partial: nothing;
#   4. ${MESHMORPH_RESULTS_DIR:-benchmarks/results}/NAME.md (benchmarks/ is this file's
#      directory, whatever the working directory).
# The file is written atomically (a temporary file in the same directory, then mv). Messages
# go to stderr, so a script's own output is unchanged. results_write returns 1 when it cannot
# write the file.

results_root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
results_mode=default      # default | file | off
results_target=""
results_partial_reasons=()
results_command=""

# results_quote WORD: WORD as the shell reads it back (plain when safe, else in '...').
results_quote() {
    if [[ $1 =~ ^[A-Za-z0-9_./:=+,%@^-]+$ ]]; then
        printf '%s' "$1"
    else
        printf "'%s'" "${1//\'/\'\\\'\'}"
    fi
}

results_init() {
    local script=${BASH_SOURCE[1]:-$0} word
    script=$(realpath -m "$script")
    script=${script#"$results_root"/}
    results_command=$script
    for word in "$@"; do results_command+=" $(results_quote "$word")"; done
    results_mode=default results_target="" results_partial_reasons=()
}

results_file() {
    [[ -n ${1:-} ]] || { echo "results_file: needs a FILE" >&2; return 2; }
    results_mode="file"
    results_target=$(realpath -m "$1")
}

results_off() { results_mode=off results_target=""; }

results_partial() { results_partial_reasons+=("$*"); }

results_body() {
    awk 'NR == 1 && /^# / { skip = 1; next } skip && /^[[:space:]]*$/ { next } { skip = 0; print }' "$1"
}

# results_destination NAME: sets results_dest to the file results_write writes ("" for
# none) and results_why to the reason when there is none.
results_destination() {
    results_dest="" results_why=""
    case $results_mode in
        file) results_dest=$results_target; return 0 ;;
        off) results_why="-no-results"; return 0 ;;
    esac
    if [[ ${MESHMORPH_NO_RESULTS:-0} == 1 ]]; then
        results_why="MESHMORPH_NO_RESULTS=1"
    elif ((${#results_partial_reasons[@]})); then
        results_why="not a full run: $(printf '%s; ' "${results_partial_reasons[@]}")"
        results_why=${results_why%; }
    else
        results_dest="${MESHMORPH_RESULTS_DIR:-$results_root/benchmarks/results}/$1.md"
    fi
}

results_cpu() {
    local model
    model=$(LC_ALL=C lscpu 2>/dev/null | awk '/^Model name:/ { sub(/^Model name:[[:space:]]*/, ""); print; exit }' || true)
    [[ -n $model ]] ||
        model=$(awk -F': *' '/^model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || true)
    echo "${model:-unknown CPU}"
}

results_machine() {
    local cpus all mem
    cpus=$(nproc 2>/dev/null || echo "?")
    all=$(nproc --all 2>/dev/null || echo "$cpus")
    mem=$(awk '/^MemTotal:/ { printf "%.1f GiB", $2 / 1048576 }' /proc/meminfo 2>/dev/null)
    printf '%s, %s CPUs' "$(results_cpu)" "$cpus"
    [[ $all == "$cpus" ]] || printf ' (of %s)' "$all"
    printf ', %s memory\n' "${mem:-? GiB}"
}

results_os() {
    local name="" version=""
    if [[ -r /etc/os-release ]]; then
        name=$(. /etc/os-release && echo "${PRETTY_NAME:-${NAME:-}}")
    fi
    [[ -r /etc/debian_version ]] && version=" (Debian $(cat /etc/debian_version))"
    echo "${name:-$(uname -s)}$version, Linux $(uname -r)"
}

# results_commit: the commit, and when the tree has uncommitted changes to tracked files,
# which (the first five), so that a "-dirty" figure can be traced.
results_commit() {
    local described changed
    described=$(git -C "$results_root" describe --always --dirty 2>/dev/null) ||
        { echo "unknown (not a git checkout)"; return 0; }
    changed=$(git -C "$results_root" status --porcelain --untracked-files=no 2>/dev/null |
              awk '{ print $NF }' | head -5 | paste -sd, - | sed 's/,/, /g')
    if [[ $described == *-dirty && -n $changed ]]; then
        echo "$described (uncommitted changes to: $changed)"
    else
        echo "$described"
    fi
}

# results_openfoam: the OpenFOAM version, from Debian's package, else the environment, else
# the banner of a tool (foamVersion, or the "Version:" line checkMesh prints).
results_openfoam() {
    local pkg banner
    # shellcheck disable=SC2016 # ${Version} is dpkg-query's field
    pkg=$(dpkg-query -W -f='${Version}' openfoam 2>/dev/null || true)
    if [[ -n $pkg ]]; then
        echo "v${pkg%%.*} (Debian package openfoam $pkg)"
        return 0
    fi
    if [[ -n ${WM_PROJECT_VERSION:-} ]]; then
        echo "${WM_PROJECT_VERSION} (WM_PROJECT_VERSION)"
        return 0
    fi
    if command -v foamVersion >/dev/null 2>&1; then
        banner=$(foamVersion 2>/dev/null | awk 'NF { print; exit }' || true)
    elif command -v checkMesh >/dev/null 2>&1; then
        # the banner's "Version:" line, printed before checkMesh finds no case
        banner=$(cd /tmp || exit; timeout 20 checkMesh -case /nonexistent 2>&1 </dev/null |
                 awk '$1 == "Version:" || $2 == "Version:" { print ($1 == "Version:" ? $2 : $3); exit }' || true)
    fi
    echo "${banner:-unknown}"
}

results_write() {
    local openfoam=0 meta=()
    while [[ $# -gt 0 ]]; do
        case $1 in
            -openfoam) openfoam=1; shift ;;
            -meta) meta+=("${2:?results_write: -meta needs a line}"); shift 2 ;;
            *) break ;;
        esac
    done
    local name=${1:?results_write: needs NAME} title=${2:?results_write: needs TITLE} body=${3:--}
    results_destination "$name"
    local dest=$results_dest
    if [[ -z $dest ]]; then
        echo "results: no results file written: $results_why" \
             "(-results FILE writes one)" >&2
        [[ $body == - ]] && cat >/dev/null
        return 0
    fi
    local dir tmp
    dir=$(dirname "$dest")
    if ! mkdir -p "$dir" || ! tmp=$(mktemp "$dir/.$(basename "$dest").XXXXXX"); then
        echo "results: error: cannot write in $dir" >&2
        return 1
    fi
    {
        echo "# $title"
        echo
        echo "<!-- Written by ${results_command%% *} through benchmarks/results.sh. Do not edit:" \
             "regenerate it (benchmarks/results/README.md). -->"
        echo
        echo "- Date: $(date -u +%Y-%m-%dT%H:%M:%SZ)"
        echo "- Machine: $(results_machine)"
        echo "- OS: $(results_os)"
        echo "- Commit: $(results_commit)"
        if ((openfoam)); then echo "- OpenFOAM: $(results_openfoam)"; fi
        echo "- OMP_NUM_THREADS: ${OMP_NUM_THREADS:-unset}"
        local line
        for line in "${meta[@]}"; do echo "- $line"; done
        echo "- Command: \`$results_command\`"
        echo
        echo "## Results"
        echo
        # shellcheck disable=SC1003 # sed's "append" command, not an escaped quote
        sed -e '$a\' -- "$body"   # verbatim, a final newline added when missing
    } >"$tmp" || { rm -f -- "$tmp"; echo "results: error: writing $dest failed" >&2; return 1; }
    chmod 644 "$tmp"
    mv -f -- "$tmp" "$dest" || { rm -f -- "$tmp"; echo "results: error: cannot write $dest" >&2; return 1; }
    echo "results: wrote $dest" >&2
}

# results_write_report [-openfoam] [-meta LINE]... NAME REPORT: results_write of a script's
# own Markdown report, its "# title" line as the title and the rest as the table.
results_write_report() {
    local options=()
    while [[ $1 == -openfoam || $1 == -meta ]]; do
        if [[ $1 == -meta ]]; then options+=("$1" "$2"); shift 2; else options+=("$1"); shift; fi
    done
    local name=${1:?results_write_report: needs NAME} report=${2:?results_write_report: needs REPORT}
    results_body "$report" |
        results_write "${options[@]}" "$name" "$(sed -n '1s/^# //p' "$report")"
}
