"""What a command imports: the assembler's passes with networkx, scipy.optimize and
scipy.integrate (with what they pull in, ~0.8 s together on this machine's runs of
``python -X importtime``), and scipy.linalg and scipy.sparse (~0.35 s with scipy's common
base) are imported where they are used, not by the command line, the
scene runner or a sweep worker, nor by a run whose model loads from the cache and integrates
on SUNDIALS or compiled_bdf; scipy.special (0.45 s) not even to build a ball bearing; pint
neither, once the conversions such a run needs are kept on disk
(:mod:`bearingsim.units.conversion_memo`). Each check runs in a fresh Python process."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from bearingsim.simulation.c_compiler import c_compiler

ROOT = Path(__file__).resolve().parent.parent

HEAVY = ("networkx", "scipy.optimize", "scipy.integrate", "scipy.linalg", "scipy.sparse",
         "scipy.special", "bearingsim.assembler.pipeline", "pint")


def _imported_after(code: str, env: dict | None = None,
                    names: tuple[str, ...] = HEAVY) -> list[str]:
    """The modules of ``names`` (default :data:`HEAVY`) imported after running ``code`` in a
    new process."""
    script = textwrap.dedent(code) + textwrap.dedent(f"""
        import json, sys
        print(json.dumps([m for m in {names!r} if m in sys.modules]))
        """)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         check=True, env={**os.environ, **(env or {})}, timeout=600)
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_the_command_line_scene_runner_and_sweep_worker_import_none_of_them():
    assert _imported_after("""
        import bearingsim.cli, bearingsim.scenes, bearingsim.scenes.runner
        import bearingsim.scenes.sweep_worker, bearingsim.simulation
        """) == []


def test_a_run_loaded_from_the_cache_imports_none_of_them(tmp_path):
    run = f"""
        import warnings
        warnings.simplefilter("ignore")
        from bearingsim.scenes import load_scene
        from bearingsim.scenes.library import builtin_scene_path
        from bearingsim.scenes.runner import run_scene
        scene = load_scene(builtin_scene_path("motor_drive_spinup"))
        run = run_scene(scene, {str(tmp_path / "out")!r}, write=False, progress=False)
        """
    env = {"BEARINGSIM_CACHE": str(tmp_path / "cache")}
    first = _imported_after(run, env)  # assembles (the passes) and stores the system
    assert "bearingsim.assembler.pipeline" in first
    assert _imported_after(run, env) == []  # loads it: no pass, no scipy solver


def test_building_a_ball_bearing_imports_none_of_them():
    """A bearing's design solves Hertz's ellipticity equation with complete elliptic
    integrals: by the arithmetic-geometric mean of the generated models
    (:func:`bearingsim.symbolic.ellipk`), not scipy.special (0.45 s to import, paid by every
    process that built a bearing: a command, a sweep's client planning its points)."""
    assert _imported_after("""
        from bearingsim.assemblies import deep_groove_ball_bearing
        deep_groove_ball_bearing("6304", "dynamic_massive_balls", speed=100.0)
        """) == []


@pytest.mark.skipif(c_compiler() is None, reason="no C compiler")
def test_a_compiled_bdf_run_loaded_from_the_cache_imports_none_of_them(tmp_path):
    """The fill-reducing order of the compiled kernel's Newton matrix (SuperLU's, through
    scipy.sparse) is kept beside the library: a later process, a sweep worker among them,
    reads it instead of importing scipy.sparse (0.35-0.5 s)."""
    run = """
        from bearingsim.assembler import assemble_cached
        from bearingsim.simulation import simulate
        from tests.models import TwoInertiaDrive
        result = simulate(assemble_cached(TwoInertiaDrive()), 0.01, method="compiled_bdf",
                          compiled=True)
        assert result.stats["method"] == "compiled_bdf"
        """
    env = {"PYTHONPATH": str(ROOT), "BEARINGSIM_CACHE": str(tmp_path / "cache")}
    assert "scipy.sparse" in _imported_after(run, env)  # orders the kernel's unknowns
    assert _imported_after(run, env) == []  # reads the order kept with the library


@pytest.mark.parametrize("method", ["LSODA", "BDF"])
def test_a_scipy_method_still_imports_scipy_integrate_when_it_runs(method):
    used = _imported_after(f"""
        from bearingsim.assembler import assemble
        from bearingsim.simulation import simulate
        from tests.models import TwoInertiaDrive
        simulate(assemble(TwoInertiaDrive()), 0.01, method={method!r})
        """, {"PYTHONPATH": str(ROOT)})
    assert "scipy.integrate" in used


def test_planning_a_sweep_with_input_expressions_does_not_import_scipy_integrate(tmp_path):
    """The a-priori cost of a point whose speed is an expression of time (its mean over the
    span, :func:`~bearingsim.scenes.sweep_order.point_features`) integrates with numpy's
    trapezoidal rule: importing scipy.integrate for it cost the sweep's client 0.3 s."""
    scene = tmp_path / "bearing.toml"
    used = _imported_after(f"""
        from pathlib import Path
        from bearingsim.scenes import load_scene
        from bearingsim.scenes.sweep import grid_points
        from bearingsim.scenes.sweep_grid import parse_grid
        from bearingsim.scenes.sweep_order import point_features
        from bearingsim.scenes.sweep_plan import plan_sweep
        from tests.scenes.sweep_scenes import torque_level_scene
        path = Path({str(scene)!r})
        path.write_text(torque_level_scene(t_end=0.1))
        plan = plan_sweep(load_scene(path), grid_points(parse_grid(
            ['inputs.shaft_speed="rpm(1000) * ramp(0, 0.02)";300'])))
        features = [point_features(j, plan.values[j.index],
                                   plan.prepared[plan.structure[j.index]].system.variable_units)
                    for j in plan.jobs]
        assert features[0]["inputs.shaft_speed"] > 0
        """, {"PYTHONPATH": str(ROOT), "BEARINGSIM_CACHE": str(tmp_path / "cache")})
    assert "scipy.integrate" not in used


def test_learning_the_cost_of_a_sweeps_points_does_not_import_scipy_optimize():
    """The client refits the points' measured times as they come in
    (:class:`~bearingsim.scenes.sweep_order.PointCosts`) with numpy: its robust fit through
    scipy.optimize.least_squares imported scipy.optimize (about 0.8 s of CPU) while the
    workers ran, taken from them on a machine with as many cores as workers."""
    used = _imported_after("""
        from bearingsim.scenes.sweep_order import PointCosts
        costs = PointCosts({k: {"span": 0.1, "rotation": 10.0 * k, "inputs.Fr": 100.0 * (k % 3)}
                            for k in range(1, 13)})
        for k in range(1, 9):
            costs.add(k, 0.1 + 0.01 * k + 1e-4 * (k % 3))
        assert costs.estimate(12) > costs.estimate(11)
        """)
    assert used == []


def test_starting_the_sweep_worker_server_waits_for_no_model_library():
    """``bearingsim sweep`` starts the process its workers fork from before anything else; the
    package's modeling language (CasADi, numpy, beartype: 0.2-0.3 s) is imported on first use,
    not by importing a submodule, so the server starts at once and its imports (the first
    points wait for them) begin that much sooner."""
    assert _imported_after("""
        import bearingsim.cli, bearingsim.sweep_preloads, bearingsim.sweep_server
        """, names=("casadi", "numpy", "beartype", "bearingsim.language")) == []


def test_the_language_is_still_importable_from_the_package():
    import bearingsim
    import bearingsim.language as language
    from bearingsim import Component, der

    assert Component is language.Component and der is language.der
    assert bearingsim.__all__ == list(language.__all__)
    assert set(language.__all__) <= set(dir(bearingsim))
    assert bearingsim.language is language
    with pytest.raises(AttributeError, match="no attribute 'Componnt'"):
        bearingsim.Componnt  # noqa: B018
    namespace: dict = {}
    exec("from bearingsim import *", namespace)  # noqa: S102
    assert set(language.__all__) <= set(namespace)


def test_the_sweep_command_starts_its_worker_server_before_it_imports_the_scenes():
    """``bearingsim sweep`` builds its parser, then starts the fork server of its workers: the
    parser names the samplers without importing the scenes package (0.4-0.5 s, which the
    server's start, and so the first sweep's workers, waited for)."""
    script = textwrap.dedent("""
        import sys
        import bearingsim.sweep_server as server

        def started(*args, **kwargs):
            print("bearingsim.scenes" in sys.modules, "casadi" in sys.modules)
            raise SystemExit(0)

        server.start_worker_server = started
        from bearingsim.cli import main
        main(["sweep", "scenes/deep_groove_duty1.toml", "--grid", "inputs.load.Fx=1,2",
              "--sampler", "sobol"])
        """)
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                         check=True, cwd=ROOT, timeout=600)
    assert out.stdout.split() == ["False", "False"]
