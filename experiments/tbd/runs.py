"""TBD's runs: the committed run folders under results/tbd, the commands that made them (their
provenance), the steps after them (digests, figures, the benchmark), and the trackers the runs hold
(their SPECs and the names the REPORT gives them)."""

from reports.core.study import Run, Step

FOLDER = "results/tbd"
TOY, CALIBRATION = f"{FOLDER}/toy-fig1a", f"{FOLDER}/toy-calibration"
GOSPA, JOINT, RUNTIME = f"{FOLDER}/gospa", f"{FOLDER}/gospa-joint", f"{FOLDER}/runtime"
D2, D3, D1_WIDE = f"{FOLDER}/d2", f"{FOLDER}/d3", f"{FOLDER}/d1-wide"
PARTICLES, SENSITIVITY, MERGE = f"{FOLDER}/particles", f"{FOLDER}/sensitivity", f"{FOLDER}/merge"
MB_READINGS = f"{FOLDER}/mb-readings"
BENCH = f"{FOLDER}/bench.json"

RUNS = [
    Run(TOY, "./build/dabench run experiments/tbd/toy-fig1a.ini --force",
        "supplement Fig. 1 on its own frame, readings D1-D3"),
    Run(CALIBRATION, "./build/dabench run experiments/tbd/toy-calibration.ini --force",
        "Fig. 1(e) over D3's (rho, sigma_h^2) grid"),
    Run(GOSPA, "./build/dabench run experiments/tbd/gospa.ini --force", "letter's Fig. 2: 400 runs x 4 trackers"),
    Run(JOINT, "./build/dabench run experiments/tbd/gospa-joint.ini --force",
        "the joint schedule on the same 400 runs"),
    Run(RUNTIME, "./build/dabench run experiments/tbd/runtime.ini --force", "supplement Fig. 4: 20 runs per point"),
    Run(D2, "./build/dabench run experiments/tbd/reading-d2.ini --force", "reading D2: tbd-gospa's first 100 runs"),
    Run(D3, "./build/dabench run experiments/tbd/reading-d3.ini --force", "reading D3: tbd-gospa's first 100 runs"),
    Run(D1_WIDE, "./build/dabench run experiments/tbd/reading-d1-wide.ini --force",
        "D1 with D3's sigma_h^2: the same 100 runs"),
    Run(MB_READINGS, "./build/dabench run experiments/tbd/mb-readings.ini --force",
        "TBD-MB without exclusivity on the same 400 runs"),
    Run(PARTICLES, "./build/dabench run experiments/tbd/particles.ini --force", "P = 2000 vs 10 000: 60 runs"),
    Run(SENSITIVITY, "./build/dabench run experiments/tbd/sensitivity.ini --force", "sigma_S^2 = 0.5, 2: 100 runs each"),
    Run(MERGE, "./build/dabench run experiments/tbd/merge.ini --force", "merge_distance = 1 m: 200 runs"),
]
FIGURES = "/usr/bin/python3 -m plots.tbd_figures"
STEPS = [
    Step("/usr/bin/python3 -m reports.digest tbd", "runs.csv, steps-mean.csv, steps-paired.csv, beliefs-summary.csv"),
    Step(f"{FIGURES} toy {TOY} --point 0 --out {TOY}/tbd_toy_d1.png", "Fig. 1 under D1"),
    Step(f"{FIGURES} toy {TOY} --point 1 --out {TOY}/tbd_toy_d2.png", "Fig. 1 under D2"),
    Step(f"{FIGURES} toy {TOY} --point 2 --out {TOY}/tbd_toy_d3.png", "Fig. 1 under D3"),
    Step(f"{FIGURES} gospa {GOSPA}", "the letter's Fig. 2"),
    Step(f"{FIGURES} gospa {GOSPA} --column gospa_p2 --out {GOSPA}/tbd_gospa_p2.png", "the same for p = 2"),
    Step(f"{FIGURES} run {GOSPA}", "Figs 2-3: run 0"),
    Step(f"{FIGURES} runtime {RUNTIME}", "Fig. 4"),
    Step(f"{FIGURES} gospa {JOINT}"),
    Step(f"{FIGURES} gospa {D2}"),
    Step(f"{FIGURES} gospa {D3}"),
    Step(f"{FIGURES} gospa {D1_WIDE}"),
    Step(f"{FIGURES} gospa {SENSITIVITY} --point 0 --out {SENSITIVITY}/tbd_gospa_sigma05.png"),
    Step(f"{FIGURES} gospa {SENSITIVITY} --point 1 --out {SENSITIVITY}/tbd_gospa_sigma2.png"),
    Step(f"{FIGURES} gospa {MERGE}"),
    Step(f"./build/dabench_bench --benchmark_filter=tbd_bp --benchmark_repetitions=3 "
         f"--benchmark_out={BENCH} --benchmark_out_format=json",
         "per-step kernel timings on one core: run it on a quiet machine"),
]

# ----------------------------------------------------------------------------- trackers

MB, IEMB, BP1, BP2 = "tbd-mb", "tbd-iemb", "tbd-bp:iterations=1", "tbd-bp:iterations=2"
MB_NONE = "tbd-mb:association=none"
MERGED = {1: "tbd-bp:iterations=1,merge_distance=1", 2: "tbd-bp:iterations=2,merge_distance=1"}
MANY_PARTICLES = {1: "tbd-bp:iterations=1,particles=10000", 2: "tbd-bp:iterations=2,particles=10000"}
BP = {1: BP1, 2: BP2}
BPJ = {1: "tbd-bp:iterations=1,schedule=joint", 2: "tbd-bp:iterations=2,schedule=joint"}
NAMES = {MB: "TBD-MB", MB_NONE: "TBD-MB without exclusivity", IEMB: "TBD-IEMB", BP1: "TBD-BP L = 1", BP2: "TBD-BP L = 2",
         BPJ[1]: "TBD-BP L = 1 joint", BPJ[2]: "TBD-BP L = 2 joint",
         MERGED[1]: "TBD-BP L = 1 merged", MERGED[2]: "TBD-BP L = 2 merged"}

# Runs on the first runs of tbd/gospa.ini (the same frames): paired with them.
MERGE_TRIALS = 200  # tbd/merge.ini: the first 200 runs of tbd/gospa.ini
MATCHED_RUNS = 100  # tbd/reading-*.ini: the first 100 runs of tbd/gospa.ini, under another reading
