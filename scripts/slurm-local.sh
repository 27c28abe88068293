#!/usr/bin/env bash
# A one-node SLURM cluster on this machine for `make test-slurm`: munged, slurmctld and slurmd of
# Debian's slurm-wlm (scripts/install-deps.sh --slurm), started as plain daemons (no systemd needed).
#
#   scripts/slurm-local.sh start    write /etc/slurm/slurm.conf, start what is not running, wait for the node
#   scripts/slurm-local.sh stop     stop slurmd and slurmctld of this configuration, munged if `start` started it
#   scripts/slurm-local.sh status   the daemons and sinfo
#
# Runs as root. The configuration is written only when /etc/slurm/slurm.conf is absent or was
# written by this script (its first line says so); a foreign one is refused. Containers: no cgroups
# (proctrack/linuxproc, task/none), consumable CPUs and memory (select/cons_tres, CR_Core_Memory),
# CPUs = nproc, RealMemory = 90 % of MemTotal. Idempotent: `start` twice is one cluster.
set -euo pipefail

action=${1:-}
conf=/etc/slurm/slurm.conf
mark="# Written by bhnsid scripts/slurm-local.sh for make test-slurm; replaced by it, never by hand."
state=/run/bhnsid-slurm-local      # what `start` started, one daemon name a line
logs=/var/log/slurm
node=$(hostname -s)

die() { echo "slurm-local: $*" >&2; exit 2; }

if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null 2>&1 || die "must run as root (it writes $conf and starts daemons); no sudo either"
  exec sudo "$0" "$@"
fi
case "$action" in start|stop|status) ;; *) die "usage: scripts/slurm-local.sh start|stop|status" ;; esac
for cmd in munged slurmctld slurmd sinfo scontrol; do
  command -v "$cmd" >/dev/null 2>&1 || [ -x "/usr/sbin/$cmd" ] ||
    die "$cmd not found: run scripts/install-deps.sh --slurm first"
done
export PATH="$PATH:/usr/sbin"
# The node name goes into slurm.conf, which slurmctld parses line by line: only a host name's own
# characters may reach it.
[[ "$node" =~ ^[A-Za-z0-9._-]+$ ]] || die "host name '$node' holds characters a slurm.conf NodeName cannot carry"

running() {  # running NAME PIDFILE: the pid file names a live process of that name
  local pid
  [ -s "$2" ] || return 1
  pid=$(cat "$2")
  [[ "$pid" =~ ^[1-9][0-9]*$ ]] || return 1  # a damaged pid file never reaches kill (kill -1 is everyone)
  [ -r "/proc/$pid/comm" ] && [ "$(cat "/proc/$pid/comm")" = "$1" ]
}

ours() { [ "$(head -n 1 "$conf" 2>/dev/null)" = "$mark" ]; }

node_state() { sinfo -h -N -n "$node" -o %t 2>/dev/null | head -n 1; }

if [ "$action" = status ]; then
  running munged /run/munge/munged.pid && echo "munged: running" || echo "munged: not running"
  running slurmctld /run/slurmctld.pid && echo "slurmctld: running" || echo "slurmctld: not running"
  running slurmd /run/slurmd.pid && echo "slurmd: running" || echo "slurmd: not running"
  sinfo 2>&1 || true
  exit 0
fi

if [ "$action" = stop ]; then
  ours || { echo "slurm-local: $conf is not this script's: nothing to stop"; exit 0; }
  # Newest first: slurmd, slurmctld (both run this script's configuration), then munged when this
  # script started it (the others authenticate through it).
  for name in slurmd slurmctld munged; do
    [ "$name" != munged ] || grep -qx munged "$state/started" 2>/dev/null || continue
    case "$name" in munged) pidfile=/run/munge/munged.pid ;; *) pidfile=/run/$name.pid ;; esac
    if running "$name" "$pidfile"; then
      pid=$(cat "$pidfile")
      kill "$pid"
      for _ in $(seq 100); do [ -d "/proc/$pid" ] || break; sleep 0.1; done
      [ -d "/proc/$pid" ] && die "$name (pid $pid) did not stop within 10 s"
      echo "slurm-local: stopped $name (pid $pid)"
    fi
  done
  rm -f "$state/started"
  exit 0
fi

# start: the configuration.
if [ -e "$conf" ] && ! ours; then
  die "$conf exists and was not written by this script; refusing to replace it (move it away or use that cluster)"
fi
cpus=$(nproc)
mem_kib=$(awk '/^MemTotal:/ {print $2}' /proc/meminfo)
real_mib=$(( mem_kib / 1024 * 9 / 10 ))
mkdir -p /etc/slurm "$state" "$logs" /var/spool/slurmctld /var/spool/slurmd
tmp=$(mktemp "$conf.XXXXXX")
cat >"$tmp" <<EOF
$mark
ClusterName=bhnsid-local
SlurmctldHost=$node
SlurmUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
StateSaveLocation=/var/spool/slurmctld
SlurmdSpoolDir=/var/spool/slurmd
SlurmctldPidFile=/run/slurmctld.pid
SlurmdPidFile=/run/slurmd.pid
SlurmctldLogFile=$logs/slurmctld.log
SlurmdLogFile=$logs/slurmd.log
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MinJobAge=3600
NodeName=$node CPUs=$cpus RealMemory=$real_mib State=UNKNOWN
PartitionName=local Nodes=$node Default=YES MaxTime=INFINITE State=UP
EOF
chmod 644 "$tmp"
changed=0
if ! cmp -s "$tmp" "$conf"; then mv "$tmp" "$conf"; changed=1; else rm -f "$tmp"; fi
touch "$state/started"

# munge: the key comes with the package (mungekey makes one when it is missing).
if ! running munged /run/munge/munged.pid; then
  [ -s /etc/munge/munge.key ] || runuser -u munge -- mungekey --create
  mkdir -p /run/munge && chown munge:munge /run/munge && chmod 755 /run/munge
  runuser -u munge -- munged
  grep -qx munged "$state/started" || echo munged >>"$state/started"
  echo "slurm-local: started munged"
fi
for _ in $(seq 50); do munge -n </dev/null | unmunge >/dev/null 2>&1 && break; sleep 0.1; done
munge -n </dev/null | unmunge >/dev/null 2>&1 || die "munge does not authenticate (see /var/log/munge/munged.log)"

for name in slurmctld slurmd; do
  if running "$name" "/run/$name.pid" && [ "$changed" = 1 ]; then
    pid=$(cat "/run/$name.pid")
    kill "$pid"
    for _ in $(seq 100); do [ -d "/proc/$pid" ] || break; sleep 0.1; done
    [ -d "/proc/$pid" ] && die "$name (pid $pid) did not stop within 10 s for the new configuration"
  fi
  if ! running "$name" "/run/$name.pid"; then
    if [ "$name" = slurmd ]; then slurmd -N "$node"; else slurmctld; fi
    grep -qx "$name" "$state/started" || echo "$name" >>"$state/started"
    echo "slurm-local: started $name"
  fi
  for _ in $(seq 100); do running "$name" "/run/$name.pid" && break; sleep 0.1; done
  running "$name" "/run/$name.pid" || die "$name did not start (see $logs/$name.log)"
done

# The node: idle (or busy with jobs) within a minute; one left down by an earlier stop is resumed.
for _ in $(seq 120); do
  s=$(node_state)
  case "$s" in
    idle|mix|mixed|alloc|allocated) echo "slurm-local: node $node is $s ($cpus CPUs, ${real_mib} MiB)"; exit 0 ;;
    down*|drain*|drng*) scontrol update nodename="$node" state=resume >/dev/null 2>&1 || true ;;
  esac
  sleep 0.5
done
die "node $node is '$(node_state)' after 60 s, not idle (see $logs/slurmctld.log and $logs/slurmd.log)"
