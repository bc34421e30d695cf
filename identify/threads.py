"""One BLAS thread for identification and diagnosis.

OpenBLAS shares a reduction (a dot product, a matrix-vector product) out among its threads, so
the same least squares rounds otherwise on a machine with another number of cores, and an
optimiser's path — and a decision taken at a threshold — can follow it: the gaps of a robot
joint of the hidden-effect suite moved in the ninth digit between one thread and two. The matrices here are small (thousands of rows, tens of
columns), and more threads buy nothing there, so ``fit_recordings`` and ``diagnose`` run on one,
whatever the machine has. (The compiled simulation kernels use no BLAS.)
"""

from __future__ import annotations

from functools import wraps

import scipy.linalg  # noqa: F401  (loads scipy's own OpenBLAS, so that the limit reaches it too)
from threadpoolctl import threadpool_limits


def one_blas_thread(func):
    """``func`` run with BLAS limited to one thread (restored after it returns)."""

    @wraps(func)
    def wrapper(*args, **kwargs):
        with threadpool_limits(limits=1, user_api="blas"):
            return func(*args, **kwargs)

    return wrapper
