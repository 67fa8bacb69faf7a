"""Run a platoonsim sweep (or calibration) on a real HyperQueue scheduler (issue 21): start a
HyperQueue server and one worker on this machine (the `hyperqueue` package from PyPI embeds
both), submit one job of N shard tasks, each `platoonsim sweep SPEC --shards N` reading its index
from HQ_TASK_ID (0..N-1), plus a collect task that depends on all of them
(`platoonsim sweep SPEC --collect`), wait, and report.

Usage: python3 submit.py PLATOONSIM SPEC OUT SHARDS WORKDIR [COMMAND ARGS...]
With COMMAND ARGS (e.g. `calibrate SCENARIO --field F --params P`; SPEC is then unused), the
shard tasks run `platoonsim COMMAND ARGS --shards N` and the last task `platoonsim COMMAND ARGS
--no-shard`, which reuses the shards' run files and writes the outputs. The worker has 2 cores
and every task asks for 1: a calibration's shards wait for each other, so N must be at most 2.
Exit 0 if every task finished; otherwise the failed tasks' errors are printed and it exits 1.
"""

import sys
import time
from pathlib import Path

from hyperqueue import Job
from hyperqueue.cluster import LocalCluster, WorkerConfig


def main():
    exe, spec, out, shards, workdir = sys.argv[1:6]
    command, collect = ["sweep", spec], ["--collect"]
    if len(sys.argv) > 6:
        command, collect = sys.argv[6:], ["--no-shard"]
    shards = int(shards)
    workdir = Path(workdir)
    workdir.mkdir(parents=True, exist_ok=True)
    started = time.monotonic()
    with LocalCluster(server_dir=str(workdir / "server")) as cluster:
        cluster.start_worker(WorkerConfig(cores=2))
        client = cluster.client()
        job = Job(default_workdir=str(workdir))
        array = [
            job.program(
                [exe, "-q", *command, "--out", out, "--shards", str(shards), "--jobs", "1"],
                stdout=str(workdir / f"shard{i}.out"),
                stderr=str(workdir / f"shard{i}.err"),
            )
            for i in range(shards)
        ]
        job.program(
            [exe, "-q", *command, "--out", out, *collect],
            deps=array,
            stdout=str(workdir / "collect.out"),
            stderr=str(workdir / "collect.err"),
        )
        submitted = client.submit(job)
        ok = client.wait_for_jobs([submitted], raise_on_error=False)
        if not ok:
            for task, failure in client.get_failed_tasks(submitted).items():
                print(f"task {task} failed: {failure.error}", file=sys.stderr)
            return 1
    print(f"hyperqueue: {shards} shard tasks and the collect task in {time.monotonic() - started:.1f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
