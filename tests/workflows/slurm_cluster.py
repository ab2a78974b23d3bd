"""A Slurm cluster of one node on this machine, for the cohort workflow's Slurm tests and for
trying the Slurm profile by hand: munged, MariaDB, slurmdbd, slurmctld and slurmd (Debian 12:
munge, mariadb-server-core, slurmdbd, slurmctld, slurmd, slurm-client), each with its
configuration, state, log and socket in one fresh temporary folder and on free localhost ports,
so the machine's own munge, MariaDB or Slurm (if any) is neither used nor touched.

Accounting (slurmdbd + MariaDB) is part of it because a site's Slurm has it and the profile's
job status script asks `sacct` first (slurmctld forgets a finished job after MinJobAge), and
because the test checks each job's requested resources in the accounting record.

The node is this machine as `slurmd -C` sees it (cores, memory). Daemons run in the foreground
as children of this process; each gets SIGTERM from the kernel if this process dies without
stopping them (PR_SET_PDEATHSIG), so even a killed test leaves no daemon behind.

As a program: starts the cluster, runs COMMAND (default: an interactive shell) with SLURM_CONF
set, then stops the cluster, whatever the command's outcome:
    python3 tests/workflows/slurm_cluster.py [--partition NAME] [--account NAME] [-- COMMAND ...]
"""
import ctypes
import os
import pathlib
import pwd
import re
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time

# Debian puts the daemons in /usr/sbin, which a non-root PATH may lack.
SBIN = ("/usr/sbin", "/usr/bin", "/sbin", "/bin")
DAEMONS = ("munged", "mariadbd", "slurmdbd", "slurmctld", "slurmd")
CLIENTS = ("sbatch", "squeue", "sacct", "sacctmgr", "scontrol", "scancel", "sinfo")
PACKAGES = "munge mariadb-server-core slurmdbd slurmctld slurmd slurm-client"


def _program(name):
    found = shutil.which(name)
    if found:
        return found
    for folder in SBIN:
        path = pathlib.Path(folder) / name
        if path.is_file() and os.access(path, os.X_OK):
            return str(path)
    return None


def missing_programs():
    """The daemons and client commands that are not installed (empty when all are)."""
    return [name for name in DAEMONS + CLIENTS if _program(name) is None]


def _free_ports(count):
    # note: the ports are free when asked (and distinct: all are held until each is known);
    # another program could take one before the daemon binds it. The daemon then fails to
    # start and says so in its log, which the error names.
    sockets = [socket.socket(socket.AF_INET, socket.SOCK_STREAM) for _ in range(count)]
    try:
        for s in sockets:
            s.bind(("127.0.0.1", 0))
        return [s.getsockname()[1] for s in sockets]
    finally:
        for s in sockets:
            s.close()


def _die_with_parent():
    # Runs in the child between fork and exec: SIGTERM when the process that started it ends.
    PR_SET_PDEATHSIG = 1
    ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGTERM)


class ClusterError(RuntimeError):
    """The cluster did not come up or go down; the message names the daemon and its log."""


class Cluster:
    """A running single-node cluster. Use as a context manager (stops on exit, also on an
    exception); `env` is the environment for Slurm commands (SLURM_CONF set); `folder` holds
    the configuration and logs/<daemon>.log. A folder it made itself is removed on a clean exit
    and kept (its path printed) after an exception."""

    def __init__(self, partition="cohort", account="cohort", folder=None):
        self.partition = partition
        self.account = account
        self.user = pwd.getpwuid(os.getuid()).pw_name
        self.owns_folder = folder is None
        self.folder = pathlib.Path(folder or tempfile.mkdtemp(prefix="glint-slurm-"))
        self.folder.chmod(0o700)  # the munge key and the database are the user's alone
        self.logs = self.folder / "logs"
        self.conf = self.folder / "slurm.conf"
        self.node = socket.gethostname().split(".")[0]
        self.processes = {}  # daemon name -> Popen
        self.env = dict(os.environ, SLURM_CONF=str(self.conf), USER=self.user)
        self.env["PATH"] = os.pathsep.join([self.env.get("PATH", ""), "/usr/sbin", "/sbin"])

    # --- start ---------------------------------------------------------------------------
    def __enter__(self):
        try:
            self.start()
        except BaseException:
            self.stop()
            raise
        return self

    def __exit__(self, exc_type, *_):
        self.stop()
        if self.owns_folder and exc_type is None:
            shutil.rmtree(self.folder, ignore_errors=True)
        elif self.owns_folder:
            print(f"glint test cluster: configuration and logs kept in {self.folder}", file=sys.stderr)
        return False

    def start(self):
        missing = missing_programs()
        if missing:
            raise ClusterError(f"not installed: {', '.join(missing)} (Debian: {PACKAGES})")
        for sub in ("logs", "state", "spool", "run", "db"):
            (self.folder / sub).mkdir(exist_ok=True)
        self.munge_socket = self.folder / "run" / "munge.socket"
        self.ports = dict(zip(("mariadb", "slurmdbd", "slurmctld", "slurmd"), _free_ports(4)))
        self._start_munged()
        self._start_mariadb()
        self._start_slurmdbd()
        self._register_account()
        self._write_slurm_conf()
        self._spawn("slurmctld", [_program("slurmctld"), "-D", "-f", str(self.conf)])
        self._spawn("slurmd", [_program("slurmd"), "-D", "-f", str(self.conf)])
        self._wait("the node to be idle", lambda: self.node_state() == "idle", 60)

    def _spawn(self, name, argv):
        log = (self.logs / f"{name}.out").open("ab")
        self.processes[name] = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=log,
                                                stderr=subprocess.STDOUT, env=self.env,
                                                preexec_fn=_die_with_parent)
        log.close()

    def _wait(self, what, ready, seconds):
        deadline = time.monotonic() + seconds
        while time.monotonic() < deadline:
            for name, process in self.processes.items():
                if process.poll() is not None:
                    raise ClusterError(f"{name} exited ({process.returncode}) while waiting for {what}; "
                                       f"see {self.logs}/{name}.log and {name}.out")
            try:
                if ready():
                    return
            except (OSError, subprocess.SubprocessError):
                pass
            time.sleep(0.2)
        raise ClusterError(f"timed out after {seconds} s waiting for {what}; logs in {self.logs}")

    def _port_open(self, port):
        with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
            s.settimeout(0.5)
            return s.connect_ex(("127.0.0.1", port)) == 0

    def _start_munged(self):
        key = self.folder / "munge.key"
        key.write_bytes(secrets.token_bytes(1024))
        key.chmod(0o400)
        # --force: munged wants its socket's folder open to every user, whose programs would ask
        # it for credentials; this folder is 0700 (it holds the key), and only this cluster's
        # daemons and the user who started it talk to this munged.
        self._spawn("munged", [_program("munged"), "--foreground", "--force", f"--socket={self.munge_socket}",
                               f"--key-file={key}", f"--pid-file={self.folder}/run/munged.pid",
                               f"--log-file={self.logs}/munged.log", f"--seed-file={self.folder}/run/munged.seed"])
        self._wait("munged's socket", self.munge_socket.exists, 20)

    def _start_mariadb(self):
        # The system tables only (slurmdbd keeps stored procedures in mysql.proc), without users,
        # help or the sys schema, which take mariadb-install-db longer; then no grant tables:
        # any client gets in. MariaDB listens on 127.0.0.1 only and holds nothing but this
        # cluster's accounting, gone with the folder.
        common = ["--no-defaults", f"--datadir={self.folder}/db", "--skip-log-bin",
                  "--innodb-buffer-pool-size=16M", "--innodb-log-file-size=8M"]
        if os.getuid() == 0:
            common.append("--user=root")  # mariadbd refuses root unless told
        tables = pathlib.Path("/usr/share/mysql/mysql_system_tables.sql")
        if not tables.is_file():
            raise ClusterError(f"{tables}: not found (Debian: mariadb-server-core)")
        sql = "create database if not exists mysql;\nuse mysql;\n" + tables.read_text()
        with (self.logs / "mariadb-bootstrap.log").open("wb") as log:
            done = subprocess.run([_program("mariadbd"), *common, "--bootstrap", "--log-warnings=0"],
                                  input=sql.encode(), stdout=log, stderr=subprocess.STDOUT, timeout=120)
        if done.returncode != 0:
            raise ClusterError(f"mariadbd --bootstrap: exit {done.returncode}; see {self.logs}/mariadb-bootstrap.log")
        argv = [_program("mariadbd"), *common,
                f"--socket={self.folder}/run/mariadb.socket", f"--port={self.ports['mariadb']}",
                "--bind-address=127.0.0.1", f"--pid-file={self.folder}/run/mariadbd.pid",
                f"--log-error={self.logs}/mariadbd.log", "--skip-grant-tables"]
        self._spawn("mariadbd", argv)
        self._wait("MariaDB", lambda: self._port_open(self.ports["mariadb"]), 60)

    def _start_slurmdbd(self):
        dbd_conf = self.folder / "slurmdbd.conf"
        dbd_conf.write_text(f"""# slurmdbd of the glint test cluster ({self.folder})
AuthType=auth/munge
AuthInfo=socket={self.munge_socket}
DbdAddr=127.0.0.1
DbdHost=localhost
DbdPort={self.ports['slurmdbd']}
SlurmUser={self.user}
PidFile={self.folder}/run/slurmdbd.pid
LogFile={self.logs}/slurmdbd.log
StorageType=accounting_storage/mysql
StorageHost=127.0.0.1
StoragePort={self.ports['mariadb']}
StorageUser={self.user}
StorageLoc=slurm_acct_db
""")
        dbd_conf.chmod(0o600)  # slurmdbd refuses a configuration others can read
        # slurmdbd has no option for its file: it reads slurmdbd.conf beside SLURM_CONF.
        self._write_slurm_conf()
        self._spawn("slurmdbd", [_program("slurmdbd"), "-D"])
        self._wait("slurmdbd", lambda: self._port_open(self.ports["slurmdbd"]), 60)

    def _register_account(self):
        sacctmgr = _program("sacctmgr")
        for args in (["add", "cluster", "glint"],
                     ["add", "account", self.account, "Description=glint test", "Organization=glint"],
                     ["add", "user", self.user, f"Account={self.account}"]):
            done = subprocess.run([sacctmgr, "-i", *args], env=self.env, capture_output=True, text=True,
                                  timeout=60)
            if done.returncode != 0:
                raise ClusterError(f"sacctmgr {' '.join(args)}: {done.stdout}{done.stderr}".strip())

    def _write_slurm_conf(self):
        node = subprocess.run([_program("slurmd"), "-C"], capture_output=True, text=True, check=True).stdout
        hardware = re.search(r"^NodeName=\S+ (.*?)$", node, re.M)
        if not hardware:
            raise ClusterError(f"slurmd -C printed no node line: {node!r}")
        # note: `slurmd -C` gives this machine's sockets, cores, threads and RealMemory; a node
        # configured with more than it has would be drained as invalid.
        self.hardware = dict(kv.split("=", 1) for kv in hardware.group(1).split())
        self.conf.write_text(f"""# slurm.conf of the glint test cluster ({self.folder})
ClusterName=glint
SlurmctldHost={self.node}(127.0.0.1)
SlurmctldPort={self.ports['slurmctld']}
SlurmdPort={self.ports['slurmd']}
SlurmUser={self.user}
SlurmdUser={self.user}
AuthType=auth/munge
AuthInfo=socket={self.munge_socket}
CredType=cred/munge
StateSaveLocation={self.folder}/state
SlurmdSpoolDir={self.folder}/spool
SlurmctldPidFile={self.folder}/run/slurmctld.pid
SlurmdPidFile={self.folder}/run/slurmd.pid
SlurmctldLogFile={self.logs}/slurmctld.log
SlurmdLogFile={self.logs}/slurmd.log
# no cgroups (a container may not offer them): processes are tracked by their parentage
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/linux
# accounting through slurmdbd; AccountingStoragePass names the munge socket for it
AccountingStorageType=accounting_storage/slurmdbd
AccountingStorageHost=127.0.0.1
AccountingStoragePort={self.ports['slurmdbd']}
AccountingStoragePass={self.munge_socket}
AccountingStorageEnforce=associations
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core_Memory
SchedulerType=sched/backfill
MpiDefault=none
ReturnToService=2
# a cancelled job's processes get SIGTERM, then SIGKILL this many seconds later (sites: 30)
KillWait=10
MinJobAge=300
InactiveLimit=0
SlurmctldTimeout=30
SlurmdTimeout=60
NodeName={self.node} NodeAddr=127.0.0.1 {' '.join(f'{k}={v}' for k, v in self.hardware.items())} State=UNKNOWN
PartitionName={self.partition} Nodes={self.node} Default=YES MaxTime=INFINITE State=UP
""")

    # --- use -----------------------------------------------------------------------------
    def run(self, *argv, check=True, timeout=60):
        """A Slurm command (sacct, scontrol, …) against this cluster; its stdout."""
        done = subprocess.run(list(argv), env=self.env, capture_output=True, text=True, timeout=timeout)
        if check and done.returncode != 0:
            raise ClusterError(f"{' '.join(argv)}: exit {done.returncode}: {done.stderr.strip()}")
        return done.stdout

    def node_state(self):
        """The node's state as sinfo prints it (idle, mixed, allocated, drained, draining, …)."""
        return self.run("sinfo", "-h", "-N", "-o", "%T", check=False).strip().rstrip("*~#!%$@^-")

    def jobs(self, fields=("JobID", "JobName", "State", "Partition", "Account", "AllocCPUS", "ReqMem",
                           "Timelimit", "Start", "End", "ExitCode")):
        """Every job of this cluster from accounting (allocations only, not steps), oldest first,
        as dicts of the fields asked."""
        out = self.run("sacct", "-X", "-a", "-P", "-n", "-S", "2000-01-01", "--format=" + ",".join(fields))
        return [dict(zip(fields, line.split("|"))) for line in out.splitlines() if line]

    def queued(self):
        """Job ids slurmctld still holds as pending, running or completing."""
        return self.run("squeue", "-h", "-o", "%i", check=False).split()

    # --- stop ----------------------------------------------------------------------------
    def stop(self):
        """Cancels every job, then ends the daemons in reverse order of starting (SIGTERM, then
        SIGKILL after 20 s). Safe to call twice and after a failed start."""
        if self.processes.get("slurmctld") and self.processes["slurmctld"].poll() is None:
            try:
                jobs = self.queued()
                if jobs:
                    self.run("scancel", *jobs, check=False)
                    deadline = time.monotonic() + 40
                    while self.queued() and time.monotonic() < deadline:
                        time.sleep(0.5)
            except (OSError, subprocess.SubprocessError):
                pass
        for name in reversed(list(self.processes)):
            process = self.processes[name]
            if process.poll() is None:
                process.terminate()
                try:
                    process.wait(timeout=20)
                except subprocess.TimeoutExpired:
                    process.kill()
                    process.wait(timeout=10)

    def leftovers(self):
        """Processes of this cluster still alive: its daemons, and any process (a job's
        slurmstepd, snakemake or glint) whose environment names this cluster's SLURM_CONF."""
        alive = [f"{name} (pid {p.pid})" for name, p in self.processes.items() if p.poll() is None]
        seen = {p.pid for p in self.processes.values()} | {os.getpid()}
        marker = f"SLURM_CONF={self.conf}".encode()
        for proc in pathlib.Path("/proc").iterdir():
            if not proc.name.isdigit() or int(proc.name) in seen:
                continue
            try:
                if marker in (proc / "environ").read_bytes().split(b"\0"):
                    cmd = (proc / "cmdline").read_bytes().replace(b"\0", b" ").decode(errors="replace")
                    alive.append(f"{cmd.strip()} (pid {proc.name})")
            except OSError:
                continue  # gone meanwhile, or not ours to read
        return alive


def main(argv):
    import argparse

    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--partition", default="cohort", help="the partition's name (default: cohort)")
    parser.add_argument("--account", default="cohort", help="the account jobs may use (default: cohort)")
    parser.add_argument("command", nargs="*", help="what to run (default: $SHELL)")
    args = parser.parse_args(argv)
    command = args.command or [os.environ.get("SHELL", "/bin/bash")]
    with Cluster(args.partition, args.account) as cluster:
        print(f"glint test cluster: node {cluster.node} "
              f"({cluster.hardware.get('CPUs')} CPUs, {cluster.hardware.get('RealMemory')} MB), partition "
              f"{cluster.partition}, account {cluster.account}; SLURM_CONF={cluster.conf}", file=sys.stderr)
        env = dict(cluster.env, SBATCH_PARTITION=cluster.partition, SBATCH_ACCOUNT=cluster.account)
        code = subprocess.call(command, env=env)
        print("glint test cluster: stopping", file=sys.stderr)
    return code


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
