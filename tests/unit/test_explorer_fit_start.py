"""What a fit in the explorer starts from: the page's current set only where it can be this
machine's. The built-in default is the paper's robot joint (σ1 1500, I 5 in rad and N·m), and
a fit that started from it kept those on a 25 kg ball-screw in m and N."""

import numpy as np
import pytest

from leuven_friction.app.explorer.data_tab import fit_start
from leuven_friction.identify.data import load_recording
from leuven_friction.model import default_params


def _rec(position_unit: str, force: float = 40.0):
    # forces of the size of the built-in set's static friction (36 and 63 N·m) unless told
    t = np.arange(200) * 1e-3
    text = f"time [s],position [{position_unit}],force [N]\n" + "".join(f"{a},{np.sin(a)},{force * np.cos(a)}\n"
                                                                      for a in t)
    return load_recording(text, name="r.csv")


@pytest.mark.parametrize("model", ["leuven", "lugre", "static"])
def test_the_built_in_default_is_no_start(model):
    assert fit_start(default_params(model), _rec("rad")) is None


def test_a_set_in_other_units_than_the_recording_is_no_start():
    mine = default_params().replace(inertia=2.0)  # changed, but in rad and N·m
    assert fit_start(mine, _rec("mm")) is None


def test_a_set_of_this_machine_is_the_start():
    mine = default_params("lugre").replace(inertia=2.0)
    start = fit_start(mine, _rec("rad"))
    assert start is not None and start.inertia == 2.0 and start.model == "leuven"


def test_a_set_whose_friction_is_of_another_size_than_the_recordings_forces_is_no_start():
    # a telescope mount's set (static friction 63 N·m here) and a pitch bearing's forces of
    # 40 kN·m, both in rad and N·m: its inertia and σ1 would be held on the bearing
    from leuven_friction.app.explorer.data_tab import other_machine

    mine = default_params().replace(inertia=2.0)
    assert fit_start(mine, _rec("rad", force=4e4)) is None
    assert "another machine's" in other_machine(mine, _rec("rad", force=4e4))
    assert fit_start(mine, _rec("rad", force=0.5)) is None  # 126 × the other way
    assert other_machine(mine, _rec("rad", force=4.0)) is None  # 16 ×: within the same machine's range
