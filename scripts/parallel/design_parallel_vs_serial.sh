#!/bin/bash
# SPDX-License-Identifier: GPL-3.0-or-later
# The design commands with -parallel against the serial ones, on tutorials/designVariables
# (the pipe, 11 variables): -variables, -variant and -sensitivity serially, decomposePar
# (simple along the pipe; the dJ/dx field with it), the same three under mpirun -np N, then
# every processor's variant points against the serial ones (compare_decomposed.py: 1e-12 of
# the extent, shared points bit-identical) and dJ/da against the serial dJ/da (1e-12
# relative). Needs OpenFOAM (decomposePar) and OpenMPI.
#
#   design_parallel_vs_serial.sh -bin DIR -out DIR [-np N]
#
# Exit 0 when they agree, 77 when OpenFOAM or mpirun is missing (a skip), 1 otherwise.
set -u
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
source_dir=$(cd "$here/../.." && pwd)
bin="" out="" np=2
while [ $# -gt 0 ]; do
    case "$1" in
        -bin) bin=$2; shift 2 ;;
        -out) out=$2; shift 2 ;;
        -np) np=$2; shift 2 ;;
        -help|-h) sed -n '3,13p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
        *) echo "design_parallel_vs_serial.sh: unknown option '$1' (try -help)" >&2; exit 2 ;;
    esac
done
[ -n "$bin" ] && [ -n "$out" ] || { echo "design_parallel_vs_serial.sh: -bin and -out are required" >&2; exit 2; }
export WM_PROJECT_DIR=${WM_PROJECT_DIR:-/usr/share/openfoam}
command -v decomposePar >/dev/null || { echo "skipped: OpenFOAM's decomposePar is not installed"; exit 77; }
command -v mpirun >/dev/null || { echo "skipped: mpirun (openmpi-bin) is not installed"; exit 77; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMP_NUM_THREADS=1

rm -rf "$out" && mkdir -p "$out" || exit 1
out=$(cd "$out" && pwd)
amplitudes="(0.8 0.3 1 0.05 -0.05 0.05 -0.05 0.02 0.02 0.02 0.02)"
make_case() {
    mkdir -p "$1/system" && cp -r "$source_dir/tutorials/pipe/constant" "$1/" &&
        cp "$source_dir/tutorials/pipe/system/controlDict" "$1/system/" &&
        cp "$source_dir/tutorials/designVariables/system/morphDict" "$1/system/" &&
        /usr/bin/python3 "$source_dir/benchmarks/morph/write_point_field.py" "$1" 0/dJdx
}
run() { # run <log> <args...>
    local log=$1
    shift
    "$@" > "$out/log.$log" 2>&1 || { echo "$* failed (see $out/log.$log)"; tail -5 "$out/log.$log"; exit 1; }
}
make_case "$out/serial" && make_case "$out/parallel" || exit 1
run serial.variables "$bin/morphMesh" -case "$out/serial" -variables
run serial.variant "$bin/morphMesh" -case "$out/serial" -variant "$amplitudes"
run serial.sensitivity "$bin/morphMesh" -case "$out/serial" -sensitivity 0/dJdx -json "$out/serial.json"
cat > "$out/parallel/system/decomposeParDict" <<DICT
FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }
numberOfSubdomains $np;
method simple;
simpleCoeffs { n (1 1 $np); delta 0.001; }
DICT
(cd "$out/parallel" && decomposePar > log.decomposePar 2>&1) ||
    { echo "decomposePar failed (see $out/parallel/log.decomposePar)"; exit 1; }
[ -f "$out/parallel/processor0/0/dJdx" ] || { echo "decomposePar did not split 0/dJdx"; exit 1; }
mpi="mpirun -np $np --oversubscribe $bin/morphMesh -case $out/parallel -parallel"
run parallel.variables $mpi -variables
run parallel.variant $mpi -variant "$amplitudes"
run parallel.sensitivity $mpi -sensitivity 0/dJdx -json "$out/parallel.json"
/usr/bin/python3 "$here/compare_decomposed.py" "$out/parallel" 1 "$np" "$out/serial/1/polyMesh/points" || exit 1
/usr/bin/python3 - "$out/serial.json" "$out/parallel.json" <<'PY'
import json, sys
s, p = (json.load(open(f))["dJda"] for f in sys.argv[1:3])
worst = max(abs(s[k] - p[k]) / max(1.0, abs(s[k])) for k in s)
print(f"dJ/da of {len(s)} variables, -parallel against serial: largest relative difference {worst:.3g}")
sys.exit(0 if worst < 1e-12 and s.keys() == p.keys() else 1)
PY
