"""The runtime: the heavy processes and their lanes, admission of requests (a few in flight per client), the
cache of computed answers and the family members' batches and memo."""
