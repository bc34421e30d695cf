"""The boundary between the Python layer and the compiled kernels, in one place.

The kernels take plain float64 arrays; this module says what lives where in them:

``ModelKind``, ``CurveKind``  the integer codes of the model and of the transition curve;
``P_*``  the parameter vector (``model.simulate.pack`` fills it);
``S_*``, ``HEADER``  the state vector: a header of scalars, then the two stacks of extrema
    of Section III-B, stack m (minima of F_h, ascending) and stack M (maxima, descending),
    each of capacity ``(len(st) - HEADER) // 2``;
``State``  a read-only view of a state vector by name, for code outside the kernels.

No numba or numpy at import: the command line imports this at start-up.
"""

from __future__ import annotations

from enum import IntEnum


class ModelKind(IntEnum):
    """The friction models, with the codes the kernels branch on."""

    LEUVEN = 0
    LUGRE = 1
    STATIC = 2

    @property
    def label(self) -> str:
        """The name used in parameter files and on the command line."""
        return self.name.lower()

    @classmethod
    def parse(cls, label: str) -> "ModelKind":
        return cls[label.upper()]


MODEL_NAMES: tuple[str, ...] = tuple(m.label for m in ModelKind)


class CurveKind(IntEnum):
    """Transition curve families: knots (z, F) or A·tanh(z/z0) + k·z with ``tF = [A, z0, k]``."""

    PIECEWISE_LINEAR = 0
    TANH_LINEAR = 1

    @property
    def label(self) -> str:
        return self.name.lower()


CURVE_NAMES: tuple[str, ...] = tuple(c.label for c in CurveKind)

# ---------------------------------------------------------------- parameter vector
P_SP = 0  # 10 Stribeck values: Fs+, Fc+, vs+, delta+, sigma2+, Fs-, Fc-, vs-, delta-, sigma2-
P_N = 10
P_NINT = 11  # n when it is a small integer (power by multiplication), else 0
P_SIGMA1 = 12
P_SIGMA0 = 13
P_REVTOL = 14
P_INERTIA = 15
P_SIZE = 16
STRIBECK_SIDE = 5  # values per velocity sign; the negative side starts at P_SP + STRIBECK_SIDE

# ---------------------------------------------------------------- state vector
S_Z, S_FB, S_DIR, S_NMIN, S_NMAX = 0, 1, 2, 3, 4
S_REVERSALS, S_CLOSINGS, S_RESETS, S_DEPTH, S_DROPPED = 5, 6, 7, 8, 9
S_SV = 10  # S(v) of the last step (reused by the plant's linearisation)
HEADER = 11


def new_state(cap: int = 64):
    """A zeroed state vector whose stacks each hold ``cap`` extrema."""
    import numpy as np  # here, not at the top: the command line imports this module at start-up

    if cap < 2:
        raise ValueError(f"stack capacity must be >= 2, got {cap}")
    return np.zeros(HEADER + 2 * cap)


class State:
    """Named access to a state vector. Only z may be set from outside (an external integrator
    of eq. (5), as the benchmark's solve_ivp baseline); the memory is the kernels' to update."""

    __slots__ = ("array",)

    def __init__(self, array):
        self.array = array

    @property
    def capacity(self) -> int:
        return (len(self.array) - HEADER) // 2

    @property
    def z(self) -> float:
        return float(self.array[S_Z])

    @z.setter
    def z(self, value: float) -> None:
        self.array[S_Z] = value

    @property
    def F_b(self) -> float:
        """F_h at the start of the current transition curve (eq. (4)); the static model keeps
        its last S(v), or the stuck force, here."""
        return float(self.array[S_FB])

    @property
    def direction(self) -> int:
        """+1 / -1: the direction of the last motion; 0 before any."""
        return int(self.array[S_DIR])

    @property
    def last_S(self) -> float:
        return float(self.array[S_SV])

    @property
    def stack_m(self) -> list[float]:
        """Minima of F_h, oldest first (the bottom is F_s-)."""
        n = int(self.array[S_NMIN])
        return self.array[HEADER : HEADER + n].tolist()

    @property
    def stack_M(self) -> list[float]:
        """Maxima of F_h, oldest first (the bottom is F_s+)."""
        n = int(self.array[S_NMAX])
        c = self.capacity
        return self.array[HEADER + c : HEADER + c + n].tolist()

    @property
    def reversals(self) -> int:
        return int(self.array[S_REVERSALS])

    @property
    def loop_closings(self) -> int:
        return int(self.array[S_CLOSINGS])

    @property
    def resets(self) -> int:
        return int(self.array[S_RESETS])

    @property
    def max_stack_depth(self) -> int:
        return int(self.array[S_DEPTH])

    @property
    def dropped_pairs(self) -> int:
        return int(self.array[S_DROPPED])

    def summary(self) -> dict:
        """The memory as a JSON-able record (``SimResult.memory``)."""
        return {
            "reversals": self.reversals,
            "loop_closings": self.loop_closings,
            "resets": self.resets,
            "max_stack_depth": self.max_stack_depth,
            "dropped_pairs": self.dropped_pairs,
            "stack_m": self.stack_m,
            "stack_M": self.stack_M,
        }
