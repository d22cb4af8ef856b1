"""The studies: a package each (its runs, its checks and its REPORT template beside its experiment files)."""
