"""JDT-VB's runs: the committed run folders under results/jdtvb, the commands that made them (their
provenance), the steps after them (Figs 5-7), and the trackers and readings the runs hold."""

from reports.core.study import Run, Step

FOLDER = "results/jdtvb"
TABLE4 = f"{FOLDER}/table4"
PAPER_TRACKERS = ["jdt-vb", "mptf", "md-hmht"]  # ours, named as the paper's three
LITERAL = "jdt-vb:literal=1"  # eq (32) fusion, no alternative heads; deletion at each of three scans
LITERAL_MEAN = "jdt-vb:literal=1,delete_on_mean=1"  # the same with the mean-of-three deletion reading
FROM_HEAD = "jdt-vb:report_from=head"
LITERAL_FROM_HEAD = "jdt-vb:literal=1,report_from=head"
READINGS = ["jdt-vb:joint_fusion=0", "jdt-vb:delete_on_mean=1", "jdt-vb:alternative_heads=0"]
MDHMHT_LITERAL = "md-hmht:literal=1"  # no alternative heads, tracks from confirmation, per-path assignments
MDHMHT_READINGS = ["md-hmht:alternative_heads=0", "md-hmht:per_parent=1", "md-hmht:hypotheses=1",
                   "md-hmht:hypotheses=10", "md-hmht:confirm_llr=4.6", "md-hmht:report_from=confirmation",
                   "md-hmht:assignment=per_path"]
# MD-HMHT's paper-literal readings taken one after the other (the decomposition).
MDHMHT_CUMULATIVE = [("md-hmht", "default"), ("md-hmht:report_from=confirmation", "+ tracks from confirmation"),
                     ("md-hmht:report_from=confirmation,alternative_heads=0", "+ one head per return group"),
                     (MDHMHT_LITERAL, "+ per-path assignments (literal=1)")]
SENSITIVITY = [("table4", "gate 20 km, cut-off 50 km (default)"), ("table4-gate50", "gate 50 km"),
               ("table4-gate100", "gate 100 km"), ("table4-cutoff100", "cut-off 100 km")]

RUNS = [
    Run(TABLE4, "./build/dabench run experiments/jdtvb/table4.ini --force", "Table IV: 400 runs x 4 trackers"),
    Run(f"{FOLDER}/table4-gate50", "./build/dabench run experiments/jdtvb/table4-gate50.ini --force"),
    Run(f"{FOLDER}/table4-gate100", "./build/dabench run experiments/jdtvb/table4-gate100.ini --force"),
    Run(f"{FOLDER}/table4-cutoff100", "./build/dabench run experiments/jdtvb/table4-cutoff100.ini --force"),
    Run(f"{FOLDER}/table4-aee", "./build/dabench run experiments/jdtvb/table4-aee.ini --force"),
    Run(f"{FOLDER}/table4-readings", "./build/dabench run experiments/jdtvb/table4-readings.ini --force"),
    Run(f"{FOLDER}/mdhmht-readings", "./build/dabench run experiments/jdtvb/mdhmht-readings.ini --force"),
    Run(f"{FOLDER}/mdhmht-readings-gate50", "./build/dabench run experiments/jdtvb/mdhmht-readings-gate50.ini --force"),
    Run(f"{FOLDER}/fig7", "./build/dabench run experiments/jdtvb/fig7.ini --force", "Fig. 7: iterations.csv"),
]
STEPS = [
    Step("/usr/bin/python3 -m plots.othr_scenario results/jdtvb/table4 --where pd=0.75,clutter=125", "Fig. 5"),
    Step("/usr/bin/python3 -m plots.othr_tracks results/jdtvb/table4 --where pd=0.75,clutter=125", "Fig. 6"),
    Step("/usr/bin/python3 -m plots.jdtvb_fig7 results/jdtvb/fig7/iterations.csv", "Fig. 7"),
]
