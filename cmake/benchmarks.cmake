# (filled in by the benchmarks work)
