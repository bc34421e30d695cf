"""Effects owned by the model: validation of a parameter file's entry, the factors inside the
simulation, and the count of significant reversals — each against an expectation written
out here, not taken from the code under test."""

import math

import numpy as np
import pytest

from leuven_friction.model import FrictionParams, ParameterError, SignalError, simulate_displacement, simulate_force
from leuven_friction.model.effects import EFFECTS, Context, Signals, predict, significant_reversals, validate_effect_entry


def _entry(name, **params):
    return {"name": name, "params": params}


def test_every_effect_declares_units_bounds_and_how_it_acts():
    for e in EFFECTS.values():
        assert e.acts_on in ("friction", "stiffness")
        assert e.params and all(p.unit and p.lo <= p.hi and p.description for p in e.params)
        assert e.separated_by


def test_every_effect_without_its_amplitudes_is_a_factor_of_one_and_with_them_is_not():
    # the diagnosis asks what a named effect does itself by switching it off (``Effect.without``):
    # that must leave exactly no effect, whatever its shape values, along a motion that
    # reverses, drifts in time and moves its load
    t = np.linspace(0.0, 50.0, 2001)
    x = 0.02 * np.sin(2 * np.pi * t / 7.0) + 0.001 * t
    ctx = Context(time=t, position=x, velocity=np.gradient(x, t), load=100.0 + 30.0 * np.sin(t / 3.0),
                  reversals=significant_reversals(x, 1e-4), min_excursion=1e-4,
                  friction_factor=1.0 + 0.2 * np.sin(t / 5.0))
    values = {"time_drift": {"b": 0.3, "tau": 8.0, "t0": 0.0}, "normal_load": {"alpha": 0.8, "N0": 90.0},
              "position_ripple": {"a": 0.1, "wavelength": 0.013, "phase": 0.4, "a2": 0.03, "phase2": 1.0},
              "cyclic_softening": {"h": -0.4, "n_c": 3.0, "min_excursion": 1e-4},
              "rate_stiffness": {"c1": 0.2, "c2": -0.05, "v_ref": 0.01, "v_floor": 1e-4},
              "travel_stiffness": {"c1": 0.3, "c2": -0.1, "s_ref": 0.01, "s_floor": 1e-4, "s_cap": 0.03,
                                   "min_excursion": 1e-4},
              "presliding_stiffness": {"kappa": 1.7}, "presliding_range": {"e": 0.8}}
    assert set(values) == set(EFFECTS)
    for name, v in values.items():
        e = EFFECTS[name]
        assert np.ptp(e.scale(v, ctx)) > 0.01 or abs(e.scale(v, ctx)[0] - 1.0) > 0.01, name
        off = e.without(v)
        assert np.all(e.scale(off, ctx) == 1.0), name
        assert {k: off[k] for k in v if k not in e.neutral} == {k: v[k] for k in v if k not in e.neutral}


def test_travel_stiffness_gives_each_stroke_the_power_of_the_travel_before_it():
    # strokes 0→1 (travel 1), 1→−3 (4), −3→−2.9 (0.1), −2.9→−5 (2.1), −5→−3→−3.05→20 (the 0.05
    # back-travel is no reversal): each sample's κ is (s/s_ref)^c1 of the stroke before its own,
    # the first stroke's (none before it) counted as s_cap, the 0.1 one as s_floor
    legs = [(0.0, 1.0), (1.0, -3.0), (-3.0, -2.9), (-2.9, -5.0), (-5.0, -3.0), (-3.0, -3.05), (-3.05, 20.0)]
    x = np.concatenate([np.linspace(a, b, 41)[(1 if i else 0):] for i, (a, b) in enumerate(legs)])
    ctx = Context(time=np.arange(x.size, dtype=float), position=x)
    values = {"c1": 0.5, "c2": 0.0, "s_ref": 2.0, "s_floor": 0.5, "s_cap": 8.0, "min_excursion": 0.09}
    k = EFFECTS["travel_stiffness"].scale(values, ctx)
    before = [8.0, 1.0, 4.0, 0.5, 2.1]
    lengths = [40, 40, 40, 40, x.size - 160]
    np.testing.assert_allclose(k, np.repeat([(s / 2.0) ** 0.5 for s in before], lengths), rtol=1e-12)
    # a path that never turns has no stroke before: s_cap throughout
    line = Context(time=np.arange(50.0), position=np.linspace(0.0, 5.0, 50))
    np.testing.assert_allclose(EFFECTS["travel_stiffness"].scale(values, line), 2.0)
    # a file whose floor lies above its cap is refused, naming the field
    with pytest.raises(ParameterError, match=r"e\.params\.s_floor: 9 exceeds s_cap 8"):
        validate_effect_entry({"name": "travel_stiffness", "params": {**values, "s_floor": 9.0}}, "e")


def test_position_ripple_takes_its_values_at_known_phases_at_each_wavelength_asked_in_turn():
    # 1 + a·sin(2πx/λ) + a2·sin(4πx/λ) along x = 0, 5, 10, 15, 2.5 mm: at λ = 20 mm those are
    # 0, 1/4, 1/2, 3/4, 1/8 of a wavelength, at λ = 40 mm 0, 1/8, 1/4, 3/8, 1/16. One context
    # keeps the sines of the last wavelength asked for; asking the other and then the first
    # again must give each its own values
    a, a2, r = 0.1, 0.04, 2**-0.5
    s16, s8 = math.sin(math.pi / 8), math.sin(math.pi / 4)
    ctx = Context(time=np.arange(5.0), position=np.array([0.0, 5e-3, 10e-3, 15e-3, 2.5e-3]))
    expected = {0.02: [1.0, 1.0 + a, 1.0, 1.0 - a, 1.0 + a * r + a2],
                0.04: [1.0, 1.0 + a * r + a2, 1.0 + a, 1.0 + a * r - a2, 1.0 + a * s16 + a2 * s8]}
    for lam in (0.02, 0.04, 0.02):
        f = EFFECTS["position_ripple"].scale({"a": a, "wavelength": lam, "phase": 0.0, "a2": a2, "phase2": 0.0}, ctx)
        assert f == pytest.approx(expected[lam], abs=1e-12), lam
    # a phase shifts the profile: φ = π/2 turns the sine into a cosine
    f = EFFECTS["position_ripple"].scale({"a": a, "wavelength": 0.02, "phase": math.pi / 2, "a2": 0.0}, ctx)
    assert f == pytest.approx([1.0 + a, 1.0, 1.0 - a, 1.0, 1.0 + a * r], abs=1e-12)
    # read at x0 = 5 mm, the phases count from there: at λ = 20 mm, x = 5 mm is the sine's
    # zero and x = 10 mm a quarter wavelength on; a file without x0 reads them at position 0
    f = EFFECTS["position_ripple"].scale({"a": a, "wavelength": 0.02, "phase": 0.0, "a2": 0.0, "x0": 5e-3}, ctx)
    assert f == pytest.approx([1.0 - a, 1.0, 1.0 + a, 1.0, 1.0 - a * r], abs=1e-12)
    assert validate_effect_entry(_entry("position_ripple", a=0.1, wavelength=0.02, phase=0.3), "e")["params"]["x0"] == 0.0


def test_rate_stiffness_is_a_power_of_the_speed_above_its_floor_and_capped():
    # c2 = 0: κ = (|v|/v_ref)^c1 — 1 at the reference speed, √2 at twice it (either sign of v),
    # the floor's value at rest, and at most e³ (a factor 20, the span of a stiffness factor)
    v = np.array([0.0, 1e-6, 0.01, 0.02, -0.04, 0.04, 1e3])
    k = EFFECTS["rate_stiffness"].scale({"c1": 0.5, "c2": 0.0, "v_ref": 0.02, "v_floor": 0.01},
                                        Context(time=np.arange(7.0), velocity=v))
    assert k[3] == pytest.approx(1.0)
    assert k[4] == pytest.approx(2**0.5) and k[5] == pytest.approx(2**0.5)
    assert k[:3] == pytest.approx(np.full(3, 0.5**0.5))
    assert k[6] == pytest.approx(np.e**3)
    # c2 > 0 stiffens both ends: ln κ = c2·ln²(|v|/v_ref)
    k2 = EFFECTS["rate_stiffness"].scale({"c1": 0.0, "c2": 0.1, "v_ref": 0.02, "v_floor": 1e-9},
                                         Context(time=np.arange(2.0), velocity=np.array([0.002, 0.2])))
    assert k2 == pytest.approx(np.full(2, np.exp(0.1 * np.log(10.0) ** 2)))


@pytest.mark.parametrize("entry, field", [
    (_entry("time_drift", b=0.1, tau=10.0), "effects.0.params.t0"),  # missing
    (_entry("time_drift", b=0.1, tau=10.0, t0=0.0, gamma=1.0), "effects.0.params.gamma"),  # unknown
    (_entry("normal_load", alpha=5.0, N0=1.0), "effects.0.params.alpha"),  # out of bounds
    (_entry("position_ripple", a=0.1, wavelength=0.0, phase=0.0), "effects.0.params.wavelength"),
    ({"name": "gremlins", "params": {}}, "effects.0.name"),
    ({"name": "time_drift"}, "effects.0.params"),
])
def test_a_bad_effect_entry_is_one_line_naming_the_field(kuka, entry, field):
    d = kuka.to_dict()
    d["effects"] = [entry]
    with pytest.raises(ParameterError) as e:
        FrictionParams.from_dict(d)
    msg = str(e.value)
    assert msg.startswith(field) and "\n" not in msg


def test_effect_entry_round_trips_through_the_parameter_dict(kuka):
    p = kuka.replace(effects=(_entry("time_drift", b=-0.2, tau=30.0, t0=0.0),))
    back = FrictionParams.from_dict(p.to_dict())
    assert back.effects[0]["name"] == "time_drift" and back.effects[0]["params"]["tau"] == 30.0
    assert validate_effect_entry(back.effects[0], "e")["params"]["b"] == -0.2


def test_ripple_second_harmonic_is_optional_and_acts_as_written(kuka):
    # a file written before the second harmonic existed still loads: a2 and phase2 default to 0
    e = validate_effect_entry(_entry("position_ripple", a=0.1, wavelength=0.02, phase=0.3), "e")
    assert e["params"]["a2"] == 0.0 and e["params"]["phase2"] == 0.0
    t = np.arange(5000) * 1e-3
    x = 0.01 * t  # one direction, 2.5 wavelengths
    base = simulate_displacement(kuka, t, x).friction_force
    p = kuka.replace(effects=(_entry("position_ripple", a=0.1, wavelength=0.02, phase=0.3, a2=0.04, phase2=-1.0),))
    got = predict(p, "displacement", Signals(time=t, position=x)).friction_force
    th = 2 * np.pi * x / 0.02
    assert np.allclose(got, base * (1 + 0.1 * np.sin(th + 0.3) + 0.04 * np.sin(2 * th - 1.0)), rtol=1e-12, atol=1e-9)


def test_friction_factor_along_a_displacement_is_the_physical_law(kuka):
    t = np.arange(20000) * 1e-3
    x = 0.05 * np.sin(2 * np.pi * 0.25 * t)
    load = 800.0 + 300.0 * np.sin(2 * np.pi * 0.07 * t)
    base = simulate_displacement(kuka, t, x).friction_force
    p = kuka.replace(effects=(_entry("time_drift", b=0.3, tau=5.0, t0=0.0), _entry("normal_load", alpha=0.7, N0=800.0)))
    got = predict(p, "displacement", Signals(time=t, position=x, load=load)).friction_force
    law = (1 + 0.3 * (1 - np.exp(-t / 5.0))) * (load / 800.0) ** 0.7
    assert np.allclose(got, base * law, rtol=1e-12, atol=1e-9)


def test_a_force_driven_plant_feels_the_friction_factor(kuka):
    # constant applied force above F_s+ of the base model but below 1.5·F_s+: the plant
    # without the effect breaks away; with friction ×1.5 everywhere (a settled drift) it sticks
    t = np.arange(4000) * 1e-3
    f = np.full(len(t), 1.2 * kuka.stribeck.positive.Fs)
    free = simulate_force(kuka, t, f)
    held = predict(kuka.replace(effects=(_entry("time_drift", b=0.5, tau=1e-6, t0=-1.0),)), "force",
                   Signals(time=t, force=f))
    assert free.position[-1] > 1e-2
    assert abs(held.position[-1]) < 1e-3  # presliding only: within the transition curve's range


def test_ripple_in_a_force_drive_is_evaluated_along_the_simulated_motion(kuka):
    t = np.arange(6000) * 1e-3
    f = np.full(len(t), 1.6 * kuka.stribeck.positive.Fs)
    lam = 0.05
    eff = _entry("position_ripple", a=0.3, wavelength=lam, phase=0.0)
    r = predict(kuka.replace(effects=(eff,)), "force", Signals(time=t, force=f))
    # the plant feels the friction it reports: momentum balance I·Δv = Σ (f − F)·dt (eq. (8))
    dt = np.diff(t)
    assert kuka.inertia * (r.velocity[-1] - r.velocity[0]) == pytest.approx(np.sum((f[1:] - r.friction_force[1:]) * dt),
                                                                            rel=0.02)
    # and the ripple rides on its own motion: the friction correlates with the ripple at its
    # own positions, and divided by it, no longer does
    s = slice(2000, None)
    ripple = np.sin(2 * np.pi * r.position[s] / lam)
    F = r.friction_force[s]
    assert np.corrcoef(F, ripple)[0, 1] > 0.5
    assert abs(np.corrcoef(F / (1 + 0.3 * ripple), ripple)[0, 1]) < 0.1


def test_significant_reversals_ignore_wiggles_below_the_threshold():
    rng = np.random.default_rng(3)
    turns = np.array([0.0, 1.0, 0.2, 0.9, 0.1, 0.5])
    x = np.concatenate([np.linspace(a, b, 200) for a, b in zip(turns[:-1], turns[1:])])
    noisy = x + rng.uniform(-0.01, 0.01, len(x))
    assert significant_reversals(x)[-1] == 4
    assert significant_reversals(noisy, 0.05)[-1] == 4
    assert significant_reversals(noisy, 0.0)[-1] > 50


def test_a_softening_counts_only_the_reversals_past_its_own_threshold():
    # four small cycles (back-travel 0.1) then three large ones (back-travel 1): a softening
    # whose min_excursion is 0.5 has counted none of the small ones, whatever the context's own
    # threshold; with n_c tiny the factor is 1 before its first counted reversal and 1 + h after
    turns = [0.0, 0.1, 0.0, 0.1, 0.0, 0.1, 0.0, 0.1, 0.0, 1.0, 0.0, 1.0, 0.0]
    x = np.concatenate([np.linspace(a, b, 50, endpoint=False) for a, b in zip(turns[:-1], turns[1:])])
    t = np.arange(len(x), dtype=float)
    ctx = Context(time=t, position=x, reversals=significant_reversals(x, 0.05), min_excursion=0.05)
    assert ctx.reversals[-1] == 11
    soft = EFFECTS["cyclic_softening"]
    k = soft.scale({"h": -0.5, "n_c": 1e-9, "min_excursion": 0.5}, ctx)
    first_big_turn = 9 * 50  # the turn at 1.0 (counted at the turning point itself)
    assert np.all(k[:first_big_turn] == 1.0)
    assert np.allclose(k[first_big_turn + 30:], 0.5)
    assert ctx.reversals_above(0.5, "cyclic_softening")[-1] == 3


def test_softening_factor_scales_the_presliding_stiffness(kuka):
    # after a reversal F_h follows F_b + F_d(κ·z) (eq. (4) with the stiffness factor): with
    # κ = 0.5 the force change over a small displacement is Table II's curve at half of it
    t = np.arange(3000) * 1e-3
    x = np.concatenate([np.linspace(0, 1e-3, 1000), np.linspace(1e-3, 0, 1000), np.linspace(0, 1e-3, 1000)])
    eff = _entry("cyclic_softening", h=-0.5, n_c=1e-6, min_excursion=0.0)  # saturated at once: κ = 0.5
    z_knots, F_knots = np.array(kuka.transition_curve.z), np.array(kuka.transition_curve.F)
    for kappa, p in ((1.0, kuka), (0.5, kuka.replace(effects=(eff,)))):
        fh = predict(p, "displacement", Signals(time=t, position=x)).hysteresis_force
        k = np.arange(2001, 2012)
        dx = x[k] - x[2000]
        expected = np.interp(kappa * dx, z_knots, F_knots)
        assert np.allclose(fh[k] - fh[2000], expected, rtol=0.03), kappa


def test_a_presliding_range_following_the_friction_factor_keeps_the_stiffness_and_scales_the_break_away(kuka):
    # a load at twice its reference with α = 1 doubles F (eq. (3) scaled whole): Table II's curve
    # at twice its forces, the spring twice as stiff. With the presliding range following that
    # factor as m^e the curve is m·F_d(z/m^e): e = 1 keeps the initial stiffness and still
    # doubles the force where the curve has saturated; e = 0.5 stiffens by √2
    t = np.arange(3000) * 1e-3
    x = np.concatenate([np.linspace(0, 2e-3, 1000), np.linspace(2e-3, -2e-3, 1000), np.linspace(-2e-3, 0, 1000)])
    load = np.full(len(t), 200.0)
    z_knots, F_knots = np.array(kuka.transition_curve.z), np.array(kuka.transition_curve.F)
    m = 2.0
    double = _entry("normal_load", alpha=1.0, N0=100.0)
    k = np.arange(1001, 1011)  # just after the reversal at 2 mrad
    dx = x[1000] - x[k]
    plain = predict(kuka, "displacement", Signals(time=t, position=x)).hysteresis_force
    for e in (None, 1.0, 0.5):
        effects = (double,) if e is None else (double, _entry("presliding_range", e=e))
        fh = predict(kuka.replace(effects=effects), "displacement", Signals(time=t, position=x, load=load)).hysteresis_force
        stretch = 1.0 if e is None else m**e
        expected = m * np.interp(dx / stretch, z_knots, F_knots)
        assert np.allclose(fh[1000] - fh[k], expected, rtol=0.03), e
        # 4 mrad back is far beyond the curve's last knot, in gross sliding: the change from
        # one sliding direction to the other is the model's without the load, doubled
        assert fh[1000] - fh[1999] == pytest.approx(m * (plain[1000] - plain[1999]), rel=0.02), e


def test_a_presliding_range_needs_a_friction_factor_and_is_one_without_friction_effects():
    ctx = Context(time=np.arange(4.0))
    with pytest.raises(ParameterError, match="friction factor"):
        EFFECTS["presliding_range"].scale({"e": 1.0}, ctx)
    from leuven_friction.model.effects import effect_scales

    fs, ss = effect_scales([_entry("presliding_range", e=0.7)], ctx)
    assert fs is None and np.all(ss == 1.0)
    fs, ss = effect_scales([_entry("presliding_range", e=0.5), _entry("time_drift", b=3.0, tau=1e-9, t0=0.0)], ctx)
    assert fs == pytest.approx([1.0, 4.0, 4.0, 4.0]) and ss == pytest.approx([1.0, 0.5, 0.5, 0.5])


def test_effect_values_are_printed_with_the_units_of_the_parameter_set():
    from leuven_friction.model.effects import format_values

    txt = format_values("cyclic_softening", {"h": -0.5888, "n_c": 8.778, "min_excursion": 3.641e-7},
                        {"position": "m", "force": "N", "time": "s"})
    assert txt == "h = -0.5888, n_c = 8.778 reversals, min_excursion = 3.641e-07 m"
    assert format_values("time_drift", {"b": 0.1, "tau": 30.0, "t0": 0.0}, {"position": "rad"}) == \
        "b = 0.1, tau = 30 s, t0 = 0 s"
    assert "v_ref = 0.02 rad/s" in format_values("rate_stiffness", {"c1": 0.1, "v_ref": 0.02},
                                                 {"position": "rad", "time": "s"})
    # an estimated value carries its 1-σ before the unit; a held one (no σ) is printed bare
    assert format_values("cyclic_softening", {"h": -0.5999, "n_c": 22.04, "min_excursion": 7.9e-7},
                         {"position": "m"}, {"h": 0.068, "n_c": 3.6}) == \
        "h = -0.5999 ± 0.068, n_c = 22.04 ± 3.6 reversals, min_excursion = 7.9e-07 m"


def test_a_shape_whose_amplitude_is_within_two_sigma_of_none_is_said_not_determined():
    # a second harmonic of magnitude 0.0055 whose sine and cosine parts have σ 0.011 each
    # (√((0.0073² + (0.0055·2.4)²)/2)): pure noise passes 2.45 such σ in 5 % of records, this
    # one does not, so where it lies says nothing and its phase gets no σ; the fundamental,
    # 0.089 against parts of σ 0.0046, keeps its phase's σ
    from leuven_friction.model.effects import EFFECTS, format_values

    ripple = {"a": 0.089, "wavelength": 0.0827, "phase": 2.38, "a2": 0.0055, "phase2": 1.14}
    sd = {"a": 0.004, "wavelength": 0.0006, "phase": 0.057, "a2": 0.0073, "phase2": 2.4}
    assert set(EFFECTS["position_ripple"].undetermined(ripple, sd)) == {"phase2"}
    txt = format_values("position_ripple", ripple, {"position": "rad"}, sd)
    assert "phase = 2.38 ± 0.057 rad" in txt
    # (the σ counted, 0.0055/0.01067, then the bar it misses)
    assert "phase2 = 1.14 rad (not determined: a2 = 0.0055 is 0.52 σ from 0, within the 2.45 σ a magnitude must " \
           "pass (σ 0.011 of its" in txt, txt
    # a drift's b = −0.25 ± 0.14 (a warm-up that came and went, fitted as one approach) is 1.8 σ
    # from none: its τ is not determined, said with the σ counted
    txt = format_values("time_drift", {"t0": 24.86, "b": -0.2496, "tau": 61.77}, {"time": "s"}, {"b": 0.14, "tau": 40.0})
    assert "tau = 61.77 s (not determined: b = -0.25 ± 0.14 is 1.8 σ from 0, within 2 σ)" in txt, txt
    # a value written without a σ because the file holds it (provenance.held: not determined in
    # the model written) says why, where it had read as a plain value; a σ is not shown for it
    held = {"b": "not determined: b = 0.285 ± 3.1: its σ exceeds the whole (100%) of what it scales"}
    txt = format_values("time_drift", {"t0": 0.722, "b": 0.2846, "tau": 20.87}, {"time": "s"}, {}, held)
    assert txt == ("t0 = 0.722 s, b = 0.2846 (not determined: b = 0.285 ± 3.1: its σ exceeds the whole (100%) of what "
                   "it scales), tau = 20.87 s"), txt
    # the wavelength is the period of both harmonics: undetermined only when neither shows
    weak_fundamental = {**ripple, "a": 0.001, "a2": 0.05}
    sd2 = {**sd, "a": 0.002, "phase": 3.0, "a2": 0.002, "phase2": 0.04}
    assert set(EFFECTS["position_ripple"].undetermined(weak_fundamental, sd2)) == {"phase"}
    assert set(EFFECTS["position_ripple"].undetermined({**weak_fundamental, "a2": 0.001},
                                                       {**sd2, "phase2": 3.0})) == {"phase", "phase2", "wavelength"}
    # a drift of b = 0.01 ± 0.02, or of b = −0.03 ± 0.02, has no time constant to speak of; at
    # b = 0.1 ± 0.02 it has
    drift = {"b": 0.01, "tau": 30.0, "t0": 0.0}
    assert set(EFFECTS["time_drift"].undetermined(drift, {"b": 0.02, "tau": 50.0})) == {"tau"}
    assert set(EFFECTS["time_drift"].undetermined({**drift, "b": -0.03}, {"b": 0.02, "tau": 50.0})) == {"tau"}
    assert EFFECTS["time_drift"].undetermined({**drift, "b": 0.1}, {"b": 0.02, "tau": 5.0}) == {}
    # … and a drift shown (b = −0.218 ± 0.045) whose τ of 25.9 s has a σ of 71 s: how fast it comes
    # is not shown; with a σ of 20 s it is
    warm = {"b": -0.218, "tau": 25.9, "t0": 4.7}
    assert set(EFFECTS["time_drift"].undetermined(warm, {"b": 0.045, "tau": 71.0})) == {"tau"}
    assert EFFECTS["time_drift"].undetermined(warm, {"b": 0.045, "tau": 20.0}) == {}
    # a drift's b = 0.30 ± 2.9 bounds nothing — friction falling to 5 % or rising sevenfold
    # within 2 σ — so it is not determined either, nor its τ; b = 0.30 ± 0.9 is an estimate (a
    # weak one, not told from none, so its τ is not determined)
    assert set(EFFECTS["time_drift"].undetermined({**drift, "b": 0.2993}, {"b": 2.9, "tau": 5.0})) == {"b", "tau"}
    assert set(EFFECTS["time_drift"].undetermined({**drift, "b": 0.2993}, {"b": 0.9, "tau": 5.0})) == {"tau"}
    assert set(EFFECTS["cyclic_softening"].undetermined({"h": -0.3, "n_c": 9.0, "min_excursion": 1e-6},
                                                        {"h": 1.4, "n_c": 2.0})) == {"h", "n_c"}
    # a softening's sign does not matter: h = −0.3 ± 0.05 is 6 σ from none
    assert EFFECTS["cyclic_softening"].undetermined({"h": -0.3, "n_c": 9.0, "min_excursion": 1e-6},
                                                     {"h": 0.05, "n_c": 2.0}) == {}
    # without the amplitude's σ (held, or not estimated) nothing is judged
    assert EFFECTS["position_ripple"].undetermined(ripple, {}) == {}


def test_significant_reversals_step_up_at_each_turning_point():
    # a zigzag through known extrema, sampled so each extremum is a sample: the count steps by
    # one exactly at every turning point whose back-travel exceeds the threshold, and stays
    # flat over a dwell
    ends = [0.0, 1.0, 0.3, 0.35, -0.5, 0.2]
    x = np.concatenate([np.linspace(a, b, 40, endpoint=False) for a, b in zip(ends[:-1], ends[1:])] + [[ends[-1]]])
    x = np.concatenate([x[:100], np.full(25, x[100]), x[100:]])  # a dwell mid-stroke
    turns_at = [i for i in range(1, len(x) - 1) if (x[i] - x[i - 1]) * (x[i + 1] - x[i]) < 0]
    assert len(turns_at) == 4
    steps = np.flatnonzero(np.diff(significant_reversals(x, 0.0)) > 0) + 1
    assert steps.tolist() == turns_at
    with pytest.raises(SignalError, match="1-D"):
        significant_reversals(np.vstack([x, x]))
    big = np.flatnonzero(np.diff(significant_reversals(x, 0.1)) > 0) + 1
    # above a 0.1 threshold the 0.3 → 0.35 wiggle (a back-travel of 0.05) is no pair of
    # reversals: the stroke from 1.0 runs on to −0.5, and only the turns at 1.0 and −0.5 count
    assert big.tolist() == [turns_at[0], turns_at[3]]


def test_a_factor_asked_for_again_follows_its_new_values():
    # the context keeps the factors it made; asked for at other values — as a Jacobian moves
    # one parameter, then goes back — each must be the closed form at those values
    t = np.linspace(0.0, 10.0, 501)
    x = 0.01 * np.sin(t)
    load = 50.0 + 20.0 * np.sin(t / 2.0)
    ctx = Context(time=t, position=x, velocity=np.gradient(x, t), load=load)
    for alpha in (1.0, 0.5, 2.0, 1.0, 0.7, 1.3, 0.9, 2.4, 1.0, 0.5):
        got = EFFECTS["normal_load"].scale({"alpha": alpha, "N0": 50.0}, ctx)
        np.testing.assert_allclose(got, (load / 50.0) ** alpha, rtol=1e-14)
    for lam in (0.004, 0.005, 0.004, 0.006, 0.007, 0.0045, 0.004):
        got = EFFECTS["position_ripple"].scale({"a": 0.1, "wavelength": lam, "phase": 0.3}, ctx)
        np.testing.assert_allclose(got, 1.0 + 0.1 * np.sin(2 * np.pi * x / lam + 0.3), rtol=1e-12)
    # an effect of the same name with another factor is another effect, not a cache hit
    import dataclasses

    halved = dataclasses.replace(EFFECTS["normal_load"], factor=lambda v, c: 0.5 * (c.load / v["N0"]) ** v["alpha"])
    np.testing.assert_allclose(halved.scale({"alpha": 1.0, "N0": 50.0}, ctx), 0.5 * load / 50.0, rtol=1e-14)
    for c1 in (0.2, -0.1, 0.2):
        got = EFFECTS["rate_stiffness"].scale({"c1": c1, "c2": 0.0, "v_ref": 0.01, "v_floor": 1e-4}, ctx)
        np.testing.assert_allclose(got, (np.maximum(np.abs(ctx.velocity), 1e-4) / 0.01) ** c1, rtol=1e-12)


@pytest.mark.parametrize("name,values,word", [
    ("cyclic_softening", {"h": 0.43, "n_c": 3.0, "min_excursion": 1e-6}, "hardening"),
    ("cyclic_softening", {"h": -0.3, "n_c": 3.0, "min_excursion": 1e-6}, "softening"),
    ("time_drift", {"b": -0.2, "tau": 40.0, "t0": 0.0}, "friction falling"),
    ("time_drift", {"b": 0.0, "tau": 40.0, "t0": 0.0}, ""),
    ("position_ripple", {"a": 0.1, "wavelength": 5e-3, "phase": 0.0}, ""),
])
def test_a_signed_effect_says_which_way_it_acts(name, values, word):
    # a contact that stiffens with its reversals is named cyclic_softening with h > 0: the
    # report says "hardening" beside the name rather than leave it to the sign
    assert EFFECTS[name].sense_of(values) == word
