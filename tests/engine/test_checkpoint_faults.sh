#!/bin/sh
# Checkpoints under faults, on one rank:
#  1. a run killed with SIGKILL after a checkpoint, with a dump frame and a thermo line left half
#     written and temporary files of killed writes lying beside its outputs, restarts from its
#     checkpoint into the same folder: the temporary files are removed (said on stderr), the thermo
#     log, dump, flux log and snapshot index are cut back to the checkpoint's step, and the finished
#     series equal a straight run's byte for byte (no duplicated row, no truncated frame);
#  2. an HDF5 thermo log continued past a checkpoint and restarted from that older checkpoint keeps
#     each step once;
#  3. a checkpoint with one changed byte in a dataset, or a changed step attribute, is refused with a
#     message naming the file and what differs.
# Usage: test_checkpoint_faults.sh MDPORE PYTHON SCENE
set -u
M=$1; PY=$2; S=$3
W=checkpoint_faults_test; rm -rf $W; mkdir -p $W; cd $W || exit 1
fail() { echo "FAIL: $*"; exit 1; }
$PY -c "import h5py" 2>/dev/null || { echo "SKIP: $PY has no h5py"; exit 77; }
ckpt_step() { h5dump -a step "$1" | sed -n 's/^ *(0): //p'; }

# --- 1. SIGKILL mid-run, restart into the same folder --------------------------------------------
$M run --output-dir straight $S > straight.log 2>&1 || fail "straight run"
$M run --output-dir killed $S > killed.log 2>&1 &
pid=$!
last=0
while kill -0 $pid 2>/dev/null; do
  last=$(tail -n 1 killed/thermo.csv 2>/dev/null | cut -d, -f1)
  case $last in ''|*[!0-9]*) last=0 ;; esac
  [ "$last" -ge 250 ] && break
  sleep 0.05
done
kill -9 $pid 2>/dev/null || fail "the run ended (at step $last) before it could be killed"
wait $pid 2>/dev/null
ck=$(ckpt_step killed/restart.h5)
echo "killed at thermo step $last; checkpoint at step $ck"
[ "$ck" -ge 100 ] && [ "$ck" -lt 600 ] || fail "checkpoint step '$ck'"
# What a kill inside a write leaves: temporary files of the dead process, a half frame, a half row.
cp killed/restart.h5 killed/restart.h5.tmp.$pid
echo '{"half": ' > killed/summary.json.tmp.$pid
printf 'ITEM: TIMESTEP\n%s\nITEM: NUMBER OF ATOMS\n12\nITEM: BOX BOU' $((last + 50)) >> killed/dump.lammpstrj
printf '%s,1.2345' $((last + 10)) >> killed/thermo.csv
$M run --restart killed/restart.h5 --steps $((600 - ck)) --output-dir killed $S > restart.log 2> restart.err ||
  { cat restart.err; fail "restart after SIGKILL"; }
cat restart.err
grep -q "removed killed/restart.h5.tmp.$pid" restart.err || fail "stale checkpoint temporary not removed/reported"
grep -q "removed killed/summary.json.tmp.$pid" restart.err || fail "stale summary temporary not removed/reported"
[ -e killed/restart.h5.tmp.$pid ] && fail "killed/restart.h5.tmp.$pid still there"
grep -q "thermo.csv: restart at step $ck: dropped" restart.err || fail "thermo rows past the checkpoint not reported"
grep -q "dump.lammpstrj: restart at step $ck" restart.err || fail "dump trim not reported"
for f in thermo.csv dump.lammpstrj flux.csv snap.xdmf; do
  cmp straight/$f killed/$f || fail "$f after kill + restart differs from the straight run's"
done
h5diff straight/snap_000000600.h5 killed/snap_000000600.h5 || fail "final snapshots differ"
dups=$(grep -v '^[#s]' killed/thermo.csv | cut -d, -f1 | sort | uniq -d | wc -l)
[ "$dups" -eq 0 ] || fail "$dups duplicated thermo steps"
echo "kill + restart: stale temporaries removed; thermo, dump, flux, snapshot index equal the straight run's"

# --- 2. HDF5 thermo log restarted from an older checkpoint ---------------------------------------
sed 's/file: thermo.csv/file: thermo.h5/' $S > h5.yaml
$M run --steps 100 --output-dir h5 h5.yaml > /dev/null 2>&1 || fail "h5: first 100 steps"
cp h5/restart.h5 ck100.h5
$M run --steps 100 --restart h5/restart.h5 --output-dir h5 h5.yaml > /dev/null 2>&1 || fail "h5: to 200"
$M run --steps 100 --restart ck100.h5 --output-dir h5 h5.yaml > /dev/null 2> h5.err || fail "h5: again from 100"
grep -q "thermo.h5: restart at step 100: dropped 10 row(s)" h5.err || { cat h5.err; fail "h5 trim not reported"; }
$PY - <<'PYEOF' || fail "h5 thermo steps"
import h5py, numpy as np
s = h5py.File("h5/thermo.h5", "r")["thermo"][:, 0]
print(f"h5 thermo: {len(s)} rows, steps {s[0]:.0f}..{s[-1]:.0f}")
assert np.array_equal(s, np.arange(0, 201, 10)), s
PYEOF

# --- 3. corrupted checkpoints are refused ---------------------------------------------------------
cp straight/restart.h5 bad_data.h5
cp straight/restart.h5 bad_step.h5
$PY - <<'PYEOF' || fail "corrupting"
import h5py
with h5py.File("bad_data.h5", "r+") as f:
    x = f["velocity"][...]
    x[7, 1] = -x[7, 1] + 1e-9   # one value of one particle
    f["velocity"][...] = x
with h5py.File("bad_step.h5", "r+") as f:
    f.attrs.modify("step", f.attrs["step"] - 100)
PYEOF
for c in bad_data bad_step; do
  if $M run --steps 10 --restart $c.h5 --output-dir $c $S > $c.out 2> $c.err; then
    fail "$c.h5 accepted"
  fi
  cat $c.err
  grep -q "$c.h5: corrupted checkpoint refused" $c.err || fail "$c: no clear refusal"
done
grep -q "dataset 'velocity'" bad_data.err || fail "bad_data: the dataset is not named"
grep -q "header attributes (step 500" bad_step.err || fail "bad_step: the header is not named"
echo "corrupted checkpoints refused with the file and what differs"
