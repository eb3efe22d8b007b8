"""The tables of scripts/benchmark_table.py (RESULTS.md), one module per section; the script is the entry point."""
