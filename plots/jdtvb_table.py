#!/usr/bin/python3
"""Table IV of JDT-VB (jdt-vb-multipath-othr, Sec. IV-B) as Markdown, from a tracking run's
summary.csv: per setting (sweep point) and tracker, NVT, TPD, NFT, TTL, AEE-R (km), AEE-B
(mrad), MOSPA and TET (s) as mean +- standard error over the Monte Carlo runs.

Usage:
  /usr/bin/python3 -m plots.jdtvb_table RUN_DIR/summary.csv [--paper] [--out table.md]

With --paper, each setting that is one of the paper's (pd in {0.75, 0.4}, N_c in {125, 400},
and, where the columns exist, scans 30, scan_interval 16, process_psd 1e-8) is followed by the
paper's own rows for MPTF, MD-HMHT and JDT-VB, marked "(paper)"; the numbers are copied below
from Table IV. Cells: mean +- SE (3 significant digits); "(n=N)" when the metric is defined in
fewer runs than the tracker completed (TTL and AEE need a followed target); "-" when it is
never defined. The `runs` column is ok/trials; failed or skipped runs are not averaged.
Prints to stdout or --out; exit status 2 with a one-line message when the input is unusable.
"""

import argparse
import csv
import math
import sys

# (summary metric, table heading); TTL in scans, AEE-R and MOSPA in km, AEE-B in mrad.
METRICS = [("nvt", "NVT"), ("tpd", "TPD"), ("nft", "NFT"), ("ttl_scans", "TTL"), ("aee_range_km", "AEE-R (km)"),
           ("aee_bearing_mrad", "AEE-B (mrad)"), ("mospa_km", "MOSPA"), ("tet_s", "TET (s)")]

# Table IV of the paper, (pd, N_c) -> tracker -> values in METRICS order, as printed. MATLAB
# on an Intel Core i5 with 4 GB RAM (Sec. IV-A), so TET is not comparable with ours.
PAPER_TABLE_IV = {
    (0.75, 125): {"MPTF": ["3.92", "0.99", "1.86", "0.24", "1.56", "1.42", "18.7", "9.08"],
                  "MD-HMHT": ["3.88", "0.96", "0.40", "0.47", "2.47", "1.20", "10.9", "81.8"],
                  "JDT-VB": ["3.80", "0.97", "0.57", "0.38", "1.59", "0.58", "10.4", "7.42"]},
    (0.75, 400): {"MPTF": ["3.84", "0.99", "12.7", "0.14", "1.6", "1.54", "37.5", "58.6"],
                  "MD-HMHT": ["3.31", "0.86", "1.21", "0.69", "3.01", "1.80", "31.6", "1279"],
                  "JDT-VB": ["3.72", "0.96", "2.18", "0.70", "1.88", "0.50", "22.4", "79.6"]},
    (0.4, 125): {"MPTF": ["2.04", "0.63", "3.93", "3.44", "2.49", "2.28", "30.8", "22.4"],
                 "MD-HMHT": ["3.04", "0.63", "0.51", "0.14", "4.03", "2.10", "31.2", "76.1"],
                 "JDT-VB": ["3.50", "0.88", "0.94", "0.38", "2.19", "0.98", "18.2", "7.85"]},
    (0.4, 400): {"MPTF": ["1.88", "0.65", "15.2", "3.58", "2.47", "2.24", "39.6", "48.5"],
                 "MD-HMHT": ["1.91", "0.45", "1.14", "0.70", "4.33", "2.30", "39.7", "1233"],
                 "JDT-VB": ["3.23", "0.87", "1.90", "0.48", "2.41", "1.16", "23.1", "82.4"]},
}
PAPER_SCENARIO = {"scans": 30.0, "scan_interval": 16.0, "process_psd": 1e-8}
PAPER_NAMES = {"jdt-vb": "JDT-VB", "mptf": "MPTF", "md-hmht": "MD-HMHT"}


def fail(message):
    print(f"jdtvb_table.py: {message}", file=sys.stderr)
    sys.exit(2)


def number(text):
    return float(text) if text not in ("", None) else math.nan


def significant(value, digits=3):
    if not math.isfinite(value):
        return "-"
    if value == 0:
        return "0"
    return f"{value:.{digits}g}"


def cell(row, metric):
    mean, se = number(row.get(f"{metric}_mean")), number(row.get(f"{metric}_se"))
    count, ok = int(row.get(f"{metric}_count") or 0), int(row.get("ok") or 0)
    if not math.isfinite(mean):
        return "-"
    text = significant(mean) + (f" ± {significant(se, 2)}" if math.isfinite(se) else "")
    return text + (f" (n={count})" if count < ok else "")


def paper_setting(params):
    """The paper's (pd, N_c) key if the point's parameters are one of Table IV's settings."""
    try:
        pd, clutter = float(params["pd"]), float(params["clutter"])
    except (KeyError, ValueError):
        return None
    for key, value in PAPER_SCENARIO.items():
        if key in params and abs(float(params[key]) - value) > 1e-9 * value:
            return None
    for setting in PAPER_TABLE_IV:
        if abs(setting[0] - pd) < 1e-9 and abs(setting[1] - clutter) < 1e-9:
            return setting
    return None


def read(path):
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            rows, header = list(reader), reader.fieldnames or []
    except OSError as error:
        fail(f"{path}: {error.strerror}")
    for column in ["algorithm", "trials", "ok"] + [f"{m}_mean" for m, _ in METRICS]:
        if column not in header:
            fail(f"{path}: no column '{column}' (is this the summary.csv of a tracking run?)")
    if not rows:
        fail(f"{path}: no rows")
    first = 1 if header[0] == "point" else 0
    return rows, header[first:header.index("algorithm")]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("summary")
    parser.add_argument("--paper", action="store_true", help="add the paper's Table IV rows for matching settings")
    parser.add_argument("--out")
    args = parser.parse_args()
    rows, params = read(args.summary)
    varying = [p for p in params if len({r[p] for r in rows}) > 1]
    shown = [p for p in ("pd", "clutter") if p in params] + [p for p in varying if p not in ("pd", "clutter")]

    lines = ["| setting | tracker | runs | " + " | ".join(h for _, h in METRICS) + " |",
             "|---|---|---|" + "---|" * len(METRICS)]
    settings = []
    for r in rows:
        key = tuple(r[p] for p in params)
        if key not in settings:
            settings.append(key)
    for key in settings:
        point = dict(zip(params, key))
        label = ", ".join(f"{'N_c' if p == 'clutter' else p} = {point[p]}" for p in shown)
        for r in (r for r in rows if tuple(r[p] for p in params) == key):
            name = r["algorithm"]
            lines.append(f"| {label} | {name} | {r['ok']}/{r['trials']} | "
                         + " | ".join(cell(r, m) for m, _ in METRICS) + " |")
        setting = paper_setting(point) if args.paper else None
        if setting is not None:
            for tracker, values in PAPER_TABLE_IV[setting].items():
                lines.append(f"| {label} | {tracker} (paper) | 100 | " + " | ".join(values) + " |")
    notes = ["", "Mean ± standard error over runs; TTL in scans; MOSPA in km (OSPA cut-off and order: meta.json "
             "`tracking_metrics`)."]
    if args.paper:
        notes.append("Rows marked (paper) are Table IV of the JDT-VB paper (100 runs, MATLAB on an Intel Core i5: "
                     "TET is not comparable). Our names: " + ", ".join(f"{k} = {v}" for k, v in PAPER_NAMES.items())
                     + ".")
    text = "\n".join(lines + notes) + "\n"
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)
        print(args.out, file=sys.stderr)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
