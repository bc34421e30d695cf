"""The words a recording's columns go by and the units they may be written in: what the reader
(``data.load_recording``) recognises, and what a command's ``--help`` says of it. Kept apart
from the reader, which loads numpy and pandas, so that ``--help`` does not."""

from __future__ import annotations

ALIASES = {  # header names, lower case, units stripped; the German ones as lab software writes them
    "time": ("time", "t", "timestamp", "time_s", "seconds", "zeit"),
    "position": ("position", "x", "q", "angle", "pos", "displacement", "theta", "joint_angle", "carriage", "weg",
                 "winkel"),
    "force": ("force", "torque", "applied_torque", "applied_force", "u", "tau", "motor_torque", "f", "kraft",
              "moment", "drehmoment"),
    "velocity": ("velocity", "v", "speed", "qd", "omega", "geschwindigkeit"),
    # (Ft beside Fn: a tribometer's tangential force, which is its friction)
    "friction": ("friction", "friction_force", "friction_torque", "ff", "ft", "f_t", "tangential_force",
                 "reibkraft", "reibmoment", "reibung"),
    # a slewing ring's or a pitch bearing's load is its tilting moment
    "normal_load": ("normal_load", "load", "normal_force", "fn", "f_n", "n_load", "normal", "n", "normal_load_n",
                    "force_normal", "normalforce", "normalkraft", "preload", "axial_load", "bending_moment",
                    "tilting_moment", "tilt_moment", "overturning_moment", "kippmoment", "biegemoment"),
    "temperature": ("temperature", "temp", "t_oil", "celsius", "temperatur"),
}

# a tribometer's friction coefficient, taken (times the normal load) where no friction or force column is
COF_NAMES = frozenset(("cof", "mu", "µ", "μ", "coefficient_of_friction", "friction_coefficient", "coeff_of_friction",
                       "reibwert", "reibungszahl", "reibungskoeffizient"))

UNITS_ACCEPTED = ("s, ms, us, min; m, mm, um, nm, in, mil, ft; rad, mrad, urad, deg (degree), arcmin, arcsec, rev; N, mN, uN, kN, MN, lbf (lb), ozf; "
                  "their products for a torque (N·m, N*m, N.m, N-m, mN·m, N·mm, Nmm, mNm, lbf·in, in-lb, lbf·ft) and "
                  "quotients for a speed (mm/s, in/s, deg/s, rad/s, rev/min; rpm); °C, K; any of them with a size in front "
                  "(50 nm, 0.001 deg: one step of an encoder logged in counts)")


def columns_help() -> str:
    """How a file's columns are recognised and its units read, for a command's --help (from
    ALIASES and UNITS_ACCEPTED: what the reader does, said once)."""
    import textwrap

    def para(text, indent=""):
        return textwrap.fill(text, 78, initial_indent=indent, subsequent_indent=indent + "  ")

    return "\n".join(
        [para("columns are recognised by their header names (any case; for time, position, force and friction "
              "a word of a longer name too: tau_motor, x_mm), unless --columns names them:")]
        + [para(f"{sig}: {', '.join(ALIASES[sig])}", "  ") for sig in ALIASES]
        + [para("a name that reads as a reference, model or estimate (q_ref, friction_model), or a motion's "
                "command (pos_cmd, vel_cmd), is not taken; a force's command (force_cmd) is, as the force applied."),
           para("without a friction or force column, a friction coefficient (" + ", ".join(sorted(COF_NAMES)) + ") "
                "is read as the friction divided by the normal load, which must then have a column; without a "
                "position column, the velocity is integrated into one."),
           para("units: in brackets after the name ('pos [mm]', 'time [ms]') or as its last word (x_mm); a "
                "header without one is read as SI. Known: " + UNITS_ACCEPTED + ".")])
