#!/bin/bash
# Submit a phase diagram as a SLURM job array and its merge:
#
#   PHASE_DIAGRAM=$PWD/target/release/phase-diagram OUT=$PWD/antikink.csv \
#       bash examples/slurm/submit.sh --array=0-15
#
# Arguments go to the array's sbatch (e.g. --array=0-15, --partition=...). Prints the two job ids.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
array=$(sbatch --parsable --export=ALL "$@" "$here/phase-diagram.sbatch")
array=${array%%;*}
merge=$(sbatch --parsable --export=ALL --dependency="afterok:$array" "$here/merge.sbatch")
echo "array job $array, merge job $merge (runs when every task of $array has succeeded)"
