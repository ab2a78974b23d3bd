"""Pairs per minute of the cohort workflow: local `snakemake -j2` against the Slurm profile on a
one-node cluster of this machine (slurm_cluster.py), for cohorts of condyle phantom pairs
(phantom_cohort.py) swept with the workflow's default settings (config.yaml). Not a test: the
figures go into README ("Cohort runs"). Each run starts from an empty results folder; the time
is snakemake's whole run, table and summary included.

    python3 tests/workflows/cohort_throughput.py build/default/tools/glint [PAIRS ...]   (default: 20 100)
    python3 tests/workflows/cohort_throughput.py build/default/tools/glint pictures [PAIRS ...] [--rounds N]
        local `-j2` only, the workflow's default against `pictures=false` (--no-pictures), alternating
        N rounds (default 2) on the same scans; medians
"""
import pathlib
import subprocess
import sys
import tempfile
import time

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import phantom_cohort  # noqa: E402
import slurm_cluster  # noqa: E402

WORKFLOW = HERE.parent.parent / "workflows" / "cohort"


def timed(command, env=None):
    started = time.monotonic()
    done = subprocess.run(command, env=env, capture_output=True, text=True)
    seconds = time.monotonic() - started
    if done.returncode != 0:
        sys.exit(f"{' '.join(command)}: exit {done.returncode}\n{done.stderr[-3000:]}")
    return seconds


def main(glint, counts):
    glint = str(pathlib.Path(glint).resolve())
    rows = []
    with tempfile.TemporaryDirectory(prefix="glint-throughput-") as tmp, slurm_cluster.Cluster() as cluster:
        tmp = pathlib.Path(tmp)
        env = dict(cluster.env, SBATCH_PARTITION=cluster.partition, SBATCH_ACCOUNT=cluster.account)
        for n in counts:
            manifest = phantom_cohort.write_cohort(tmp / f"scans{n}", glint, n)
            base = ["snakemake", "-s", str(WORKFLOW / "Snakefile"), "--config", f"manifest={manifest}",
                    f"glint={glint}"]
            local = timed([*base, "-d", str(tmp / f"local{n}"), "-j2"])
            first = max((int(j["JobID"]) for j in cluster.jobs()), default=0)
            slurm = timed([*base, "-d", str(tmp / f"slurm{n}"), "--profile", str(WORKFLOW / "profiles" / "slurm")], env)
            jobs = [j for j in cluster.jobs(fields=("JobID", "State", "ElapsedRaw")) if int(j["JobID"]) > first]
            busy = sum(int(j["ElapsedRaw"]) for j in jobs)
            same = (tmp / f"local{n}" / "cohort.csv").read_bytes() == (tmp / f"slurm{n}" / "cohort.csv").read_bytes()
            rows.append((n, local, slurm, len(jobs), busy, same))
            print(f"{n} pairs: local -j2 {local:.0f} s ({60 * n / local:.1f} pairs/min), Slurm {slurm:.0f} s "
                  f"({60 * n / slurm:.1f} pairs/min), {len(jobs)} jobs, {busy / max(len(jobs), 1):.1f} s each "
                  f"in Slurm, tables {'equal' if same else 'DIFFER'}", flush=True)
    print(f"\nnode: {cluster.hardware.get('CPUs')} CPUs, {cluster.hardware.get('RealMemory')} MB")
    return 0 if all(r[5] for r in rows) else 1


def pictures_ab(glint, counts, rounds):
    """Local runs with and without pictures, alternating, on the same scans."""
    import statistics
    glint = str(pathlib.Path(glint).resolve())
    with tempfile.TemporaryDirectory(prefix="glint-throughput-") as tmp:
        tmp = pathlib.Path(tmp)
        for n in counts:
            manifest = phantom_cohort.write_cohort(tmp / f"scans{n}", glint, n)
            base = ["snakemake", "-s", str(WORKFLOW / "Snakefile"), "--config", f"manifest={manifest}",
                    f"glint={glint}"]
            times = {"pictures": [], "no pictures": []}
            for r in range(rounds):
                order = [("pictures", []), ("no pictures", ["pictures=false"])]
                for name, extra in order if r % 2 == 0 else order[::-1]:
                    times[name].append(timed([*base, *extra, "-d", str(tmp / f"{name}{n}_{r}".replace(" ", "_")),
                                              "-j2"]))
            line = ", ".join(f"{k} {statistics.median(v):.0f} s ({60 * n / statistics.median(v):.1f} pairs/min)"
                             for k, v in times.items())
            print(f"{n} pairs, local -j2, medians of {rounds}: {line}", flush=True)
    return 0


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    if len(sys.argv) > 2 and sys.argv[2] == "pictures":
        args = sys.argv[3:]
        rounds = 2
        if "--rounds" in args:
            at = args.index("--rounds")
            rounds = int(args[at + 1])
            del args[at:at + 2]
        sys.exit(pictures_ab(sys.argv[1], [int(a) for a in args] or [20], rounds))
    sys.exit(main(sys.argv[1], [int(a) for a in sys.argv[2:]] or [20, 100]))
