"""Where the explorer listens: the host and port checked before the server starts.

The web server library would, left alone, hang on a port out of range or a host name that does
not resolve, and silently move to the next port when the one asked for is taken. Here every one
of those is a one-line error before anything starts, ``--port 0`` picks a free port (the server
prints the one it got), and a host other than loopback gets a warning: the explorer has no
authentication, so whoever can reach the port can use it and upload files to it.
"""

from __future__ import annotations

import errno
import ipaddress
import socket
import threading
from dataclasses import dataclass

from ..model.errors import FrictionError

RESOLVE_TIMEOUT = 5.0  # seconds to wait for a host name lookup


class ListenError(FrictionError):
    """A host or port the explorer cannot listen on; names the option and the reason."""


@dataclass(frozen=True)
class ListenAddress:
    host: str
    port: int  # 0: the server picks a free one
    addresses: tuple[str, ...]  # what the host resolves to
    loopback: bool  # every address is a loopback address: reachable from this machine only

    def network_warning(self) -> str | None:
        if self.loopback:
            return None
        where = ("all network interfaces" if any(ipaddress.ip_address(a.split("%")[0]).is_unspecified
                                                 for a in self.addresses) else ", ".join(self.addresses))
        return (f"warning: --host {self.host} makes the explorer reachable from the network "
                f"({where}), without authentication: anyone who can reach the port "
                "can use it and upload files to it. Use --host 127.0.0.1 unless you mean that.")


def _resolve(host: str, port: int, timeout: float) -> list:
    """getaddrinfo with a time limit (it has none of its own)."""
    result: dict = {}

    def lookup():
        try:
            result["info"] = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM, flags=socket.AI_PASSIVE)
        except (OSError, UnicodeError) as e:
            result["error"] = e

    t = threading.Thread(target=lookup, daemon=True)
    t.start()
    t.join(timeout)
    if t.is_alive():
        raise ListenError(f"--host {host}: no answer from the name lookup within {timeout:g} s")
    if "error" in result:
        e = result["error"]
        reason = getattr(e, "strerror", None) or str(e)
        raise ListenError(f"--host {host}: cannot resolve ({reason})")
    return result["info"]


def check_listen_address(host: str, port: int, timeout: float = RESOLVE_TIMEOUT) -> ListenAddress:
    """The checked address, or a ListenError saying in one line what is wrong."""
    if not isinstance(port, int) or not 0 <= port <= 65535:
        raise ListenError(f"--port {port}: must be between 0 and 65535 (0 picks a free port)")
    if not host or not host.strip():
        raise ListenError("--host: empty")
    infos = _resolve(host, port, timeout)
    addresses = []
    for family, socktype, proto, _, sockaddr in infos:
        addr = sockaddr[0]
        if addr not in addresses:
            addresses.append(addr)
        if port == 0:
            continue
        # the port must be free on every address the server will bind (same options as the
        # server's own listening socket, so a port in TIME_WAIT does not count as taken)
        try:
            s = socket.socket(family, socktype, proto)
        except OSError:  # a family this machine lacks (no IPv6): the server skips it too
            continue
        with s:
            s.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
            if family == socket.AF_INET6:
                s.setsockopt(socket.IPPROTO_IPV6, socket.IPV6_V6ONLY, 1)
            try:
                s.bind(sockaddr)
            except OSError as e:
                if e.errno == errno.EADDRINUSE:
                    raise ListenError(f"--port {port}: already in use on {addr} (choose another port, "
                                      "or --port 0 for a free one)") from None
                if e.errno == errno.EADDRNOTAVAIL:
                    raise ListenError(f"--host {host}: {addr} is not an address of this machine") from None
                if e.errno == errno.EACCES:
                    raise ListenError(f"--port {port}: not permitted on {addr} (ports below 1024 need "
                                      "privileges)") from None
                raise ListenError(f"--host {host} --port {port}: cannot listen on {addr} ({e.strerror})") from None
    loopback = all(_is_loopback(a) for a in addresses)
    return ListenAddress(host, port, tuple(addresses), loopback)


def _is_loopback(addr: str) -> bool:
    try:
        return ipaddress.ip_address(addr.split("%")[0]).is_loopback
    except ValueError:
        return False


def check_served_port(asked: int, url: str) -> None:
    """After start: the server must listen on the port asked for (it would otherwise have moved
    to the next free one without a word, e.g. when another program took the port meanwhile)."""
    got = int(url.rsplit(":", 1)[1].split("/")[0])
    if asked and got != asked:
        raise ListenError(f"--port {asked}: already in use (the server could only get port {got}); "
                          "choose another port, or --port 0 for a free one")
