"""A scene is confined to its folder, and its tables load strictly (issue 30, items 1, 2, 4).

Every test here fails on the code before issue 30: absolute paths, ``..``, symbolic links and
``~`` were followed; the environment and /etc/passwd were printed in error messages; a typo in
the first data row was dropped as a "unit row"; ``Fr [kN]`` was read in N; duplicate headers
and short rows were accepted or reported without the row.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import casadi as ca
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim.cli import main, printable
from bearingsim.files import PathOutsideError, confined_path
from bearingsim.scenes import SceneError, load_scene
from bearingsim.scenes.tables import column_unit, scene_output_folder
from bearingsim.simulation.inputs import table_expression

SCENE = """
title = "sandbox"
outputs = ["Rs"]
{top}
[assembly]
name = "double_layer_bearing"
[inputs]
shaft_speed = {speed}
[simulation]
t_end = 0.2
n_points = 11
[output]
folder = {folder}
"""


def _scene(folder: Path, speed: str = "100.0", top: str = "", out: str = '"out"',
           name: str = "s.toml") -> Path:
    path = folder / name
    path.write_text(SCENE.format(speed=speed, top=top, folder=out))
    return path


def _problems(path: Path, **kwargs) -> str:
    with pytest.raises(SceneError) as info:
        load_scene(path, **kwargs)
    return str(info.value)


def _table(folder: Path, text: str, name: str = "tab.csv") -> str:
    (folder / name).write_text(text)
    return f'{{ file = "{name}", column = "w" }}'


# ----------------------------------------------------------------------------- confinement
@pytest.mark.skipif(not Path("/proc/self/environ").exists(), reason="needs /proc")
@pytest.mark.parametrize("allow", [[], ["/proc/self"]])
def test_a_table_never_quotes_the_environment(tmp_path, allow):
    """Issue 30: ``{ file = "/proc/self/environ", column = "x" }`` printed every variable."""
    path = _scene(tmp_path, '{ file = "/proc/self/environ", column = "x" }')
    message = _problems(path, allow_paths=allow)
    assert "inputs.shaft_speed" in message
    environ = Path("/proc/self/environ").read_bytes().decode(errors="replace").split("\0")
    for entry in environ:
        if "=" in entry and len(entry.split("=", 1)[1]) >= 4:
            assert entry.split("=", 1)[1] not in message
    if not allow:
        assert "is an absolute path" in message and "--allow-path" in message


@pytest.mark.skipif(not Path("/etc/passwd").is_file(), reason="needs /etc/passwd")
@pytest.mark.parametrize("allow", [[], ["/etc"]])
def test_a_datasheet_never_quotes_the_file(tmp_path, allow):
    """Issue 30: ``bearings = "/etc/passwd"`` printed ``root:x:0:0:...``."""
    path = _scene(tmp_path, top='bearings = "/etc/passwd"')
    message = _problems(path, allow_paths=allow)
    assert "bearings" in message and "root:" not in message and ":x:" not in message


@pytest.mark.parametrize("name, words", [
    ("../t.csv", "with '..'"),
    ("{abs}", "an absolute path"),
    ("~/t.csv", "'~' is not expanded"),
    ("link.csv", "outside the scene folder"),
])
def test_table_paths_leading_out_of_the_scene_folder_are_refused(tmp_path, name, words):
    inner, outside = tmp_path / "scene", tmp_path / "elsewhere"
    inner.mkdir()
    outside.mkdir()
    (outside / "t.csv").write_text("time,w\n0,0\n1,100\n")
    (tmp_path / "t.csv").write_text("time,w\n0,0\n1,100\n")
    (inner / "link.csv").symlink_to(outside / "t.csv")
    name = name.format(abs=outside / "t.csv")
    path = _scene(inner, f'{{ file = "{name}", column = "w" }}')
    message = _problems(path)
    assert "inputs.shaft_speed.file" in message and words in message
    assert "--allow-path" in message


def test_an_allowed_folder_opens_paths_into_it_only(tmp_path):
    inner, outside = tmp_path / "scene", tmp_path / "data"
    inner.mkdir()
    outside.mkdir()
    (outside / "t.csv").write_text("time,w\n0,0\n1,100\n")
    path = _scene(inner, f'{{ file = "{outside / "t.csv"}", column = "w" }}')
    scene = load_scene(path, allow_paths=[outside])
    assert scene.inputs["shaft_speed"].values == [0.0, 100.0]
    (inner / "up.csv").symlink_to(tmp_path / "x.csv")  # allowed: data, not tmp_path
    (tmp_path / "x.csv").write_text("time,w\n0,0\n1,100\n")
    path = _scene(inner, '{ file = "up.csv", column = "w" }')
    assert "outside the scene folder and the allowed folders" in _problems(
        path, allow_paths=[outside])


def test_the_output_folder_is_inside_the_scene_folder(tmp_path, monkeypatch):
    """Issue 30: ``output.folder`` could be ``../x`` or absolute, and was relative to the
    current folder rather than to the scene file."""
    inner = tmp_path / "scene"
    inner.mkdir()
    monkeypatch.chdir(tmp_path)
    scene = load_scene(_scene(inner, out='"results/a"'))
    assert scene_output_folder(scene) == (inner / "results" / "a").resolve()
    for bad in ('"../out"', f'"{tmp_path / "out"}"', '"~/out"'):
        assert "output.folder" in _problems(_scene(inner, out=bad))
    scene = load_scene(_scene(inner, out=f'"{tmp_path / "out"}"'), allow_paths=[tmp_path])
    assert scene_output_folder(scene) == (tmp_path / "out").resolve()


def test_a_fifo_is_refused_without_blocking(tmp_path):
    os.mkfifo(tmp_path / "fifo.csv")
    message = _problems(_scene(tmp_path, '{ file = "fifo.csv", column = "w" }'))
    assert "not a regular file" in message


def test_a_fifo_as_the_scene_file_is_refused_without_blocking(tmp_path, capsys):
    os.mkfifo(tmp_path / "scene.toml")
    assert main(["validate", "--no-assemble", str(tmp_path / "scene.toml")]) == 2
    assert "is not a regular file" in capsys.readouterr().err


def test_an_inline_table_too_large_for_memory_is_refused(tmp_path, monkeypatch):
    import bearingsim.scenes.tables as tables

    monkeypatch.setattr(tables, "available_memory", lambda: 1_000_000)
    times = ", ".join(str(k) for k in range(1000))
    message = _problems(_scene(tmp_path, f"{{ times = [{times}], values = [{times}] }}"))
    assert "inputs.shaft_speed: the inline table inputs.shaft_speed: 1000 rows" in message


def test_confined_path_resolves_inside_the_base(tmp_path):
    (tmp_path / "a").mkdir()
    assert confined_path("a/b.csv", tmp_path) == (tmp_path / "a" / "b.csv").resolve()
    with pytest.raises(PathOutsideError):
        confined_path("a/../../b.csv", tmp_path)
    with pytest.raises(PathOutsideError):
        confined_path("", tmp_path)


def test_the_cli_takes_allow_path_and_reports_a_refused_path(tmp_path, capsys):
    outside = tmp_path / "data"
    outside.mkdir()
    (outside / "t.csv").write_text("time,w\n0,0\n1,100\n")
    inner = tmp_path / "scene"
    inner.mkdir()
    path = _scene(inner, f'{{ file = "{outside / "t.csv"}", column = "w" }}')
    assert main(["validate", "--no-assemble", str(path)]) == 2
    assert "--allow-path" in capsys.readouterr().err
    assert main(["validate", "--no-assemble", "--allow-path", str(outside), str(path)]) == 0


def test_printable_strips_terminal_escapes_and_controls():
    text = "a\x1b[31mred\x1b[0m \x1b]0;owned\x07b\x07\x08c\r\nd\u202eE\tf\x9b2Jg"
    assert printable(text) == "ared bc\ndE\tfg"


def test_the_cli_does_not_pass_a_title_s_escape_sequences_to_the_terminal(tmp_path, capsys):
    """Issue 30: a scene title with terminal escape sequences reached the console."""
    path = _scene(tmp_path)
    path.write_text(path.read_text().replace('title = "sandbox"',
                                             'title = "ok\\u001b]0;owned\\u0007\\u001b[2J"'))
    assert main(["run", str(path), "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "\x1b" not in out and "\x07" not in out and "ok" in out


# ----------------------------------------------------------------------------- tables
def test_header_units_are_converted_to_si(tmp_path):
    """Issue 30: ``Fr [kN]`` and ``time [ms]`` headers were ignored (read as N and s)."""
    speed = _table(tmp_path, "time [ms],w [rpm]\n0,0\n200,1000\n")
    scene = load_scene(_scene(tmp_path, speed))
    table = scene.inputs["shaft_speed"]
    assert table.times == [0.0, 0.2]
    assert table.values[1] == pytest.approx(1000 * 2 * np.pi / 60, rel=1e-15)
    assert scene.input_units["shaft_speed"] == "rad/s"


def test_a_unit_that_does_not_fit_the_input_is_refused_at_validation(tmp_path):
    from bearingsim.scenes import validate_scene

    speed = _table(tmp_path, "time,w [kN]\n0,0\n1,1\n")
    with pytest.raises(SceneError, match="input shaft_speed is in rad/s"):
        validate_scene(_scene(tmp_path, speed))


def test_a_unit_row_still_works_and_a_typo_in_the_first_row_is_an_error(tmp_path):
    """Issue 30: ``0,1O0`` as the first data row was silently dropped as a "unit row"."""
    speed = _table(tmp_path, "time,w\ns,rpm\n0,0\n1,600\n")
    assert load_scene(_scene(tmp_path, speed)).inputs["shaft_speed"].values[1] == \
        pytest.approx(20 * np.pi)
    speed = _table(tmp_path, "time,w\n0,1O0\n1,600\n")
    message = _problems(_scene(tmp_path, speed))
    assert "tab.csv: line 2, column 'w': not a number" in message
    speed = _table(tmp_path, "time,w\n0.O,100\n1,600\n2,700\n")  # was dropped: 2 rows left
    message = _problems(_scene(tmp_path, speed))
    assert "tab.csv: line 2, column 'time': not a number" in message
    speed = _table(tmp_path, "time,w\nzero,hundred\n1,600\n")
    assert "line 2, column 1: neither a number nor a unit" in _problems(_scene(tmp_path, speed))


@pytest.mark.parametrize("text, words", [
    ("time,w\n0,0\n1,2,3\n", "line 3 has 3 cells, the header 2"),
    ("time,w\n0,0\n1\n", "line 3 has 1 cells, the header 2"),
    ("time,w,w\n0,0,0\n1,1,1\n", "columns 2 and 3 of the header have the same name 'w'"),
    ("time,w [w]\n0,0\n1,1\n", "the unit of column 'w' is not known"),
    ("time,w [degC]\n0,0\n1,1\n", "the unit of column 'w' is not known"),
    ("time [N],w\n0,0\n1,1\n", "column 'time' is in N, not a time unit"),
    ("time,w\n0,0\n1,nan\n", "line 3, column 'w': not finite"),
    ("", "no header row"),
    ("time,w\n0,0\n2,1\n1,2\n", "times must increase strictly: data row 3 has t = 1 s after "
                                 "t = 2 s in row 2"),  # was "a table needs ..." with no row
    ("time,w\n0,0\n", "a table needs at least two rows and a value per time; got 1 time(s)"),
    # before: only "column 'time' not in the header row; allowed: 1 column(s) with other text"
    ("time;w\n0;0\n1;1\n", "not in the header row; the header row is one column with ';' "
                            "in it: the file's cells must be separated by commas"),
    ("time\tw\n0\t0\n1\t1\n", "one column with '\\t' in it"),
])
def test_malformed_tables_are_errors_naming_the_row_or_column(tmp_path, text, words):
    message = _problems(_scene(tmp_path, _table(tmp_path, text)))
    assert words in message and "inputs.shaft_speed" in message


def test_a_table_too_large_for_memory_is_refused_before_the_run(tmp_path, monkeypatch):
    import bearingsim.scenes.tables as tables

    monkeypatch.setattr(tables, "available_memory", lambda: 10_000_000)
    rows = "\n".join(f"{k},{k}" for k in range(10_000))
    message = _problems(_scene(tmp_path, _table(tmp_path, "time,w\n" + rows + "\n")))
    assert "10000 rows would need about 0.04 GB" in message


def test_column_units_known_and_refused():
    assert column_unit("kN") == (1e3, "N")
    assert column_unit("ms") == (1e-3, "s")
    assert column_unit("-") == (1.0, None)
    assert column_unit("Pa.s") == (1.0, "Pa.s")
    # the units library reads any unit of a model quantity (1 lbf = 4.4482216152605 N, NIST SP 811)
    assert column_unit("lbf") == pytest.approx((4.4482216152605, "N"))
    assert column_unit("kN m") == pytest.approx((1e3, "N.m"))
    for bad in ("degC", "m^x", "bogons", "kN +"):
        with pytest.raises(ValueError):
            column_unit(bad)


@settings(max_examples=60, deadline=None)
@given(st.lists(st.floats(-1e6, 1e6), min_size=2, max_size=40),
       st.lists(st.floats(1e-3, 10.0), min_size=39, max_size=39),
       st.lists(st.floats(-0.5, 1.5), min_size=1, max_size=10))
def test_the_linear_time_table_matches_numpy_interp(values, steps, probes):
    """The O(n) interpolation (``casadi.pw_lin`` with symbolic rows is O(n^2): 277 s for a
    10^5-row table) equals ``numpy.interp`` (end values held), exactly at the rows."""
    n = len(values)
    times = np.concatenate([[0.0], np.cumsum(steps[:n - 1])])
    t, q = ca.SX.sym("t"), ca.SX.sym("q", 2 * n)
    fn = ca.Function("u", [t, q], [table_expression(t, q[:n], q[n:])])
    qv = np.concatenate([times, values])
    at = np.concatenate([times, times[0] + np.asarray(probes) * (times[-1] - times[0])])
    got = np.array([float(fn(x, qv)) for x in at])
    want = np.interp(at, times, values)
    assert np.array_equal(got[:n], np.asarray(values))
    scale = max(1.0, float(np.max(np.abs(values))))
    assert np.allclose(got, want, rtol=0, atol=1e-12 * scale)


# ----------------------------------------------------------------------------- properties
_UNITS = {"time": ["s", "ms"], "value": ["rpm", "rad/s", "kN", "N", "mm", "N mm", "deg", "-"]}
_FACTORS = {"s": (1.0, "s"), "ms": (1e-3, "s"), "rpm": (math.pi / 30.0, "rad/s"),
            "rad/s": (1.0, "rad/s"), "kN": (1e3, "N"), "N": (1.0, "N"), "mm": (1e-3, "m"),
            "N mm": (1e-3, "N.m"), "deg": (math.pi / 180.0, "rad"), "-": (1.0, None)}
"""Each unit's factor to SI and SI unit, from the units' definitions (1 r/min = 2 pi / 60
rad/s; 1 deg = pi / 180 rad)."""


@settings(max_examples=40, deadline=None)
@given(st.lists(st.floats(-1e9, 1e9, allow_nan=False), min_size=2, max_size=30),
       st.sampled_from(_UNITS["time"]), st.sampled_from(_UNITS["value"]),
       st.booleans())
def test_a_written_table_reads_back_in_si(tmp_path_factory, values, t_unit, v_unit, unit_row):
    """Property: any table written with units in the header (or a unit row) reads back as
    value x factor (repr round-trips a float exactly), in order, with the unit recorded."""
    from bearingsim.scenes.tables import read_table_file

    folder = tmp_path_factory.mktemp("t")
    times = [0.5 * k for k in range(len(values))]
    head = ("time,w\n" + f"{t_unit},{v_unit}\n") if unit_row else f"time [{t_unit}],w [{v_unit}]\n"
    body = "".join(f"{t!r},{v!r}\n" for t, v in zip(times, values, strict=True))
    (folder / "t.csv").write_text(head + body)
    got_t, got_v, source, unit = read_table_file("inputs.w", {"file": "t.csv", "column": "w"},
                                                 folder)
    t_factor = _FACTORS[t_unit][0]
    v_factor, si = _FACTORS[v_unit]
    assert got_t == pytest.approx([t * t_factor for t in times], rel=1e-15)
    assert got_v == pytest.approx([v * v_factor for v in values], rel=1e-15)
    assert unit == si and source == "t.csv:w"


@settings(max_examples=200, deadline=None)
@given(st.text(max_size=60))
def test_printable_leaves_no_control_character(text):
    import unicodedata

    clean = printable(text)
    assert all(c in "\n\t" or unicodedata.category(c) != "Cc" for c in clean)
    assert "\x1b" not in clean and "\u202e" not in clean
    if all(c.isprintable() or c in "\n\t" for c in text):  # plain text is left as it is
        assert clean == text


@settings(max_examples=200, deadline=None)
@given(st.lists(st.sampled_from(["a", "b", "..", ".", "link", "c.csv"]), min_size=1,
                max_size=6))
def test_confined_path_never_leaves_the_base(tmp_path_factory, parts):
    """Property: whatever a relative name of these parts (with ``..`` and a link out) is,
    the result is inside the base, or the name is refused."""
    root = tmp_path_factory.mktemp("c")
    base = root / "base"
    (base / "a" / "b").mkdir(parents=True)
    (root / "out").mkdir()
    (base / "a" / "link").symlink_to(root / "out")
    try:
        path = confined_path("/".join(parts), base)
    except PathOutsideError:
        return
    assert path == base.resolve() or base.resolve() in path.parents


def test_files_with_a_byte_order_mark_read_as_without(tmp_path):
    """Excel's "CSV UTF-8" and Notepad write a UTF-8 byte-order mark first: a table's first
    column was then '\\ufefftime' ("column 'time' not in the header row"), a scene file "not
    valid TOML (line 1, column 1)" and a datasheet's first column unknown. The mark is now
    skipped: each reads as the same file without it."""
    from bearingsim.catalog import get_bearing, load_datasheet, unregister_bearing
    from bearingsim.scenes.tables import read_table_file

    bom = "\ufeff"
    (tmp_path / "t.csv").write_text(bom + "time [s],w [rpm]\n0,0\n0.5,3000\n", encoding="utf-8")
    assert (tmp_path / "t.csv").read_bytes().startswith(b"\xef\xbb\xbf")
    times, values, _, unit = read_table_file("inputs.w", {"file": "t.csv", "column": "w"},
                                             tmp_path)
    assert list(times) == [0.0, 0.5] and unit == "rad/s"
    assert list(values) == pytest.approx([0.0, 3000 * math.pi / 30], rel=1e-15)
    scene = load_scene("double_layer_rs")
    (tmp_path / "scene.toml").write_text(bom + scene.text, encoding="utf-8")
    assert load_scene(tmp_path / "scene.toml").to_dict() == scene.to_dict()
    (tmp_path / "mine.csv").write_text(bom + "designation,d_mm,D_mm,B_mm,Z,Dw_mm,dm_mm\n"
                                       "BOM6005,25,47,12,10,6.35,36\n", encoding="utf-8")
    try:
        assert load_datasheet(tmp_path / "mine.csv") == ["BOM6005"]
        assert get_bearing("BOM6005").ball_count == 10
    finally:
        unregister_bearing("BOM6005")
