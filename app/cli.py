"""The ``leuven-friction`` command line."""

from __future__ import annotations

import argparse
import sys

from ..model.errors import FrictionError
from ..model.layout import MODEL_NAMES


class UserError(FrictionError):
    """A mistake in the command line itself: printed as one line, exit status 2."""


# one text for every command that reads a recording (the mapping itself: ``identify.data.parse_column_mapping``)
COLUMNS_HELP = ("column mapping, e.g. time=t,position=q,{example}; force=-F takes column F with its sign "
                "turned; velocity=- takes no column for a signal")
UNITS_HELP = ("units of signals, over the header's own, as its brackets would give them, e.g. "
              "'force=0.025 N*m,time=ms' (a motor current in A: its torque constant per A as the unit)")


def _params(path: str | None, model: str | None):
    from ..identify.paramfile import load_params
    from ..model import as_model, default_params

    p = load_params(path) if path else default_params()
    if path:
        from ..model.params import sanity_warnings

        for w in sanity_warnings(p):  # valid but physically odd: said, not refused
            print(f"warning: {path}: {w}", file=sys.stderr)
    return as_model(p, model) if model else p


def say_if_compiling(*modules: str, out=sys.stderr) -> bool:
    """Say so where the compiled kernels a command runs (the simulator's, ``model.kernels``, and
    any of ``modules`` besides) have no compiled cache yet: numba compiles them on their first use
    on a machine (``cache=True`` keeps them), and that run takes 30–60 s more (a fit of the sample
    36 s against 3 s once cached; a new user's first fit, beside other runs, 76 s against 8; the
    diagnosis's own kernels, compiled on its first run after a fit had compiled the simulator's,
    made a servo axis's first diagnosis 34 s against 18, unsaid). Looked up without importing
    numba (the command line starts light)."""
    import importlib.util
    import os
    from pathlib import Path

    def cached(module: str) -> bool:
        spec = importlib.util.find_spec(f"leuven_friction.{module}")
        if spec is None or not spec.origin:
            return True
        src = Path(spec.origin)
        # numba's cache: beside the source, else NUMBA_CACHE_DIR, else the user's cache directory
        places = [src.parent / "__pycache__", Path(os.environ.get("NUMBA_CACHE_DIR") or Path.home() / ".cache" / "numba")]
        return any(any(d.rglob(f"{src.stem}.*.nbi")) for d in places if d.is_dir())

    if all(cached(m) for m in ("model.kernels", *modules)):
        return False
    print("note: compiling the simulator's kernels for this machine (the first run only: 30–60 s more)", file=out)
    return True


def _recording(arg: str) -> str:
    """A recording argument: ``sample:NAME`` names a recording shipped with the package."""
    from ..sample_data import resolve

    return resolve(arg)


def _refuse_repeats(args: list[str], paths: list[str]) -> None:
    """One file given twice would count its samples twice: every σ would come out √2 too small."""
    from pathlib import Path

    seen: dict[Path, str] = {}
    for arg, path in zip(args, paths):
        key = Path(path).resolve()
        if key in seen:
            also = "" if seen[key] == arg else f" (also as {seen[key]})"
            raise UserError(f"{arg}: given twice{also}; each recording counts once in a fit")
        seen[key] = arg


def _table(result_runs, labels) -> dict:
    """The simulated series as named columns; several runs one under the other, labelled."""
    import numpy as np

    names = result_runs[0].columns().keys()
    table = {}
    if len(result_runs) > 1:
        table["run"] = np.repeat(np.asarray(labels, dtype=object), [len(r) for r in result_runs])
    for c in names:
        parts = [r.columns()[c] for r in result_runs]
        table[c] = parts[0] if len(parts) == 1 else np.concatenate(parts)
    return table


def _units_said(params, rec=None) -> str:
    """The units of the columns ``simulate`` writes (its header names carry none, so scripts
    reading ``friction_force`` keep working): the parameter set's — not said where a recording
    ``rec`` driving it is of another kind of machine (its columns are then in its own units)."""
    if rec is not None:
        from ..identify.data import other_kind_of_machine

        if other_kind_of_machine(params.units, rec.units):
            return ""
    u = params.units
    pos, force = u.get("position"), u.get("force")
    if not (pos and force):
        return ""
    t = u.get("time", "s")
    return f" (in the parameter set's units: time {t}, position and z {pos}, velocity {pos}/{t}, forces {force})"


def _write_table(table: dict, path: str) -> None:
    """CSV, or Parquet for a .parquet/.pq name; streamed into a file beside the target and
    renamed into place (nothing half-written)."""
    from ..identify.io import table_format, write_table
    from .outputs import Outputs

    with Outputs({"--out": path}) as outputs:
        staged = outputs.stage(path)
        try:
            write_table(table, staged, fmt=table_format(path))
        except OSError as e:
            raise UserError(f"--out {path}: cannot write ({e.strerror})") from None


def cmd_simulate(args) -> int:
    if args.list or args.experiment:  # the experiments import scipy: only when asked for
        from ..model.experiments import EXPERIMENTS, run_experiment
    if args.list:
        for name, (_, text) in EXPERIMENTS.items():
            print(f"{name:26s} {text}")
        return 0
    if not args.out:
        raise UserError("simulate: --out OUT.csv is required")
    from .outputs import check_output_path

    check_output_path(args.out, "--out")  # before the work
    from ..identify.io import require_pyarrow, table_format

    if table_format(args.out) == "mat":  # .mat is read, not written
        raise UserError(f"--out {args.out}: MATLAB files are read, not written; use .csv or .parquet")
    if table_format(args.out) == "parquet":
        require_pyarrow(f"--out {args.out}")  # a missing pyarrow is said before the work, naming the user's file
    params = _params(args.params, args.model)
    if args.experiment and args.smooth_path:
        raise UserError("--smooth-path: only with --input (an experiment's motion is not logged)")
    say_if_compiling()
    if args.experiment:
        if args.experiment not in EXPERIMENTS:
            raise UserError(f"--experiment: unknown {args.experiment!r}; known: {', '.join(EXPERIMENTS)}")
        if said := held_inertia_note(args.params, params, "force"):
            print(said, file=sys.stderr)
        res = run_experiment(args.experiment, params)
        table = _table(res.runs, res.labels)
        _write_table(table, args.out)
        print(f"{args.experiment} ({params.model}): {len(table['time'])} rows -> {args.out}{_units_said(params)}")
        if "drive" in res.summary:  # in the file's own scales (``model.experiments.force_scale``)
            print(f"  {res.summary['drive']}")
        return 0
    if not args.input:
        raise UserError("simulate: give --experiment NAME, --input REC.csv or --list")
    if args.smooth_path and args.drive != "displacement":
        raise UserError("--smooth-path: only with --drive displacement (the logged position is what is smoothed)")
    from ..identify.data import load_recording, parse_column_mapping, parse_unit_mapping
    from ..model.simulate import simulate_displacement, simulate_force

    cols = parse_column_mapping(args.columns)
    need = ("time", "position") if args.drive == "displacement" else ("time", "force")
    stages = _Stages()
    # only what the drive and the effects use: a gap in a friction column does not stop a simulation
    rec = load_recording(_recording(args.input), columns=cols, units=parse_unit_mapping(args.units), require=need,
                         only=need + ("normal_load",))
    stages.verbose = len(rec) >= _BIG_RECORDING
    stages.done(f"read {len(rec)} rows from {args.input}")
    say_reading(rec)
    if not args.params:
        print(default_params_warning(params.units, rec.units), file=sys.stderr)
    elif (warning := units_mismatch(args.params, params, rec)):
        print(warning, file=sys.stderr)
    if said := held_inertia_note(args.params, params, args.drive):
        print(said, file=sys.stderr)
    position = rec.position
    if args.smooth_path:
        import numpy as np

        from ..identify.diagnose import compared_path

        if len(rec) < 50:
            raise UserError(f"--smooth-path: {args.input} has {len(rec)} rows; the position's noise and encoder "
                            f"step are estimated from at least 50")
        cp = compared_path(np.asarray(rec.position, dtype=float), float(np.median(np.diff(rec.time))))
        position = cp.path
        stages.done(f"path smoothed as diagnose compares it: {cp.window} samples, wiggles below {2 * cp.h:.3g} removed")
    if params.effects:
        # a model extended by the diagnosis predicts with its effects, for either drive (the
        # one prediction path of model.effects; a force drive evaluates them along its motion)
        from ..model.effects import Signals, effect_of, predict

        loaded = [e["name"] for e in params.effects if "load" in effect_of(e["name"]).needs]
        if loaded and rec.normal_load is None:
            # said with the file and the option, before the model's own "needs the load signal"
            raise UserError(f"{args.input}: the parameter file's effect {loaded[0]} needs the normal load, and no "
                            f"column of this file is read as it: name it with --columns normal_load=<column>")

        sig = Signals(time=rec.time, position=position if args.drive == "displacement" else None,
                      force=rec.force, load=rec.normal_load)
        r = predict(params, args.drive, sig)
    elif args.drive == "displacement":
        r = simulate_displacement(params, rec.time, position)
    else:
        r = simulate_force(params, rec.time, rec.force)
    stages.done("simulated")
    _write_table(_table([r], [params.model]), args.out)
    stages.done(f"wrote {args.out}")
    print(f"{args.input} driven by {args.drive} ({params.model}): {len(r)} rows -> {args.out}{_units_said(params, rec)}")
    if said := start_state_note(params.model):
        print(f"  {said}")
    if args.drive == "displacement" and not args.smooth_path and (said := encoder_path_note(rec, params)):
        print(f"  {said}")
    return 0


def encoder_path_note(rec, params) -> str:
    """Where a displacement drive runs along a position logged in encoder steps coarse for the
    model: a step ENCODER_COARSE or more of its presliding range (the model follows each step,
    its presliding force jumping with it), or σ1 × one step per sample ENCODER_COARSE or more of
    F_s (σ1·dz/dt jumping as the velocity does, between 0 and a step per sample) — said, with
    the option that drives along the path smoothed (a spindle's 2¹⁶-count encoder, σ1 = 1.76
    N·m·s/rad, read friction peaks of twice its F_s, unsaid); "" otherwise."""
    import numpy as np

    from ..identify.diagnose import presliding_range
    from ..identify.segment import detect_noise

    step = getattr(detect_noise(np.asarray(rec.position, dtype=float)), "step", None)
    if not step or params.model not in ("leuven", "lugre"):
        return ""
    z_p = presliding_range(params)
    jump = params.sigma1 * step / float(np.median(np.diff(rec.time)))
    fs = max(abs(params.stribeck.positive.Fs), abs(params.stribeck.negative.Fs))
    if step < ENCODER_COARSE * z_p and jump < ENCODER_COARSE * fs:
        return ""
    u = params.units
    return (f"the position moves in steps of {step:.3g} {u.position} (an encoder's), {step / z_p:.2g} of the model's "
            f"presliding range {z_p:.3g}: the model follows each step, its presliding force jumping with it, and "
            f"σ1·dz/dt jumps by up to {jump:.3g} {u.force} ({jump / fs:.2g} × F_s) as the velocity does between 0 "
            f"and a step per sample; --smooth-path drives along the path smoothed as diagnose compares it")


ENCODER_COARSE = 0.1  # an encoder step this fraction of the presliding range, or σ1 × a step per sample of F_s, is said


def start_state_note(model: str) -> str:
    """What a simulation along a recording does not know: the machine's history before its first
    row. The model starts there with an empty memory (section III-B's stacks hold only the outer
    loop, F_h = 0; LuGre's z = 0), the machine from wherever its last motion left it, so the two
    may differ until the first gross sliding resets both (``diagnose``, comparing friction, starts at the first
    reversal and leaves a constant free until then: ``identify.diagnose.initial_memory``).
    A static model holds no memory: "" for it."""
    state = {"leuven": "F_h = 0, the memory holding only the outer loop", "lugre": "z = 0"}.get(model)
    if state is None:
        return ""
    return (f"the model starts at the first row with an empty memory ({state}); the machine's history before the log is not "
            f"in the file: until the first gross sliding the friction simulated may differ from the machine's by "
            f"where that history left it (diagnose compares from the first reversal on, a constant of its own "
            f"left free until that sliding)")


def say_reading(rec) -> None:
    """How a recording was read (units converted, columns ignored, rows left out), on stderr."""
    for note in rec.notes:
        print(f"{rec.source}: {note}", file=sys.stderr)


def held_inertia_note(path: str | None, params, drive: str) -> str:
    """A line where the parameter file's inertia is the built-in default (the file has none,
    ``FrictionParams.defaulted``) or was held by the fit, not estimated (its
    ``provenance.held``: a recording of measured friction does not determine it, and the fit
    keeps the built-in paper's 5 kg·m²), or "": a joint with 0.9 N·m of friction, simulated along
    its own motion, read ±91 N·m of applied force from that 5, and nothing said."""
    held = (params.provenance or {}).get("held") or {}
    what = ("the applied_force column (friction + inertia × acceleration, eq. (8)) depends on it, the friction "
            "column does not" if drive == "displacement" else "the motion simulated depends on it")
    if path and "inertia" in params.defaulted:
        # a file that leaves the inertia out holds the built-in 5 kg·m², another machine's (a
        # spindle of 0.004 kg·m², simulated from its torque, turned a hundredth of its log's angle)
        return (f"note: {path}: no inertia in the file: the built-in default {params.inertia:g} is used, not this "
                f"machine's: {what}; set this machine's inertia in the file")
    if not path or "inertia" not in held:
        return ""
    return (f"note: {path}: inertia {params.inertia:g} was held by the fit, not estimated (provenance.held.inertia "
            f"says why): {what}; set this machine's inertia in the file")


def units_said(rec_units: dict) -> str:
    """A recording's units as a warning names them: its position's, and its force's where a force
    or friction column was read (the loader fills in SI for a header without units; a simulation
    driven by the position reads no force column, whether the file has one or not)."""
    force = rec_units.get("force") or rec_units.get("friction")
    return f"{rec_units.get('position')} and {force}" if force else f"{rec_units.get('position')} (no force read)"


def default_params_warning(param_units: dict, rec_units: dict) -> str:
    """What simulating a recording without --params means: the paper's robot joint, whose
    numbers are another machine's — in other units too, when the recording's differ."""
    line = ("no --params: simulated with the built-in default, the paper's KUKA IR 361 axis 1 (give --params with "
            "this machine's parameters, e.g. from `fit`)")
    from ..identify.data import other_kind_of_machine

    if other_kind_of_machine(param_units, rec_units):
        line += (f"; its parameters are in {param_units.get('position')} and {param_units.get('force')}, the recording in "
                 f"{units_said(rec_units)}: the friction is not of this scale")
    return line


def units_mismatch(path: str, params, rec) -> str | None:
    """A warning where a parameter file and a recording are of different kinds of machine (one in
    m and N, the other in rad and N·m), or of machines of another size (its friction 30 times the
    recording's forces, or a thirtieth): the numbers would be applied to the recording as they
    are. Said, not refused: a header without units is read as SI of the kind its names suggest."""
    from ..identify.data import other_kind_of_machine, other_size_of_machine

    param_units = params.units
    if not other_kind_of_machine(param_units, rec.units):
        size = other_size_of_machine(params, rec)
        return None if size is None else (f"warning: {path}: {size}; what the data do not determine is taken from it "
                                           f"as it is (fit this recording without --params)")
    return (f"warning: {path} is in {param_units.get('position')} and {param_units.get('force')}, {rec.source} in "
            f"{units_said(rec.units)}: parameters of "
            f"another kind of machine are applied as they are (fit this recording, or write its units in its header)")


_BIG_RECORDING = 500_000  # rows from which a command says what each stage took


class _Stages:
    """A stderr line after each stage of a command on a big recording, with the time it took,
    so that on an hour-long recording the user sees the work advance and where time goes."""

    def __init__(self):
        import time

        self._clock = time.perf_counter
        self._t = self._clock()
        self.verbose = False

    def done(self, what: str) -> None:
        now = self._clock()
        if self.verbose:
            print(f"{what} ({now - self._t:.2f} s)", file=sys.stderr, flush=True)
        self._t = now


def _progress(frac, msg):
    if not sys.stderr.isatty():
        # a log file gets one plain line per stage, not a bar redrawn with carriage returns
        print(f"{int(100 * frac):3d}% {msg}", file=sys.stderr, flush=True)
        return
    bar = "#" * int(round(20 * frac))
    print(f"\r[{bar:20s}] {int(100 * frac):3d}% {msg:60s}", end="", file=sys.stderr, flush=True)


def _threshold_items(items) -> dict:
    """--threshold NAME=VALUE, repeated, as {name: number}; each item refused in one line
    unless it reads so (which names are settable is the command's to check)."""
    out = {}
    for item in items or []:
        name, sep, value = item.partition("=")
        try:
            out[name.strip()] = float(value)
        except ValueError:
            raise UserError(f"--threshold {item!r}: expected name=number") from None
        if not sep:
            raise UserError(f"--threshold {item!r}: expected name=number")
    return out


def diagnosis_kernels(space: str) -> tuple[str, ...]:
    """The modules whose compiled kernels a diagnosis runs besides the simulator's (a fit does not
    compile them): the windows' only where it compares positions — a comparison in friction
    never runs them, and naming them there said "compiling" on every run."""
    return ("identify.diagnose", "model.windows") if space == "position" else ("identify.diagnose",)


def cmd_diagnose(args) -> int:
    from ..identify.data import load_recording, parse_column_mapping, parse_unit_mapping
    from ..identify.diagnose import diagnose, reading_overrides
    from ..identify.fit import fit_recordings
    from ..identify.paramfile import params_to_yaml
    from .outputs import Outputs, json_text

    if args.softening_thresholds is not None and args.softening_thresholds < 1:
        raise UserError(f"--softening-thresholds {args.softening_thresholds}: must be at least 1 (1 tries the "
                        f"smallest significant back-travel alone)")
    reading = reading_overrides(_threshold_items(args.threshold))  # a bad setting is refused before any file is read
    outputs = Outputs({"--json": args.json, "--html": args.html, "--out": args.out})  # checked before the work
    cols = parse_column_mapping(args.columns)
    rec = load_recording(_recording(args.data), columns=cols, units=parse_unit_mapping(args.units),
                         require=("time", "position"))
    say_reading(rec)
    say_if_compiling(*diagnosis_kernels(args.space))
    if args.params:
        params = _params(args.params, None)
        if (warning := units_mismatch(args.params, params, rec)):
            print(warning, file=sys.stderr)
    else:
        print("no --params: fitting the base model first", file=sys.stderr)
        try:
            params = fit_recordings([rec]).params
        except FrictionError as e:
            raise UserError(f"diagnose: cannot fit a base model ({e}); give --params") from None
    try:
        from ..identify.diagnose import Settings

        chosen = {"space": args.space, "must_settle": args.require_settling, "refit_base": args.refit_base,
                  "reading": tuple(reading.items())}
        if args.softening_thresholds is not None:
            chosen["softening_thresholds"] = args.softening_thresholds
        d = diagnose(rec, params, progress=_progress, settings=Settings(**chosen))
    except FrictionError as e:
        print(file=sys.stderr)
        raise UserError(f"diagnose: {e}") from None
    print(file=sys.stderr)
    print(d.text())
    if args.refit_base and d.effects:
        # the option chooses what is written where nothing is named; a model with effects named
        # is refitted with them in any case
        print(f"--refit-base: not used: {', '.join(d.effects)} named, and the model written is the base refitted "
              f"with {'them' if len(d.effects) > 1 else 'it'}", file=sys.stderr)
    with outputs:  # all or none
        if args.json:
            outputs.write_text(args.json, json_text(d.summary()))
        if args.html:
            from .report import diagnosis_html

            outputs.write_text(args.html, diagnosis_html(d, args.data))
        if args.out:
            outputs.write_text(args.out, params_to_yaml(d.params_after.validate()))
    if args.out:
        what = ("with " + ", ".join(d.effects) if d.effects else
                "(its base refitted alone)" if d.params_after is not d.params_before else "(unchanged)")
        print(f"model {what} -> {args.out}{held_effects_said(d.params_after.effects, d.effects)}")
    return 0


def held_effects_said(written, named) -> str:
    """The effects a written model carries that were not named (a stiffness effect an effect was
    judged beside, held with it: ``presliding_range``), with their values, or "": a user found
    ``presliding_range e = −0.42`` in the file and nothing on the console said it."""
    held = [e for e in written if e["name"] not in named]
    if not held:
        return ""
    return "; also written, held beside them and not named: " + "; ".join(
        f"{e['name']} ({', '.join(f'{k} = {v:.3g}' for k, v in e['params'].items())})" for e in held)


def _positive_n(text: str) -> float:
    """--n: a finite number > 0 (eq. (5)'s exponent), refused with one line otherwise."""
    try:
        x = float(text)
    except ValueError:
        raise UserError(f"--n: expected a number, got {text!r}") from None
    if not (x > 0 and x < float("inf")):
        raise UserError(f"--n: the exponent n of eq. (5) must be a finite number > 0, got {text!r}")
    return x


def cmd_fit(args) -> int:
    from ..identify.data import load_recording, parse_column_mapping, parse_unit_mapping
    from ..identify.fit import fit_recordings
    from ..identify.paramfile import params_to_yaml
    from .outputs import Outputs

    n = _positive_n(args.n)  # refused before any file is read
    outputs = Outputs({"--out": args.out})  # checked before the work
    cols = parse_column_mapping(args.columns)
    base = _params(args.params, None) if args.params else None  # None: the fit says its held values are the paper's
    overrides = _threshold_items(args.threshold)
    from ..identify.segment import Thresholds

    Thresholds.checked(overrides)  # a bad setting is refused before any file is read
    # every fit finds its levels and branches in the position: a file without one is refused as it is read
    units = parse_unit_mapping(args.units)
    paths = [_recording(path) for path in args.data]
    _refuse_repeats(args.data, paths)
    recs = [load_recording(path, columns=cols, units=units, require=("time", "position")) for path in paths]
    from ..identify.segment import check_force_or_friction

    for r in recs:
        say_reading(r)
        if base is not None and (warning := units_mismatch(args.params, base, r)):
            print(warning, file=sys.stderr)
    for r in recs:
        check_force_or_friction(r)  # before the kernels' compile note: nothing will be simulated
    if not args.no_refine:
        say_if_compiling()  # the refinement simulates

    try:
        res = fit_recordings(recs, base=base, n=n, fit_n=args.fit_n, progress=_progress, thresholds=overrides,
                             friction_sign=args.friction_sign, refine=not args.no_refine)
    except FrictionError as e:
        print(file=sys.stderr)
        raise UserError(f"fit: {e}") from None
    print(file=sys.stderr)
    print(res.report())
    print(_against_friction(recs, res.params))
    with outputs:
        outputs.write_text(args.out, params_to_yaml(res.params.validate()))
    print(f"parameters -> {args.out}")
    for said in res.warnings:  # last, where it is read: the whole fit rests on it
        print(f"warning: {said}", file=sys.stderr)
    return 0


def _against_friction(recs, params) -> str:
    """The fit's report section on its friction gap per recording, as `diagnose` compares it."""
    from ..identify.diagnose import gap_by_regime
    from ..identify.errors import FrictionError

    lines = ["[[The model fitted against each recording's friction, compared as `diagnose` compares it]]"]
    for r in recs:
        try:
            lines.append(f"    {r.source}: {gap_by_regime(r, params)}")
        except FrictionError as e:
            lines.append(f"    {r.source}: not compared: {e}")
    # the fit's model may leave many noise floors where `diagnose` refits a base much closer (a
    # guideway made apart: 15.6 against 3.9); the option that writes that base is named here
    lines.append("    (`diagnose --params` with this file tells what the gap is made of; where it finds the base off "
                 "and names nothing, `diagnose --refit-base --out FILE` writes the base it refitted)")
    return "\n".join(lines)


def cmd_serve(args) -> int:
    from .listen import check_listen_address, check_served_port

    # host and port first: a bad one is a one-line error, never a hang or a silent move
    addr = check_listen_address(args.host, args.port)
    if args.data:
        from pathlib import Path

        args.data = _recording(args.data)
        if not Path(args.data).is_file():
            raise UserError(f"--data: {args.data} is not a file")
        from ..identify.data import DataError, load_recording

        try:  # said on the console as well as on the page (where its columns can still be chosen)
            load_recording(args.data)
        except DataError as e:
            print(f"--data: {e} (the explorer says so on its page too)", file=sys.stderr, flush=True)
    params = _params(args.params, None)
    warning = addr.network_warning()
    if warning:
        print(warning, file=sys.stderr, flush=True)
    from .server import serve

    serve(params, host=args.host, port=args.port, data=args.data,
          ready=lambda url: check_served_port(args.port, url))
    return 0


def cmd_bench(args) -> int:
    from .outputs import Outputs, json_text

    outputs = Outputs({"--json": args.json})  # checked before the work
    from .bench import ALL_SECTIONS, run_all

    sections = tuple(args.only.split(",")) if args.only else ALL_SECTIONS
    unknown = [s for s in sections if s not in ALL_SECTIONS]
    if unknown:
        raise UserError(f"--only: unknown section {unknown[0]!r}; known: {', '.join(ALL_SECTIONS)}")
    results = run_all(quick=args.quick, progress=lambda msg: print(msg, file=sys.stderr), sections=sections)
    print(json_text(results), end="")
    if args.json:
        with outputs:
            outputs.write_text(args.json, json_text(results))
    return 0


def cmd_samples(args) -> int:
    from pathlib import Path

    from .. import sample_data
    from .outputs import Outputs

    chosen = args.names or list(sample_data.names())
    files = {name: sample_data.path(name) for name in chosen}
    if args.list or not args.out:
        for name, path in files.items():
            print(f"sample:{path.stem:26s} {sample_data.DESCRIPTIONS.get(path.stem, '')}")
        if not args.out:
            print(f"(files in {next(iter(files.values())).parent}; copy them with --out DIR)", file=sys.stderr)
        return 0
    out_dir = Path(args.out)
    if out_dir.exists() and not out_dir.is_dir():
        raise UserError(f"--out {out_dir}: not a directory")
    if not out_dir.exists() and not out_dir.parent.is_dir():
        raise UserError(f"--out {out_dir}: directory {out_dir.parent} does not exist")
    targets = [out_dir / p.name for p in files.values()]
    for target in targets:
        if target.exists():  # a user's copy may have been edited: never overwrite it
            raise UserError(f"--out {target}: already exists; remove it or choose another directory")
    created = not out_dir.exists()
    if created:
        out_dir.mkdir()
    try:
        with Outputs([("--out", t) for t in targets]) as outputs:
            for path, target in zip(files.values(), targets):
                outputs.write_bytes(target, path.read_bytes())
    except BaseException:
        if created and not any(out_dir.iterdir()):
            out_dir.rmdir()  # all or none: not even the directory
        raise
    for target in targets:
        print(target)
    return 0


def build_parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(prog="leuven-friction", description="Leuven integrated friction model: simulate, fit, explore.")
    sub = ap.add_subparsers(dest="command", required=True)
    from ..identify.columns import columns_help

    # the commands that read a recording say how its columns and units are read
    reads_files = {"epilog": columns_help(), "formatter_class": argparse.RawDescriptionHelpFormatter}

    sv = sub.add_parser("serve", help="start the web explorer (viser)")
    sv.add_argument("--host", default="127.0.0.1", help="address to bind (default 127.0.0.1)")
    sv.add_argument("--port", type=int, default=8080, help="port (default 8080; 0 picks a free one)")
    sv.add_argument("--params", help="parameter YAML to start from (default: the paper's KUKA IR 361 axis 1)")
    sv.add_argument("--data", help="a CSV recording to fit at start (or sample:NAME, see `samples`)")
    sv.set_defaults(func=cmd_serve)

    s = sub.add_parser("simulate", help="run a paper experiment or drive the model with a recording", **reads_files)
    s.add_argument("--experiment", help="experiment name (see --list)")
    s.add_argument("--list", action="store_true", help="list the experiments")
    s.add_argument("--model", choices=MODEL_NAMES, help="model kind (default: the file's, else leuven)")
    s.add_argument("--params", help="parameter YAML (default: the paper's KUKA IR 361 axis 1)")
    s.add_argument("--input", help="recorded CSV to drive the model with (or sample:NAME)")
    s.add_argument("--drive", choices=["displacement", "force"], default="displacement",
                   help="which recorded column drives the model (default: displacement)")
    s.add_argument("--smooth-path", action="store_true",
                   help="drive along the logged position smoothed as `diagnose` compares it (encoder steps and "
                        "sensor noise are measurement, not motion; the output's position column is that path); "
                        "default: the position as logged")
    s.add_argument("--columns", help=COLUMNS_HELP.format(example="force=tau"))
    s.add_argument("--units", help=UNITS_HELP)
    s.add_argument("-o", "--out", help="output table: CSV, or Parquet for a .parquet name")
    s.set_defaults(func=cmd_simulate)

    f = sub.add_parser("fit", help="fit S(v) and the transition curve to recorded CSV data", **reads_files)
    f.add_argument("data", nargs="+", help="recorded CSV/TSV files (or sample:NAME for a shipped one, see `samples`)")
    f.add_argument("-o", "--out", required=True, help="parameter YAML to write")
    f.add_argument("--columns", help=COLUMNS_HELP.format(example="force=tau"))
    f.add_argument("--units", help=UNITS_HELP)
    f.add_argument("--params", help="starting/default parameters for what the data cannot determine")
    f.add_argument("--n", default="7", help="exponent n of eq. (5) (default 7, as the paper)")
    f.add_argument("--fit-n", action="store_true", help="estimate n as well")
    f.add_argument("--threshold", action="append", metavar="NAME=VALUE",
                   help="override a segmentation threshold derived from the data (SI units; repeatable; the report "
                        "prints them all; settable: window, v_floor, rel_tol, min_run, f_turn, x_turn, load_tol, min_travel)")
    f.add_argument("--friction-sign", choices=["auto", "action", "reaction"], default="auto",
                   help="sign convention of a measured friction column: auto detects a reaction force (positive while "
                        "the position decreases) and flips it (default auto)")
    f.add_argument("--no-refine", action="store_true", help="skip the output-error refinement")
    f.set_defaults(func=cmd_fit)

    d = sub.add_parser("diagnose", help="find the physical effect the model misses, add it, show the gap shrink", **reads_files)
    d.add_argument("data", help="recorded CSV/TSV (time, position, and friction or applied force), or sample:NAME")
    d.add_argument("--params", help="current model (default: fit the base model to the data first)")
    d.add_argument("--columns", help=COLUMNS_HELP.format(example="friction=F"))
    d.add_argument("--units", help=UNITS_HELP)
    d.add_argument("--json", help="write the result (effects named, gap per step, regimes, candidates with their "
                                  "cross-validation evidence, confounded pairs) as JSON")
    d.add_argument("--html", help="write a self-contained HTML report")
    d.add_argument("-o", "--out", help="write the extended model as YAML")
    d.add_argument("--space", choices=("friction", "position"), default="friction",
                   help="where a recording with an applied force (no friction column) is compared: friction taken "
                        "from eq. (8) averaged over a few samples (default), or position by output error of the "
                        "plant simulated in short windows")
    d.add_argument("--require-settling", action=argparse.BooleanOptionalAction, default=True,
                   help="do not name an effect whose change is not seen to settle within the session (its "
                        "saturation scale at a bound, e.g. a softening's n_c, or a drift's τ or b at a bound), since a trend along the session's schedule "
                        "would look the same: report it as seen, not named (the default). --no-require-settling "
                        "names it, with that caveat")
    d.add_argument("--refit-base", action="store_true",
                   help="where nothing is named, write (--out) the base refitted alone by output error — the level, "
                        "the presliding stiffness, n, σ1, the S(v) levels and the transition curve's segments — "
                        "instead of the file as given")
    d.add_argument("--softening-thresholds", type=int, metavar="K",
                   help="back-travels tried as what counts as a softening's reversal: the smallest significant "
                        "one × 1, 2, 4 … (K of them while 6 reversals remain; each screened, the best two fitted, "
                        "the one that fits best written; default 6; 1 tries the smallest alone, about a fifth "
                        "faster, and names fewer effects right on the hidden-effect suite; a min_excursion set "
                        "with --threshold is the one tried)")
    d.add_argument("--threshold", action="append", metavar="NAME=VALUE",
                   help="set a threshold of the motion reading instead of its derivation from the recording (SI "
                        "units; repeatable; the report's first note prints them all, marking those set): window "
                        "(the smoothing window, odd, samples: the velocity's noise and so the rest speed follow "
                        "it), v_rest (|v| below it counts as presliding), min_excursion (the back-travel of a "
                        "significant reversal, a softening's too)")
    d.set_defaults(func=cmd_diagnose)

    sm = sub.add_parser("samples", help="list the sample recordings shipped with the package, or copy them out")
    sm.add_argument("names", nargs="*", help="which samples (default: all); see --list")
    sm.add_argument("--list", action="store_true", help="list them (the default without --out)")
    sm.add_argument("-o", "--out", help="directory to copy the CSV files into (created if its parent exists)")
    sm.set_defaults(func=cmd_samples)

    b = sub.add_parser("bench", help="measure simulator (and fit) speed")
    b.add_argument("--quick", action="store_true", help="smaller problem sizes")
    b.add_argument("--only", help="comma-separated sections to run (simulator, startup, io, scale; from a source "
                   "checkout also identification, diagnosis)")
    b.add_argument("--json", help="also write the results to this JSON file")
    b.set_defaults(func=cmd_bench)
    return ap


def main(argv=None) -> int:
    args = build_parser().parse_args(argv)
    try:
        return args.func(args)
    except FrictionError as e:  # the user's mistakes only; a bug still shows as a bug
        print(f"error: {e}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130


if __name__ == "__main__":
    sys.exit(main())
