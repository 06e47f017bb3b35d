"""Python benchmarks (python3 -m weft.bench NAME)."""
