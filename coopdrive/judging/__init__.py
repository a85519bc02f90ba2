"""Judging a recorded or live run: metrics from ground truth, plots and an HTML report."""
