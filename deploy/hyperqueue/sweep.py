"""A sweep on HyperQueue from Python (`pip install hyperqueue`): N shard tasks and a collect
task that depends on them, on an existing server (`hq server start`) or, with --local, on a
server and worker started here (the wheel embeds both; the project's test does this).

    python3 deploy/hyperqueue/sweep.py SPEC.toml OUT_DIR N [--local]
"""

import sys
from pathlib import Path

from hyperqueue import Client, Job
from hyperqueue.cluster import LocalCluster, WorkerConfig


def submit(client, spec, out, n):
    job = Job(default_workdir=str(Path(out).resolve()))
    shards = [
        job.program(["platoonsim", "sweep", spec, "--out", out, "--shards", str(n), "--jobs", "1"])
        for _ in range(n)
    ]
    job.program(["platoonsim", "sweep", spec, "--out", out, "--collect"], deps=shards)
    return client.wait_for_jobs([client.submit(job)], raise_on_error=False)


def main():
    spec, out, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
    Path(out).mkdir(parents=True, exist_ok=True)
    if "--local" in sys.argv[4:]:
        with LocalCluster() as cluster:
            cluster.start_worker(WorkerConfig())
            ok = submit(cluster.client(), spec, out, n)
    else:
        ok = submit(Client(), spec, out, n)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
