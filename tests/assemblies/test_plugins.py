"""Assembly plug-ins (issue 16 item 6): a distribution's ``bearingsim.assemblies`` entry points
appear in scenes, ``bearingsim list`` and ``bearingsim export-fmu``, like a built-in assembly.

Each test installs a tiny distribution for real: a ``*.dist-info`` directory with
``entry_points.txt`` and a module beside it, on ``sys.path`` (importlib.metadata finds it there).
"""

from __future__ import annotations

import sys
import textwrap
import warnings
import zipfile

import pytest

from bearingsim.assemblies.plugins import PluginError, PluginWarning
from bearingsim.cli import main
from bearingsim.scenes import parse_scene, run_scene
from bearingsim.scenes.registry import REGISTRY, get_spec

FLYWHEEL = '''
from bearingsim.assemblies.spec import ArgSpec, AssemblySpec
from bearingsim.components.rotational import Inertia


def flywheel(J=0.05, w0=100.0):
    """A free flywheel."""
    return Inertia(J=J, w0=w0, name="flywheel")


flywheel.SCENE_SPEC = AssemblySpec(
    name="{name}", description="a free flywheel (plug-in)", fidelity_arg=None,
    build=lambda args, fidelity: flywheel(args["J"], args["w0"]),
    args={{"J": ArgSpec("float", 0.05, "inertia [kg m^2]", low=0.0),
          "w0": ArgSpec("float", 100.0, "start speed [rad/s]")}},
    fidelities=("rigid",), auto_fidelities=("rigid",), output_fidelity=[("*", "rigid")],
    default_outputs=["w"])
'''


def install(root, module: str, source: str, entries: dict[str, str],
            dist: str = "bsim-flywheel") -> None:
    """Write ``module.py`` and a dist-info of ``dist`` 0.1 with the given entry points."""
    (root / f"{module}.py").write_text(textwrap.dedent(source), encoding="utf-8")
    info = root / f"{dist.replace('-', '_')}-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {dist}\nVersion: 0.1\n",
                                   encoding="utf-8")
    lines = "".join(f"{k} = {v}\n" for k, v in entries.items())
    (info / "entry_points.txt").write_text(f"[bearingsim.assemblies]\n{lines}",
                                           encoding="utf-8")


@pytest.fixture
def site(tmp_path, monkeypatch):
    """A folder on sys.path for the test's distributions; the registry forgets the plug-ins
    before and after."""
    root = tmp_path / "site"
    root.mkdir()
    monkeypatch.syspath_prepend(str(root))
    REGISTRY.reload_plugins()
    yield root
    for name in [m for m in sys.modules if m.startswith("bsim_plugin_")]:
        del sys.modules[name]
    REGISTRY.reload_plugins()


def test_a_plugin_assembly_is_listed_runs_in_a_scene_and_is_found_by_name(site, capsys):
    install(site, "bsim_plugin_fly", FLYWHEEL.format(name="flywheel"),
            {"flywheel": "bsim_plugin_fly:flywheel"})
    assert main(["list", "assemblies"]) == 0
    out = capsys.readouterr().out
    assert "  flywheel: a free flywheel (plug-in)" in out
    assert "      w0: start speed [rad/s]; a number in rad/s (or with a unit); default 100.0" in out
    assert get_spec("flywheel") is REGISTRY.plugins["flywheel"]
    run = run_scene(parse_scene('[assembly]\nname = "flywheel"\nw0 = 50.0\n'
                                '[simulation]\nt_end = 0.5\n', None), write=False)
    assert run.summary["assembly"] == "flywheel"
    assert run.summary["outputs"]["w"]["final"] == pytest.approx(50.0)


def test_an_entry_point_may_load_the_spec_itself_and_is_loaded_once(site):
    source = FLYWHEEL.format(name="wheel") + "\nSPEC = flywheel.SCENE_SPEC\nLOADS = []\n"
    install(site, "bsim_plugin_spec", source, {"wheel": "bsim_plugin_spec:SPEC"})
    spec = REGISTRY["wheel"]
    assert spec.name == "wheel" and "wheel" in REGISTRY and "wheel" in list(REGISTRY)
    module = sys.modules["bsim_plugin_spec"]
    module.LOADS.append(1)
    import importlib

    assert REGISTRY["wheel"] is spec  # not discovered again: the module is not re-imported
    assert importlib.import_module("bsim_plugin_spec").LOADS == [1]


def test_export_fmu_accepts_a_plugin_assembly_by_name(site, tmp_path, capsys):
    pytest.importorskip("fmpy")
    install(site, "bsim_plugin_fmu", FLYWHEEL.format(name="flywheel"),
            {"flywheel": "bsim_plugin_fmu:flywheel"})
    target = tmp_path / "flywheel.fmu"
    assert main(["export-fmu", "flywheel", str(target), "--arg", "J=0.2", "--kinds", "CS"]) == 0
    with zipfile.ZipFile(target) as fmu:
        description = fmu.read("modelDescription.xml").decode()
    assert 'name="J"' in description and 'start="0.2"' in description
    assert main(["export-fmu", "flywheel", str(target), "--arg", "K=1"]) == 2
    assert ("bearingsim export-fmu: flywheel has no argument K; arguments: J, w0"
            in capsys.readouterr().err)


def test_a_broken_plugin_is_a_warning_naming_it_and_list_still_works(site, capsys):
    install(site, "bsim_plugin_broken", "raise ImportError('needs numpy 9')\n",
            {"broken": "bsim_plugin_broken:flywheel",
             "notaspec": "textwrap:dedent"}, dist="bsim-broken")
    assert main(["list", "assemblies"]) == 0  # the command prints its warnings as lines
    captured = capsys.readouterr()
    prefix = f"bearingsim list: warning: {PluginWarning.__name__}: "
    texts = sorted(line[len(prefix):] for line in captured.err.splitlines()
                   if line.startswith(prefix))
    assert len(texts) == 2
    assert texts[0].startswith("assembly plug-in entry point broken = bsim_plugin_broken:"
                               "flywheel (distribution bsim-broken 0.1) skipped: loading it "
                               "raised ImportError: needs numpy 9")
    assert "notaspec = textwrap:dedent (distribution bsim-broken 0.1)" in texts[1]
    assert "neither an AssemblySpec nor" in texts[1]
    assert "duplex_pair" in captured.out and "Traceback" not in captured.err
    with pytest.raises(KeyError, match="needs numpy 9"):
        get_spec("broken")


def test_a_name_clash_with_a_builtin_assembly_is_an_error_naming_both(site, capsys):
    install(site, "bsim_plugin_clash", FLYWHEEL.format(name="duplex_pair"),
            {"duplex": "bsim_plugin_clash:flywheel"}, dist="bsim-clash")
    with pytest.raises(PluginError, match=r"entry point duplex = bsim_plugin_clash:flywheel "
                                          r"\(distribution bsim-clash 0.1\).*built-in assembly "
                                          r"'duplex_pair' \(bearingsim.assemblies.duplex.scene\)"):
        REGISTRY["duplex_pair"]
    assert main(["list", "assemblies"]) == 2
    err = capsys.readouterr().err
    assert "bearingsim list: assembly plug-in entry point duplex" in err
    assert "Traceback" not in err


def test_two_plugins_with_one_name_are_an_error_naming_both(site):
    install(site, "bsim_plugin_one", FLYWHEEL.format(name="wheel"),
            {"wheel": "bsim_plugin_one:flywheel"}, dist="bsim-one")
    install(site, "bsim_plugin_two", FLYWHEEL.format(name="wheel"),
            {"wheel2": "bsim_plugin_two:flywheel"}, dist="bsim-two")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(PluginError, match=r"bsim-one 0.1\) and entry point wheel2 = "
                                              r"bsim_plugin_two:flywheel \(distribution "
                                              r"bsim-two 0.1\) both name"):
            list(REGISTRY)
