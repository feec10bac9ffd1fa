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


@pytest.fixture(scope="module")
def df_pair():
    from bearingsim.studies.duplex import DuplexModel

    return DuplexModel("7020C", "DF")


def test_reprs_show_units(df_pair):
    """Issue 16 item 4: the reprs of Result, System, Modes and Equilibrium printed bare
    numbers and names; they now carry units (engineering units for values)."""
    from bearingsim.assembler import assemble
    from bearingsim.assemblies import double_layer_bearing
    from bearingsim.simulation import simulate

    system = assemble(double_layer_bearing())
    assert "shaft_speed [rad/s]" in repr(system) and "Fr [N]" in repr(system)
    res = simulate(system, 0.05, inputs={"shaft_speed": 1000.0}, n_points=3)
    text = repr(res)
    assert "0 .. 0.05 s" in text and len(text) < 300
    assert any(f"{n} [" in text for n in res.names[:4])
    assert "[1]" not in text and "Rs [-]" in repr(
        type(res)(res.t, ["Rs", "w_shaft"], res.values[:2], {"Rs": "1", "w_shaft": "rad/s"}))
    html = res._repr_html_()
    # the shaft speed's final value in r/min: 1000 rad/s = 9549.3 r/min
    assert "9549.3 r/min" in html and "<th>unit (SI)</th>" in html
    model = df_pair
    eq = model.equilibrium({"Fz": 1000.0})
    text = repr(eq)
    assert text.startswith("<Equilibrium: shaft x ") and " um" in text and " deg" in text
    assert " kN" in text and "spacer force" in text
    # the DF pair carries the 1 kN: the row axial loads differ by 1 kN
    loads = eq.row_axial_loads
    assert abs(loads[0] - loads[1]) == pytest.approx(1000.0, rel=1e-3)
    modes = model.modes({"Fz": 1000.0})
    text = repr(modes)
    assert f"axial {modes.frequency('axial'):.5g} Hz" in text
    assert "radial x" in text and "damping ratio 0.0025 [-]" in text
