"""A one-node Slurm cluster on this machine, for tests: munged, slurmctld and slurmd on
localhost with every file (key, config, state, spool, logs, sockets) in a temporary
directory, started by `with OneNodeCluster() as c:` and stopped at its end.

It runs as whoever starts it (root in CI): the daemons and the jobs share that user, so
nothing needs privileges and nothing of the machine's own Slurm or munge is touched.
Commands run through c.run([...]) see the cluster through SLURM_CONF.
"""
import os
import shutil
import signal
import socket
import subprocess
import tempfile
import time

NODE = "foveal-node"
DAEMONS = ["munged", "mungekey", "slurmctld", "slurmd", "sbatch", "sinfo", "scontrol"]


def missing_programs():
    """The programs of munge and slurm-wlm not found (on PATH or in /usr/sbin)."""
    path = os.environ.get("PATH", "") + ":/usr/sbin:/sbin"
    return [p for p in DAEMONS if shutil.which(p, path=path) is None]


def free_ports(count):
    """Ports nothing listens on now (bound and released; a race is unlikely on a test box)."""
    socks = [socket.socket() for _ in range(count)]
    try:
        for s in socks:
            s.bind(("127.0.0.1", 0))
        return [s.getsockname()[1] for s in socks]
    finally:
        for s in socks:
            s.close()


class ClusterError(RuntimeError):
    pass


class OneNodeCluster:
    def __init__(self, cpus=None, keep=False):
        self.cpus = cpus or os.cpu_count() or 1
        self.keep = keep
        self.dir = None
        self.procs = {}

    def path(self, name):
        return os.path.join(self.dir, name)

    def env(self):
        e = dict(os.environ)
        e["SLURM_CONF"] = self.path("slurm.conf")
        e["PATH"] = e.get("PATH", "") + ":/usr/sbin:/sbin"
        return e

    def run(self, args, check=True, timeout=120, **kw):
        r = subprocess.run(args, env=self.env(), capture_output=True, text=True, timeout=timeout, **kw)
        if check and r.returncode != 0:
            raise ClusterError(f"{' '.join(args)}: exit {r.returncode}\n{r.stdout}{r.stderr}")
        return r

    def _write_config(self):
        user = subprocess.run(["id", "-un"], capture_output=True, text=True, check=True).stdout.strip()
        ctld_port, slurmd_port = free_ports(2)
        for d in ("state", "spool"):
            os.makedirs(self.path(d))
        config = f"""# A one-node test cluster (tests/cluster/slurm_cluster.py); everything in {self.dir}.
ClusterName=foveal-test
SlurmctldHost=localhost(127.0.0.1)
SlurmctldPort={ctld_port}
SlurmdPort={slurmd_port}
SlurmUser={user}
SlurmdUser={user}
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket={self.path("munge.socket")}
StateSaveLocation={self.path("state")}
SlurmdSpoolDir={self.path("spool")}
SlurmctldPidFile={self.path("slurmctld.pid")}
SlurmdPidFile={self.path("slurmd.pid")}
SlurmctldLogFile={self.path("slurmctld.log")}
SlurmdLogFile={self.path("slurmd.log")}
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups in a container or a CI box: track processes by their parents.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
# The node is whatever this machine is: trust the CPU count below over the hardware's.
SlurmdParameters=config_overrides
MinJobAge=600
NodeName={NODE} NodeHostname=localhost NodeAddr=127.0.0.1 CPUs={self.cpus} State=UNKNOWN
PartitionName=test Nodes={NODE} Default=YES MaxTime=INFINITE State=UP
"""
        with open(self.path("slurm.conf"), "w") as f:
            f.write(config)

    def _start(self, name, args):
        log = open(self.path(name + ".stdout"), "w")
        self.procs[name] = subprocess.Popen(args, env=self.env(), stdout=log, stderr=subprocess.STDOUT,
                                            start_new_session=True)

    def _wait(self, what, ready, timeout):
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            for name, p in self.procs.items():
                if p.poll() is not None:
                    raise ClusterError(f"{name} exited ({p.returncode}) while waiting for {what}:\n{self.logs()}")
            if ready():
                return
            time.sleep(0.2)
        raise ClusterError(f"timed out after {timeout} s waiting for {what}:\n{self.logs()}")

    def logs(self):
        out = []
        for name in ("munged.log", "slurmctld.log", "slurmd.log", "munged.stdout", "slurmctld.stdout", "slurmd.stdout"):
            p = self.path(name)
            if os.path.exists(p):
                with open(p, errors="replace") as f:
                    tail = f.read().splitlines()[-25:]
                out.append(f"--- {name}\n" + "\n".join(tail))
        return "\n".join(out)

    def __enter__(self):
        missing = missing_programs()
        if missing:
            raise ClusterError("not installed: " + ", ".join(missing) + " (apt-get install slurm-wlm munge; scripts/bootstrap.sh --tests)")
        self.dir = tempfile.mkdtemp(prefix="foveal-slurm-")
        os.chmod(self.dir, 0o700)  # munged refuses a key or socket others could reach
        try:
            self._write_config()
            self.run(["mungekey", "--create", "--keyfile", self.path("munge.key")])
            os.chmod(self.path("munge.key"), 0o400)
            # -F: in the foreground, so that this process owns it and stops it.
            self._start("munged", ["munged", "-F", "--force", "--socket", self.path("munge.socket"),
                                   "--key-file", self.path("munge.key"), "--pid-file", self.path("munged.pid"),
                                   "--log-file", self.path("munged.log"), "--seed-file", self.path("munged.seed")])
            self._wait("munged's socket", lambda: os.path.exists(self.path("munge.socket")), 60)
            self._start("slurmctld", ["slurmctld", "-D", "-i"])
            self._wait("slurmctld", lambda: self.run(["scontrol", "ping"], check=False).returncode == 0 and
                       "UP" in self.run(["scontrol", "ping"], check=False).stdout, 60)
            self._start("slurmd", ["slurmd", "-D", "-N", NODE])
            self._wait("the node to come up idle",
                       lambda: self.run(["sinfo", "-h", "-n", NODE, "-o", "%T"], check=False).stdout.strip() == "idle", 60)
        except BaseException:
            self.__exit__(None, None, None)
            raise
        return self

    def __exit__(self, *exc):
        # slurmd first (it ends its jobs' steps), then the controller, then munge.
        for name in ("slurmd", "slurmctld", "munged"):
            p = self.procs.pop(name, None)
            if p is None or p.poll() is not None:
                continue
            os.killpg(p.pid, signal.SIGTERM)
            try:
                p.wait(timeout=15)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
        if self.dir and not self.keep:
            shutil.rmtree(self.dir, ignore_errors=True)
        return False
