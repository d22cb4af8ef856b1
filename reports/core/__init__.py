"""What every study's checks share: verdict rules, statistics, data access, formatting, templates."""
