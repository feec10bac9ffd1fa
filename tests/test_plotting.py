"""Value-axis scale of the result plots."""

import matplotlib

matplotlib.use("Agg")

import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from bearingsim.plotting import WIDE_RANGE, is_wide_positive, set_value_scale  # noqa: E402


def test_positive_series_over_three_decades_get_a_log_axis():
    life = np.array([4.2e6, 1.0e5, 1.2e3, np.inf])  # inf (at rest) is ignored
    assert is_wide_positive([life])
    fig, ax = plt.subplots()
    set_value_scale(ax, [life])
    assert ax.get_yscale() == "log"
    plt.close(fig)


def test_narrow_signed_or_empty_series_stay_linear():
    assert not is_wide_positive([np.array([1.0, 0.9 * WIDE_RANGE])])
    assert not is_wide_positive([np.array([-1.0, 1e6])])
    assert not is_wide_positive([np.array([0.0, 1e6])])
    assert not is_wide_positive([np.array([np.nan, np.inf])])
    # the range is taken over all series of one axis
    assert is_wide_positive([np.array([1.0, 2.0]), np.array([5e3])])
    fig, ax = plt.subplots()
    set_value_scale(ax, [np.array([0.0, 0.2])])
    assert ax.get_yscale() == "linear"
    plt.close(fig)
