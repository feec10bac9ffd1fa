"""Duplex pairs of angular contact bearings (docs/studies.md, section B): preload, stiffness
from the exact Jacobian, DF/DB/DT arrangements, natural frequencies and invalid input."""

from __future__ import annotations

import dataclasses
import math
import warnings

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies.duplex import (
    PRELOAD_FRACTIONS,
    DuplexOptions,
    DuplexPair,
    ShaftSpec,
    duplex_pair,
    offset_preload,
    preload_force,
    preload_offset,
    preload_stiffness,
)
from bearingsim.catalog import get_bearing
from bearingsim.components.ball_row import row_parameters
from bearingsim.errors import ParameterError, SpeedLimitWarning
from bearingsim.physics.hertz import combined_load_deflection_constant
from bearingsim.physics.shaft_modes import MODE_NAMES, modal_analysis
from bearingsim.studies.duplex import DuplexModel, RowUnloadedWarning
from bearingsim.studies.duplex_sweep import sweep
from bearingsim.units import deg
from tests.components.test_ball_row import jones_contact_angle

ROW = row_parameters("7020C")
A = (ROW.fi + ROW.fo - 1.0) * ROW.Dw
K_BALL = combined_load_deflection_constant(ROW.K_i, ROW.K_o)


@pytest.fixture(scope="module")
def df():
    return DuplexModel("7020C", "DF")


@pytest.fixture(scope="module")
def db():
    return DuplexModel("7020C", "DB")


def _row_axial_stiffness(fa, alpha0=ROW.alpha0, z=20):
    """dFa/d(delta_a) of Jones's closed form ``Fa = Z K A^1.5 sin a g^1.5``, g = cos a0/cos a - 1
    with ``delta_a = A (cos a0 tan a - sin a0)``; analytic derivatives in a."""
    a = jones_contact_angle(fa, z, K_BALL, A, alpha0)
    g = math.cos(alpha0) / math.cos(a) - 1.0
    c = z * K_BALL * A**1.5
    dfa = c * (math.cos(a) * g**1.5
               + 1.5 * math.sin(a) * g**0.5 * math.cos(alpha0) * math.sin(a) / math.cos(a) ** 2)
    ddelta = A * math.cos(alpha0) / math.cos(a) ** 2
    return dfa / ddelta, a


@pytest.mark.parametrize("level", ["light", "medium", "heavy"])
def test_preload_and_pair_axial_stiffness_equal_the_rows_closed_form(df, level):
    force = get_bearing("7020C").preload[level]
    eq = df.equilibrium(preload=level)
    assert eq.row_axial_loads == pytest.approx([force, force], rel=1e-9)
    assert abs(eq.spacer_force) == pytest.approx(force, rel=1e-9)
    k_row, alpha = _row_axial_stiffness(force)
    assert eq.alpha_i == pytest.approx(np.full((2, 20), alpha), rel=1e-6)
    k = df.stiffness(eq)
    assert k[2, 2] == pytest.approx(2.0 * k_row, rel=1e-6)


def test_stiffness_is_the_exact_jacobian_of_the_equilibrium(df):
    eq = df.equilibrium(preload="medium", loads={"Fx": 800.0, "Fz": 300.0, "My": 40.0})
    k = df.stiffness(eq)
    base = {"Fx": 800.0, "Fz": 300.0, "My": 40.0}
    steps = {"Fx": 20.0, "Fy": 20.0, "Fz": 20.0, "Mx": 2.0, "My": 2.0}
    compliance = np.empty((5, 5))
    for j, (name, h) in enumerate(steps.items()):
        plus, minus = dict(base), dict(base)
        plus[name] = base.get(name, 0.0) + h
        minus[name] = base.get(name, 0.0) - h
        dq = (df.equilibrium(loads=plus, preload="medium").displacement
              - df.equilibrium(loads=minus, preload="medium").displacement)
        compliance[:, j] = dq / (2 * h)
    assert np.linalg.inv(compliance) == pytest.approx(k, rel=2e-4, abs=2e-4 * np.abs(k).max())


def test_df_and_db_differ_only_in_tilt_stiffness_as_pressure_centres_predict(df, db):
    eq_f, eq_b = df.equilibrium(preload="light"), db.equilibrium(preload="light")
    k_f, k_b = df.stiffness(eq_f), db.stiffness(eq_b)
    for i in (0, 1, 2):
        assert k_f[i, i] == pytest.approx(k_b[i, i], rel=1e-9)
    assert k_b[3, 3] > k_f[3, 3]
    half = 0.5 * ShaftSpec().row_spacing
    c = 0.5 * ROW.dm * math.tan(eq_f.alpha_i.mean())  # pressure centre beyond/before the row
    predicted = ((half + c) / (half - c)) ** 2
    for i in (3, 4):
        assert k_b[i, i] / k_f[i, i] == pytest.approx(predicted, rel=0.01)
        # tilt stiffness ~ sum over rows of k_radial * (pressure-centre distance)^2
        assert k_f[i, i] == pytest.approx(k_f[0, 0] * (half - c) ** 2, rel=0.02)


def test_frequencies_rise_with_preload(df):
    result = sweep(df, "preload", ["light", "medium", "heavy"])
    assert result.values == pytest.approx([540.0, 1270.0, 2550.0])
    assert np.all(np.diff(result.frequencies, axis=0) > 0)


def test_axial_mode_is_most_sensitive_to_contact_angle(df):
    result = sweep(df, "contact_angle", [deg(15.0), deg(25.0), deg(30.0)], preload=1270.0)
    change = result.relative_change()
    assert MODE_NAMES[int(np.argmax(change))] == "axial"
    assert np.all(np.diff(result.frequencies[:, MODE_NAMES.index("axial")]) > 0)


def test_swept_values_take_units(df):
    """sweep's values take numbers with a unit, as the model's arguments do (docs/units.md):
    ["15 deg", ...] raised a ValueError from float("15 deg")."""
    with_units = sweep(df, "contact_angle", ["15 deg", "25 deg"], preload="1.27 kN")
    in_si = sweep(df, "contact_angle", [deg(15.0), deg(25.0)], preload=1270.0)
    np.testing.assert_array_equal(with_units.values, in_si.values)
    np.testing.assert_allclose(with_units.frequencies, in_si.frequencies, rtol=1e-12)
    with pytest.raises(ParameterError, match=r"sweep: contact_angle: 'kg' is not a unit of rad"):
        sweep(df, "contact_angle", ["15 kg"])


def test_ball_position_angle_barely_changes_frequencies(df):
    result = sweep(df, "ball_position_angle", np.linspace(0.0, 2 * np.pi / 20, 4),
                   preload="light")
    assert np.all(result.relative_change() < 1e-3)


def test_modes_are_named_and_damped_by_the_loss_factor(df):
    modes = df.modes(preload="medium")
    assert sorted(modes.names) == sorted(MODE_NAMES)
    assert modes.damping_ratios == pytest.approx(np.full(5, 0.0025))
    assert modes.frequency("radial x") == pytest.approx(modes.frequency("radial y"), rel=1e-9)
    axial = modes.shapes[:, modes.names.index("axial")]
    assert np.argmax(np.abs(axial)) == 2
    c = modes.damping_matrix()
    phi = modes.shapes
    modal = phi.T @ c @ phi
    w = 2 * np.pi * modes.frequencies
    assert np.diag(modal) == pytest.approx(2 * 0.0025 * w, rel=1e-9)


def test_tandem_pair_shares_axial_load_equally():
    dt = DuplexModel("7020C", "DT")
    eq = dt.equilibrium(loads={"Fz": 3000.0}, preload="light")
    loads = eq.row_axial_loads
    assert loads[0] == pytest.approx(loads[1], rel=1e-9)
    assert loads.sum() == pytest.approx(3000.0 + 540.0, rel=1e-9)
    modes = modal_analysis(dt.stiffness(eq), dt.mass)
    assert np.all(modes.frequencies > 0)


def test_invalid_inputs_give_clear_errors():
    with pytest.raises(ParameterError, match="preload"):
        duplex_pair("7020C", "DF", preload=-100.0)
    with pytest.raises(ParameterError, match="preload class"):
        duplex_pair("7020C", "DF", preload="extreme")
    with pytest.raises(ParameterError, match="contact_angle"):
        duplex_pair("7020C", "DB", contact_angle=deg(50.0))
    with pytest.raises(ParameterError, match="unloaded"):
        duplex_pair("7020C", "DF", spacer_offset=+5e-6)  # DF needs a negative difference
    with pytest.raises(ParameterError, match="arrangement"):
        duplex_pair("7020C", "XX")
    with pytest.raises(ParameterError, match="preload classes"):
        duplex_pair("6204", "DF", preload="light")
    with pytest.raises(ParameterError, match="shaft"):
        duplex_pair("7020C", shaft={"radius": 0.05})
    assert math.isclose(preload_offset("7020C", 540.0, "DB"), -preload_offset("7020C", 540.0))


def test_external_load_that_unloads_a_row_warns(df):
    with pytest.warns(RowUnloadedWarning, match="row"):
        eq = df.equilibrium(loads={"Fz": 10 * 540.0}, preload="light")
    assert np.all(np.isfinite(eq.Q_i))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        df.equilibrium(loads={"Fz": 540.0}, preload="light")


def test_pair_structure_and_speed_binding():
    pair = duplex_pair("7020A", "DB", preload="heavy", speed=100.0)
    assert isinstance(pair, DuplexPair)
    assert pair.preload_force == 4310.0
    assert pair.directions == (-1, 1)
    assert pair.spacer_width_difference > 0


def test_spring_housing_acts_in_series_with_each_row():
    k_h = 5e7
    soft = DuplexModel("7020C", "DF", {"housing_stiffness": (1e9, 1e9, k_h, 1e7, 1e7),
                                       "housing_damping": (10.0,) * 5})
    eq = soft.equilibrium(preload="light")
    k = soft.stiffness(eq)
    # the housing springs lie in the preload loop too: the rows keep less than 540 N
    assert eq.row_axial_loads[0] == pytest.approx(eq.row_axial_loads[1], rel=1e-9)
    assert eq.row_axial_loads[0] < 540.0
    k_row, _ = _row_axial_stiffness(eq.row_axial_loads[0])
    assert k[2, 2] == pytest.approx(2.0 / (1.0 / k_row + 1.0 / k_h), rel=1e-6)


# ---------------------------------------------------------------- the pair's own configuration
@pytest.fixture(scope="module")
def heavy():
    return DuplexModel("7020C", "DF", pair_options={
        "preload": "heavy", "contact_angle": deg(20.0), "ball_position_angle": 0.1})


def test_pair_options_configuration_is_the_default_and_explicit_arguments_override(heavy):
    eq = heavy.equilibrium()
    assert eq.row_axial_loads == pytest.approx([2550.0, 2550.0], rel=1e-9)
    assert heavy.preload_force() == 2550.0
    params = heavy.parameters()
    assert params["row[0].alpha0"] == params["row[1].alpha0"] == pytest.approx(deg(20.0))
    assert params["row[0].psi0"] == params["row[1].psi0"] == 0.1
    # explicit arguments win over the pair's configuration
    light = heavy.equilibrium(preload="light")
    assert light.row_axial_loads == pytest.approx([540.0, 540.0], rel=1e-9)
    other = heavy.parameters(contact_angle=deg(25.0), ball_position_angle=0.0)
    assert other["row[0].alpha0"] == pytest.approx(deg(25.0))
    assert other["row[0].psi0"] == 0.0
    assert heavy.parameters(bearing="7020A")["row[0].alpha0"] == pytest.approx(
        get_bearing("7020A").free_contact_angle)
    # modes and sweeps start from the same configuration
    default = heavy.modes().frequencies
    assert default == pytest.approx(heavy.modes(preload="heavy", contact_angle=deg(20.0),
                                                ball_position_angle=0.1).frequencies, rel=1e-9)
    assert np.all(default > heavy.modes(preload="light").frequencies)
    swept = sweep(heavy, "ball_position_angle", [0.1])
    assert swept.frequencies[0] == pytest.approx([heavy.modes().frequency(n) for n in MODE_NAMES],
                                                 rel=1e-9)


def test_pair_options_speed_reaches_the_system_parameters():
    # 2000 rad/s (19 100 r/min) lies above the pair's limiting speed, 0.8 x 14 000 r/min
    with pytest.warns(SpeedLimitWarning, match="limiting speed of a pair of 7020C"):
        fast = DuplexModel("7020C", "DF", pair_options={"speed": 2000.0,
                                                        "speed_effects": True})
    with pytest.warns(SpeedLimitWarning):
        eq = fast.equilibrium()
    assert eq.parameters["shaft.speed"] == 2000.0
    at_rest = fast.equilibrium(speed=0.0)
    assert at_rest.parameters["shaft.speed"] == 0.0
    assert at_rest.row_axial_loads == pytest.approx([540.0, 540.0], rel=1e-6)
    # centrifugal ball loads raise the rows' axial load at the pair's speed
    assert np.all(eq.row_axial_loads > 1.5 * at_rest.row_axial_loads)


def test_spacer_offset_sets_the_reported_and_the_solved_preload():
    offset = preload_offset("7020C", 1270.0, "DF")
    pair = DuplexPair(DuplexOptions("7020C", "DF", spacer_offset=offset))
    assert pair.preload_force == pytest.approx(1270.0, rel=1e-9)
    assert pair.preload is None and pair.spacer_width_difference == offset
    assert offset_preload("7020C", offset, "DF") == pytest.approx(1270.0, rel=1e-9)
    with pytest.raises(ParameterError, match="either preload"):
        DuplexOptions("7020C", "DF", preload="heavy", spacer_offset=offset)
    model = DuplexModel("7020C", "DF", pair_options={"spacer_offset": offset})
    assert model.parameters()["inner_spacer.width_difference"] == offset
    assert model.equilibrium().row_axial_loads == pytest.approx([1270.0, 1270.0], rel=1e-9)
    assert model.preload_force() == pytest.approx(1270.0, rel=1e-9)
    assert model.equilibrium(preload="light").row_axial_loads == pytest.approx([540.0, 540.0],
                                                                               rel=1e-9)


def test_tandem_spacer_mismatch_shares_the_spring_preload_unequally():
    dt = DuplexModel("7020C", "DT", pair_options={"spacer_offset": 2e-6, "preload": "medium"})
    assert dt.pair.preload_force == 1270.0
    for preload, force in ((None, 1270.0), ("light", 540.0)):
        eq = dt.equilibrium(preload=preload)
        assert eq.parameters["inner_spacer.width_difference"] == 2e-6
        loads = eq.row_axial_loads
        assert loads.sum() == pytest.approx(force, rel=1e-9)
        assert loads[1] > 1.2 * loads[0]


def test_pair_options_the_studies_cannot_honour_are_rejected():
    with pytest.raises(ParameterError, match="axisymmetric"):
        DuplexModel("7020C", "DF", pair_options={"axisymmetric": True})
    with pytest.raises(ParameterError, match="unknown pair option"):
        DuplexModel("7020C", "DF", pair_options={"preloads": "heavy"})
    with pytest.raises(ParameterError, match="arrangement"):
        DuplexModel("7020C", "DF", pair_options={"arrangement": "DB"})


def test_a_speed_brings_its_effects_and_the_shaft_follows_the_bore():
    """Issue 16: DuplexModel ignored a speed unless pair_options={'speed_effects': True}, and
    every bearing got the 7020's 100 mm x 400 mm shaft without a word."""
    from bearingsim.assemblies.duplex import ShaftSpec
    from bearingsim.studies.duplex import DuplexModel

    assert duplex_pair("7014C", preload=500.0, speed=500.0).row[0].speed_effects
    assert not duplex_pair("7014C", preload=500.0).row[0].speed_effects
    assert not duplex_pair("7014C", preload=500.0, speed=500.0,
                           speed_effects=False).row[0].speed_effects
    spec = duplex_pair("7014C", preload=500.0).shaft_spec
    assert (spec.diameter, spec.length, spec.row_spacing) == pytest.approx((0.070, 0.280, 0.210))
    default = duplex_pair("7020C").shaft_spec  # the study's 7020: unchanged
    assert (default.diameter, default.length, default.row_spacing) == pytest.approx(
        (0.100, 0.400, 0.300))
    with pytest.warns(UserWarning, match="not the bore of 7014C"):
        duplex_pair("7014C", preload=500.0, shaft=ShaftSpec())
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        duplex_pair("7014C", preload=500.0, shaft={"diameter": 0.070, "length": 0.3})
    model = DuplexModel("7020C", "DF")
    with pytest.raises(ParameterError, match="without speed effects"):
        model.parameters(speed=800.0)
    assert DuplexModel("7020C", "DF", pair_options={"speed_effects": True}).parameters(
        speed=800.0)["shaft.speed"] == 800.0


# ------------------------------------------------- issue 16 item 5: preload rule and damping
def test_a_bearing_without_preload_classes_takes_a_class_as_a_fraction_of_c():
    """7014C has no catalogued classes: light/medium/heavy are PRELOAD_FRACTIONS of its C at
    15 deg; classes of catalogued bearings and forces are unchanged."""
    g = get_bearing("7014C")
    assert g.preload is None and g.dynamic_load_rating == 48500.0
    forces = [duplex_pair("7014C", "DF", preload=c).preload_force
              for c in ("light", "medium", "heavy")]
    assert forces[0] < forces[1] < forces[2]
    assert forces == pytest.approx([0.0085 * 48500.0, 0.020 * 48500.0, 0.040 * 48500.0])
    assert duplex_pair("7014C", "DB", preload=800.0).preload_force == 800.0
    assert duplex_pair("7020C", "DF", preload="medium").preload_force == 1270.0
    # 7014AC (25 deg) takes the 25 deg fractions
    assert preload_force(get_bearing("7014AC"), "medium") == pytest.approx(0.033 * 46000.0)


def test_the_preload_fractions_are_those_the_catalogued_classes_imply():
    """PRELOAD_FRACTIONS: the 7020 series' classes over the ISO 281 C of their ball set."""
    from bearingsim.physics.life import dynamic_load_rating

    for designation in ("7020C", "7020A5", "7020A"):
        g = get_bearing(designation)
        c = dynamic_load_rating(g.ball_diameter, g.pitch_diameter, g.ball_count,
                                g.contact_angle)
        implied = [getattr(g.preload, level) / c for level in ("light", "medium", "heavy")]
        table = PRELOAD_FRACTIONS[round(math.degrees(g.contact_angle))]
        assert table == pytest.approx(implied, rel=0.03)


def test_a_class_without_classes_or_c_names_the_bearing_and_the_choices():
    bare = dataclasses.replace(get_bearing("7014C"), designation="7014X",
                               dynamic_load_rating=None)
    with pytest.raises(ParameterError, match=r"7014X.*no dynamic load rating C.*preload in N"):
        duplex_pair(bare, "DF", preload="medium")
    assert duplex_pair(bare, "DF", preload=500.0).preload_force == 500.0
    with pytest.raises(ParameterError, match=r"preload class must be 'light', 'medium' or"):
        duplex_pair("7014C", "DF", preload="extreme")


def test_preload_stiffness_is_the_diagonal_of_the_exact_stiffness(df):
    pair = df.pair
    delta0 = 0.5 * abs(pair.spacer_width_difference)
    estimate = preload_stiffness(pair.geometry, pair.directions, pair.shaft_spec.positions,
                                 (delta0, delta0))
    exact = np.diag(df.stiffness(df.equilibrium()))
    assert estimate == pytest.approx(exact, rel=1e-3)


def test_damping_ratio_is_checked_and_sets_the_shaft_dampers(df):
    for bad in (-0.1, 1.5):
        with pytest.raises(ParameterError, match="damping_ratio"):
            duplex_pair("7020C", "DF", damping_ratio=bad)
    assert "shaft.c_z" not in df.system.parameter_names  # no damper, no parameters
    pair = duplex_pair("7020C", "DF", damping_ratio=0.1)
    system = assemble(pair)
    c = dict(zip(system.parameter_names, system.p0(), strict=True))
    k = np.diag(df.stiffness(df.equilibrium()))
    assert c["shaft.c_z"] == pytest.approx(2 * 0.1 * math.sqrt(k[2] * df.mass[2, 2]), rel=1e-3)
    assert c["shaft.c_ty"] == pytest.approx(2 * 0.1 * math.sqrt(k[4] * df.mass[4, 4]), rel=1e-3)


def test_the_shipped_time_domain_scene_settles_at_the_quasi_static_equilibrium(df, tmp_path):
    """duplex_pair_axial: with its damping ratio the values at t_end are the equilibrium under
    both load steps (undamped, the shaft rang for ever and t_end caught one point of it)."""
    from bearingsim.scenes import load_scene, run_scene

    scene = load_scene("duplex_pair_axial")
    assert scene.args["damping_ratio"] == 0.1
    final = run_scene(scene, tmp_path).summary["outputs"]
    eq = df.equilibrium(loads={"Fz": 2000.0, "Fx": 1000.0})
    assert final["shaft.z"]["final"] == pytest.approx(eq.displacement[2], rel=2e-3)
    assert final["shaft.x"]["final"] == pytest.approx(eq.displacement[0], rel=2e-3)
    assert final["shaft.ty"]["final"] == pytest.approx(eq.displacement[4], rel=2e-3)


def test_a_scene_gives_the_preload_by_class_by_rule_or_by_force():
    from bearingsim.scenes import SceneError, parse_scene
    from bearingsim.scenes.registry import build_component

    def pair(extra):
        scene = parse_scene('[simulation]\nt_end = 0.01\n[assembly]\nname = "duplex_pair"\n'
                            'bearing = "7014C"\n' + extra, None)
        spec = scene.spec
        return build_component(spec, spec.with_defaults(scene.args), spec.fidelities[0])

    assert pair('preload = "medium"\n').preload_force == pytest.approx(970.0)
    assert pair("preload_force = 800.0\n").preload_force == 800.0
    assert pair("").preload_force == pytest.approx(0.0085 * 48500.0)  # light by default
    with pytest.raises(ParameterError, match="either preload .* or preload_force"):
        pair('preload = "heavy"\npreload_force = 800.0\n')
    with pytest.raises(SceneError, match="preload_force"):
        pair("preload_force = -5.0\n")


def test_a_configuration_solves_its_spacer_offset_once(monkeypatch):
    """Every equilibrium recomputed the spacer offset of its preload (a Python root search over
    the balls, ~0.1 s, most of a duplex equilibrium's time); now it is solved once per
    configuration, with the same numbers."""
    import bearingsim.studies.duplex as study

    model = study.DuplexModel("7020C", "DF")
    first = model.equilibrium({"Fz": 1000.0}, preload="medium")
    calls = []
    real = study.preload_offset
    monkeypatch.setattr(study, "preload_offset", lambda *a: calls.append(a) or real(*a))
    study._spacer_offset.cache_clear()
    again = [model.equilibrium({"Fz": f}, preload="medium") for f in (1000.0, 2000.0, 500.0)]
    assert len(calls) == 1
    np.testing.assert_array_equal(again[0].state, first.state)
    assert model.parameters(preload="heavy") != model.parameters(preload="medium")
    assert len(calls) == 2
