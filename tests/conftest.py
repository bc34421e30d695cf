from pathlib import Path

import numpy as np
import pytest

from leuven_friction.model import default_params


@pytest.fixture(scope="session")
def kuka():
    return default_params()


@pytest.fixture(scope="session")
def kuka_lugre():
    return default_params("lugre")


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


# The suite's kinds are its folders: unit/ and integration/ run by default (`pytest -q`),
# slow/ (Monte Carlo, diagnosis of unseen recordings, the wheel check) and browser/ (real chromium) are marked here and
# selected with `pytest -m slow` / `pytest -m browser` (see `.ci/run`).
_KIND_OF_FOLDER = {"slow": pytest.mark.slow, "browser": pytest.mark.browser}


def _kind_selected(kind: str, markexpr: str) -> bool:
    if not markexpr:
        return True
    try:
        from _pytest.mark.expression import Expression

        return bool(Expression.compile(markexpr).evaluate(lambda name, **_: name == kind))
    except Exception:  # an expression this cannot read: collect, and let -m deselect as usual
        return True


def pytest_ignore_collect(collection_path, config):
    # a kind that -m deselects is not even imported: `pytest -q` does not pay for (or trip
    # over) the browser and statistical suites' imports
    if collection_path.parent == Path(__file__).parent and collection_path.name in _KIND_OF_FOLDER:
        if not _kind_selected(collection_path.name, config.getoption("markexpr")):
            return True
    return None


def pytest_collection_modifyitems(config, items):
    for item in items:
        folder = item.path.parent.name
        if folder in _KIND_OF_FOLDER:
            item.add_marker(_KIND_OF_FOLDER[folder])
