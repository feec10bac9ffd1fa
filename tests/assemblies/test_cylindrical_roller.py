"""The cylindrical roller bearing (issue 29, item 3): line contact, ratings and life, the roller
row, the product's levels, its scene and its FMU (the checks against published numbers are in
tests/physics/test_published_roller_checks.py, part of the validation report).

Sources (cited per test):

* SKF General Catalogue 6000 (Russian edition, data as of 2006): NU 2xx/3xx ECP product tables
  and dimension tables pp. 522-533; clearance p. 512 Table 1; friction pp. 92-101.
* NSK Rolling Bearings CAT. No. E1102e: single-row cylindrical roller bearings pp. B84-B85;
  Technical Data section 15.1 (2), p. A 129 (roller approach constant 0.000077).
* NSK technical report CAT. No. E728g, section 5.1, eqs. (4), (5): ``Q_max = 4.37 Fr/(Z cos a)``
  (point contact), ``4.08 Fr/(Z cos a)`` (line contact), zero clearance.
* ISO 281:2007 Table 7 (fc of radial roller bearings) and its constants 207.9 and 1.04.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim.assembler import assemble
from bearingsim.assemblies.cylindrical_roller import (
    CylindricalRollerOptions,
    cylindrical_roller_bearing,
)
from bearingsim.catalog import get_bearing
from bearingsim.catalog.rollers import (
    get_roller_bearing,
)
from bearingsim.components.ball_row import BallRow, row_parameters
from bearingsim.components.roller_row import (
    RollerRow,
    roller_row_equilibrium,
    roller_row_loads,
    roller_row_parameters,
    roller_row_stiffness,
)
from bearingsim.components.rolling_element import (
    ElementGeometry,
    ElementRow,
    LineContact,
    PointContact,
    friction_key,
    resolve_geometry,
    static_equivalent_load,
)
from bearingsim.errors import CatalogError, ParameterError
from bearingsim.physics.contact_law import contact_load
from bearingsim.physics.friction import palmgren_m0
from bearingsim.physics.hertz import combined_load_deflection_constant
from bearingsim.physics.life import (
    roller_reference_rating_life,
)
from bearingsim.physics.line_contact import (
    palmgren_deflection,
    palmgren_load,
    slice_loads,
)
from bearingsim.simulation import simulate

NU206 = get_roller_bearing("NU206")


# ----------------------------------------------------------------------------- line contact


@settings(max_examples=50, deadline=None)
@given(load=st.floats(1.0, 1e5), length=st.floats(1e-3, 0.05), n=st.integers(1, 20))
def test_line_contact_inverse_and_slices(load, length, n):
    delta = palmgren_deflection(load, length)
    assert palmgren_load(delta, length) == pytest.approx(load, rel=1e-10)
    assert sum(slice_loads([delta] * n, length)) == pytest.approx(load, rel=1e-10)
    assert palmgren_load(-delta, length) == 0.0
    # a gap of 1000 regularization lengths carries (1e-3 / 4)^(10/9) of the load: nothing
    assert 0.0 < palmgren_load(-delta, length, smooth=1e-3 * delta) < 1e-7 * load


# ----------------------------------------------------------------------------- roller row


def test_clearance_narrows_the_load_zone():
    """With the normal clearance (32.5 um) fewer rollers carry more (Q_max Z / Fr > 4.08)."""
    p = roller_row_parameters(NU206)
    q = np.array(roller_row_equilibrium(p, 12, 10, (5000.0, 0.0)).contacts.Q)
    assert q.max() * 12 / 5000.0 > 5.0
    assert np.count_nonzero(q > 1.0) < 6


def test_misalignment_loads_the_roller_ends_and_costs_life():
    """A tilt about y moves the load of the rollers at psi = 0 to one end (edge loading of the
    straight roller), needs a moment from the shaft, odd in the tilt, raises p_max and lowers
    the ISO/TS 16281 life."""
    p = roller_row_parameters(NU206)
    straight = roller_row_equilibrium(p, 12, 10, (8000.0, 0.0))
    tilted = roller_row_equilibrium(p, 12, 10, (8000.0, 0.0), (0.0, 1e-3))
    back = roller_row_equilibrium(p, 12, 10, (8000.0, 0.0), (0.0, -1e-3))
    slices = tilted.contacts.q[0]
    assert np.all(np.diff(slices) > 0) and slices[-1] > 1.5 * slices[0]
    assert tilted.moment[1] == pytest.approx(-back.moment[1], rel=1e-9)
    assert abs(tilted.moment[1]) > 1.0 and abs(straight.moment[1]) < 1e-6
    assert max(tilted.contacts.p_max) > 1.1 * max(straight.contacts.p_max)
    life = [roller_reference_rating_life(e.contacts.q, e.contacts.q, NU206.dynamic_load_rating,
                                         NU206.gamma) for e in (straight, tilted)]
    assert life[1] < 0.9 * life[0]  # 16 % lower at 1 mrad and 8 kN


def test_roller_life_is_consistent_with_iso_281_and_line_contact():
    """At zero clearance the sliced life is 1 (10^6 rev) at Fr = C, as ISO 281 defines C (to
    the difference of 12 discrete rollers from the integrals); line contacts give the load-life
    exponent 4 (ISO 281 uses 10/3 for the bearing)."""
    p = roller_row_parameters(NU206, clearance=0.0)
    c = NU206.dynamic_load_rating

    def life(load):
        q = roller_row_equilibrium(p, 12, 5, (load, 0.0)).contacts.q
        return roller_reference_rating_life(q, q, c, NU206.gamma)

    assert life(c) == pytest.approx(1.0, abs=0.03)
    assert life(5000.0) / life(10000.0) == pytest.approx(16.0, rel=1e-6)


def test_stiffness_is_the_derivative_of_the_loads():
    p = roller_row_parameters(NU206)
    eq = roller_row_equilibrium(p, 12, 10, (6000.0, 0.0), (0.0, 5e-4))
    k = roller_row_stiffness(p, 12, 10, eq.inner)
    for j, h in ((0, 1e-9), (4, 1e-7)):
        plus, minus = eq.inner.copy(), eq.inner.copy()
        plus[j] += h
        minus[j] -= h
        fp = roller_row_loads(p, plus.tolist(), [0.0] * 5, 12, 10).inner_load
        fm = roller_row_loads(p, minus.tolist(), [0.0] * 5, 12, 10).inner_load
        column = -(np.array(fp, dtype=float) - np.array(fm, dtype=float)) / (2 * h)
        np.testing.assert_allclose(k[:, j], column, rtol=1e-5, atol=1e-3 * abs(k[j, j]))
    assert k[0, 0] > 1e8 and np.all(k[2] == 0.0)


# ----------------------------------------------------------------------------- the seam
def test_ball_and_roller_implement_the_seam():
    ball_geometry = get_bearing("6204")
    assert isinstance(ball_geometry, ElementGeometry) and isinstance(NU206, ElementGeometry)
    assert isinstance(BallRow("6204"), ElementRow) and isinstance(RollerRow("NU206"), ElementRow)
    assert friction_key(ball_geometry) == "deep_groove_ball"  # unchanged for balls
    assert friction_key(NU206) == "cylindrical_roller"
    assert resolve_geometry("NU 206") is NU206 and resolve_geometry("6204") is ball_geometry
    with pytest.raises(CatalogError, match="NU999"):
        resolve_geometry("NU999")
    assert static_equivalent_load(3000.0, 500.0, NU206) == 3000.0
    rp = row_parameters("6204")
    k = combined_load_deflection_constant(rp.K_i, rp.K_o)
    assert PointContact(k).load(2e-6) == contact_load(k, 2e-6)
    assert PointContact(k).approach(float(contact_load(k, 2e-6))) == pytest.approx(2e-6)
    assert LineContact(0.01).load(LineContact(0.01).approach(2500.0)) == pytest.approx(2500.0)


# ----------------------------------------------------------------------------- the product
def test_options_are_checked_once_with_clear_errors():
    with pytest.raises(ParameterError, match=r"misalignment\[1\].*rad"):
        CylindricalRollerOptions("NU206", misalignment=(0.0, 0.02))
    with pytest.raises(ParameterError, match="clearance"):
        CylindricalRollerOptions("NU206", clearance=-1e-6)
    with pytest.raises(ParameterError, match="Fz"):
        CylindricalRollerOptions("NU206", loads={"Fz": 10.0})
    with pytest.raises(CatalogError, match="NU206"):
        CylindricalRollerOptions("NU999")
    with pytest.raises(ParameterError, match="unknown option"):
        cylindrical_roller_bearing("NU206", speed=3.0)


@pytest.fixture(scope="module")
def quasi_static_system():
    model = cylindrical_roller_bearing("NU206", misalignment=(0.0, 5e-4))
    return assemble(model, outputs=["row.Q[0]", "row.inner.x", "row.inner.y", "row.p_max[0]",
                                    "guide.frame.My"])


def test_quasi_static_level_solves_the_row_equilibrium(quasi_static_system):
    """The assembled model's Newton blocks reach the numeric equilibrium at every load of a
    ramp (from the clearance at rest to 8 kN)."""
    result = simulate(quasi_static_system, 1.0, inputs={"load.Fx": lambda t: 8000.0 * t},
                      n_points=5)
    p = roller_row_parameters(NU206)
    for k, t in enumerate(result.t[1:], start=1):
        eq = roller_row_equilibrium(p, 12, 10, (8000.0 * t, 0.0), (0.0, 5e-4))
        assert result["row.inner.x"][k] == pytest.approx(eq.inner[0], rel=1e-7)
        assert result["row.Q[0]"][k] == pytest.approx(eq.contacts.Q[0], rel=1e-6)
        # the guide's flow is the reaction: minus the moment it applies to the ring
        assert result["guide.frame.My"][k] == pytest.approx(-eq.moment[1], rel=1e-5)


def test_torque_level_palmgren_and_skf_rows():
    """Palmgren: M = M0 + f1 P1 dm with f1 = 0.0003, P1 = Fr for cylindrical roller bearings
    (Harris & Kotzalas, f1 table). SKF (GC 6000 pp. 91-101): Grr = R1 dm^2.41 Fr^0.31,
    Gsl = S1 dm^0.9 Fa + S2 dm Fr (series 2: 1.09e-6, 0.16, 0.0015), mu_EHL = 0.02."""
    speed, fr = 300.0, 4000.0
    values = {}
    for friction in ("palmgren", "skf"):
        model = cylindrical_roller_bearing("NU206", "torque", friction_model=friction)
        system = assemble(model, outputs=["bearing.M"])
        result = simulate(system, 0.05, inputs={"drive.w_in": speed, "bearing.Fr": fr},
                          n_points=3)
        values[friction] = -float(result["bearing.M"][-1])
        bearing = model.bearing
    dm = NU206.pitch_diameter
    lubricant = bearing.lubricant
    m0 = palmgren_m0(lubricant.kinematic_viscosity(), speed, dm,
                     lubricant.palmgren_f0("cylindrical_roller", "2"))
    assert values["palmgren"] == pytest.approx(float(m0) + 0.0003 * fr * dm, rel=1e-3)
    # SKF by hand (catalogue units: N mm, mm, r/min, mm^2/s)
    nu = bearing.lubricant.kinematic_viscosity() * 1e6
    n = speed * 30 / math.pi
    dm_mm = dm * 1e3
    g_rr = 1.09e-6 * dm_mm**2.41 * fr**0.31
    g_sl = 0.0015 * dm_mm * fr
    phi_ish = 1 / (1 + 1.84e-9 * (n * dm_mm) ** 1.28 * nu**0.64)
    krs = {"oil_bath": 3e-8, "oil_jet": 3e-8, "grease": 6e-8, "oil_mist": 6e-8}.get(
        bearing.lubricant.method, 0.0)
    d, big_d = NU206.bore * 1e3, NU206.outside_diameter * 1e3
    phi_rs = math.exp(-krs * nu * n * (d + big_d) * math.sqrt(5.1 / (2 * (big_d - d))))
    phi_bl = math.exp(-2.6e-8 * (n * nu) ** 1.4 * dm_mm)
    mu_sl = phi_bl * bearing.lubricant.mu_bl + (1 - phi_bl) * 0.02
    hand = (phi_ish * phi_rs * g_rr * (nu * n) ** 0.6 + g_sl * mu_sl) * 1e-3
    assert values["skf"] == pytest.approx(hand, rel=1e-3)


def test_scene_runs_and_post_processes(tmp_path):
    from bearingsim.scenes import run_scene
    from bearingsim.scenes.library import builtin_scene_path

    run = run_scene(builtin_scene_path("cylindrical_roller_radial"), out=tmp_path)
    names = sorted(p.name for p in tmp_path.iterdir())
    assert "cylindrical_roller_radial.roller_loads.png" in names
    s = run.series
    assert s["Q_max"][-1] >= s["row.Q[0]"][-1] > 0.25 * 10000.0
    assert 1.5e9 < s["p_max"][-1] < 3e9
    assert s["L10r"][0] == np.inf and 0 < s["L10r"][-1] < np.inf
    # a life in the unit the statics scenes give it (it was "1" here, "Mrev" there)
    from bearingsim.scenes.statics_table import _DEEP_GROOVE_COLUMNS

    assert run.summary["outputs"]["L10r"]["unit"] == _DEEP_GROOVE_COLUMNS["L10r"][0] == "Mrev"


def test_fmu_matches_simulate(tmp_path):
    """The quasi-static level as an FMU (CS and ME in fmpy) gives simulate's values."""
    from fmpy import simulate_fmu

    from bearingsim.fmu import export_fmu

    outputs = ["row.Q[0]", "row.inner.x", "guide.frame.My"]
    model = cylindrical_roller_bearing("NU204", misalignment=(0.0, 5e-4), n_slices=2)
    system = assemble(model, outputs=outputs)
    path = export_fmu(system, tmp_path / "nu204.fmu", inputs={"load.Fx": 6000.0})
    reference = simulate(system, 1.0, inputs={"load.Fx": 6000.0}, n_points=3)
    for kind in ("CoSimulation", "ModelExchange"):
        fmu = simulate_fmu(str(path), fmi_type=kind, stop_time=1.0, output_interval=0.5,
                           output=outputs, start_values={"load.Fx": 6000.0})
        for name in outputs:
            assert fmu[name][-1] == pytest.approx(reference[name][-1], rel=1e-8), (kind, name)


def test_spindle_nu_is_the_non_locating_bearing():
    """Spindle (7014C DB pair at the nose, NU 210 at the rear): after a radial step the shaft is
    at rest and the three rows carry the load (force balance); the NU row takes a share of it
    and, after an axial step, none of the axial load (no axial load path)."""
    from bearingsim.assemblies import spindle

    model = spindle("7014C", "NU210", "DB", preload="light", damping_ratio=0.1)
    names = ["nu.inner.Fx", "nu.inner.Fz", "pair.row[0].inner.Fx", "pair.row[1].inner.Fx",
             "pair.row[0].inner.Fz", "pair.row[1].inner.Fz", "pair.shaft.vx"]
    system = assemble(model, outputs=names)
    result = simulate(system, 0.04, inputs={"pair.shaft.Fx": 2000.0, "pair.shaft.Fz": 1000.0},
                      n_points=5, method="LSODA", rtol=1e-6, atol=1e-12)
    end = {n: float(result[n][-1]) for n in names}
    radial = end["nu.inner.Fx"] + end["pair.row[0].inner.Fx"] + end["pair.row[1].inner.Fx"]
    assert radial == pytest.approx(2000.0, rel=1e-4)
    assert end["pair.row[0].inner.Fz"] + end["pair.row[1].inner.Fz"] == pytest.approx(
        1000.0, rel=1e-4)
    assert end["nu.inner.Fz"] == 0.0
    assert abs(end["pair.shaft.vx"]) < 1e-6  # settled: the loads above are the equilibrium
    assert 0.2 * 2000.0 < end["nu.inner.Fx"] < 0.5 * 2000.0


@settings(max_examples=25, deadline=None)
@given(x=st.floats(-4e-5, 4e-5), y=st.floats(-4e-5, 4e-5), tx=st.floats(-1e-3, 1e-3),
       ty=st.floats(-1e-3, 1e-3), n=st.integers(1, 6))
def test_row_loads_balance_and_follow_the_rollers(x, y, tx, ty, n):
    """Action and reaction on the rings; the force on the inner ring is minus the sum of the
    roller loads along their azimuths; turning the displacement by one roller pitch together
    with the rollers' azimuth gives the same roller loads, shifted by one."""
    p = roller_row_parameters(NU206)
    c = roller_row_loads(p, [x, y, 0.0, tx, ty], [0.0] * 5, 12, n)
    np.testing.assert_allclose(c.outer_load, [-v for v in c.inner_load])
    psi = 2 * np.pi * np.arange(12) / 12
    q = np.array(c.Q, dtype=float)
    assert c.inner_load[0] == pytest.approx(-np.sum(q * np.cos(psi)), abs=1e-9)
    assert c.inner_load[1] == pytest.approx(-np.sum(q * np.sin(psi)), abs=1e-9)
    assert c.inner_load[2] == 0.0
    step = 2 * np.pi / 12
    turn = [x * np.cos(step) - y * np.sin(step), x * np.sin(step) + y * np.cos(step), 0.0,
            tx * np.cos(step) - ty * np.sin(step), tx * np.sin(step) + ty * np.cos(step)]
    turned = roller_row_loads(p, turn, [0.0] * 5, 12, n)
    np.testing.assert_allclose(np.roll(q, 1), np.array(turned.Q, dtype=float), rtol=1e-9,
                               atol=1e-9)


def test_contact_pressures_plot_in_mpa():
    """The scene's p_max is plotted in MPa (an engineering unit), not Pa."""
    from bearingsim.units import display_unit

    assert display_unit("Pa", [2.1e9]) == (1e-6, "MPa")


def test_catalogue_rows_follow_their_stated_rules():
    """The CSV header's rules: Dw = (E - F)/2, dm = (E + F)/2, Z = floor(0.8 pi dm / Dw), Pd the
    middle of SKF's normal clearance group (GC 6000 p. 512, Table 1: d <= 30 mm 20-45 um,
    30-40 mm 25-50 um, 40-50 mm 30-60 um, 50-65 mm 40-70 um)."""
    import csv
    from importlib import resources

    text = resources.files("bearingsim.catalog").joinpath("cylindrical_rollers.csv").read_text()
    rows = list(csv.DictReader(line for line in text.splitlines() if not line.startswith("#")))
    assert len(rows) == 18
    normal = ((30, 32.5), (40, 37.5), (50, 45.0), (65, 55.0))
    for row in rows:
        f, e, d = float(row["F_mm"]), float(row["E_mm"]), float(row["d_mm"])
        assert float(row["Dw_mm"]) == pytest.approx((e - f) / 2)
        assert float(row["dm_mm"]) == pytest.approx((e + f) / 2)
        assert int(row["Z"]) == math.floor(0.8 * math.pi * (e + f) / 2 / ((e - f) / 2))
        assert float(row["Pd_um"]) == next(pd for top, pd in normal if d <= top)


def test_bearingsim_list_shows_the_roller_catalogue(capsys):
    from bearingsim.cli import main

    assert main(["list", "bearings", "--filter", "NU20"]) == 0
    out = capsys.readouterr().out
    assert "cylindrical roller bearings" in out
    assert "NU206" in out and "Z=12" in out and "44.0/ 36.5 kN" in out
