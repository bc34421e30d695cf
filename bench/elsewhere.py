"""The diagnosis on recordings of a second, independent generator (``synth/elsewhere.py``).

``synth/elsewhere.py`` was written apart from this package and from ``synth/``: a generalised
Maxwell-slip contact with a rate-dependent sliding law, its own 20 kHz integrator, a robot
joint under a PID at 500 Hz with an 18-bit encoder (74,000 samples, the speeds visited in a
shuffled order, a presliding range of one to three encoder steps) and a tribometer logged in
ms, mm and mN as a reaction force. Its effects are the issue's shapes, imposed inside its loop.
Two rules of the diagnosis were set looking at its robot joints of seeds 1–3 (the averaging
limit of eq. (8) and the rests left out, ``unresolved_rest``); seeds from 4 on were drawn after.

Each case is diagnosed as a new user would run it: ``fit`` first (no parameter file), then
``diagnose`` from that fit, the path ``leuven-friction diagnose FILE`` takes without --params.

``python -m bench.elsewhere [--seeds 1 2] [--kinds robot_joint tribometer] [--out FILE]``
prints one line a case and the confusion matrix true × named.
"""

from __future__ import annotations

import json
import sys
import time

EFFECTS = ("none", "position_ripple", "time_drift", "normal_load", "cyclic_softening")


def cases(seeds, kinds) -> list:
    """(kind, seed, effect, load_ramp): every effect on every seed and kind, and the tribometer's
    load ramped while the contact sticks (a normal-load dependence by construction)."""
    out = []
    for kind in kinds:
        for seed in seeds:
            for effect in EFFECTS:
                out.append((kind, seed, effect, False))
                if kind == "tribometer":
                    out.append((kind, seed, effect, True))
    return out


def expected(effect: str, load_ramp: bool) -> list:
    return sorted(({effect} - {"none"}) | ({"normal_load"} if load_ramp else set()))


def run_case(kind, seed, effect, load_ramp) -> dict:
    import io

    from leuven_friction.identify.data import load_recording
    from leuven_friction.identify.diagnose import diagnose
    from leuven_friction.identify.fit import fit_recordings
    from synth.elsewhere import file_stem, make

    name = file_stem(kind, seed, effect, load_ramp) + ".csv"
    row = {"case": name, "expected": expected(effect, load_ramp), "named": [], "unsettled": [], "confounded": []}
    t0 = time.perf_counter()
    try:
        df, _ = make(kind, seed, effect, load_ramp=True) if load_ramp else make(kind, seed, effect)
        buf = io.StringIO()
        df.to_csv(buf, index=False, float_format="%.10g")
        rec = load_recording(buf.getvalue().encode(), name=name)
        d = diagnose(rec, fit_recordings([rec]).params)
        row.update(named=list(d.effects), unsettled=[c["name"] for c in d.unsettled],
                   confounded=[c["effects"] for c in d.confounded], gaps=[s["rms"] for s in d.steps],
                   noise=d.noise)
    except Exception as e:  # a failure is a result too: counted, not hidden
        row["error"] = f"{type(e).__name__}: {e}"
    row["seconds"] = time.perf_counter() - t0
    return row


def main(argv=None) -> int:
    import argparse

    from bench.diagnosis import confusion, format_matrix

    ap = argparse.ArgumentParser(prog="python -m bench.elsewhere", description=__doc__.splitlines()[0])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--kinds", nargs="+", choices=("robot_joint", "tribometer"), default=["robot_joint", "tribometer"])
    ap.add_argument("--out", help="write the rows as JSON here (after every case)")
    args = ap.parse_args(argv)
    rows = []
    for kind, seed, effect, ramp in cases(args.seeds, args.kinds):
        r = run_case(kind, seed, effect, ramp)
        rows.append(r)
        print(f"{r['case']}: expected {r['expected']} named {r['named']}"
              + (f" seen, not named {r['unsettled']}" if r["unsettled"] else "")
              + (f" ERROR {r['error']}" if "error" in r else "") + f" ({r['seconds']:.1f} s)", flush=True)
        if args.out:
            with open(args.out, "w") as fh:
                json.dump({"rows": rows}, fh, indent=1)
    print(format_matrix(confusion(rows)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
