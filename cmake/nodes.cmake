# (filled in by the nodes work)
