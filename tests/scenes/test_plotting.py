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
    # dimensionless: [-], not [1]; labels from the descriptions (issue 27)
    assert fig.axes[0].get_ylabel() == "speed distribution ratio n_z /\nn_i [-]"
    host = Figure()
    ax = host.add_subplot()
    assert res.plot(["Rs", "w_middle"], ax=ax) is host and len(ax.lines) == 1
    assert len(host.axes) == 2 and len(host.axes[1].lines) == 1  # r/min on a twin axis
    assert len(repr(res)) < 200 and "11 points" in repr(res)
    assert len(repr(system)) < 200 and "states" in repr(system)


def test_scene_plots_use_engineering_units(tmp_path, monkeypatch):
    """Issue 16: the scene plots showed raw SI (rad/s) and [1]. Speeds are now in r/min,
    torques below 1 N m in N mm, dimensionless quantities [-] (the CSV stays SI)."""
    import matplotlib.figure

    from bearingsim.scenes import load_scene, run_scene
    from bearingsim.units import display_unit

    assert display_unit("rad/s", [100.0]) == pytest.approx((30 / 3.141592653589793, "r/min"))
    assert display_unit("m", [2e-5]) == (1e6, "µm") and display_unit("1", [0.3]) == (1.0, "-")
    labels = []
    real_savefig = matplotlib.figure.Figure.savefig

    def capture(fig, *args, **kwargs):
        labels.extend(ax.get_ylabel() for ax in fig.axes)
        return real_savefig(fig, *args, **kwargs)

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", capture)
    run_scene(load_scene("double_layer_friction"), out=tmp_path)
    # labelled by description (issue 27), not by the dotted name
    assert any(label.endswith("[-]") and label.startswith("speed distribution ratio")
               for label in labels)
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
    assert isinstance(frame, pd.DataFrame) and frame.index.name == "time"
    assert frame["Rs"].iloc[-1] == res.final("Rs") and frame.attrs["units"]["Rs"] == "1"
    assert res.to_pandas(internal=True).shape == (11, len(res.names))
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
    # the shaft speed's final value in r/min, in the unit its unit column names (issue 27:
    # the value was in N mm beside a unit column N.m): 1000 rad/s = 9549.3 r/min
    assert "<td>9549.3</td><td>r/min</td>" in html and "<th>unit</th>" in html
    model = df_pair
    eq = model.equilibrium({"Fz": 1000.0})
    text = repr(eq)
    assert text.startswith("<Equilibrium: shaft x ") and " µm" in text and " deg" in text
    assert " kN" in text and "spacer force" in text
    # the DF pair carries the 1 kN: the row axial loads differ by 1 kN
    loads = eq.row_axial_loads
    assert abs(loads[0] - loads[1]) == pytest.approx(1000.0, rel=1e-3)
    modes = model.modes({"Fz": 1000.0})
    text = repr(modes)
    assert f"axial {modes.frequency('axial'):.5g} Hz" in text
    assert "radial x" in text and "damping ratio 0.0025 [-]" in text


def _scene_figures(name, t_end):
    from bearingsim.scenes import load_scene, run_scene
    from bearingsim.scenes.run_figures import scene_figures

    scene = load_scene(name)
    scene.simulation.t_end = t_end
    if name == "deep_groove_duty1":
        scene.args["n_slices"] = 0
    run = run_scene(scene, write=False)
    units = {**run.result.units, **{n: q.unit for n, q in run.prepared.post.items()}}
    return run, dict(scene_figures(run.prepared, run.result, run.series, name, units))


# every shipped scene's figures (labels, display units, loads from 0, no self-plot):
# tests/scenes/test_scene_analyses.py::test_every_shipped_figure_reads_as_a_report (issue 27)


def test_ball_loads_against_azimuth_match_the_model_and_stribeck():
    """The deep-groove scene's ball loads against azimuth: the plotted points are the model's
    ball loads at the end of the ramp (938 N), at their azimuths from the load direction; the
    most loaded ball sits at 0 deg with Q_max Z / Fr between Stribeck's 4.37 (zero clearance)
    and 6 (the 6304's normal clearance narrows the loaded zone), and the loads balance Fr (the
    contact angles under this radial load are below 1 deg: cos(alpha) > 0.9998)."""
    run, figures = _scene_figures("deep_groove_radial", 1.0)
    model, stribeck = figures["deep_groove_radial.ball_loads.png"].axes[0].lines[:2]
    psi_deg, q = model.get_xdata(), model.get_ydata() * 1e3  # plotted in kN
    z, fr = 7, 938.0
    final = np.array([run.result[f"row.Q_i[{j}]"][-1] for j in range(z)])
    assert np.sort(q) == pytest.approx(np.sort(final), rel=1e-12)
    assert psi_deg[np.argmax(q)] == pytest.approx(0.0, abs=1e-9)
    assert sorted(np.round(np.abs(psi_deg), 6)) == pytest.approx(
        sorted(np.round(np.abs(np.angle(np.exp(2j * np.pi * np.arange(z) / z), deg=True)), 6)))
    assert 4.37 < q.max() * z / fr < 6.0
    assert max(stribeck.get_ydata()) * 1e3 == pytest.approx(4.37 * fr / z)
    assert abs(run.result["row.alpha_i[0]"][-1]) < np.radians(1.0)
    assert np.sum(q * np.cos(np.radians(psi_deg))) == pytest.approx(fr, rel=1e-3)


def test_duplex_modes_are_plotted_by_name_and_match_the_study(df_pair):
    """The DF pair scene's modes figure: one curve per mode name, each with its own marker and
    line style, so the radial x and y modes, which coincide under the preload alone, are both
    visible; before the load steps they are the study's modes at no load."""
    from bearingsim.physics.shaft_modes import MODE_NAMES

    _, figures = _scene_figures("duplex_pair_axial", 0.0015)  # before the axial step
    ax = figures["duplex_pair_axial.modes.png"].axes[0]
    assert [line.get_label() for line in ax.lines] == list(MODE_NAMES)
    assert len({(line.get_marker(), line.get_linestyle(), line.get_markersize())
                for line in ax.lines}) == len(MODE_NAMES)
    study = df_pair.modes(preload="light").by_name()
    for line in ax.lines:
        assert line.get_ydata() == pytest.approx(study[line.get_label()], rel=1e-6)
    x, y = (ax.lines[MODE_NAMES.index(n)].get_ydata() for n in ("radial x", "radial y"))
    assert x == pytest.approx(y, rel=1e-9)


def test_one_display_unit_per_quantity_kind():
    """Issue 27 item 4: one display unit per kind whatever the magnitude (was N below 1 kN and
    kN above, N mm below 1 N m and N m above, um or mm), so two curves of one kind never sit on
    axes in different units; plots and engineering() agree."""
    from bearingsim.units import display_unit, engineering

    assert display_unit("N", [200.0, 2500.0]) == display_unit("N", [200.0]) == (1e-3, "kN")
    assert display_unit("N.m", [0.5, 5.0]) == pytest.approx((1e3, "N mm"))
    assert display_unit("m", [0.5]) == (1e6, "µm") and display_unit("um") == (1.0, "µm")
    assert engineering(2500.0, "N") == "2.5 kN" and engineering(5.0, "N.m") == "5000 N mm"


def test_a_registered_assembly_declares_its_own_plots():
    """AssemblySpec.plots: a registered assembly's figures are drawn beside the time traces;
    the variables they read are kept by the pruning but stay out of the CSV series."""
    import dataclasses

    from bearingsim.assemblies.double_layer import SCENE_SPEC
    from bearingsim.assemblies.spec import AssemblyPlot
    from bearingsim.plotting import Curve, FigureSpec, Panel
    from bearingsim.scenes import register, run_scene
    from bearingsim.scenes.registry import unregister
    from bearingsim.scenes.run_figures import scene_figures
    from bearingsim.scenes.scene import parse_scene

    def middle(prep, result, series):
        return FigureSpec("middle", "middle ring", [Panel(
            [Curve(result.t, series["w_middle"], "w_middle")], "time", "s", "speed",
            "rad/s")])

    spec = dataclasses.replace(SCENE_SPEC, name="my_double_layer", plots=lambda args, fid: [
        AssemblyPlot("middle", ("w_middle",), middle)])
    register(spec)
    try:
        scene = parse_scene('outputs = ["Rs"]\n[assembly]\nname = "my_double_layer"\n'
                            'fidelity = "kinematic"\n[inputs]\nshaft_speed = 100.0\n'
                            '[simulation]\nt_end = 0.1\nn_points = 5\n')
        run = run_scene(scene, write=False)
    finally:
        unregister("my_double_layer")
    assert run.prepared.plot_outputs == ["w_middle"] and list(run.series) == ["Rs"]
    figures = dict(scene_figures(run.prepared, run.result, run.series, "x",
                                 run.result.units))
    assert set(figures) == {"x.middle.png", "x.png"}  # built-in plots go by the built-in name
    ax = figures["x.middle.png"].axes[0]
    assert ax.get_ylabel() == "speed [r/min]"
    assert ax.lines[0].get_ydata()[-1] == pytest.approx(run.result.final("w_middle") * 30
                                                         / np.pi)


def test_result_plot_labels_stay_on_the_figure(tmp_path):
    """The README's figure (shaft and middle-ring speed, then Rs) cut its first axis label
    off at the top: one line "shaft (inner ring) speed, middle ring speed [r/min]" longer than
    the panel. Several variables on one axis are named by the legend, the axis by its unit; a
    long description is wrapped."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    from bearingsim.assembler import assemble
    from bearingsim.assemblies import double_layer_bearing
    from bearingsim.simulation import simulate

    res = simulate(assemble(double_layer_bearing()), 0.2, inputs={"shaft_speed": 100.0},
                   n_points=11)
    fig = res.plot(["w_shaft", "w_middle", "Rs"])
    FigureCanvasAgg(fig).draw()
    renderer = fig.canvas.get_renderer()
    assert fig.axes[0].get_ylabel() == "[r/min]"
    height = fig.bbox.height
    for ax in fig.axes:
        box = ax.yaxis.label.get_window_extent(renderer)
        assert 0 <= box.y0 and box.y1 <= height, ax.get_ylabel()


@pytest.mark.parametrize("scene", ["double_layer_friction", "deep_groove_radial"])
def test_a_saved_figure_is_drawn_once(tmp_path, monkeypatch, scene):
    """``Figure.tight_layout`` left a placeholder layout engine behind, and ``savefig`` drew
    every figure of a scene twice (once with rendering off, to lay it out again, then to
    render it). The figures now keep the tight layout they found
    (:func:`bearingsim.plotting.keep_tight_layout`): one draw a save, the same pixels."""
    import matplotlib.figure

    from bearingsim.scenes import load_scene, run_scene

    draws, saves = [], []
    real_draw, real_savefig = matplotlib.figure.Figure.draw, matplotlib.figure.Figure.savefig

    def draw(fig, renderer):
        draws.append(fig)
        return real_draw(fig, renderer)

    def savefig(fig, *args, **kwargs):
        saves.append(fig)
        return real_savefig(fig, *args, **kwargs)

    monkeypatch.setattr(matplotlib.figure.Figure, "draw", draw)
    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", savefig)
    run_scene(load_scene(scene), out=tmp_path)
    assert saves and draws == saves


def test_inputs_sharing_a_panel_are_told_apart():
    """The spindle scene's two load steps (Fx, Fz, both in kN) were drawn in one panel in the
    same grey and the same solid line: its legend could not say which was which. Inputs
    stay grey and take the line styles in turn."""
    from bearingsim.plotting import LINESTYLES
    from bearingsim.scenes.run_figures import time_figures

    t = np.linspace(0.0, 0.08, 81)
    inputs = {"Fx": 2000.0 * (t > 0.002), "Fz": 1000.0 * (t > 0.02)}
    units = {"Fx": "N", "Fz": "N", "x": "m"}
    ((_, fig),) = time_figures("s", t, {"x": 1e-5 * (t > 0.002)}, units, [], "steps",
                               inputs=inputs)
    lines = fig.axes[0].get_lines()
    assert [line.get_linestyle() for line in lines] == list(LINESTYLES[:2])
    assert {line.get_color() for line in lines} == {"0.35"}
    assert len({line.get_linestyle() for line in fig.axes[0].get_legend().get_lines()}) == 2


def test_statics_bars_show_the_pressure_limit_and_their_values(tmp_path, monkeypatch):
    """The 6304 statics figure drew the ISO 76 limit (4200 MPa) outside its pressure panel,
    whose axis stopped at the largest pressure (2109 MPa): the legend named a line that could
    not be seen, and the margin to the limit, the panel's answer, was not shown. And the value
    above the tallest bar of a panel ran into the panel's top edge."""
    import matplotlib.figure
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Annotation

    from bearingsim.scenes import load_scene, run_scene

    figures = []
    real_savefig = matplotlib.figure.Figure.savefig

    def capture(fig, *args, **kwargs):
        figures.append(fig)
        return real_savefig(fig, *args, **kwargs)

    monkeypatch.setattr(matplotlib.figure.Figure, "savefig", capture)
    run_scene(load_scene("deep_groove_statics"), out=tmp_path)
    (fig,) = figures
    FigureCanvasAgg(fig).draw()
    renderer = fig.canvas.get_renderer()
    pressure = next(ax for ax in fig.axes if ax.get_ylabel().endswith("[MPa]"))
    assert pressure.get_ylim()[1] > 4200.0 and pressure.get_ylim()[0] == 0.0
    assert [t.get_text() for t in pressure.texts if not isinstance(t, Annotation)] == [
        "ISO 76 static limit 4,200 MPa"]
    for ax in fig.axes:
        top = ax.get_window_extent(renderer).y1
        values = [t for t in ax.texts if isinstance(t, Annotation)]
        assert len(values) == 4
        assert all(t.get_window_extent(renderer).y1 <= top for t in values), ax.get_ylabel()


def test_elements_of_an_array_are_told_apart_on_a_figure():
    """``inner[0].Q`` and ``inner[1].Q`` (the contact loads of balls 0 and 1) were both
    labelled "normal contact load": one axis label said nothing of which ball, and two
    elements in one panel had the same legend entry. An element's label names it."""
    from bearingsim.scenes import load_scene, prepare
    from bearingsim.scenes.plots import describe
    from bearingsim.scenes.run_figures import time_figures

    prep = prepare(load_scene("deep_groove_duty1"))
    assert describe("inner[0].Q", prep) == "normal contact load, inner[0]"
    assert describe("w_cage", prep) == "cage speed"  # a scalar as before
    t = np.linspace(0.0, 0.01, 11)
    series = {"inner[0].Q": 100.0 + t, "inner[1].Q": 200.0 + t}
    ((_, fig),) = time_figures("s", t, series, {n: "N" for n in series},
                               [["inner[0].Q", "inner[1].Q"]], "loads", prep=prep)
    labels = [text.get_text() for text in fig.axes[0].get_legend().get_texts()]
    assert labels == ["normal contact load, inner[0]", "normal contact load, inner[1]"]
