"""A private single-node Slurm cluster (munged + slurmctld + slurmd on localhost) for tests.

Everything lives in one temporary folder: the munge key and socket, slurm.conf, state, spool, logs and pid files.
Ports are picked free at start. Nothing system-wide is used or changed, so the test runs beside (or without) a
real Slurm installation. The daemons run in the foreground as our children, each in its own session, and get
SIGKILL from the kernel if this process dies first (PR_SET_PDEATHSIG), so even a test killed with SIGKILL leaves
no daemon behind. stop() kills the daemons and every process that carries this cluster's SLURM_CONF (the
slurmstepd and job processes slurmd started), then removes the folder.
"""

import ctypes
import getpass
import os
import shutil
import signal
import socket
import subprocess
import tempfile
import time

PR_SET_PDEATHSIG = 1
START_TIMEOUT_S = 30


class ClusterError(Exception):
    """A daemon did not start or a Slurm command failed; the message carries the daemon logs."""


def _die_with_parent():
    # Runs in the child between fork and exec: the kernel kills it when the test process exits for any reason.
    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(PR_SET_PDEATHSIG, signal.SIGKILL)


def _free_port():
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _require_program(name):
    path = shutil.which(name, path=os.environ.get("PATH", "") + ":/usr/sbin:/sbin")
    if path is None:
        raise ClusterError(f"{name} not found: install the Debian packages slurm-wlm and munge "
                           "(tools/setup-deps.sh)")
    return path


class SlurmCluster:
    def __init__(self):
        # A short base keeps the munge socket path under the 108-byte AF_UNIX limit whatever TMPDIR is.
        self.root = tempfile.mkdtemp(prefix="sward-slurm-", dir="/tmp")
        self.conf = os.path.join(self.root, "slurm.conf")
        self.logs = {}
        self._daemons = []
        self.env = dict(os.environ, SLURM_CONF=self.conf)
        # Settings a user's environment may hold that would send our commands elsewhere.
        for key in ("SLURM_CLUSTERS", "SLURM_PARTITION", "SBATCH_PARTITION", "SBATCH_ACCOUNT"):
            self.env.pop(key, None)

    def path(self, *parts):
        return os.path.join(self.root, *parts)

    # -- start -------------------------------------------------------------------------------------------------

    def start(self):
        os.chmod(self.root, 0o711)  # munged wants its socket reachable by every user
        for d in ("munge", "state", "spool", "log"):
            os.mkdir(self.path(d), 0o755 if d == "munge" else 0o700)
        self._start_munge()
        self._write_conf()
        self._spawn("slurmctld", [_require_program("slurmctld"), "-D", "-c", "-f", self.conf])
        self._wait_for(lambda: self._slurm_ok(["sinfo", "-h"]), "slurmctld", "answering sinfo")
        self._spawn("slurmd", [_require_program("slurmd"), "-D", "-N", "localhost", "-f", self.conf])
        self._wait_for(self._node_idle, "slurmd", "node localhost idle")

    def _start_munge(self):
        key = self.path("munge", "munge.key")
        subprocess.run([_require_program("mungekey"), "--create", "--keyfile", key], check=True,
                       capture_output=True)
        os.chmod(key, 0o600)
        self.socket = self.path("munge", "munge.socket")
        # In the foreground munged logs to stderr, which _spawn keeps. --force: munged refuses a key whose parent
        # folders (here /tmp) are writable by others, sticky or not.
        self._spawn("munged", [_require_program("munged"), "--foreground", "--force", "--socket", self.socket,
                               "--key-file", key,
                               "--pid-file", self.path("munge", "munged.pid"),
                               "--seed-file", self.path("munge", "munged.seed")])
        self._wait_for(self._munge_ok, "munged", "a credential round trip")

    def _write_conf(self):
        user = getpass.getuser()
        self.logs["slurmctld"] = self.path("log", "slurmctld.log")
        self.logs["slurmd"] = self.path("log", "slurmd.log")
        settings = {
            "ClusterName": "sward-test",
            "SlurmctldHost": "localhost(127.0.0.1)",
            "SlurmctldPort": _free_port(),
            "SlurmdPort": _free_port(),
            "SlurmUser": user,
            "SlurmdUser": user,
            "AuthType": "auth/munge",
            "CredType": "cred/munge",
            "AuthInfo": f"socket={self.socket}",
            "StateSaveLocation": self.path("state"),
            "SlurmdSpoolDir": self.path("spool"),
            "SlurmctldPidFile": self.path("slurmctld.pid"),
            "SlurmdPidFile": self.path("slurmd.pid"),
            "SlurmctldLogFile": self.logs["slurmctld"],
            "SlurmdLogFile": self.logs["slurmd"],
            "SlurmctldDebug": "info",
            "SlurmdDebug": "info",
            "MailProg": "/bin/true",
            # No cgroups: process groups track jobs, no task binding, no accounting daemons.
            "ProctrackType": "proctrack/pgid",
            "TaskPlugin": "task/none",
            "JobAcctGatherType": "jobacct_gather/none",
            "AccountingStorageType": "accounting_storage/none",
            "JobCompType": "jobcomp/none",
            "MpiDefault": "none",
            "SelectType": "select/cons_tres",
            "SelectTypeParameters": "CR_CPU",
            "SchedulerType": "sched/backfill",
            "ReturnToService": 2,
            # A dependent job whose dependency failed is cancelled instead of pending for ever, so sbatch --wait
            # on it returns.
            "DependencyParameters": "kill_invalid_depend",
        }
        lines = [f"{k}={v}" for k, v in settings.items()]
        lines.append(f"NodeName=localhost NodeAddr=127.0.0.1 CPUs={os.cpu_count()} State=UNKNOWN")
        lines.append("PartitionName=test Nodes=localhost Default=YES MaxTime=INFINITE State=UP")
        with open(self.conf, "w") as f:
            f.write("\n".join(lines) + "\n")

    def _spawn(self, name, argv):
        log = open(self.path("log", f"{name}.stdout"), "w")
        self.logs[f"{name} stdout"] = log.name
        proc = subprocess.Popen(argv, env=self.env, stdin=subprocess.DEVNULL, stdout=log, stderr=subprocess.STDOUT,
                                start_new_session=True, preexec_fn=_die_with_parent)
        log.close()
        self._daemons.append((name, proc))

    def _wait_for(self, ready, name, what):
        deadline = time.monotonic() + START_TIMEOUT_S
        proc = dict(self._daemons)[name]
        while time.monotonic() < deadline:
            if proc.poll() is not None:
                raise ClusterError(f"{name} exited with status {proc.returncode} while starting\n"
                                   + self.log_text())
            if ready():
                return
            time.sleep(0.2)
        raise ClusterError(f"{name} not ready ({what}) after {START_TIMEOUT_S} s\n" + self.log_text())

    def _munge_ok(self):
        if not os.path.exists(self.socket):
            return False
        cred = subprocess.run(["munge", "--no-input", "--socket", self.socket], capture_output=True)
        if cred.returncode != 0:
            return False
        return subprocess.run(["unmunge", "--socket", self.socket], input=cred.stdout,
                              capture_output=True).returncode == 0

    def _slurm_ok(self, argv):
        return subprocess.run(argv, env=self.env, capture_output=True).returncode == 0

    def _node_idle(self):
        out = subprocess.run(["sinfo", "-h", "-n", "localhost", "-o", "%T"], env=self.env, capture_output=True,
                             text=True)
        return out.returncode == 0 and out.stdout.strip() == "idle"

    # -- use ---------------------------------------------------------------------------------------------------

    def run(self, argv, timeout, cwd=None):
        """Runs a Slurm client command against this cluster; returns CompletedProcess (text)."""
        try:
            return subprocess.run(argv, env=self.env, cwd=cwd or self.root, capture_output=True, text=True,
                                  timeout=timeout)
        except subprocess.TimeoutExpired:
            queue = subprocess.run(["squeue", "-a", "-l"], env=self.env, capture_output=True, text=True).stdout
            raise ClusterError(f"{' '.join(argv)} did not finish in {timeout} s; queue:\n{queue}\n"
                               + self.log_text())

    def log_text(self):
        parts = []
        for name, path in self.logs.items():
            try:
                with open(path, errors="replace") as f:
                    text = f.read()
            except OSError:
                continue
            if text.strip():
                parts.append(f"--- {name} log ({path}) ---\n{text[-6000:]}")
        return "\n".join(parts)

    # -- stop --------------------------------------------------------------------------------------------------

    def _our_pids(self):
        """Processes (other than this one) whose environment holds this cluster's SLURM_CONF."""
        marker = b"\0" + f"SLURM_CONF={self.conf}".encode() + b"\0"
        pids = []
        for entry in os.listdir("/proc"):
            if not entry.isdigit() or int(entry) == os.getpid():
                continue
            try:
                with open(f"/proc/{entry}/environ", "rb") as f:
                    if marker in b"\0" + f.read() + b"\0":
                        pids.append(int(entry))
            except OSError:
                continue  # gone, or not ours to read
        return pids

    def stop(self):
        """Kills every daemon and job process of this cluster and removes its folder; returns leftover pids."""
        for _, proc in self._daemons:
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
        for _ in range(50):
            pids = self._our_pids()
            if not pids:
                break
            for pid in pids:
                try:
                    os.kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
            time.sleep(0.1)
        leftover = self._our_pids()
        shutil.rmtree(self.root, ignore_errors=True)
        return leftover
