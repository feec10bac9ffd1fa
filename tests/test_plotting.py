"""Value-axis scale of the result plots."""

import matplotlib
import pytest

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


def test_result_plot_keeps_the_backend_and_draws_into_a_given_axes(tmp_path):
    """Issue 16: Result.plot(path=...) switched the session to Agg (a notebook lost its inline
    plots) and plotted through pyplot (shown twice); it now builds a Figure without pyplot."""
    import matplotlib
    from matplotlib.figure import Figure

    from bearingsim.assembler import assemble
    from bearingsim.assemblies import double_layer_bearing
    from bearingsim.simulation import simulate

    system = assemble(double_layer_bearing())
    res = simulate(system, 0.2, inputs={"shaft_speed": 100.0}, n_points=11)
    backend = matplotlib.get_backend()
    fig = res.plot(["Rs", "w_middle"], path=tmp_path / "rs.png")
    assert matplotlib.get_backend() == backend
    assert (tmp_path / "rs.png").is_file() and len(fig.axes) == 2
    assert fig.axes[0].get_ylabel() == "Rs\n[-]"  # dimensionless: [-], not [1]
    host = Figure()
    ax = host.add_subplot()
    assert res.plot(["Rs", "w_middle"], ax=ax) is host and len(ax.lines) == 2
    assert len(repr(res)) < 200 and "11 points" in repr(res)
    assert len(repr(system)) < 200 and "states" in repr(system)


def test_scene_plots_use_engineering_units(tmp_path, monkeypatch):
    """Issue 16: the scene plots showed raw SI (rad/s) and [1]. Speeds are now in r/min,
    torques below 1 N m in N mm, dimensionless quantities [-] (the CSV stays SI)."""
    import matplotlib.figure

    from bearingsim.scenes import load_scene, run_scene
    from bearingsim.units import display_unit

    assert display_unit("rad/s", [100.0]) == pytest.approx((30 / 3.141592653589793, "r/min"))
    assert display_unit("m", [2e-5]) == (1e6, "um") and display_unit("1", [0.3]) == (1.0, "-")
    labels = []
    real_savefig = matplotlib.figure.Figure.savefig

    def capture(fig, *args, **kwargs):
        labels.extend(ax.get_ylabel() for ax in fig.axes)
        return real_savefig(fig, *args, **kwargs)

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", capture)
    run_scene(load_scene("double_layer_friction"), out=tmp_path)
    assert any(label.endswith("[-]") and label.startswith("Rs") for label in labels)
    assert any(label.endswith("[N mm]") for label in labels)
    assert not any("[1]" in label or "[rad/s]" in label for label in labels)


def test_result_as_a_table_and_in_a_notebook():
    """Issue 16: no to_pandas/to_xarray; the repr dumped kilobytes."""
    pd = pytest.importorskip("pandas")

    from bearingsim.assembler import assemble
    from bearingsim.assemblies import double_layer_bearing
    from bearingsim.errors import ParameterError
    from bearingsim.simulation import simulate

    res = simulate(assemble(double_layer_bearing()), 0.2, inputs={"shaft_speed": 100.0},
                   n_points=11)
    frame = res.to_pandas()
    assert isinstance(frame, pd.DataFrame) and frame.index.name == "time [s]"
    assert frame["Rs [-]"].iloc[-1] == res.final("Rs") and frame.shape == (11, len(res.names))
    html = res._repr_html_()
    assert "<table>" in html and "Rs" in html and len(html) < 4000
    try:
        import xarray  # noqa: F401
    except ImportError:
        with pytest.raises(ParameterError, match="xarray"):
            res.to_xarray()
    else:
        assert res.to_xarray()["Rs"].attrs["units"] == "1"
