"""A tracking run's trials.csv as per-run metric values by (setting, tracker), for the JDT-VB study:
means with standard errors, and paired differences of two trackers on the same draws (every
tracker of a run sees the same scenario draw at each (point, trial))."""

import math

from reports.core import data, markdown, stats

# Table IV's metrics: (trials.csv column, heading, "higher is better").
METRICS = [("nvt", "NVT", True), ("tpd", "TPD", True), ("nft", "NFT", False), ("ttl_scans", "TTL", False),
           ("aee_range_km", "AEE-R (km)", False), ("aee_bearing_mrad", "AEE-B (mrad)", False),
           ("mospa_km", "MOSPA (km)", False)]
HEADING = {m: h for m, h, _ in METRICS} | {"tet_s": "TET (s)", "false_tracks": "false", "ghost_tracks": "ghost"}
HIGHER_IS_BETTER = {m: up for m, _, up in METRICS} | {"tet_s": False}
SETTINGS = [(0.75, 125), (0.75, 400), (0.4, 125), (0.4, 400)]  # Table IV's column order


def setting_label(setting):
    pd, clutter = setting
    return f"p_d = {pd:g}, N_c = {clutter:g}"


def short_label(setting):
    """"0.4/125": (p_d, N_c) in claim details."""
    return f"{setting[0]:g}/{setting[1]:g}"


class TrackingRun:
    """trials.csv of a tracking run: values[(setting, tracker)][metric] = {trial: value or None}."""

    def __init__(self, root, folder):
        self.folder = folder
        self.rows = data.read_rows(root, f"{folder}/trials.csv")
        if not self.rows:
            raise data.DataError(f"{folder}/trials.csv: no rows")
        self.values = {}
        self.status = {}
        self.trackers = []
        for r in self.rows:
            key = ((data.number(r["pd"]), data.number(r["clutter"])), r["algorithm"])
            if r["algorithm"] not in self.trackers:
                self.trackers.append(r["algorithm"])
            trial = int(r["trial"])
            self.status.setdefault(key, {})[trial] = r["status"]
            cell = self.values.setdefault(key, {})
            for column, text in r.items():
                if column in ("point", "pd", "clutter", "trial", "seed", "algorithm", "status"):
                    continue
                try:
                    cell.setdefault(column, {})[trial] = data.number(text)
                except data.DataError:
                    pass

    def settings(self):
        return sorted({s for s, _ in self.values}, key=lambda s: (-s[0], s[1]))

    def has(self, setting, tracker):
        return (setting, tracker) in self.values

    def series(self, setting, tracker, metric):
        """{trial: value} of the runs that completed ("ok") and define the metric."""
        key = (setting, tracker)
        if key not in self.values:
            raise data.DataError(f"{self.folder}: no runs of {tracker} at {setting_label(setting)}")
        status = self.status[key]
        column = self.values[key].get(metric)
        if column is None:
            raise data.DataError(f"{self.folder}/trials.csv: no column '{metric}'")
        return {t: v for t, v in column.items() if status[t] == "ok" and v is not None and math.isfinite(v)}

    def mean(self, setting, tracker, metric):
        """(mean, se, n) over the runs that define the metric."""
        return stats.mean_se(self.series(setting, tracker, metric).values())

    def runs(self, setting, tracker):
        status = self.status[(setting, tracker)]
        return sum(1 for s in status.values() if s == "ok"), len(status)

    def paired(self, setting, a, b, metric):
        """(mean, se, n) of a - b over the runs where both define the metric."""
        return stats.paired(self.series(setting, a, metric), self.series(setting, b, metric))

    def cell(self, setting, tracker, metric):
        """"mean ± se", with "(n=N)" when fewer runs define it than completed."""
        m, se, n = self.mean(setting, tracker, metric)
        ok, _ = self.runs(setting, tracker)
        text = markdown.pm(m, se)
        return text + (f" (n={n})" if n < ok else "")
