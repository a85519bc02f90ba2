"""RunAborted: a run that cannot go on (its services could not start, or all of them exited); the command line
says why in one line."""


class RunAborted(RuntimeError):
    pass
