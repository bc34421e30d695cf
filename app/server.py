"""``leuven-friction serve``: start the web explorer (see ``app.explorer``)."""

from __future__ import annotations

from .explorer import serve

__all__ = ["serve"]
