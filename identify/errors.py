"""Errors of identification, under the one user-facing base of ``model.errors``."""

from __future__ import annotations

from ..model.errors import FrictionError


class DataError(FrictionError):
    """Recorded data that cannot be used; the message names file, column and row."""


class IdentificationError(FrictionError):
    """The data load but do not support the estimate asked for (no levels, no presliding
    branches, too few samples); the message says what is missing and what would supply it."""
