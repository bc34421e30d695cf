"""The web explorer (viser): one module per tab, see ``app.explorer.app``."""

from .app import Explorer, serve

__all__ = ["Explorer", "serve"]
