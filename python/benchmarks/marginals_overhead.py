#!/usr/bin/python3
"""Per-call overhead of dabench.marginals() over the algorithm's own time, on problems of the BP
paper's 2×3 baseline (Fig. 6 top left: Pd 0.6, λ_fa 0.01, r 1) at one spacing.

For each of --problems problems drawn as a run draws them, it times (a) the kernel alone, as
`dabench solve --time` does (dabench.time_solver: the solver's calls repeated on that problem), and
(b) dabench.marginals(psi, algorithm) called from Python in a loop on the same problem, and (c)
marginals_batch over the pool on one thread. The overhead is (b) − (a): checking and reading the
array, the solver lookup, the GIL release, and the new marginals array.

    PYTHONPATH=build/python /usr/bin/python3 python/benchmarks/marginals_overhead.py [--algorithm bp] [--spacing 2]
"""
import argparse
import statistics
import time

import dabench


def per_call_seconds(function, calls):
    best = float("inf")
    for _ in range(5):  # best of 5 rounds: the least disturbed by other processes
        start = time.perf_counter()
        for _ in range(calls):
            function()
        best = min(best, (time.perf_counter() - start) / calls)
    return best


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--algorithm", default="bp")
    parser.add_argument("--spacing", type=float, default=2.0)
    parser.add_argument("--problems", type=int, default=16)
    parser.add_argument("--calls", type=int, default=20000)
    args = parser.parse_args()
    params = dict(rows=2, cols=3, pd=0.6, lambda_fa=0.01, r=1, spacing=args.spacing)
    pool = [dabench.draw("grid", seed=2014, trial=k, point_params=params)["psi"] for k in range(args.problems)]
    kernel, python, overhead = [], [], []
    for psi in pool:
        k = dabench.time_solver(psi, args.algorithm, budget_s=0.2)["median_us"]
        p = 1e6 * per_call_seconds(lambda: dabench.marginals(psi, args.algorithm), args.calls)
        kernel.append(k)
        python.append(p)
        overhead.append(p - k)
    start = time.perf_counter()
    rounds = max(1, args.calls // len(pool))
    for _ in range(rounds):
        dabench.marginals_batch(pool, args.algorithm, threads=1)
    batch = 1e6 * (time.perf_counter() - start) / (rounds * len(pool))
    print(f"{args.algorithm} on {len(pool)} problems of the 2x3 baseline at spacing {args.spacing} "
          f"(median over problems, us per call)")
    print(f"  kernel (time_solver)          {statistics.median(kernel):8.3f}")
    print(f"  dabench.marginals()           {statistics.median(python):8.3f}")
    print(f"  overhead per call             {statistics.median(overhead):8.3f}  (max {max(overhead):.3f})")
    print(f"  marginals_batch, per problem  {batch:8.3f}  (mean over the pool, 1 thread)")


if __name__ == "__main__":
    main()
