"""The readme study's runs: the quick start's reference run, the Open MPI measurements behind
docs/clusters.md (throughput, efficiency) and the work queue's fig3 runs (issue 31), and the steps
after them (the README's figure, the quick start's digests, the schedule predictions)."""

from reports.core.study import Run, Step

QUICKSTART = "results/quickstart"
CLUSTER = "results/cluster"
MPI = "mpirun --allow-run-as-root"
PAIRS = ["a", "b"]
SCHEDULE_DIGEST = f"{CLUSTER}/schedule-predictions.csv"  # `dabench schedule` on the committed runs

RUNS = [Run(QUICKSTART, "./build/dabench run experiments/quickstart.ini --out results/quickstart --force",
            "the quick start's reference run")]
RUNS += [
    Run(f"{CLUSTER}/throughput-threads2",
        "./build/dabench run experiments/readme/bp-throughput.ini --threads 2 --force --out results/cluster/throughput-threads2"),
    Run(f"{CLUSTER}/throughput-np2",
        f"{MPI} -np 2 ./build/dabench run experiments/readme/bp-throughput.ini --threads 1 --force "
        "--out results/cluster/throughput-np2"),
    Run(f"{CLUSTER}/throughput-np3",
        f"{MPI} --oversubscribe -np 3 ./build/dabench run experiments/readme/bp-throughput.ini --threads 1 --force "
        "--out results/cluster/throughput-np3"),
]
for _pair in PAIRS:
    RUNS += [
        Run(f"{CLUSTER}/efficiency-threads2-{_pair}",
            "./build/dabench run experiments/readme/cluster-efficiency.ini --threads 2 --force "
            f"--out results/cluster/efficiency-threads2-{_pair}"),
        Run(f"{CLUSTER}/efficiency-np2-{_pair}",
            f"{MPI} -np 2 ./build/dabench run experiments/readme/cluster-efficiency.ini --threads 1 --force "
            f"--out results/cluster/efficiency-np2-{_pair}"),
    ]
SCHEDULE_RUNS = {  # fig3 at 8 trials, as issue 31 measures the work queue: 1 and 2 threads, and 2 with --costs-from
    "threads1": "--threads 1",
    "threads2": "--threads 2",
    "threads2-costs-from": "--threads 2",
}
for _name, _threads in SCHEDULE_RUNS.items():
    RUNS.append(Run(f"{CLUSTER}/schedule-fig3-8-{_name}",
                    f"./build/dabench run experiments/multiscan/fig3.ini --trials 8 {_threads} --force "
                    f"--out results/cluster/schedule-fig3-8-{_name}"
                    + (f" --costs-from {CLUSTER}/schedule-fig3-8-threads1" if _name.endswith("costs-from") else "")))
STEPS = [Step("/usr/bin/python3 -m reports.digest readme", f"{SCHEDULE_DIGEST}: the predictions of docs/clusters.md"),
         Step("/usr/bin/python3 -m plots.fig6 results/quickstart/summary.csv --out results/quickstart/fig6.png "
              "--title \"2x3 grid, Pd = 0.6, lambda_fa = 0.01, r = 1\"", "the README's figure"),
         Step("/usr/bin/python3 -m reports.quickstart_check --digests results/quickstart",
              "digests of the first 100, 200 and 1000 trials per spacing, which a shorter quick start is compared with")]
