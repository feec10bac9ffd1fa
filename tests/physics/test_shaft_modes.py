"""The rigid shaft's modal analysis (bearingsim.physics.shaft_modes): analytic frequencies of an
uncoupled system, and bad input refused with named errors (a float or a 3 x 3 matrix raised an
AttributeError or a LinAlgError from inside numpy and scipy before)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bearingsim.errors import ParameterError
from bearingsim.physics.shaft_modes import MODE_NAMES, modal_analysis

K = np.diag([2.0e8, 3.0e8, 5.0e8, 4.0e6, 6.0e6])  # N/m, N/rad... per degree of freedom
M = np.diag([12.0, 12.0, 12.0, 0.15, 0.15])  # kg, kg m^2


def test_uncoupled_frequencies_are_sqrt_k_over_m():
    modes = modal_analysis(K, M)
    expected = {name: math.sqrt(k / m) / (2.0 * math.pi)
                for name, k, m in zip(MODE_NAMES, np.diag(K), np.diag(M), strict=True)}
    for name, f in expected.items():
        assert modes.frequency(name) == pytest.approx(f, rel=1e-12)
    assert np.all(np.diff(modes.frequencies) >= 0.0)
    np.testing.assert_allclose(modes.damping_ratios, 0.0025)


@pytest.mark.parametrize(("stiffness", "mass", "loss", "named"), [
    (1.0, M, 0.005, "stiffness"),
    (np.eye(3), M, 0.005, "stiffness"),
    (K, np.full((5, 5), np.nan), 0.005, "mass"),
    (K, -M, 0.005, "mass matrix"),
    (K, M, -0.1, "loss_factor"),
])
def test_bad_input_is_refused_with_a_named_error(stiffness, mass, loss, named):
    with pytest.raises(ParameterError, match=named):
        modal_analysis(stiffness, mass, loss)
