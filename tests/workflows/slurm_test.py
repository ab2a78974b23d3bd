"""The cohort workflow on a real Slurm: a cluster of one node started on this machine
(slurm_cluster.py: munged, MariaDB, slurmdbd, slurmctld, slurmd), the workflow run through the
shipped profile (workflows/cohort/profiles/slurm), its cohort table held against a local
`snakemake -j2` run of the same manifest, byte for byte.

    python3 tests/workflows/slurm_test.py            the cohort through the profile (workflow.slurm)
    python3 tests/workflows/slurm_test.py --faults   a job cancelled mid-run, a node drained and
                                                     resumed, each finished by a rerun (workflow.slurm_faults)

Exits 77 (CTest's skip) naming what is missing when Slurm, munge or MariaDB are not installed
(tools/test installs them). GLINT_EXE and GLINT_SOURCE_DIR come from CTest.
"""
import csv
import os
import pathlib
import signal
import subprocess
import sys
import tempfile
import time

import pytest

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import phantom_cohort  # noqa: E402
import slurm_cluster  # noqa: E402

SOURCE = pathlib.Path(os.environ.get("GLINT_SOURCE_DIR", HERE.parent.parent))
GLINT = os.environ.get("GLINT_EXE", "")
WORKFLOW = SOURCE / "workflows" / "cohort"
PROFILE = WORKFLOW / "profiles" / "slurm"
# One core per pair, so the two-core node runs two pairs at once, as -j2 does locally; a small
# memory request fits any machine the tests run on.
THREADS, MEM_MB, MINUTES = 1, 600, 5
RESOURCES = [f"threads_per_pair={THREADS}", f"mem_mb_per_pair={MEM_MB}", f"minutes_per_pair={MINUTES}"]


def snakemake(work, manifest, *extra, slurm=None, settings=phantom_cohort.SMALL):
    """The cohort workflow's command line: local with -j2, or through the profile on `slurm`."""
    command = ["snakemake", "-s", str(WORKFLOW / "Snakefile"), "-d", str(work),
               *(["--profile", str(PROFILE)] if slurm else ["-j2", "--keep-going"]),
               "--config", f"manifest={manifest}", f"glint={GLINT}", *settings, *RESOURCES, *extra]
    env = dict(slurm.env, SBATCH_PARTITION=slurm.partition, SBATCH_ACCOUNT=slurm.account) if slurm else None
    return command, env


def run(command, env=None, timeout=600):
    return subprocess.run(command, env=env, capture_output=True, text=True, timeout=timeout)


def jobs_by_pair(cluster, since=0):
    """{pair id: [sacct rows of its jobs, oldest first]} of the sweep jobs after job id `since`."""
    out = {}
    for job in cluster.jobs():
        if int(job["JobID"]) > since:
            assert job["JobName"].startswith("glint-sweep-"), job  # only pairs are Slurm jobs
            subject, pair = job["JobName"][len("glint-sweep-"):].split("-", 1)
            out.setdefault(f"{subject}/{pair}", []).append(job)
    return out


def last_job_id(cluster):
    return max((int(j["JobID"]) for j in cluster.jobs()), default=0)


def pair_files(work):
    """{pair folder: (inode, mtime ns) of its report.json}: a pair swept again changes both."""
    return {p.parent: (p.stat().st_ino, p.stat().st_mtime_ns) for p in (work / "pairs").glob("*/*/report.json")}


class Head:
    """snakemake running in the background (the submitting host's process), its output in a
    file (a pipe nobody reads could fill and stop it)."""

    def __init__(self, command, env):
        self.output = tempfile.TemporaryFile("w+")
        self.process = subprocess.Popen(command, env=env, stdout=self.output, stderr=subprocess.STDOUT, text=True)

    def text(self):
        self.output.seek(0)
        return self.output.read()

    def finish(self, seconds):
        """Waits for snakemake to end (interrupting it, then killing it, if it does not);
        its exit code."""
        try:
            return self.process.wait(timeout=seconds)
        except subprocess.TimeoutExpired:
            self.process.send_signal(signal.SIGINT)
            try:
                self.process.wait(timeout=60)
            except subprocess.TimeoutExpired:
                self.process.kill()
            pytest.fail(f"snakemake still running after {seconds} s:\n{self.text()[-5000:]}")


def wait_for(what, ready, seconds, head=None):
    deadline = time.monotonic() + seconds
    while time.monotonic() < deadline:
        value = ready()
        if value:
            return value
        if head is not None and head.process.poll() is not None:
            pytest.fail(f"snakemake ended ({head.process.returncode}) before {what}:\n{head.text()[-5000:]}")
        time.sleep(0.3)
    pytest.fail(f"timed out after {seconds} s waiting for {what}")


@pytest.fixture(scope="module")
def cluster(tmp_path_factory):
    assert GLINT, "GLINT_EXE must be set (ctest sets it)"
    # A CTest timeout or Ctrl-C ends pytest through SIGTERM / SIGINT: the cluster still stops.
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(143))
    # In pytest's temporary folder: kept for a look after a failure, pruned by pytest later.
    with slurm_cluster.Cluster(folder=tmp_path_factory.mktemp("cluster")) as c:
        yield c
    assert c.leftovers() == [], "processes of the test cluster still running"


# --- the cohort through the profile (workflow.slurm) -----------------------------------------

@pytest.fixture(scope="module")
def cohort(tmp_path_factory, cluster):
    data = tmp_path_factory.mktemp("scans")
    manifest = phantom_cohort.write_cohort(data, GLINT, 3, refused=["BAD"])
    local = tmp_path_factory.mktemp("local")
    command, _ = snakemake(local, manifest)
    done = run(command)
    assert done.returncode == 0, (done.stdout, done.stderr)
    slurm = tmp_path_factory.mktemp("slurm")
    command, env = snakemake(slurm, manifest, slurm=cluster)
    started = time.monotonic()
    done = run(command, env)
    seconds = time.monotonic() - started
    assert done.returncode == 0, (done.stdout, done.stderr)
    print(f"cohort of {len(cluster.jobs())} pairs through the Slurm profile: {seconds:.1f} s")
    return {"local": local, "slurm": slurm, "manifest": manifest, "done": done, "command": command, "env": env}


def test_cohort_table_equals_the_local_run_byte_for_byte(cohort):
    for name in ("cohort.csv", "cohort.json"):
        assert (cohort["slurm"] / name).read_bytes() == (cohort["local"] / name).read_bytes(), name


def test_one_slurm_job_per_pair_with_the_resources_asked(cohort, cluster):
    pairs = jobs_by_pair(cluster)
    assert sorted(pairs) == ["BAD/0_to_1", "S000/0_to_1", "S001/0_to_1", "S002/0_to_1"]
    for pair, jobs in pairs.items():
        assert len(jobs) == 1, (pair, jobs)
        job = jobs[0]
        assert job["State"] == "COMPLETED" and job["ExitCode"] == "0:0", job
        assert (job["Partition"], job["Account"]) == (cluster.partition, cluster.account)
        assert int(job["AllocCPUS"]) == THREADS
        assert job["ReqMem"] == f"{MEM_MB}M"
        assert job["Timelimit"] == f"00:{MINUTES:02d}:00"


def test_logs_per_job_beside_the_pair_logs(cohort, cluster):
    work = cohort["slurm"]
    for pair, (job,) in jobs_by_pair(cluster).items():
        subject, name = pair.split("/")
        slurm_log = work / "logs" / "slurm" / f"glint-sweep-{subject}-{name}-{job['JobID']}.log"
        assert slurm_log.is_file(), slurm_log
        assert "Finished job" in slurm_log.read_text(), slurm_log  # the node's snakemake, to the end
        assert (work / "logs" / subject / f"{name}.log").is_file()


def test_a_refused_pair_has_glints_reason_and_the_others_complete(cohort):
    with (cohort["slurm"] / "cohort.csv").open(newline="") as f:
        rows = list(csv.DictReader(f))
    (bad,) = [r for r in rows if r["subject"] == "BAD"]
    log = (cohort["slurm"] / "logs" / "BAD" / "0_to_1.log").read_text()
    assert bad["error"] == log.strip().splitlines()[-1]  # glint's one line, as it printed it
    assert bad["error"].startswith("glint: error: mesh") and "truncated.ply" in bad["error"]
    assert bad["regions"] == bad["coverage"] == bad["report"] == ""  # no numbers
    done = [r for r in rows if r["subject"] != "BAD"]
    assert len(done) == 3 and all(r["error"] == "" and r["report"].endswith("/report.json") for r in done)
    assert "glint refused the input of 1 of 4 pair(s)" in cohort["done"].stderr


def test_a_second_run_submits_nothing(cohort, cluster):
    before = last_job_id(cluster)
    again = run(cohort["command"], cohort["env"])
    assert again.returncode == 0 and "Nothing to be done" in again.stdout + again.stderr, again.stderr
    assert last_job_id(cluster) == before


def test_the_cluster_stops_and_leaves_no_process(cohort, cluster):
    cluster.stop()
    assert cluster.leftovers() == []


# --- faults (workflow.slurm_faults) ----------------------------------------------------------

# Larger sweeps than SMALL (seconds of glint per pair), so a job is caught while glint writes.
FAULT_SETTINGS = ["size=128", "azimuth_step=30", "elevations=[-60,-30,0,30,60]"]
FAULT_SUBJECTS = 6


@pytest.fixture(scope="module")
def fault_cohort(tmp_path_factory, cluster):
    data = tmp_path_factory.mktemp("fault-scans")
    manifest = phantom_cohort.write_cohort(data, GLINT, FAULT_SUBJECTS)
    local = tmp_path_factory.mktemp("fault-local")
    command, _ = snakemake(local, manifest, settings=FAULT_SETTINGS)
    done = run(command)
    assert done.returncode == 0, (done.stdout, done.stderr)
    return manifest, local


def glint_under_way(cluster, work, since=0, pair=None):
    """A running sweep job after job id `since` (of `pair`, if given) whose glint is writing its
    staging folder (pairs/<subject>/<pair>.partial-<pid>): (job id, pair), or None."""
    for staging in (work / "pairs").glob("*/*.partial-*"):
        name = f"{staging.parent.name}/{staging.name.split('.partial-')[0]}"
        if pair not in (None, name):
            continue
        jobs = cluster.run("squeue", "-h", "-t", "R", "-o", "%i", "-n", "glint-sweep-" + name.replace("/", "-"),
                           check=False).split()
        if jobs and int(jobs[0]) > since:
            return jobs[0], name
    return None


def test_fault_cancelled_job_is_retried_then_finished_by_a_rerun(fault_cohort, cluster, tmp_path):
    manifest, local = fault_cohort
    start = last_job_id(cluster)
    command, env = snakemake(tmp_path, manifest, slurm=cluster, settings=FAULT_SETTINGS)
    head = Head(command, env)
    # scancel a job while its glint writes: the profile's restart-times runs it once more, with
    # twice the memory and time; cancel that attempt too, and the pair is left to a rerun.
    first, pair = wait_for("glint under way", lambda: glint_under_way(cluster, tmp_path, start), 120, head)
    cluster.run("scancel", first)
    second, _ = wait_for(f"the retry of {pair}", lambda: glint_under_way(cluster, tmp_path, int(first), pair),
                         120, head)
    cluster.run("scancel", second)
    assert head.finish(300) != 0, "a pair was cancelled twice: the run must fail"
    # keep-going: every other pair finished; the cancelled one left nothing a table could count.
    attempts = jobs_by_pair(cluster, start)[pair]
    assert [j["State"].split()[0] for j in attempts] == ["CANCELLED", "CANCELLED"], attempts
    assert [j["ReqMem"] for j in attempts] == [f"{MEM_MB}M", f"{2 * MEM_MB}M"]
    assert not (tmp_path / "pairs" / pair).exists()
    # A glint that ends on scancel's SIGTERM removes its staging folder; one still inside a view
    # when its 3 s watchdog fires (a loaded node) leaves it, never under the pair's own name.
    leftovers = list((tmp_path / "pairs").glob("*/*.partial-*"))
    assert all(p.name.startswith(pair.split("/")[1] + ".partial-") for p in leftovers), leftovers
    assert not (tmp_path / "cohort.csv").exists()
    swept = pair_files(tmp_path)
    assert len(swept) == FAULT_SUBJECTS - 1, head.text()
    # The rerun sweeps the cancelled pair only, and the table is the local run's.
    rerun_from = last_job_id(cluster)
    again = run(command, env)
    assert again.returncode == 0, (again.stdout, again.stderr)
    assert sorted(jobs_by_pair(cluster, rerun_from)) == [pair]
    assert not list((tmp_path / "pairs").glob("*/*.partial-*")), "the rerun left a staging folder"
    assert {k: v for k, v in pair_files(tmp_path).items() if k in swept} == swept
    assert (tmp_path / "cohort.csv").read_bytes() == (local / "cohort.csv").read_bytes()


def test_fault_drained_node_then_resumed_is_finished_by_a_rerun(fault_cohort, cluster, tmp_path):
    manifest, local = fault_cohort
    start = last_job_id(cluster)
    command, env = snakemake(tmp_path, manifest, slurm=cluster, settings=FAULT_SETTINGS)
    head = Head(command, env)
    wait_for("glint under way", lambda: glint_under_way(cluster, tmp_path, start), 120, head)
    cluster.run("scontrol", "update", f"nodename={cluster.node}", "state=drain", "reason=glint test")
    # Running jobs finish on a draining node; the others wait, and snakemake waits with them.
    wait_for("the node drained", lambda: cluster.node_state() == "drained", 120, head)
    # note: waited for, not read at once: snakemake submits its next job when it sees the last
    # one end, and the node may drain in between (CI once found every submitted job finished).
    pending = wait_for("a job waiting on the drained node",
                       lambda: [j for j in cluster.jobs() if int(j["JobID"]) > start and j["State"] == "PENDING"],
                       60, head)
    time.sleep(3)
    assert head.process.poll() is None, "snakemake gave up on jobs waiting for a drained node"
    # The user stops waiting (Ctrl-C): snakemake cancels what it submitted (cluster-cancel).
    head.process.send_signal(signal.SIGINT)
    head.finish(120)
    assert wait_for("the queue emptied", lambda: not cluster.queued() or None, 60)
    assert {j["State"].split()[0] for j in cluster.jobs() if j["JobID"] in {p["JobID"] for p in pending}} == \
        {"CANCELLED"}
    swept = pair_files(tmp_path)
    assert 0 < len(swept) < FAULT_SUBJECTS, head.text()
    cluster.run("scontrol", "update", f"nodename={cluster.node}", "state=resume")
    wait_for("the node back", lambda: cluster.node_state() == "idle", 60)
    rerun_from = last_job_id(cluster)
    again = run(command, env)
    assert again.returncode == 0, (again.stdout, again.stderr)
    redone = sorted(jobs_by_pair(cluster, rerun_from))
    assert len(redone) == FAULT_SUBJECTS - len(swept)
    assert not {str(p.relative_to(tmp_path / "pairs")) for p in swept} & set(redone)
    assert {k: v for k, v in pair_files(tmp_path).items() if k in swept} == swept
    assert (tmp_path / "cohort.csv").read_bytes() == (local / "cohort.csv").read_bytes()


if __name__ == "__main__":
    missing = slurm_cluster.missing_programs()
    if missing:
        print(f"skipped: not installed: {', '.join(missing)} (Debian: {slurm_cluster.PACKAGES}; tools/test "
              "installs them)")
        sys.exit(77)
    faults = "--faults" in sys.argv[1:]
    args = [a for a in sys.argv[1:] if a != "--faults"]
    sys.exit(pytest.main([__file__, "-q", "-s", "-p", "no:cacheprovider", "-k",
                          "fault" if faults else "not fault", *args]))
