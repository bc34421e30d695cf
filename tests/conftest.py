import numpy as np
import pytest

from model import default_params


@pytest.fixture(scope="session")
def kuka():
    return default_params()


@pytest.fixture(scope="session")
def kuka_lugre():
    return default_params("lugre")


@pytest.fixture
def rng():
    return np.random.default_rng(12345)
