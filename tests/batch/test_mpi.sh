#!/bin/sh
# The MPI build (-DJUMPCYL_MPI=ON) under `mpirun -n 2` writes the same bytes
# as one process: a sweep, a Monte Carlo job, and a Monte Carlo job stopped
# part way and resumed under mpirun. Usage: test_mpi.sh PATH_TO_JUMPCYL
# PATH_TO_PLAIN_JUMPCYL (the build without MPI stops the job: MPI's start
# needs shared memory that ulimit -f takes away).
set -eu
tool=$1
plain=$2
dir=$(mktemp -d /tmp/jc_mpi_XXXXXX)
trap 'rm -rf "$dir"' EXIT
mpirun="mpirun -n 2 --oversubscribe"
[ "$(id -u)" = 0 ] && mpirun="$mpirun --allow-run-as-root"
export OMPI_MCA_rmaps_base_oversubscribe=1
fail() { echo "FAILED: $*" >&2; exit 1; }

grid="--vary incline=10:50:2 --vary rod-offset=2cm:8cm:1cm --vary impact-law=stronge,newton"
"$tool" sweep $grid --threads 1 --output "$dir/one.csv" > /dev/null
$mpirun "$tool" sweep $grid --threads 1 --output "$dir/two.csv" > /dev/null
cmp "$dir/one.csv" "$dir/two.csv" || fail "sweep: mpirun -n 2 differs from one process"
echo "passed: sweep ($(($(wc -l < "$dir/one.csv") - 1)) cases) under mpirun -n 2 is the one-process file"

"$tool" mc --samples 3000 --seed 5 --threads 2 --output "$dir/mc1.csv" > "$dir/mc1.txt"
$mpirun "$tool" mc --samples 3000 --seed 5 --threads 1 --output "$dir/mc2.csv" > "$dir/mc2.txt"
cmp "$dir/mc1.csv" "$dir/mc2.csv" || fail "mc: mpirun -n 2 rows differ from one process"
cmp "$dir/mc1.txt" "$dir/mc2.txt" || fail "mc: mpirun -n 2 summary differs from one process"
echo "passed: mc (3000 samples) under mpirun -n 2: the same rows and the same summary"

# Resume under mpirun: a job stopped by ulimit -f 40 keeps its first
# rows in FILE.part, the tool's own (job line, row checksums).
(ulimit -f 40; "$plain" mc --samples 3000 --seed 5 --threads 1 --output "$dir/mc3.csv" > /dev/null 2>&1) &&
  fail "mc: not stopped by ulimit -f 40"
kept=$(($(wc -l < "$dir/mc3.csv.part") - 2))
[ "$kept" -gt 0 ] || fail "mc: no row kept in mc3.csv.part"
$mpirun "$tool" mc --samples 3000 --seed 5 --threads 1 --output "$dir/mc3.csv" --resume > "$dir/mc3.txt" 2> /dev/null
cmp "$dir/mc1.csv" "$dir/mc3.csv" || fail "mc: resumed under mpirun differs"
cmp "$dir/mc1.txt" "$dir/mc3.txt" || fail "mc: the summary of a resumed job differs"
echo "passed: mc resumed under mpirun -n 2 after $kept kept rows: the same file and summary"
echo "3 passed, 0 failed"
