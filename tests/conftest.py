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
# slow/ (Monte Carlo, hidden-effect suites) and browser/ (real chromium) are marked here and
# selected with `pytest -m slow` / `pytest -m browser` (see `.ci/run`).
_KIND_OF_FOLDER = {"slow": pytest.mark.slow, "browser": pytest.mark.browser}


def pytest_collection_modifyitems(config, items):
    for item in items:
        folder = item.path.parent.name
        if folder in _KIND_OF_FOLDER:
            item.add_marker(_KIND_OF_FOLDER[folder])
