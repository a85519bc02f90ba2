"""The exit statuses of every `coopdrive` command, said once."""

EXIT_OK = 0
# The command ran and what it checked failed: a run, a run of a sweep, a health check.
EXIT_FAILED = 1
# The command could not start: a bad flag or file (argparse exits with 2 for a flag it does not know, too).
EXIT_USAGE = 2
# A service or group whose launcher died ended itself (runtime/launcher_watch.py).
EXIT_ORPHANED = 3
# A sweep stopped by its --time-limit with every run that finished passed: no failure, but not a whole sweep.
EXIT_INCOMPLETE = 4
