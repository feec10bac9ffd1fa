"""Issue 27 item 5: a Result fits pandas and xarray (plain variable names, units beside them,
the requested outputs first) and plots by name into a caller's axes, one axis per unit kind,
labelled with the variables' descriptions in display units."""

from __future__ import annotations

import math

import numpy as np
import pytest
from matplotlib.figure import Figure

from bearingsim.assembler import assemble
from bearingsim.assemblies import double_layer_bearing
from bearingsim.errors import ParameterError
from bearingsim.simulation import Result, simulate

pd = pytest.importorskip("pandas")


@pytest.fixture(scope="module")
def res():
    system = assemble(double_layer_bearing("61905", "61907"))
    return simulate(system, 0.3, inputs={"shaft_speed": 5000 * math.pi / 30, "Fr": 200.0},
                    n_points=31)


def test_frame_columns_are_plain_names_with_units_in_attrs(res):
    """Old code: columns "Rs [-]", so df["Rs"] raised KeyError; 69 columns, mostly connector
    torques and derivatives."""
    df = res.to_pandas()
    assert df["Rs"].iloc[-1] == res.final("Rs")
    assert df.index.name == "time" and df.attrs["units"]["time"] == "s"
    assert df.attrs["units"]["w_middle"] == "rad/s" and df.attrs["units"]["Rs"] == "1"
    assert df.attrs["descriptions"]["w_middle"] == "middle ring speed"
    # the assembly's own variables only, no connector torques or derivatives
    assert set(df.columns) == {"Rs", "M_shaft", "Fr", "Fa", "shaft_speed", "w_middle", "w_shaft"}
    assert list(df.columns) == res.columns()
    full = res.to_pandas(internal=True)
    assert full.shape == (31, len(res.names)) and list(full.columns[:7]) == list(df.columns)
    assert list(res.to_pandas(names=["w_shaft", "Rs"]).columns) == ["w_shaft", "Rs"]
    assert df["shaft_speed"].iloc[-1] == pytest.approx(5000 * math.pi / 30, rel=1e-12)  # SI


def test_requested_outputs_come_first():
    system = assemble(double_layer_bearing("61905", "61907"), outputs=["M_shaft", "Rs"])
    res = simulate(system, 0.05, inputs={"shaft_speed": 100.0}, n_points=3)
    assert list(res.to_pandas().columns) == ["M_shaft", "Rs"]
    assert list(res.to_pandas(internal=True).columns[:2]) == ["M_shaft", "Rs"]


def test_getitem_by_name_and_by_list(res):
    assert np.array_equal(res["Rs"], res.values[res.names.index("Rs")])
    sub = res[["Rs", "w_middle"]]
    assert isinstance(sub, Result) and sub.names == ["Rs", "w_middle"]
    assert np.array_equal(sub["w_middle"], res["w_middle"]) and sub.units["w_middle"] == "rad/s"
    assert list(sub.to_pandas().columns) == ["Rs", "w_middle"]
    with pytest.raises(KeyError, match="did you mean w_middle"):
        res[["Rs", "w_midle"]]
    with pytest.raises(ParameterError, match="variable name|name must be str"):
        res.final(5)


def test_plot_a_name_into_a_given_axes(res):
    """Old code: res.plot("Rs", ax=ax) iterated the string and raised KeyError "no variable
    'R'"; a list drew every curve on one axis without a y label."""
    host = Figure()
    ax = host.add_subplot()
    assert res.plot("Rs", ax=ax) is host
    assert len(ax.lines) == 1 and ax.get_ylabel() == "speed distribution ratio n_z /\nn_i [-]"
    assert np.array_equal(ax.lines[0].get_ydata(), res["Rs"])


def test_plot_one_axis_per_unit_kind_in_display_units(res):
    host = Figure()
    ax = host.add_subplot()
    res.plot(["Rs", "w_middle", "w_shaft", "M_shaft"], ax=ax)
    labels = [a.get_ylabel() for a in host.axes]
    assert labels == ["speed distribution ratio n_z /\nn_i [-]",
                      "[r/min]",  # two variables: the legend names them
                      "friction torque on the shaft [N mm]"]
    speeds = host.axes[1].lines[1].get_ydata()
    assert speeds[-1] == pytest.approx(5000.0, rel=1e-9)  # r/min, not rad/s
    torque = host.axes[2].lines[0].get_ydata()
    assert torque[-1] == pytest.approx(res.final("M_shaft") * 1e3, rel=1e-12)  # N mm
    fig = res.plot(["Rs", "w_middle", "w_shaft"])  # a figure of its own: one panel per kind
    assert len(fig.axes) == 2 and fig.axes[-1].get_xlabel() == "time [s]"


def test_html_value_and_unit_agree(res):
    """Old code: the value in N mm beside a unit column "N.m", and "um" for µm."""
    html = res._repr_html_()
    m = res.final("M_shaft") * 1e3
    assert f"<td>{m:.6g}</td><td>N mm</td>" in html
    assert f"<td>{res.final('w_shaft') * 30 / math.pi:.6g}</td><td>r/min</td>" in html
    assert "N.m" not in html and "um<" not in html


def test_xarray_carries_units(res):
    xr = pytest.importorskip("xarray")
    ds = res.to_xarray()
    assert isinstance(ds, xr.Dataset) and set(ds.data_vars) == set(res.columns())
    assert ds["w_middle"].attrs == {"units": "rad/s", "long_name": "middle ring speed"}
    assert ds["time"].attrs["units"] == "s"
    assert float(ds["Rs"][-1]) == res.final("Rs")
    assert len(res.to_xarray(internal=True).data_vars) == len(res.names)


def test_label_of_an_unknown_name_is_refused_with_close_matches(res):
    """Old code: res.label("foo") returned "foo [-]" and res.label("Rss") "Rss [-]", labels of
    variables the result does not have; res.label("t") "t [-]"."""
    assert res.label("Rs") == "speed distribution ratio n_z / n_i [-]"
    assert res.label("w_middle") == "middle ring speed [r/min]"
    assert res.label("t") == res.label("time") == "time [s]"
    with pytest.raises(KeyError, match=r"no variable 'Rss' in the result; did you mean Rs\?"):
        res.label("Rss")
    with pytest.raises(KeyError, match=r"no variable 'foo' in the result; its variables are "
                                       r"Rs, .* in all, Result.names\)"):
        res.label("foo")
    with pytest.raises(ParameterError, match="a variable is named by text"):
        res.label(3)
