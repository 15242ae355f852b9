#!/bin/sh
# Run a scene on 2 ranks into a fresh output directory, then run a checker script on that directory.
# Usage: run_then_check.sh MDPORE "MPIEXEC [FLAGS]" PYTHON SCENE OUTDIR CHECKER [CHECKER ARGS...]
set -u
M=$1; MPI=$2; PY=$3; S=$4; D=$5; C=$6; shift 6
rm -rf "$D"
$MPI -n 2 $M run --output-dir "$D" "$S" || { echo "FAIL: mdpore run $S"; exit 1; }
exec $PY "$C" "$D" "$@"
