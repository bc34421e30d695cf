"""The user-facing errors: one base, so that the command line and the web app turn exactly these
into one-line messages, and every other exception still shows as the bug it is."""

from __future__ import annotations


class FrictionError(ValueError):
    """A mistake in what the user gave us (a file, a parameter, a setting), told in one line that
    names the file, column, row or field and says what to fix."""


class ParameterError(FrictionError):
    """A parameter set or parameter file that violates the model's rules; names the dotted field."""


class SignalError(FrictionError):
    """A time series handed to a simulator that cannot be simulated (too short, not finite,
    time not increasing); names the signal and the sample."""
