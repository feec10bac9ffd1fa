"""Sweep samples from scipy.stats.qmc: stratification (Latin hypercube: one point per cell in
every dimension; Sobol with 2^m points: one per dyadic interval in every dimension, the
(t, m, s)-net property of Sobol' 1967), ranges, seeds, and the CLI flags."""

from __future__ import annotations

import math
import subprocess
import sys
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bearingsim.cli import _parser
from bearingsim.scenes.sampling import (
    SampleBalanceWarning,
    SweepError,
    check_key,
    crossed_points,
    parse_sample,
    sample_points,
)
from bearingsim.scenes.sweep_grid import check_point_keys, parse_grid

RANGES = {"parameters.shaft.J": (1e-4, 1e-3), "inputs.shaft_speed": (100.0, 600.0)}


def _cells(points, key, n):
    lo, hi = RANGES[key]
    return sorted(int(math.floor((p[key] - lo) / (hi - lo) * n)) for p in points)


@given(n=st.integers(1, 64), seed=st.integers(0, 2**32 - 1),
       method=st.sampled_from(["lhs", "lhs-optimal"]))
@settings(max_examples=30, deadline=None)
def test_latin_hypercube_puts_one_point_in_every_cell(n, seed, method):
    points = sample_points(RANGES, n, seed, method=method)
    assert len(points) == n
    for key in RANGES:
        assert _cells(points, key, n) == list(range(n))


@pytest.mark.parametrize("m", [1, 3, 6])
def test_sobol_power_of_two_is_stratified_in_each_dimension(m):
    n = 2**m
    points = sample_points(RANGES, n, seed=5, method="sobol")
    for key in RANGES:
        assert _cells(points, key, n) == list(range(n))


def test_unscrambled_samples_are_cell_centres_and_sobol_starts_at_the_origin():
    centres = sample_points({"inputs.x": (0.0, 1.0)}, 4, seed=0, scramble=False)
    assert sorted(p["inputs.x"] for p in centres) == pytest.approx([0.125, 0.375, 0.625,
                                                                    0.875])
    sobol = sample_points({"inputs.x": (0.0, 1.0)}, 4, seed=0, method="sobol", scramble=False)
    assert [p["inputs.x"] for p in sobol] == pytest.approx([0.0, 0.5, 0.75, 0.25])


def test_seeds_reproduce_and_differ():
    a = sample_points(RANGES, 16, seed=3, method="sobol")
    assert a == sample_points(RANGES, 16, seed=3, method="sobol")
    assert a != sample_points(RANGES, 16, seed=4, method="sobol")
    assert sample_points(RANGES, 7, seed=3) == sample_points(RANGES, 7, seed=3)


@given(lo=st.floats(-1e6, 1e6), width=st.floats(1e-6, 1e6), n=st.integers(1, 40))
@settings(max_examples=40, deadline=None)
@pytest.mark.filterwarnings("ignore::bearingsim.scenes.sampling.SampleBalanceWarning")
def test_samples_stay_in_their_range(lo, width, n):
    hi = lo + width
    if not hi > lo:
        return
    for method in ("lhs", "sobol"):
        values = np.array([p["inputs.x"] for p in sample_points({"inputs.x": (lo, hi)}, n,
                                                                  seed=1, method=method)])
        assert np.all(values >= lo) and np.all(values <= hi)


@pytest.mark.parametrize(("n", "below", "above"), [(3, 2, 4), (100, 64, 128)])
def test_a_sobol_sample_of_other_than_a_power_of_two_warns(n, below, above):
    """Before, the count was taken silently (scipy's own warning filtered out): 100 Sobol
    points fill only about 75-83 of the 100 equal intervals of a key, where 64 or 128 fill
    every one; it still runs as asked."""
    with pytest.warns(SampleBalanceWarning) as caught:
        points = sample_points(RANGES, n, seed=5, method="sobol")
    assert len(points) == n
    assert [str(w.message) for w in caught] == [
        f"--sampler sobol with --samples {n}: a Sobol sample of n points is balanced (one point "
        f"in each of n equal intervals of every key's range) only when n is a power of two; "
        f"the first {n} points of the sequence leave some intervals empty and crowd others. "
        f"Use --samples {below} or {above}, or --sampler lhs (balanced for any n)"]
    assert len(set(_cells(points, "inputs.shaft_speed", n))) < n  # the unfilled intervals


@pytest.mark.parametrize(("n", "method"), [(1, "sobol"), (2, "sobol"), (64, "sobol"),
                                           (100, "lhs"), (3, "lhs-optimal")])
def test_balanced_samples_do_not_warn(n, method):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert len(sample_points(RANGES, n, seed=5, method=method)) == n


def test_bad_specifications_are_named():
    with pytest.raises(SweepError, match="--samples must be >= 1"):
        sample_points(RANGES, 0)
    with pytest.raises(SweepError, match="--seed must be a non-negative integer or None, "
                                         "got -1"):
        sample_points(RANGES, 4, seed=-1)  # was numpy's ValueError from deep inside
    # before: TypeErrors from the comparison or from numpy's SeedSequence
    for seed in (1.5, "3", True):
        with pytest.raises(SweepError, match="--seed must be"):
            sample_points(RANGES, 4, seed=seed)
    for n in (2.5, "4", None, True):
        with pytest.raises(SweepError, match=r"--samples must be >= 1 \(a whole number\)"):
            sample_points(RANGES, n)
    assert len(sample_points(RANGES, np.int64(4), seed=np.int64(2))) == 4
    # before: "1,,2" ran as far as the point, refused as "the expression ''"; "1;;2" and "1;"
    # dropped the empty value without a word
    for values in ("1,,2", "1;;2"):
        with pytest.raises(SweepError, match=r"--grid inputs.x: value 2 of 3 is empty"):
            parse_grid([f"inputs.x={values}"])
    for values in (",", ";", ""):
        with pytest.raises(SweepError, match=r"--grid inputs.x: no values"):
            parse_grid([f"inputs.x={values}"])
    assert parse_grid(["inputs.x=1,2,"]) == parse_grid(["inputs.x=1;2;"]) == {
        "inputs.x": ["1", "2"]}
    # every point checked, whatever run_sweep's type check sampled (beartype checks one item)
    with pytest.raises(SweepError, match="sweep point 2 must be a dict"):
        check_point_keys([{}, {}, 5, {}])
    with pytest.raises(SweepError, match="must start with inputs."):
        check_point_keys([{"x": 1}])
    with pytest.raises(SweepError, match="allowed: lhs, lhs-optimal, sobol"):
        sample_points(RANGES, 4, method="halton")
    with pytest.raises(SweepError, match="low < high"):
        parse_sample(["inputs.x=2:1"])
    with pytest.raises(SweepError, match=r"--sample inputs.x: low and high are different "
                                         r"quantities \(in SI N and m\), got '1 kN:2 m'"):
        parse_sample(["inputs.x=1 kN:2 m"])  # before: "need finite low < high"
    with pytest.raises(SweepError, match="must start with"):
        parse_sample(["x=1:2"])
    with pytest.raises(SweepError, match="allowed simulation settings"):
        check_key("simulation.solver")


def test_a_key_given_twice_is_refused_not_overwritten():
    """A new-user trial: `--grid inputs.Fr=1,2 --grid inputs.Fr=3` ran one point, Fr = 3 (the
    second --grid replaced the first's values without a word); the same for --sample, and a
    key both gridded and sampled ran with the sample's values only."""
    with pytest.raises(SweepError, match=r"--grid inputs.Fr is given twice; give all its "
                                         r"values in one: --grid inputs.Fr=v1,v2,..."):
        parse_grid(["inputs.Fr=1,2", "inputs.Fa=0", "inputs.Fr=3"])
    with pytest.raises(SweepError, match=r"--sample inputs.Fr is given twice"):
        parse_sample(["inputs.Fr=1:2", " inputs.Fr =3:4"])
    grid = [{"inputs.Fr": 1.0, "inputs.Fa": 0.0}, {"inputs.Fr": 2.0, "inputs.Fa": 0.0}]
    with pytest.raises(SweepError, match=r"inputs.Fr: both gridded \(--grid\) and sampled"):
        crossed_points(grid, [{"inputs.Fr": 5.0, "inputs.x": 1.0}])


def test_grid_and_sample_points_cross_with_the_sample_fastest():
    grid = [{"inputs.Fr": 1.0}, {"inputs.Fr": 2.0}]
    samples = [{"inputs.x": 0.5}, {"inputs.x": 0.7}, {"inputs.x": 0.9}]
    assert crossed_points(grid, samples) == [
        {"inputs.Fr": fr, "inputs.x": x} for fr in (1.0, 2.0) for x in (0.5, 0.7, 0.9)]
    assert crossed_points([{}], samples) == samples


def test_cli_flags_kept_and_sampler_added():
    args = _parser().parse_args(["sweep", "s.toml", "--sample", "inputs.x=1:2", "--samples",
                                 "16", "--seed", "7", "--sampler", "sobol", "--no-scramble"])
    assert (args.samples, args.seed, args.sampler, args.no_scramble) == (16, 7, "sobol", True)
    assert _parser().parse_args(["sweep", "s.toml"]).sampler == "lhs"


def test_a_sweep_imports_scipy_stats_only_to_sample() -> None:
    """scipy.stats takes about half a second to import: a grid sweep (the sweep modules and the
    command line's sweep) never loads it; the first sample does."""
    code = ("import sys\n"
            "import bearingsim.cli, bearingsim.scenes.sweep\n"
            "before = 'scipy.stats' in sys.modules\n"
            "from bearingsim.scenes.sampling import sample_points\n"
            "sample_points({'inputs.a': (0.0, 1.0)}, 4)\n"
            "print(before, 'scipy.stats' in sys.modules)\n")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["False", "True"]


def test_a_range_that_is_not_numbers_is_told_that_units_work():
    """``rpm(1000):rpm(2000)`` was told "low and high must be numbers", though numbers with a
    unit work (``1000 rpm:2000 rpm``)."""
    with pytest.raises(SweepError, match=r"inputs\.shaft_speed: low and high must be numbers "
                                         r"\(SI\) or numbers with a unit \('1000 rpm:2000 rpm'\)"):
        parse_sample(["inputs.shaft_speed=rpm(1000):rpm(2000)"])
    low, high, unit = parse_sample(["inputs.shaft_speed=1000 rpm:2000 rpm"])["inputs.shaft_speed"]
    assert (low, high, unit) == (pytest.approx(1000 * math.pi / 30, rel=1e-12),
                                 pytest.approx(2000 * math.pi / 30, rel=1e-12), "rad/s")


def test_a_sampled_range_with_a_unit_is_checked_against_the_key(client, tmp_path):
    """``--sample "inputs.load.Fx=1 mm:2 mm"`` ran, with forces of 1-2 mN: the range's unit was
    converted to SI and dropped, so a length passed for a force. A range given with a unit now
    keeps it (``parse_sample`` gives (low, high, SI unit)), its sampled values carry it, and the
    sweep refuses a point of another quantity as it does a grid's ``"1 mm"``. A force in kN
    gives the same sample, in N, as the plain range in N."""
    from bearingsim.scenes import load_scene
    from bearingsim.scenes.sweep import run_sweep

    assert parse_sample(["inputs.load.Fx=1 mm:2 mm"]) == {"inputs.load.Fx": (0.001, 0.002, "m")}
    in_kn = sample_points(parse_sample(["inputs.load.Fx=1 kN:2 kN"]), 3, seed=4)
    in_n = sample_points(parse_sample(["inputs.load.Fx=1000:2000"]), 3, seed=4)
    assert [p["inputs.load.Fx"] for p in in_kn] == [f"{p['inputs.load.Fx']!r} N" for p in in_n]

    scene = load_scene("deep_groove_statics")
    at = {"inputs.shaft_speed": "1000 rpm"}
    mm = sample_points(parse_sample(["inputs.load.Fx=1 mm:2 mm"]), 2, seed=4)
    with pytest.raises(SweepError, match=r"inputs\.load\.Fx: input load\.Fx is in N, but its "
                                         r"value is given in m"):
        run_sweep(scene, [{**at, **p} for p in mm], client=client, out=tmp_path / "mm",
                  progress=False)
    res = run_sweep(scene, [{**at, **p} for p in in_kn], client=client, out=tmp_path / "kN",
                    progress=False)
    assert [r["inputs.load.Fx"] for r in res.rows] == [p["inputs.load.Fx"] for p in in_n]
    assert all(r["status"] == "ok" for r in res.rows)
