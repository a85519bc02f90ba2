"""Benchmarks: each measures coopdrive against a baseline in the same run (`make bench`)."""
