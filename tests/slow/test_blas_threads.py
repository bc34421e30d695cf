"""The same recording gives the same fit and the same diagnosis whatever number of BLAS threads
numpy is given (``identify.threads``): OpenBLAS shares a reduction out among its threads, and
the rounding that follows had moved a diagnosis's gaps between one thread and two."""

import json
import os
import subprocess
import sys

from synth.hidden import SUITE_RATE, make_case

CLI = "import sys; from leuven_friction.app.cli import main; sys.exit(main(sys.argv[1:]))"


def _run(args: list, cwd, threads: int) -> None:
    env = dict(os.environ, OPENBLAS_NUM_THREADS=str(threads), OMP_NUM_THREADS=str(threads), MKL_NUM_THREADS=str(threads))
    r = subprocess.run([sys.executable, "-c", CLI, *args], cwd=cwd, env=env, capture_output=True, text=True)
    assert r.returncode == 0, r.stderr[-3000:]


def test_fit_and_diagnosis_are_the_same_on_one_blas_thread_and_on_two(tmp_path):
    # a robot joint with a hidden ripple, whose diagnosis named the ripple and a softening on
    # either thread count, with the gaps after them apart in the ninth digit
    df, _, _ = make_case("robot_joint", 1029, ("position_ripple",), rate=SUITE_RATE["robot_joint"])
    out = {}
    for threads in (1, 2):
        run = tmp_path / str(threads)
        run.mkdir()
        df.to_csv(run / "joint.csv", index=False)
        _run(["fit", "joint.csv", "--out", "fit.yaml"], run, threads)
        _run(["diagnose", "joint.csv", "--params", "fit.yaml", "--json", "report.json"], run, threads)
        fitted = [line for line in (run / "fit.yaml").read_text().splitlines() if not line.strip().startswith("date:")]
        report = json.loads((run / "report.json").read_text())
        report.pop("work")  # wall time
        out[threads] = fitted, report
    assert out[1][0] == out[2][0]
    assert out[1][1]["effects"], out[1][1]  # the diagnosis compared names something here
    assert out[1][1] == out[2][1]
