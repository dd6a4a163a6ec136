"""Output: tables, charts and field files. Never solves."""
