"""The duplex pair is held to its catalogue limits, as the single bearings are.

Before, its shaft loads were unbounded: ``DuplexModel("7020C", "DF").equilibrium(loads={"Fx":
1e8})`` gave a 6.4 mm shaft displacement and 6 418 kN ball loads without a word. Now the pair's
constant loads and load inputs are held to its static load rating by the ISO 76 rules for pairs
(warn above it, refuse beyond 10 x):

* C0 of a DB, DF or DT pair = 2 x C0 of one bearing: SKF General Catalogue 6000 (Russian ed.,
  2006 data), p. 414, "load ratings of paired bearings";
* DB or DF: X0 = 1, Y0 = 2 x the single row's (15 deg: 0.92); single and DT: X0 = 0.5,
  Y0 = 0.46 at 15 deg, P0 = Fr if larger: NSK Super Precision Bearings (Russian ed.), p. 146,
  Table 2.1; SKF General Catalogue 6000, p. 415 (40 deg: single and tandem
  P0 = 0.5 Fr + 0.26 Fa, DB/DF P0 = Fr + 0.52 Fa).

The 7020 rows carry no catalogue C0 (the catalogues' ratings belong to other ball sets,
tests/physics/test_published_tables.py), so the pair is rated by the ISO 76 C0 of the ball set
the model uses: f0 Z Dw^2 cos a with f0 = 16.11 (ISO 76 Table 2 at Dw cos a / dm = 0.1102),
Z = 20, Dw = 14.288 mm, a = 15 deg: 63.48 kN. The 7014C carries GMN's C0 = 46.0 kN.
"""

import math
import re
import warnings

import pytest

from bearingsim.assemblies.cylindrical_roller.spindle import spindle
from bearingsim.assemblies.duplex import DuplexOptions, duplex_pair
from bearingsim.assemblies.duplex.limits import (
    pair_load_bounds,
    pair_speed_factor,
    rated_geometry,
)
from bearingsim.assemblies.duplex.preload import preload_force
from bearingsim.catalog import get_bearing
from bearingsim.errors import ParameterError, PlasticDeformationWarning, SpeedLimitWarning
from bearingsim.physics.life import pair_static_load_rating, static_load_factors
from bearingsim.simulation import steady_state
from bearingsim.studies.duplex import DuplexModel

C0_7020C = 63.48e3  # N: ISO 76 of the 7020C ball set (see the module)


@pytest.fixture(scope="module")
def df():
    return DuplexModel("7020C", "DF")


@pytest.mark.parametrize("arrangement, factors", [(None, (0.5, 0.46)), ("DT", (0.5, 0.46)),
                                                  ("DB", (1.0, 0.92)), ("DF", (1.0, 0.92))])
def test_iso76_factors_of_pairs_are_the_catalogues(arrangement, factors):
    """NSK Super Precision Bearings p. 146, Table 2.1, 15 deg: "single, DT" X0 0.5, Y0 0.46;
    "DB or DF" X0 1, Y0 0.92."""
    assert static_load_factors(get_bearing("7014C"), arrangement) == pytest.approx(factors)


def test_the_pair_rating_is_twice_one_bearings():
    """SKF General Catalogue 6000 p. 414: C0 = 2 x C0 of a single bearing."""
    assert pair_static_load_rating(46.0e3) == 92.0e3
    with pytest.raises(ParameterError, match="arrangement must be 'DB', 'DF' or 'DT'"):
        static_load_factors(get_bearing("7014C"), "DX")


def test_a_bearing_without_c0_is_rated_by_its_ball_set():
    g = rated_geometry(get_bearing("7020C"))
    assert g.static_load_rating == pytest.approx(C0_7020C, rel=1e-3)
    assert "C0" in g.estimated
    assert rated_geometry(get_bearing("7014C")).static_load_rating == 46.0e3


def test_the_shaft_load_inputs_carry_the_pair_rating():
    """7014C DB (C0 46 kN, Y0 0.46), rows 3 bores = 210 mm apart, centred: a radial force alone
    reaches the pair's C0 at 2 C0 = 92 kN, an axial one at C0 / Y0 = 100 kN (one bearing carries
    each axial direction: P0 = 0.92 Fa against 2 C0). A moment alone loads each row radially
    with M / l, l the distance between the pressure centres (DB: 210 mm + dm tan a = 234.1 mm),
    so it reaches the rating at C0 l = 10.77 kN m."""
    shaft = duplex_pair("7014C", "DB").shaft.declarations
    c0 = 46.0e3
    assert shaft["Fx"].warn_above == pytest.approx(2 * c0, rel=1e-12)
    assert (shaft["Fx"].low, shaft["Fx"].high) == pytest.approx((-20 * c0, 20 * c0))
    assert shaft["Fy"].warn_above == pytest.approx(2 * c0, rel=1e-12)
    assert shaft["Fz"].warn_above == pytest.approx(c0 / 0.46, rel=1e-12)
    lever = 0.210 + 0.090 * math.tan(math.radians(15.0))
    assert shaft["My"].warn_above == pytest.approx(c0 * lever, rel=1e-12)
    assert shaft["Mx"].limit == "static load"


def test_a_tandem_pair_shares_the_axial_load():
    """DT: P0 = max(Fr, 0.5 Fr + 0.46 Fa) against 2 C0, so Fa alone reaches it at 2 C0 / 0.46."""
    bounds = pair_load_bounds(DuplexOptions("7020C", "DT"))
    assert bounds["Fz"]["warn_above"] == pytest.approx(2 * C0_7020C / 0.46, rel=1e-3)


def test_the_reported_load_is_refused(df):
    with pytest.raises(ParameterError, match=r"DuplexModel\(7020C DF\): the static equivalent "
                                             r"load 1e\+08 N is more than 10 x the static load "
                                             r"rating C0 = 2 x 6348\d N of a DF pair of 7020C"):
        df.equilibrium(loads={"Fx": 1e8})


@pytest.mark.filterwarnings("ignore::bearingsim.studies.duplex.RowUnloadedWarning")
def test_a_load_above_the_pair_rating_warns_and_one_below_does_not(df):
    # DF: P0 = 0.92 Fa = 146 kN above 2 C0 = 127 kN (the input Fz is above C0 / Y0 = 138 kN
    # too: one warning, of the loads together; it warned of both)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        df.equilibrium(loads={"Fz": 2.5 * C0_7020C})
    plastic = [str(w.message) for w in caught if w.category is PlasticDeformationWarning]
    assert len(plastic) == 1
    assert re.search(r"static equivalent load 14600\d N exceeds the static load rating",
                     plastic[0])
    with warnings.catch_warnings():
        warnings.simplefilter("error", PlasticDeformationWarning)
        eq = df.equilibrium(loads={"Fx": 1.9 * C0_7020C})
    assert eq.Q_i.max() < 20e3


def test_a_load_input_beyond_ten_times_is_refused_by_name(df):
    with pytest.raises(ParameterError, match=r"input shaft\.Fx = 1\.9044e\+06 \[N\] is outside "
                                             r"its valid range \[-1\.2696\de\+06, 1\.2696"):
        steady_state(df.system, inputs={"shaft.Fx": 30 * C0_7020C},
                     parameters=df.parameters())


def test_the_spindle_bounds_only_the_axial_load():
    """In the spindle the NU bearing shares the radial loads and moments (statically
    indeterminate): only Fz, which passes through the pair alone, is bounded."""
    shaft = spindle("7014C", "NU210", "DB").pair.shaft.declarations
    assert shaft["Fz"].warn_above == pytest.approx(46.0e3 / 0.46, rel=1e-12)
    assert all(shaft[k].warn_above is None for k in ("Fx", "Fy", "Mx", "My"))


# --------------------------------------------------------------------------- limiting speed
RPM = math.pi / 30.0


def test_the_7020_rows_carry_nsks_limiting_speeds():
    """NSK Super Precision Bearings (Russian ed.), p. 56, series 70 standard: 7020C 9 200 r/min
    with grease, 14 000 r/min with oil; 7020A5 8 000 / 12 000; 7020A 6 000 / 8 000 (the oil
    values are entered, as GMN's for 7014C)."""
    for name, oil in (("7020C", 14000.0), ("7020A5", 12000.0), ("7020A", 8000.0)):
        assert get_bearing(name).limiting_speed == pytest.approx(oil * RPM, rel=1e-12)


def test_the_reported_speed_is_refused_before_the_solver():
    """Before: speed=1e5 rad/s (955 000 r/min) was accepted and failed inside CasADi's
    FastNewton. A pair runs at 0.8 x one bearing's limiting speed (SKF General Catalogue 6000
    p. 414: about 20 % lower; NSK Super Precision p. 170, Table 5.1: DB, light preload 0.80):
    11 200 r/min for 7020C; warned above it, refused beyond twice it."""
    with pytest.raises(ParameterError, match=r"speed 100000 rad/s \(954930 r/min\) is more than "
                                             r"2 x the limiting speed of a pair of 7020C .*"
                                             r"11200 r/min; valid range \[0, 22400\] r/min"):
        DuplexOptions("7020C", "DF", speed=1e5)
    with pytest.warns(SpeedLimitWarning, match=r"12000 r/min\) exceeds the limiting speed of a "
                                               r"pair of 7020C .*11200 r/min"):
        DuplexOptions("7020C", "DF", speed=12000 * RPM)
    with warnings.catch_warnings():
        warnings.simplefilter("error", SpeedLimitWarning)
        DuplexOptions("7020C", "DF", speed=11000 * RPM)


def test_a_higher_preload_lowers_the_pairs_limiting_speed(df):
    """NSK Super Precision Bearings p. 170, Table 5.1 (DB): 0.80 of one bearing's limiting
    speed at light preload, 0.65 medium, 0.55 heavy; between the classes interpolated in the
    preload force (7020C: light 540 N, medium 1270 N, heavy 2550 N), beyond them held. The
    pair was allowed 0.8 x 14 000 r/min at every preload."""
    g = get_bearing("7020C")
    light, medium, heavy = (preload_force(g, c) for c in ("light", "medium", "heavy"))
    assert [pair_speed_factor(g, f) for f in (0.5 * light, light, medium, heavy, 2 * heavy)] \
        == pytest.approx([0.80, 0.80, 0.65, 0.55, 0.55], abs=1e-12)
    assert pair_speed_factor(g, 0.5 * (light + medium)) == pytest.approx(0.725, abs=1e-12)
    with pytest.warns(SpeedLimitWarning, match=r"10000 r/min\) exceeds the limiting speed of a "
                                               r"pair of 7020C at 2550 N preload \(0\.55 x"):
        DuplexOptions("7020C", "DF", speed=10000 * RPM, preload="heavy")
    with warnings.catch_warnings():
        warnings.simplefilter("error", SpeedLimitWarning)
        DuplexOptions("7020C", "DF", speed=10000 * RPM, preload="light")
    with pytest.warns(SpeedLimitWarning, match=r"at 1270 N preload"), \
            pytest.raises(ParameterError, match="without speed effects"):  # checked first
        df.parameters(speed=10000 * RPM, preload="medium")


def test_a_study_configuration_speed_is_checked_too(df):
    with pytest.raises(ParameterError, match=r"DuplexModel\(7020C\): speed 100000 rad/s"):
        df.parameters(speed=1e5)


# --------------------------------------------------------------------------- solver failures
def test_a_newton_block_that_fails_says_so_without_casadis_dump(capfd):
    """Before: a pair run beyond what its ball equations solve (here a 7020C without a
    limiting speed at 1e5 rad/s, on CasADi's VM) printed CasADi's dump of the inputs of
    newton0, ode and f (hundreds of numbers) on standard error, then failed with CasADi's
    four-line chain ending "Set 'error_on_fail' option to false to ignore this error"."""
    import dataclasses

    from bearingsim.assembler import assemble
    from bearingsim.errors import SimulationError
    from bearingsim.simulation import simulate

    unlimited = dataclasses.replace(get_bearing("7020C"), designation="7020X",
                                    limiting_speed=None)
    system = assemble(duplex_pair(unlimited, "DF", speed=1e5, damping_ratio=0.1))
    with pytest.raises(SimulationError, match=r"LSODA failed near t = 0 s of 0\.01 s \(the "
                                              r"Newton iteration of the nonlinear block newton0 "
                                              r"did not converge"):
        simulate(system, 0.01, method="LSODA", compiled=False, n_points=3)
    printed = capfd.readouterr()
    for text in (printed.out, printed.err):
        assert "Input 0" not in text and "Function newton0" not in text


def test_a_steady_state_without_a_root_says_so_without_casadis_dump(capfd):
    """steady_state on CasADi's VM where the ball equations have no root (a 7020C without a
    limiting speed at 1e5 rad/s) printed CasADi's dump of the Newton block's inputs on
    standard error at every point it tried; now only the error, which says why."""
    import dataclasses

    from bearingsim.assembler import assemble
    from bearingsim.errors import SimulationError
    from bearingsim.simulation import steady_state

    unlimited = dataclasses.replace(get_bearing("7020C"), designation="7020X",
                                    limiting_speed=None)
    system = assemble(duplex_pair(unlimited, "DF", speed=1e5, damping_ratio=0.1))
    with pytest.raises(SimulationError, match=r"steady state not found: .*a nonlinear block of "
                                              r"the model found no root"):
        steady_state(system, compiled=False)
    printed = capfd.readouterr()
    for text in (printed.out, printed.err):
        assert "Input 0" not in text and "Function newton0" not in text


def test_a_tandem_pair_warns_of_axial_load_against_its_loaded_direction():
    """A DT pair takes axial load in one direction; the reverse beyond its spring preload
    makes the rows separate. The row model (a full groove) carried it on the rows instead:
    ``equilibrium({"Fz": -20000})`` of a 7020C DT pair gave -0.37 mm without a word (its spring
    preload is 540 N, light class: 0.0085 C0 of one row's ball set at 15 deg, rounded)."""
    from bearingsim.studies.duplex import RowUnloadedWarning

    model = DuplexModel("7020C", "DT")
    spring = model.parameters()["spring.Fz"]
    assert spring == pytest.approx(540.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RowUnloadedWarning)
        model.equilibrium({"Fz": 2000.0})  # the loaded direction: no warning
        model.equilibrium({"Fz": -0.9 * spring})  # the spring still holds the rows
    with pytest.warns(RowUnloadedWarning, match=r"Fz = -2000 N acts against the tandem pair's "
                                                r"loaded direction beyond its spring preload "
                                                r"of 540 N"):
        model.equilibrium({"Fz": -2000.0})
