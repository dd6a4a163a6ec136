"""Models: each offers ``solve(case, **options) -> Result``."""
