"""The papers' figures and tables as functions of a run's CSV files: one module per figure family
(fig6, fig6_paper, fig7, multiscan_cdf, othr_*, jdtvb_*, tbd_figures, leaderboard, the tables).
Each module's main() is its command line: `python3 -m plots.<module> --help` from the repository
root. The studies' checks (experiments/) import these modules; nothing here imports a study."""
