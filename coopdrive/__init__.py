"""coopdrive: a cooperative automated driving stack on Zenoh."""

import os

# Before numpy or scipy loads OpenBLAS (each ships its own copy): the stack's matrices are a filter's 6 x 6 or
# 8 x 8 and their small batches, which OpenBLAS never splits over threads. Yet each copy starts a pool of worker
# threads when it loads, and they spin waiting for work before they sleep: 0.25 s of CPU per interpreter that
# imports both (0.60 s against 0.35 s of user CPU to import numpy and scipy here), taken from the other core
# while a run starts its processes and the test suite runs its commands. A value set by the user stands.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
