"""Command line (issue 8): run, validate, list, sweep; exit codes and messages."""

from __future__ import annotations

import json
import math
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

import bearingsim
from bearingsim.cli import main
from bearingsim.scenes import SceneError

SCENES = Path(__file__).resolve().parent.parent / "scenes"

FAST = """
title = "cli test"
outputs = ["Rs"]
[assembly]
name = "double_layer_bearing"
[inputs]
shaft_speed = "rpm(1000) * ramp(0, 0.1)"
[simulation]
t_end = 0.2
n_points = 21
[output]
folder = "out"
"""


@pytest.fixture
def scene_file(tmp_path):
    path = tmp_path / "fast.toml"
    path.write_text(FAST)
    return path


def test_list_shows_assemblies_components_bearings_and_lubricants(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    for word in ("double_layer_bearing", "motor_drive", "fidelity: auto", "PalmgrenBearing",
                 "Inertia", "61905", "ISO VG 32", "L10h"):
        assert word in out


def test_validate_ok(scene_file, capsys):
    assert main(["validate", str(scene_file)]) == 0
    out = capsys.readouterr().out
    assert "valid" in out and "torque" in out and "pruned" in out


def test_validate_without_assembling(scene_file, capsys):
    assert main(["validate", "--no-assemble", str(scene_file)]) == 0
    assert "not checked against the model" in capsys.readouterr().out


def test_validate_reports_key_line_and_allowed_values(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(FAST.replace('name = "double_layer_bearing"',
                                'name = "double_layer_bearing"\nlubrication = "olive oil"'))
    assert main(["validate", str(bad)]) == 2
    err = capsys.readouterr().err
    assert f"{bad}:6: assembly.lubrication: unknown lubricant 'olive oil'" in err
    assert "allowed: ISO VG 10" in err


def test_missing_scene_file(tmp_path, capsys):
    assert main(["run", str(tmp_path / "nope.toml")]) == 2
    assert "not found" in capsys.readouterr().err


def test_run_writes_files_into_the_scene_folder(scene_file, tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["run", str(scene_file)]) == 0
    out = capsys.readouterr().out
    assert "skipped (pruned)" in out and "Rs = " in out
    files = sorted(p.name for p in (tmp_path / "out").iterdir())
    # the time traces, and Rs against the ramped shaft speed (the assembly's own plot)
    assert files == ["fast.csv", "fast.png", "fast.rs_speed.png", "fast.summary.json"]
    summary = json.loads((tmp_path / "out" / "fast.summary.json").read_text())
    assert summary["fidelity"]["chosen"] == "torque"  # kinematic Rs: outside 5 %


def test_run_passes_the_progress_choice_to_the_solver(scene_file, tmp_path, monkeypatch,
                                                      capsys):
    """Issue 16: ``run`` showed nothing for long runs; now the solver's bar on a terminal,
    none with --no-progress or when standard error is not a terminal."""
    import bearingsim.scenes as scenes

    seen, real = [], scenes.run_scene

    def spy(*args, **kwargs):
        seen.append(kwargs["progress"])
        return real(*args, **kwargs)

    monkeypatch.setattr(scenes, "run_scene", spy)
    assert main(["run", str(scene_file), "--out", str(tmp_path / "a"), "--no-progress"]) == 0
    assert main(["run", str(scene_file), "--out", str(tmp_path / "b")]) == 0
    assert seen == [False, None]
    err = capsys.readouterr().err  # not a terminal: no bar, only the run's warning lines
    assert all(line.startswith("bearingsim run: warning: ") for line in err.splitlines())


def test_run_reports_a_failed_simulation_with_exit_1(tmp_path, capsys):
    path = tmp_path / "diverge.toml"
    path.write_text(FAST + '[initial]\n"middle.sleeve.w" = 1e308\n')
    assert main(["run", str(path), "--out", str(tmp_path / "o")]) == 1
    assert "simulation failed" in capsys.readouterr().err


def test_sweep_bad_grid_key_is_exit_2(scene_file, capsys):
    assert main(["sweep", str(scene_file), "--grid", "speed=1,2"]) == 2
    assert "must start with" in capsys.readouterr().err


def test_sweep_with_a_key_gridded_twice_is_exit_2(scene_file, capsys):
    """Before: the second --grid of a key replaced the first's values and the sweep ran."""
    assert main(["sweep", str(scene_file), "--grid", "inputs.Fr=1,2", "--grid",
                 "inputs.Fr=3"]) == 2
    assert "--grid inputs.Fr is given twice" in capsys.readouterr().err


def test_sweep_needs_a_grid_or_sample(scene_file, capsys):
    assert main(["sweep", str(scene_file)]) == 2
    assert "--grid" in capsys.readouterr().err


def test_sweep_bad_counts_name_their_flags(scene_file, capsys):
    """Before: ``--seed -1`` ended in numpy's traceback ("expected non-negative integer"), and
    ``--workers 0`` was refused as run_sweep's ``n_workers`` without naming the flag."""
    assert main(["sweep", str(scene_file), "--sample", "inputs.Fr=1:2", "--seed", "-1"]) == 2
    assert "--seed must be a non-negative integer or None, got -1" in capsys.readouterr().err
    assert main(["sweep", str(scene_file), "--grid", "inputs.Fr=1,2", "--workers", "0"]) == 2
    assert "--workers" in capsys.readouterr().err


def test_console_script_runs_sweep_on_a_local_cluster(scene_file, tmp_path):
    """Neither point settles by t_end (the intermediate ring still speeds up): the summary
    counts them as not settled, and warns as a run of one of them does (before: ``2 point(s):
    2 ok, 0 failed`` and no warning)."""
    proc = subprocess.run(
        [sys.executable, "-m", "bearingsim.cli", "sweep", str(scene_file), "--grid",
         "inputs.shaft_speed=50;100*min(t,1)", "--out", str(tmp_path / "sw"),
         "--no-progress"], capture_output=True, text=True, timeout=120,
        env={**os.environ, "PYTHONPATH": str(Path(bearingsim.__file__).parents[1])})
    assert proc.returncode == 0, proc.stderr
    assert ("2 point(s): 0 settled, 2 not settled (values flagged: settled False), 0 failed; "
            "1 model(s) built") in proc.stdout
    assert proc.stderr.splitlines() == [
        "bearingsim sweep: warning: NotSettledWarning: cli test: 2 of 2 point(s) had not "
        "settled at t_end (their rows say settled False and name the outputs in unsettled). "
        "Run longer (simulation.t_end), ask analysis = \"steady\" for the settled points, or "
        "set transient_on_purpose = true"]
    assert (tmp_path / "sw" / "fast.sweep.csv").is_file()


def test_sweep_warns_of_a_sobol_sample_that_is_not_a_power_of_two(tmp_path, capsys):
    """A line of the command before the sweep runs (before: nothing), and the sweep runs as
    asked (here on an in-process scheduler)."""
    from distributed import Client

    from tests.scenes.sweep_scenes import torque_level_scene

    scene = tmp_path / "torque.toml"
    scene.write_text(torque_level_scene())
    with Client(processes=False, n_workers=1, threads_per_worker=1,
                dashboard_address=":0") as client:
        assert main(["sweep", str(scene), "--scheduler", client.scheduler.address, "--sample",
                     "inputs.shaft_speed=100:300", "--samples", "3", "--sampler", "sobol",
                     "--out", str(tmp_path / "sw"), "--no-progress"]) == 0
    out, err = capsys.readouterr()
    assert err.splitlines() == [
        "bearingsim sweep: warning: SampleBalanceWarning: --sampler sobol with --samples 3: a "
        "Sobol sample of n points is balanced (one point in each of n equal intervals of every "
        "key's range) only when n is a power of two; the first 3 points of the sequence leave "
        "some intervals empty and crowd others. Use --samples 2 or 4, or --sampler lhs "
        "(balanced for any n)"]
    assert out.startswith("3 point(s): 3 settled, 0 not settled, 0 failed;")


def test_sweep_draws_no_progress_bar_into_a_log(tmp_path, capsys):
    """Standard error that is not a terminal (a log file, a pipe) gets no progress bar unless
    asked, as ``bearingsim run`` does (before: the bar's carriage-return frames, ``0%| ...
    | 0/3 [00:00<?, ?point/s]``, and its blanked line before the summary)."""
    from distributed import Client

    from tests.scenes.sweep_scenes import torque_level_scene

    scene = tmp_path / "torque.toml"
    scene.write_text(torque_level_scene())
    with Client(processes=False, n_workers=1, threads_per_worker=1,
                dashboard_address=":0") as client:
        assert main(["sweep", str(scene), "--scheduler", client.scheduler.address, "--grid",
                     "inputs.shaft_speed=100,200,300", "--out", str(tmp_path / "sw")]) == 0
    out, err = capsys.readouterr()
    assert "point/s" not in err and "\r" not in err
    assert out.startswith("3 point(s): 3 settled, 0 not settled, 0 failed;")


def test_demo_and_export_fmu_commands_are_kept():
    from bearingsim.cli import _parser

    parser = _parser()
    assert parser.parse_args(["demo", "--out", "x"]).out == "x"
    assert parser.parse_args(["export-fmu", "a", "b"]).rest == ["a", "b"]


def test_demo_runs_the_built_in_demo_scenes(tmp_path, capsys):
    from bearingsim.scenes.library import DEMO_SCENES

    assert main(["demo", "--out", str(tmp_path)]) == 0
    for name in DEMO_SCENES:
        for suffix in (".csv", ".summary.json"):
            assert (tmp_path / f"{name}{suffix}").is_file()
    # the plots that answer each demo scene's question (issue 16 item 4, issue 27 item 1)
    for name in ("motor_drive_spinup.rs_speed", "motor_drive_spinup", "double_layer_rs.steady",
                 "duplex_modes.modes", "deep_groove_statics.statics"):
        assert (tmp_path / f"{name}.png").is_file()
    summary = json.loads((tmp_path / "double_layer_rs.summary.json").read_text())
    rs = [row["Rs"] for row in summary["rows"]]
    assert all(0.0 < r < 0.5 for r in rs)  # between a standing and a rolling middle ring (0.43)


def test_built_in_scenes_are_package_data_and_run_by_name(tmp_path):
    from bearingsim.scenes import load_scene
    from bearingsim.scenes.library import FOLDER, builtin_scenes

    names = builtin_scenes()
    assert "double_layer_rs" in names and len(names) >= 7
    assert Path(FOLDER).is_relative_to(Path(bearingsim.__file__).parent)
    assert load_scene("double_layer_rs").path.endswith("double_layer_rs.toml")
    with pytest.raises(SceneError, match="built-in scenes: .*double_layer_rs"):
        load_scene(tmp_path / "missing.toml")


def test_a_folder_named_like_a_built_in_scene_does_not_hide_it(tmp_path, monkeypatch, capsys):
    """``bearingsim run double_layer_rs --out double_layer_rs`` wrote into a folder of the
    scene's name; run again from there (``--overwrite``), the name resolved to that folder,
    and the run stopped: "scene file double_layer_rs is not a regular file". A folder is no
    scene file: the name is the built-in scene's."""
    from bearingsim.scenes import load_scene
    from bearingsim.sweep_preloads import scene_file

    monkeypatch.chdir(tmp_path)
    assert main(["run", "double_layer_rs", "--out", "double_layer_rs"]) == 0
    assert (tmp_path / "double_layer_rs").is_dir()
    assert main(["run", "double_layer_rs", "--out", "double_layer_rs", "--overwrite"]) == 0
    assert "not a regular file" not in capsys.readouterr().err
    builtin = load_scene("double_layer_rs").path
    assert Path(builtin).is_file() and scene_file("double_layer_rs") == Path(builtin).resolve()


def test_a_second_run_into_the_same_folder_needs_overwrite(tmp_path, capsys):
    """Issue 16: runs overwrote their output folder silently."""
    scene = str(SCENES / "double_layer_rs.toml")
    assert main(["run", scene, "--out", str(tmp_path)]) == 0
    first = (tmp_path / "double_layer_rs.summary.json").stat().st_mtime_ns
    assert main(["run", scene, "--out", str(tmp_path)]) == 2
    err = capsys.readouterr().err
    assert "earlier run" in err and "double_layer_rs.csv" in err and "--overwrite" in err
    assert (tmp_path / "double_layer_rs.summary.json").stat().st_mtime_ns == first
    assert main(["run", scene, "--out", str(tmp_path), "--overwrite"]) == 0
    (tmp_path / "other.csv").write_text("kept")  # files of other scenes do not count
    assert main(["run", str(SCENES / "double_layer_friction.toml"), "--out",
                 str(tmp_path)]) == 0


def test_version_and_export_fmu_help(capsys):
    """Issue 16: no --version; export-fmu --help exited 2."""
    from bearingsim import __version__

    with pytest.raises(SystemExit) as exit_:
        main(["--version"])
    assert exit_.value.code == 0 and __version__ in capsys.readouterr().out
    with pytest.raises(SystemExit) as exit_:
        main(["export-fmu", "--help"])
    assert exit_.value.code == 0
    out = capsys.readouterr().out
    assert "--arg NAME=VALUE" in out and "FMI 2.0 or 3.0" in out


def test_export_fmu_of_an_unknown_name_lists_what_it_takes(capsys):
    """The command takes scene files and built-in scenes too: the refusal of a name it does
    not know said "expected pkg.module:callable, file.py:callable or an assembly name", and
    the command's help "export an assembly"."""
    assert main(["export-fmu", "nothing", "out.fmu"]) == 2  # before: SystemExit, status 1
    assert capsys.readouterr().err == (
        "bearingsim export-fmu: expected a scene file (*.toml) or built-in scene, an assembly "
        "name (bearingsim list), pkg.module:callable or file.py:callable, got 'nothing'\n")
    with pytest.raises(SystemExit):
        main(["--help"])
    assert "the model a scene runs, as an FMU" in " ".join(capsys.readouterr().out.split())


FACTORY = '''
from bearingsim.assemblies import double_layer_bearing


def bearing(inner="61905", outer="61907", speed=100.0):
    return double_layer_bearing(inner, outer, speed=speed)
'''


def test_export_fmu_from_a_file_and_the_current_folder_with_factory_arguments(tmp_path,
                                                                               monkeypatch,
                                                                               capsys):
    """Issue 16: ./mymod.py:F gave a raw TypeError, mymod:F could not be imported from the
    current folder, and factory arguments could not be given."""
    fmpy = pytest.importorskip("fmpy")
    (tmp_path / "my_bearings.py").write_text(FACTORY)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(sys, "path", [p for p in sys.path if p not in ("", str(tmp_path))])
    by_file = tmp_path / "by_file.fmu"
    assert main(["export-fmu", "./my_bearings.py:bearing", str(by_file), "--kinds", "CS",
                 "--arg", "outer=61908", "--arg", "speed=250.0", "--outputs", "Rs"]) == 0
    fmpy.read_model_description(str(by_file))
    by_module = tmp_path / "by_module.fmu"
    assert main(["export-fmu", "my_bearings:bearing", str(by_module), "--kinds", "CS",
                 "--outputs", "Rs"]) == 0
    assert main(["export-fmu", "./my_bearings.py:bearing", str(tmp_path / "x.fmu"),
                 "--arg", "colour=red"]) == 2
    assert "unexpected keyword argument 'colour'" in capsys.readouterr().err


def test_summaries_show_engineering_units():
    """Issue 16: everything printed in SI (rad/s, m, rad) and dimensionless as [1]."""
    from bearingsim.units import engineering

    assert engineering(1047.1975512, "rad/s") == "10000 r/min"
    assert engineering(1047.1975512, "rad/s", both=True) == "10000 r/min (1047.2 rad/s)"
    assert engineering(12.5e-6, "m") == "12.5 µm"
    assert engineering(0.0125, "m") == "12500 µm"
    assert engineering(math.radians(15.0), "rad") == "15 deg"
    assert engineering(2500.0, "N") == "2.5 kN" and engineering(250.0, "N") == "0.25 kN"
    assert engineering(-0.0318, "N.m") == "-31.8 N mm"
    assert engineering(0.2, "1") == "0.2 [-]"


def test_list_bearings_with_ratings_speeds_and_a_filter(capsys):
    """Issue 16: bearingsim list showed no C, C0, angle, speeds or preload classes and had no
    search."""
    assert main(["list", "bearings", "--filter", "619"]) == 0
    out = capsys.readouterr().out
    rows = [line for line in out.splitlines() if line.startswith("  ")]
    assert len(rows) == 4 and all("619" in r for r in rows)
    assert "C/C0  7.02/ 4.30 kN" in out and "n_lim  22000 r/min" in out and "a= 0.0 deg" in out
    assert main(["list", "bearings", "--filter", "7020c"]) == 0
    assert "preload L/M/H 540/1270/2550 N" in capsys.readouterr().out
    assert main(["list", "scenes"]) == 0
    assert "double_layer_rs" in capsys.readouterr().out


def test_list_states_each_assembly_arguments_unit_range_and_default(capsys):
    """`bearingsim list` named the arguments only, while the scene docs send a reader there
    for an argument's unit; each argument is now a line with what it takes."""
    assert main(["list", "assemblies", "--filter", "roller"]) == 0
    out = capsys.readouterr().out
    assert ("      tilt_y: misalignment about y [rad]; a number in rad (or with a unit), -0.01 "
            "to 0.01; default 0.0") in out
    assert ("      clearance: diametral clearance [m] (default: catalogue, normal group); a "
            "number in m (or with a unit), >= 0") in out
    assert "      friction_model: friction model (torque level); one of palmgren, skf" in out
    assert main(["list", "assemblies", "--filter", "double_layer"]) == 0
    out = capsys.readouterr().out
    assert "; default ISO VG 32, ISO VG 32\n" in out
    assert "middle_ring_drag: the middle ring's laminar drag in the oil (torque level); a table" \
           " of radius, gap, length, wetted" in out


def test_the_core_install_pulls_no_test_tool():
    """Issue 16: pip install bearingsim installed pytest, hypothesis, ruff, libcosimpy and
    pythonfmu; they are extras now ([test], [fmu-cosim]), and make demo installs the core only."""
    import tomllib

    root = Path(__file__).resolve().parent.parent
    project = tomllib.loads((root / "pyproject.toml").read_text())["project"]
    core = " ".join(project["dependencies"])
    for tool in ("pytest", "hypothesis", "ruff", "libcosimpy", "pythonfmu", "xdist", "nbclient",
                 "ipykernel", "pandas", "dask", "distributed", "ziglang"):
        assert tool not in core
    extras = project["optional-dependencies"]
    assert "libcosimpy>=0.0.6" in extras["fmu-cosim"]
    assert extras["dask"] == ["dask[distributed]>=2024.1"]  # sweeps only: not in the demo
    assert "bearingsim[dask,fmu-cosim,fmu-cross,notebook]" in extras["test"]
    assert isinstance(project["license"], str)  # SPDX string: no setuptools deprecation warning
    makefile = (root / "Makefile").read_text()
    assert "demo: $(BASE)" in makefile and 'pip install --quiet -e .\n' in makefile


def test_warnings_are_lines_of_the_command_each_once(tmp_path, capsys):
    """A new-user trial: a run above the limiting speed printed Python's warning format twice
    (``.../entry_points.py:43: SpeedLimitWarning: ...`` and the source line ``return
    func(*args, **kwargs)``), an unsettled run ``runner.py:260: NotSettledWarning: ...``."""
    text = (SCENES / "double_layer_friction.toml").read_text(encoding="utf-8")
    text = re.sub(r"(?m)^shaft_speed = .*$", 'shaft_speed = "50000 rpm"', text)
    text = re.sub(r"(?m)^t_end = .*$", "t_end = 0.01", text)
    scene = tmp_path / "fast.toml"
    scene.write_text(text, encoding="utf-8")
    assert main(["run", str(scene)]) == 0
    err = capsys.readouterr().err.splitlines()
    speed = [line for line in err if "SpeedLimitWarning" in line]
    assert len(speed) == 1
    assert speed[0].startswith("bearingsim run: warning: SpeedLimitWarning: input shaft_speed "
                               "reaches 50000 r/min")
    assert any(line.startswith("bearingsim run: warning: NotSettledWarning: ") for line in err)
    assert not any(".py:" in line or "return " in line for line in err)


@pytest.mark.parametrize("command", ["run", "validate", "export-fmu"])
def test_ctrl_c_is_one_line_of_the_command(command, tmp_path, capsys, monkeypatch):
    """Ctrl-C while a command works (the scene still loading, the model assembling or
    integrating) printed Python's traceback ending in KeyboardInterrupt, exit status 1; now
    one line and the shell's status for SIGINT, 130 (a sweep says how to resume)."""
    import bearingsim.cli
    import bearingsim.fmu

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(bearingsim.cli, f"_{command}", interrupted, raising=False)
    monkeypatch.setattr(bearingsim.fmu, "cli_export", interrupted)
    scene = SCENES / "double_layer_friction.toml"
    argv = ([command, "double_layer_bearing", str(tmp_path / "x.fmu")]
            if command == "export-fmu" else [command, str(scene)])
    assert main(argv) == 130
    captured = capsys.readouterr()
    assert captured.err == f"bearingsim {command}: interrupted\n"
    assert not (tmp_path / "x.fmu").exists()


def _options_with_defaults(parser):
    """(command, option, default, help) of every option of a parser and its sub-commands
    whose default is a value (not None, not a switch's False, not a repeatable option's empty
    list)."""
    import argparse

    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                for _, option, default, text in _options_with_defaults(sub):
                    yield name, option, default, text
        elif (action.option_strings
              and action.default not in (None, False, [], argparse.SUPPRESS)
              and action.help is not argparse.SUPPRESS):
            yield parser.prog, action.option_strings[-1], action.default, action.help or ""


def test_every_option_with_a_default_states_it_in_its_help():
    """A new-user trial: `bearingsim sweep --help` did not say that --samples is 8, --seed 0
    and --workers 2."""
    from bearingsim.cli import _parser
    from bearingsim.fmu.cli import build_parser

    options = [*_options_with_defaults(_parser()), *_options_with_defaults(build_parser())]
    assert len(options) >= 7
    silent = [(cmd, opt, default) for cmd, opt, default, text in options
              if "default" not in text]
    assert silent == []


def test_every_command_of_a_scene_says_it_takes_a_built_in_scene_name(capsys):
    """A new-user trial: ``bearingsim validate --help`` and ``bearingsim sweep --help`` said
    "scene TOML file", though both run a built-in scene by name as ``bearingsim run`` does
    (whose help said so)."""
    for command in ("run", "validate", "sweep"):
        with pytest.raises(SystemExit):
            main([command, "--help"])
        assert "built-in scene name" in " ".join(capsys.readouterr().out.split()), command
    assert main(["validate", "double_layer_rs", "--no-assemble"]) == 0


def test_a_reader_that_stops_early_ends_the_command_quietly():
    """`bearingsim list | head -1` ended with "bearingsim list: Broken pipe" on standard error
    (a BrokenPipeError taken for a file error); now the command stops quietly with the status
    of a process a closed pipe stops (128 + SIGPIPE), as other tools do."""
    import signal

    proc = subprocess.Popen([sys.executable, "-m", "bearingsim.cli", "list"],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    proc.stdout.close()  # the reader is gone before the first line
    err = proc.stderr.read().decode()
    assert proc.wait(timeout=120) == 128 + signal.SIGPIPE
    assert err == ""


def test_validate_lists_the_variables_outputs_may_ask_for(tmp_path, capsys):
    """An unknown output sent the reader to "the CSV of a run without 'outputs'", which holds
    the default outputs only; `bearingsim validate --variables` lists every variable of the
    scene's model, and works on the scene with the unknown output."""
    scene = tmp_path / "pair.toml"
    scene.write_text('outputs = ["Fa_inner"]\n[assembly]\nname = "duplex_pair"\n'
                     '[simulation]\nt_end = 1\n')
    assert main(["validate", str(scene)]) == 2
    assert "the model's variables (bearingsim validate --variables lists them)" in \
        capsys.readouterr().err
    assert main(["validate", "--variables", str(scene)]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert re.fullmatch(r"duplex_pair at fidelity quasi-static: \d+ variables", lines[0])
    assert "  shaft.x [m]: x of the centre of mass" in lines
    assert "  shaft.Mx [N.m]: external load Mx at the centre of mass" in lines
    listed = lines[1:lines.index(next(x for x in lines if x.startswith("parameters (")))]
    assert int(lines[0].split(": ")[1].split()[0]) == len(listed) > 100
    roller = tmp_path / "roller.toml"
    roller.write_text('[assembly]\nname = "cylindrical_roller_bearing"\n[simulation]\nt_end = 1\n')
    assert main(["validate", "--variables", str(roller)]) == 0
    out = capsys.readouterr().out
    assert out.startswith("cylindrical_roller_bearing at fidelity quasi-static: ")  # auto's top
    assert "post-processed (computed after the run):\n  Q_max [N]: " in out


def test_validate_variables_lists_the_parameters_a_scene_may_set(tmp_path, capsys):
    """Nothing listed the parameters a scene's [parameters] or a sweep's parameters.<name>
    may set: a user had to read the component reference for the dotted names. They follow
    the variables, each with its unit, the value the scene runs with (its own [parameters]
    included) and its range."""
    scene = tmp_path / "oil.toml"
    scene.write_text('[assembly]\nname = "double_layer_bearing"\nfidelity = "torque"\n'
                     '[parameters]\n"inner_layer.nu" = "46 mm^2/s"\n'
                     '[simulation]\nt_end = 1\n')
    assert main(["validate", "--variables", str(scene)]) == 0
    out = capsys.readouterr().out
    head = "parameters ([parameters] sets them, a sweep varies them as parameters.<name>):\n"
    assert head in out
    listed = out.split(head)[1].splitlines()
    assert ("  inner_layer.nu [m2/s]: kinematic viscosity of the (base) oil at operating "
            "temperature; 46 mm²/s (4.6e-05 m2/s); 0 to 0.01 m2/s") in listed
    assert "  outer_layer.nu [m2/s]: kinematic viscosity of the (base) oil at operating " \
           "temperature; 32 mm²/s (3.2e-05 m2/s); 0 to 0.01 m2/s" in listed
    assert any(x.startswith("  inner_layer.f0 [-]: Palmgren") and x.endswith("; >= 0")
               for x in listed)


@pytest.mark.parametrize("command", ["run", "sweep", "demo"])
def test_an_empty_output_folder_is_refused(command, capsys):
    """Before: ``--out ""`` (an unset shell variable) wrote into the current folder."""
    args = {"run": ["run", "deep_groove_radial"], "demo": ["demo"],
            "sweep": ["sweep", "deep_groove_radial", "--grid", "inputs.load.Fx=1,2"]}[command]
    with pytest.raises(SystemExit) as exit_:
        main([*args, "--out", ""])
    assert exit_.value.code == 2
    assert "argument --out: an empty folder name; give . for the current folder" in \
        capsys.readouterr().err
