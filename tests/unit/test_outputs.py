"""Output files: checked before the work, written all or none; and the explorer's listening
address checked before the server starts."""

import os
import socket

import pytest

from leuven_friction.app.listen import ListenError, check_listen_address, check_served_port
from leuven_friction.app.outputs import OutputError, Outputs, check_output_path, json_text


def test_output_path_reasons(tmp_path):
    with pytest.raises(OutputError, match=r"^--out .*: directory .*nodir does not exist$"):
        check_output_path(tmp_path / "nodir" / "p.yaml", "--out")
    with pytest.raises(OutputError, match=r"is a directory; give a file name"):
        check_output_path(tmp_path, "--out")
    ro = tmp_path / "ro.yaml"
    ro.write_text("keep")
    ro.chmod(0o444)
    with pytest.raises(OutputError, match=r"the file is read-only"):
        check_output_path(ro, "--out")
    f = tmp_path / "file"
    f.write_text("")
    with pytest.raises(OutputError, match=r"is not a directory"):
        check_output_path(f / "p.yaml", "--out")
    assert check_output_path(tmp_path / "new.yaml", "--out") == tmp_path / "new.yaml"
    assert sorted(os.listdir(tmp_path)) == ["file", "ro.yaml"]  # the checks leave nothing behind


def test_outputs_are_all_or_none(tmp_path):
    a, b = tmp_path / "a.json", tmp_path / "b.html"
    with pytest.raises(RuntimeError):
        with Outputs({"--json": a, "--html": b}) as out:
            out.write_text(a, "{}")
            raise RuntimeError("the report failed half-way")
    assert os.listdir(tmp_path) == []
    with Outputs({"--json": a, "--html": b, "--out": None}) as out:
        out.write_text(a, "{}")
        assert not a.exists()  # staged, not yet in place
        out.write_text(b, "<html/>")
    assert a.read_text() == "{}" and b.read_text() == "<html/>"
    assert sorted(os.listdir(tmp_path)) == ["a.json", "b.html"]


def test_one_bad_output_path_refuses_all_before_the_work(tmp_path):
    ok = tmp_path / "ok.json"
    with pytest.raises(OutputError, match=r"^--html "):
        Outputs({"--json": ok, "--html": tmp_path / "nodir" / "r.html"})
    with pytest.raises(OutputError, match=r"the same file as --json"):
        Outputs({"--json": ok, "--out": ok})
    assert os.listdir(tmp_path) == []


def test_listen_port_out_of_range():
    with pytest.raises(ListenError, match=r"^--port 99999: must be between 0 and 65535"):
        check_listen_address("127.0.0.1", 99999)


def test_listen_host_that_does_not_resolve():
    # .invalid is reserved never to resolve (RFC 2606)
    with pytest.raises(ListenError, match=r"^--host example\.invalid: (cannot resolve|no answer)"):
        check_listen_address("example.invalid", 8080)


def test_listen_taken_port_is_an_error_naming_it():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        s.listen()
        port = s.getsockname()[1]
        with pytest.raises(ListenError, match=rf"^--port {port}: already in use on 127\.0\.0\.1"):
            check_listen_address("127.0.0.1", port)
    with pytest.raises(ListenError, match=r"already in use"):
        check_served_port(8080, "http://127.0.0.1:8081")
    check_served_port(0, "http://127.0.0.1:43211")  # --port 0: whatever port was free


def test_listen_warns_for_hosts_reachable_from_the_network():
    assert check_listen_address("127.0.0.1", 0).network_warning() is None
    assert check_listen_address("localhost", 0).loopback
    w = check_listen_address("0.0.0.0", 0).network_warning()
    assert "reachable from the network" in w and "without authentication" in w


def test_json_written_is_strict_json_with_null_where_a_number_is_not_finite():
    # a regime too short for its noise floor had "noise": NaN, which JavaScript's JSON.parse refuses
    import json

    text = json_text({"regimes": {"load changing": {"n": 6, "noise": float("nan")}}, "gaps": [1.5, float("inf")]})
    strict = json.loads(text, parse_constant=lambda c: pytest.fail(f"non-standard constant {c}"))
    assert strict == {"regimes": {"load changing": {"n": 6, "noise": None}}, "gaps": [1.5, None]}
