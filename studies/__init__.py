"""Runnable studies reproducing the reference dissertation's comparisons.

Each study writes CSV tables and PNG figures under ``results/<study>/`` and prints
a summary. Run with ``python -m studies.<name>``.
"""
