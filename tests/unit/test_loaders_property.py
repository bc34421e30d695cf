"""Property-based tests of the two loaders users feed files to: whatever the input, a CSV
recording or a YAML parameter file either loads or raises the user-facing error
(``FrictionError``, one line) — never another exception (a traceback is never a user's error
message)."""

import math

import numpy as np
import yaml
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from leuven_friction.identify.data import ALIASES, load_recording
from leuven_friction.identify.paramfile import load_params, params_from_yaml
from leuven_friction.model import FrictionError, FrictionParams, default_params

# no wall-clock limits in tests: hypothesis' per-example deadline is off
SETTINGS = settings(max_examples=150, deadline=None, suppress_health_check=[HealthCheck.too_slow], database=None,
                    derandomize=True)

# -- CSV recordings -------------------------------------------------------------------------------
NAMES = sorted({a for names in ALIASES.values() for a in names}) + ["", "x y", "Ω", "time", "time", "#", '"q"']
UNITS = ["", " [mm]", " (uN)", " [s]", " (ms)", " [deg]", " [furlong]", " [", " ()", " [N*m]"]
CELLS = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(min_value=-(10 ** 30), max_value=10 ** 30).map(str),
    st.sampled_from(["", "abc", "1,5", "-", "nan", "inf", "1e400", "0x10", "   ", '"', "1;2", "TRUE", "#x"]),
)


SIGNAL_HEADERS = [["time", "t", "Time (s)", "time [ms]", "Zeit"], ["position", "x [mm]", "Angle [mrad]", "q (deg)"],
                  ["force", "torque [N*m]", "Friction (uN)", "tau"], ["velocity", "v [mm/s]", "temperature"]]


@st.composite
def csv_texts(draw):
    """Mostly well-formed tables (recognised headers, numeric rows, increasing time) with a
    few corruptions: odd separators, unknown units, bad or missing cells, ragged rows,
    comments, blank lines, duplicated columns."""
    sep = draw(st.sampled_from([",", ";", "\t", " ", ",", "|"]))
    ncol = draw(st.integers(1, 4))
    header = [draw(st.sampled_from(SIGNAL_HEADERS[i])) if draw(st.integers(0, 5))
              else draw(st.sampled_from(NAMES)) + draw(st.sampled_from(UNITS)) for i in range(ncol)]
    nrow = draw(st.integers(0, 40))
    decimal_comma = sep == ";" and draw(st.booleans())
    corrupt = set(draw(st.lists(st.integers(0, max(nrow - 1, 0)), max_size=3)))
    ragged = draw(st.integers(-1, max(nrow - 1, 0))) if draw(st.integers(0, 3)) == 0 else None
    dt = draw(st.sampled_from([1e-3, 0.5, 1.0, 1e-9]))
    rows = []
    for i in range(nrow):
        cells = [repr(i * dt)] + [repr(float(np.sin(0.3 * i + j))) for j in range(1, ncol)]
        if decimal_comma:
            cells = [c.replace(".", ",") for c in cells]
        if i in corrupt:
            cells[draw(st.integers(0, ncol - 1))] = draw(CELLS)
        if i == ragged:
            cells = cells[:draw(st.integers(0, ncol))] + [draw(CELLS)] * draw(st.integers(0, 2))
        rows.append(sep.join(cells))
    lines = [sep.join(header)] + rows
    if draw(st.booleans()):
        lines.insert(0, "# " + draw(st.text(max_size=20)).replace("\n", " ").replace("\r", " "))
    if draw(st.booleans()):
        lines.insert(draw(st.integers(0, len(lines))), "")
    return "\n".join(lines) + draw(st.sampled_from(["", "\n", "\r\n"]))


def _loads_or_user_error(source, **kw):
    try:
        rec = load_recording(source, name="rec.csv", **kw)
    except FrictionError as e:
        assert "\n" not in str(e).strip(), str(e)
        return
    assert len(rec.time) >= 1 and np.all(np.isfinite(rec.time))


@SETTINGS
@given(csv_texts(), st.sampled_from([("time",), ("time", "position"), ("time", "force")]))
def test_any_csv_text_loads_or_is_a_user_error(text, require):
    _loads_or_user_error(text.encode("utf-8"), require=require)


@SETTINGS
@given(st.binary(max_size=300))
def test_any_bytes_load_or_are_a_user_error(data):
    _loads_or_user_error(data)


@SETTINGS
@given(st.text(max_size=300))
def test_any_text_loads_or_is_a_user_error(text):
    _loads_or_user_error(text.encode("utf-8"))


# -- YAML parameter files -------------------------------------------------------------------------
LEAVES = st.one_of(
    st.none(), st.booleans(), st.integers(), st.integers(min_value=10 ** 300, max_value=10 ** 420),
    st.floats(allow_nan=True, allow_infinity=True), st.text(max_size=8),
    st.lists(st.floats(allow_nan=False), max_size=4), st.dictionaries(st.text(max_size=4), st.integers(), max_size=3),
)


def _paths(d, prefix=()):
    if isinstance(d, dict):
        for k, v in d.items():
            yield prefix + (k,)
            yield from _paths(v, prefix + (k,))
    elif isinstance(d, list):
        for i, v in enumerate(d):
            yield prefix + (i,)
            yield from _paths(v, prefix + (i,))


BASE = default_params().to_dict()
BASE_PATHS = list(_paths(BASE))


@st.composite
def mutated_parameter_dicts(draw):
    """The paper's valid parameter set with a few fields replaced, removed or added."""
    d = yaml.safe_load(yaml.safe_dump(BASE))
    for _ in range(draw(st.integers(1, 3))):
        path = draw(st.sampled_from(BASE_PATHS))
        parent = d
        try:
            for key in path[:-1]:
                parent = parent[key]
            action = draw(st.sampled_from(["replace", "delete", "add"]))
            if action == "replace":
                parent[path[-1]] = draw(LEAVES)
            elif action == "delete":
                del parent[path[-1]]
            elif isinstance(parent, dict):
                parent[draw(st.one_of(st.text(max_size=6), st.integers()))] = draw(LEAVES)
            else:
                parent.append(draw(LEAVES))
        except (KeyError, IndexError, TypeError):
            pass  # an earlier change removed or replaced this path's parent
    return d


def _yaml_loads_or_user_error(text):
    try:
        p = params_from_yaml(text, "p.yaml")
    except FrictionError as e:
        assert "\n" not in str(e).strip() and str(e).startswith("p.yaml"), str(e)
        return
    assert isinstance(p, FrictionParams)
    assert all(math.isfinite(v) for v in p.stribeck.as_array())
    assert FrictionParams.from_dict(p.to_dict()) == p  # whatever loads also writes and loads back


@SETTINGS
@given(mutated_parameter_dicts())
def test_any_mutated_parameter_file_loads_or_is_a_user_error(d):
    _yaml_loads_or_user_error(yaml.safe_dump(d, allow_unicode=True))


@SETTINGS
@given(st.text(max_size=400))
def test_any_yaml_text_loads_or_is_a_user_error(text):
    _yaml_loads_or_user_error(text)


@settings(max_examples=40, deadline=None, derandomize=True, database=None,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(st.binary(max_size=200))
def test_any_parameter_file_bytes_load_or_are_a_user_error(tmp_path_factory, data):
    path = tmp_path_factory.mktemp("yaml") / "p.yaml"
    path.write_bytes(data)
    try:
        load_params(path)
    except FrictionError as e:
        assert "\n" not in str(e).strip(), str(e)
