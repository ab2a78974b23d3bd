#!/usr/bin/env python3
"""Snakemake's --cluster-status for Slurm: prints `running`, `success` or `failed` for the job id
it is given (what `sbatch --parsable` printed).

Accounting (sacct) is asked first: slurmctld forgets a finished job after MinJobAge (300 s by
default). slurmctld (scontrol) answers when accounting has no record of the job yet (it is
written a moment after submission) or the cluster keeps none. A job slurmctld no longer knows
has ended: without accounting its outcome is lost, and `success` hands the verdict to Snakemake,
which then fails the job unless its outputs are there. When neither can be reached the job is
reported running, and Snakemake asks again.
"""
import subprocess
import sys

# Slurm's job states (squeue(1), "JOB STATE CODES"): still under way, or finished well.
UNDER_WAY = {"PENDING", "CONFIGURING", "RUNNING", "COMPLETING", "SUSPENDED", "STOPPED", "RESIZING",
             "REQUEUED", "REQUEUE_FED", "REQUEUE_HOLD", "SIGNALING", "STAGE_OUT", "RESV_DEL_HOLD"}
DONE = "COMPLETED"


def verdict(state):
    # sacct writes "CANCELLED by <uid>": the state is the first word.
    word = state.split()[0] if state.split() else ""
    if word == DONE:
        return "success"
    return "running" if word in UNDER_WAY else "failed"


def ask(argv):
    try:
        done = subprocess.run(argv, capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.SubprocessError) as e:
        return None, str(e)
    return (done.stdout, "") if done.returncode == 0 else (None, done.stderr.strip())


def main(job):
    job = job.split(";")[0]  # "id;cluster" on sites with several clusters
    out, sacct_error = ask(["sacct", "-X", "-n", "-P", "--format=State", "-j", job])
    states = (out or "").split()
    if states:
        return verdict(out.strip().splitlines()[0])
    out, scontrol_error = ask(["scontrol", "show", "job", "-o", job])
    if out is not None:
        for field in out.split():
            if field.startswith("JobState="):
                return verdict(field.split("=", 1)[1])
    if "Invalid job id" in scontrol_error:
        if sacct_error:
            return "success"
        print(f"status.py: Slurm job {job} is unknown to accounting and to slurmctld", file=sys.stderr)
        return "failed"
    print(f"status.py: Slurm job {job}: no answer yet (sacct: {sacct_error or 'no record'}; "
          f"scontrol: {scontrol_error or 'no state'})", file=sys.stderr)
    return "running"


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: status.py SLURM_JOB_ID")
    print(main(sys.argv[1]))
