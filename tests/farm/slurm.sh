#!/usr/bin/env bash
# The Slurm recipe of docs/farm.md, run for real on a single-node Slurm cluster that this
# script starts on this machine (Debian's slurm-wlm and munge; run as root):
#
#   tests/farm/slurm.sh PRISM WORK
#
# It writes a slurm.conf for this host, starts munged, slurmctld and slurmd, submits the
# job array of tiles (docs/farm.md's render_tiles.sbatch) and the stitch job that waits for
# it (--dependency=afterok), compares the stitched frame bit for bit with a render in one
# process, does the same for the turntable's frames as an array, then stops the daemons.
# Exits 0 when every comparison holds, 3 when the cluster cannot be started here (not root,
# Slurm or munge missing, the daemons never ready), anything else on a failure.
set -euo pipefail
cannot_start() {
    echo "slurm: cannot start a cluster here: $*" >&2
    exit 3
}
[ "$(id -u)" = 0 ] || cannot_start "not root"
for tool in slurmctld slurmd sbatch munged compare; do
    command -v "$tool" >/dev/null || cannot_start "no $tool"
done
prism=$(realpath "$1")
work=$(mkdir -p "$2" && realpath "$2")
root=$(cd "$(dirname "$0")/../.." && pwd)
host=$(hostname -s)
etc=$work/slurm-etc
state=$work/slurm-state
mkdir -p "$etc" "$state/ctld" "$state/d" "$work/out"
# The node as slurmd sees it (CPUs, sockets, cores, memory), less a fifth of the memory.
node=$(slurmd -C | head -1 | awk '{ for (i = 1; i <= NF; i++) if ($i ~ /^RealMemory=/) { split($i, m, "="); $i = "RealMemory=" int(m[2] * 0.8) } print }')

cat > "$etc/slurm.conf" <<EOF
ClusterName=prism-test
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
StateSaveLocation=$state/ctld
SlurmdSpoolDir=$state/d
SlurmctldPidFile=$state/slurmctld.pid
SlurmdPidFile=$state/slurmd.pid
SlurmctldLogFile=$state/slurmctld.log
SlurmdLogFile=$state/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
ReturnToService=2
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/filetxt
JobCompLoc=$state/jobs.txt
$node State=UNKNOWN
PartitionName=render Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
# Slurm 22.05 loads a cgroup plugin even when nothing is constrained: v1, left unmounted.
cat > "$etc/cgroup.conf" <<EOF
CgroupPlugin=cgroup/v1
CgroupAutomount=no
EOF
export SLURM_CONF=$etc/slurm.conf

stop_daemons() {
    [ -f "$state/slurmd.pid" ] && kill "$(cat "$state/slurmd.pid")" 2>/dev/null || true
    [ -f "$state/slurmctld.pid" ] && kill "$(cat "$state/slurmctld.pid")" 2>/dev/null || true
}
trap stop_daemons EXIT

# munge: a key of its own if the machine has none, and the daemon.
if [ ! -s /etc/munge/munge.key ]; then
    dd if=/dev/urandom bs=1 count=1024 of=/etc/munge/munge.key 2>/dev/null
fi
chown munge:munge /etc/munge/munge.key 2>/dev/null || true
chmod 400 /etc/munge/munge.key
mkdir -p /run/munge && chown munge:munge /run/munge 2>/dev/null || true
pgrep -x munged >/dev/null || runuser -u munge -- /usr/sbin/munged || /usr/sbin/munged --force \
    || cannot_start "munged did not start"
munge -n | unmunge >/dev/null || cannot_start "munge does not work"

slurmctld -f "$etc/slurm.conf" || cannot_start "slurmctld did not start"
slurmd -f "$etc/slurm.conf" || cannot_start "slurmd did not start ($(tail -1 "$state/slurmd.log"))"
ready=no
for _ in $(seq 60); do
    if sinfo -h -o '%T' 2>/dev/null | grep -q idle; then
        ready=yes
        break
    fi
    sleep 1
done
[ $ready = yes ] || cannot_start "the node never became idle ($(tail -1 "$state/slurmctld.log"))"
sinfo
cd "$work/out"

# ---- Tiles: a job array and a stitch job that waits for it --------------------------------
tiles=4
cat > render_tiles.sbatch <<EOF
#!/bin/bash
#SBATCH --job-name=prism-tiles
#SBATCH --array=0-$((tiles - 1))
#SBATCH --cpus-per-task=1
#SBATCH --output=tile_%a.log
"$prism" render --width 320 --height 240 --adaptive --quiet --threads \$SLURM_CPUS_PER_TASK \\
    --tile \${SLURM_ARRAY_TASK_ID}/$tiles --skip-existing -o tile_\${SLURM_ARRAY_TASK_ID}.png
EOF
array=$(sbatch --parsable render_tiles.sbatch)
stitch=$(sbatch --parsable --dependency=afterok:"$array" --job-name=prism-stitch \
    --output=stitch.log --wrap "\"$prism\" stitch tile_*.png -o stitched.png")
echo "submitted tiles as job $array, the stitch as job $stitch"

# ---- Frames: one array task per frame -----------------------------------------------------
frames=8
cat > render_frames.sbatch <<EOF
#!/bin/bash
#SBATCH --job-name=prism-frames
#SBATCH --array=0-$((frames - 1))
#SBATCH --cpus-per-task=1
#SBATCH --output=frame_%a.log
"$prism" render "$root/assets/scenes/turntable.toml" --width 120 --height 90 --quiet \\
    --threads 1 --frame-from-env SLURM_ARRAY_TASK_ID --skip-existing -o frame_{frame:04}.png
EOF
frames_job=$(sbatch --parsable render_frames.sbatch)
echo "submitted frames as job $frames_job"

for _ in $(seq 600); do
    [ -z "$(squeue -h -o %i)" ] && break
    sleep 1
done
squeue
# Each finished job as Slurm recorded it: id, name, array task, state and exit code.
awk '{ for (i = 1; i <= NF; i++) { split($i, kv, "="); f[kv[1]] = kv[2] }
       task = ("ArrayTaskId" in f) ? f["ArrayJobId"] "_" f["ArrayTaskId"] : f["JobId"]
       printf "job %-4s %-13s %-5s %s exit %s\n", f["JobId"], f["Name"], task, f["JobState"], f["ExitCode"]
       delete f }' "$state/jobs.txt"
cat tile_2.log stitch.log

# The same images in one process, to compare with.
"$prism" render --width 320 --height 240 --adaptive --quiet -o full.png 2>/dev/null
"$prism" render "$root/assets/scenes/turntable.toml" --width 120 --height 90 --quiet \
    --frames 0..$frames -o one_{frame:04}.png 2>/dev/null
differing() {
    compare -metric AE "$1" "$2" null: 2>&1 | awk '{ print $1 }' || true
}
check() {
    [ "$(differing "$1" "$2")" = 0 ] || { echo "FAIL: $1 and $2 differ" >&2; exit 1; }
    echo "same: $1 $2"
}
check stitched.png full.png
for ((f = 0; f < frames; f++)); do
    name=$(printf '%04d' "$f")
    check "frame_$name.png" "one_$name.png"
done
echo "slurm recipe: all images equal"
