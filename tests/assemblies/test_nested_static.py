"""Quasi-static double-layer bearing (issue 5): the load passes through both layers in series."""

from __future__ import annotations

import numpy as np
import pytest

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.components.ball_row import RowParameters, row_stiffness
from bearingsim.errors import ParameterError
from bearingsim.physics.ball_equilibrium import static_state
from bearingsim.physics.bearing_design import bearing_design
from bearingsim.studies.nested_equilibrium import nested_equilibrium


@pytest.fixture(scope="module")
def radial_system():
    return assemble(double_layer_bearing("61905", "61909", fidelity="quasi-static", axial=False))


@pytest.fixture(scope="module")
def full_system():
    return assemble(double_layer_bearing("61905", "61907", fidelity="quasi-static"))


def _row(system, prefix):
    p = dict(zip(system.parameter_names, system.p0(), strict=True))
    return RowParameters(*(p[f"{prefix}.{k}"] for k in ("Dw", "dm", "fi", "fo", "alpha0", "K_i",
                                                         "K_o", "psi0", "smooth")))


def _radial_resultant(loads, angles):
    z = loads.size
    psi = 2.0 * np.pi * np.arange(z) / z
    return np.sum(loads * np.cos(angles) * np.cos(psi))


def test_both_layers_carry_the_whole_radial_load(radial_system):
    eq = nested_equilibrium(radial_system, 800.0)
    # Stribeck: the resultant of the ball loads of each layer is the applied load (series)
    assert _radial_resultant(eq.inner_ball_loads, eq.inner_contact_angles) == pytest.approx(
        800.0, rel=1e-6)
    assert _radial_resultant(eq.outer_ball_loads, eq.outer_contact_angles) == pytest.approx(
        800.0, rel=1e-6)
    # radial clearance concentrates the load above Stribeck's zero-clearance 4.37 Fr / Z
    assert eq.inner_ball_loads.max() > 4.37 * 800.0 / eq.inner_ball_loads.size
    assert eq.shaft_displacement[0] > eq.middle_displacement[0] > 0.0


def test_nested_stiffness_is_the_series_combination_of_the_layers(radial_system):
    eq = nested_equilibrium(radial_system, 800.0)
    rel_inner = [*(eq.shaft_displacement - eq.middle_displacement), 0.0, 0.0]
    rel_outer = [*eq.middle_displacement, 0.0, 0.0]
    z_i, z_o = eq.inner_ball_loads.size, eq.outer_ball_loads.size
    k_inner = row_stiffness(_row(radial_system, "inner_row"), z_i, rel_inner,
                            reference="centred")[:2, :2]
    k_outer = row_stiffness(_row(radial_system, "outer_row"), z_o, rel_outer,
                            reference="centred")[:2, :2]
    series = np.linalg.inv(np.linalg.inv(k_inner) + np.linalg.inv(k_outer))
    np.testing.assert_allclose(eq.stiffness, series, rtol=1e-6, atol=1e-6 * series.max())
    assert eq.stiffness[0, 0] < min(k_inner[0, 0], k_outer[0, 0])


def test_stiffness_grows_with_load(radial_system):
    light = nested_equilibrium(radial_system, 200.0).stiffness[0, 0]
    heavy = nested_equilibrium(radial_system, 2000.0).stiffness[0, 0]
    assert heavy > light


def test_axial_load_raises_contact_angles_and_couples_directions(full_system):
    radial = nested_equilibrium(full_system, 500.0)
    combined = nested_equilibrium(full_system, 500.0, 300.0)
    assert combined.inner_contact_angles.mean() > radial.inner_contact_angles.mean()
    assert combined.shaft_displacement[2] > combined.middle_displacement[2] > 0.0
    assert combined.stiffness.shape == (3, 3)
    assert abs(combined.stiffness[0, 2]) > 0.0
    np.testing.assert_allclose(combined.stiffness, combined.stiffness.T, rtol=1e-6,
                               atol=1e-9 * combined.stiffness.max())


@pytest.mark.parametrize("radial", [0.0, 1.0, 30.0])
def test_axial_dominated_load_goes_through_the_layers_in_series(full_system, radial):
    """100 N axial on 61905/61907 with a light or no radial load: the equilibrium is reached by load
    continuation (seated radially, axial load added, radial load taken down). The axial
    displacements equal each layer's own static solution (its inner ring against a fixed outer
    ring under the same load) in series: middle ring 70.38 um, shaft 135.13 um."""
    eq = nested_equilibrium(full_system, radial, 100.0)
    inner, outer = (static_state(bearing_design(d), {"Fz": 100.0}).ring[2]
                    for d in ("61905", "61907"))
    assert eq.middle_displacement[2] == pytest.approx(outer, rel=1e-3)
    assert eq.shaft_displacement[2] == pytest.approx(inner + outer, rel=1e-3)
    assert np.all(eq.inner_ball_loads > 0.0) and np.all(eq.outer_ball_loads > 0.0)


def test_invalid_loads_are_rejected(radial_system):
    with pytest.raises(ParameterError, match="radial"):
        nested_equilibrium(radial_system, 0.0)
    with pytest.raises(ParameterError, match="axial"):
        nested_equilibrium(radial_system, 100.0, 50.0)
    with pytest.raises(ParameterError, match=r"nested_equilibrium: radial: 'rpm' is not a unit "
                                             r"of N quantities"):
        nested_equilibrium(radial_system, "500 rpm")


def test_loads_take_units(radial_system):
    """As the assemblies' loads do (docs/units.md); "0.5 kN" was refused ("radial must be a
    number in N")."""
    with_units = nested_equilibrium(radial_system, "0.5 kN")
    in_si = nested_equilibrium(radial_system, 500.0)
    np.testing.assert_array_equal(with_units.state, in_si.state)


def test_study_fits_set_each_layers_operating_clearance():
    """docs/studies.md, section A mounts the layers with k6 shafts and H7 bores. With the CN
    clearance (NSK Table 9.9) the inner layer keeps 1.6 um; the outer layer sits on the middle
    ring, a thinner seat that gives way, so it keeps more (I-type 61909 on a 1.5 mm sleeve:
    8.6 um);
    the mounted pair is stiffer than the unmounted one (catalogue rows: the CN mean, 12.5 um)."""
    from bearingsim.catalog import get_bearing
    from bearingsim.components.middle_ring import mounted_geometries
    from bearingsim.errors import ParameterError
    from bearingsim.studies.nested_equilibrium import nested_equilibrium

    gi, go = mounted_geometries(get_bearing("61905"), get_bearing("61909"), "I")
    assert gi.diametral_clearance == pytest.approx(1.63e-6, abs=0.05e-6)
    assert go.diametral_clearance == pytest.approx(8.57e-6, abs=0.05e-6)
    _, solid = mounted_geometries(get_bearing("61905"), get_bearing("61907"), "Z")
    assert solid.diametral_clearance < go.diametral_clearance
    # the tight end of the probable band leaves the inner layer preloaded: every ball carries
    # load under a 1 N shaft load (with clearance only the loaded zone does)
    ti, to = mounted_geometries(get_bearing("61905"), get_bearing("61907"), "Z", band="largest")
    assert ti.diametral_clearance < 0.0 and ti.free_contact_angle == 0.0
    preloaded = nested_equilibrium(assemble(double_layer_bearing(
        ti, to, fidelity="quasi-static", axial=False)), 1.0)
    assert np.all(preloaded.inner_ball_loads > 1.0)
    with pytest.raises(ParameterError, match="internal preload"):
        double_layer_bearing(ti, to, fidelity="dynamic")
    mounted = nested_equilibrium(assemble(double_layer_bearing(
        "61905", "61907", fidelity="quasi-static", fits=True)), 200.0)
    unmounted = nested_equilibrium(assemble(double_layer_bearing(
        "61905", "61907", fidelity="quasi-static")), 200.0)
    assert mounted.shaft_displacement[0] < unmounted.shaft_displacement[0] - 5e-6


@pytest.mark.parametrize("fidelity", ["torque", "kinematic"])
def test_a_system_of_another_level_is_named(fidelity):
    """Old code: KeyError: 'inner_row.Dw' from deep inside (the seated guess)."""
    other = assemble(double_layer_bearing("61905", "61907", fidelity=fidelity))
    with pytest.raises(ParameterError, match=r"nested_equilibrium: expects an assembled "
                       r"quasi-static double-layer bearing \(assemble\(double_layer_bearing\("
                       r"inner, outer, fidelity='quasi-static'\)\).*has no input shaft.Fx, "
                       r"state shaft.x, state middle.x"):
        nested_equilibrium(other, 800.0)
